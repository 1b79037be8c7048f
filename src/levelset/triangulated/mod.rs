//! The exact signed distance to a closed triangulated surface.
//!
//! [`TriangulatedShape`] validates the surface (see [`topology`] for what is rejected and what is
//! repaired), builds a bounding-volume hierarchy over the triangles ([`bvh`]) and answers
//! `distance(p)` as the distance to the nearest triangle (exact: closest point on a triangle,
//! [`closest`]) signed by the angle-weighted pseudo-normal of the feature (face, edge or vertex)
//! holding the closest point (Bærentzen and Aanæs 2005): `(p − q) · n ≥ 0` outside.
//! For a closed, consistently oriented manifold the sign is right everywhere, including where the
//! closest point is a vertex or an edge, where the face normals alone disagree.

pub mod bvh;
pub mod closest;
pub mod topology;

use self::bvh::{Bvh, Nearest};
use self::closest::Feature;
use super::shapes::Shape;
use super::surface::TriangleSurface;
use crate::error::Result;
use crate::geom::DVec3;
use crate::io::SurfaceMesh;
use rayon::prelude::*;

/// A closed, oriented triangulated surface with its exact signed distance (negative inside).
#[derive(Debug, Clone)]
pub struct TriangulatedShape {
    surface: TriangleSurface,
    bvh: Bvh,
    /// Unit outward normal of each triangle.
    face_normals: Vec<DVec3>,
    /// Per triangle and local edge: the sum of the unit normals of the two triangles sharing it.
    edge_normals: Vec<[DVec3; 3]>,
    /// Per vertex: the sum of the incident unit face normals weighted by the incident angles.
    vertex_normals: Vec<DVec3>,
    flipped: usize,
    components: usize,
    volume: f64,
    area: f64,
}

impl TriangulatedShape {
    /// Validates `points` and `triangles` as a closed manifold surface, repairs its orientation
    /// (each component consistent and outward) and builds the search structure. Errors
    /// ([`crate::Error::InvalidInput`], naming the first offending vertex, triangle or edge and
    /// the count): a non-finite coordinate, an index out of range, a degenerate triangle, a hole,
    /// a non-manifold edge, a non-orientable component.
    pub fn new(points: Vec<DVec3>, triangles: Vec<[u32; 3]>) -> Result<TriangulatedShape> {
        topology::check_elements(&points, &triangles)?;
        let oriented = topology::orient(&points, &triangles)?;
        let triangles = oriented.triangles;
        let face_normals: Vec<DVec3> = triangles
            .iter()
            .map(|t| {
                let [a, b, c] = t.map(|v| points[v as usize]);
                (b - a).cross(c - a).normalize()
            })
            .collect();
        let edge_normals = (0..triangles.len())
            .map(|t| {
                let nb = oriented.neighbours[t];
                [0, 1, 2].map(|i| face_normals[t] + face_normals[nb[i] as usize])
            })
            .collect();
        let mut vertex_normals = vec![DVec3::ZERO; points.len()];
        for (t, tri) in triangles.iter().enumerate() {
            for i in 0..3 {
                let v = points[tri[i] as usize];
                let e1 = points[tri[(i + 1) % 3] as usize] - v;
                let e2 = points[tri[(i + 2) % 3] as usize] - v;
                let angle = e1.angle_between(e2);
                vertex_normals[tri[i] as usize] += angle * face_normals[t];
            }
        }
        let surface = TriangleSurface { points, triangles };
        let bvh = Bvh::new(&surface.points, &surface.triangles);
        let volume = surface.enclosed_volume();
        let area = surface.area();
        Ok(TriangulatedShape {
            surface,
            bvh,
            face_normals,
            edge_normals,
            vertex_normals,
            flipped: oriented.flipped,
            components: oriented.components,
            volume,
            area,
        })
    }

    /// [`TriangulatedShape::new`] on a surface read from a file ([`crate::io::read_obj`]).
    pub fn from_mesh(mesh: &SurfaceMesh) -> Result<TriangulatedShape> {
        Self::new(mesh.points.clone(), mesh.tris.clone())
    }

    /// The surface, with the repaired (consistent, outward) orientation.
    pub fn surface(&self) -> &TriangleSurface {
        &self.surface
    }

    /// The number of triangles whose orientation the repair reversed (0 for a consistently
    /// outward input).
    pub fn flipped_triangles(&self) -> usize {
        self.flipped
    }

    /// The number of connected components (through shared edges).
    pub fn components(&self) -> usize {
        self.components
    }

    /// The enclosed volume of the (repaired) surface.
    pub fn volume(&self) -> f64 {
        self.volume
    }

    /// The area of the surface.
    pub fn area(&self) -> f64 {
        self.area
    }

    /// The number of nodes of the bounding-volume hierarchy.
    pub fn bvh_nodes(&self) -> usize {
        self.bvh.n_nodes()
    }

    /// The nearest triangle to `p`, the closest point on it and its feature.
    pub fn nearest(&self, p: DVec3) -> Nearest {
        self.bvh.nearest(p)
    }

    /// The pseudo-normal (not unit) of the feature holding a closest point.
    fn pseudo_normal(&self, n: &Nearest) -> DVec3 {
        let t = n.triangle as usize;
        match n.feature {
            Feature::Face => self.face_normals[t],
            Feature::Edge(i) => self.edge_normals[t][i as usize],
            Feature::Vertex(i) => {
                self.vertex_normals[self.surface.triangles[t][i as usize] as usize]
            }
        }
    }

    /// The signed distances at `points`, computed in parallel (the result does not depend on
    /// the number of threads).
    pub fn distances(&self, points: &[DVec3]) -> Vec<f64> {
        points.par_iter().map(|&p| self.distance(p)).collect()
    }
}

impl Shape<DVec3> for TriangulatedShape {
    /// The distance to the nearest triangle, negative where the pseudo-normal of the closest
    /// feature points away from `p` (Bærentzen and Aanæs 2005).
    fn distance(&self, p: DVec3) -> f64 {
        let n = self.nearest(p);
        let d = n.distance_squared.sqrt();
        if (p - n.point).dot(self.pseudo_normal(&n)) < 0.0 {
            -d
        } else {
            d
        }
    }

    /// `(p − q) / d` signed, with `q` the closest point; on the surface, the unit pseudo-normal
    /// of the closest feature.
    fn gradient(&self, p: DVec3) -> DVec3 {
        let n = self.nearest(p);
        let normal = self.pseudo_normal(&n);
        let diff = p - n.point;
        let d = diff.length();
        if d > 1e-300 {
            if diff.dot(normal) < 0.0 {
                -diff / d
            } else {
                diff / d
            }
        } else {
            normal.normalize_or_zero()
        }
    }

    /// The enclosed volume of the surface.
    fn exact_area(&self) -> Option<f64> {
        Some(self.volume)
    }

    /// The area of the surface.
    fn exact_perimeter(&self) -> Option<f64> {
        Some(self.area)
    }

    /// Up to `n` of the surface's vertices (evenly strided).
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec3>> {
        let pts = &self.surface.points;
        let step = pts.len().div_ceil(n.max(1)).max(1);
        Some(pts.iter().step_by(step).copied().collect())
    }

    fn name(&self) -> String {
        format!(
            "triangulated surface ({} triangles)",
            self.surface.triangles.len()
        )
    }
}
