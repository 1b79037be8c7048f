//! A level set given as a P1 field on a mesh, seen as a shape whose interface is the field's
//! piecewise-linear zero level: what [`super::run`] adapts to for
//! [`super::AdaptTarget::LevelSet`].
//!
//! At any point `p` (004 §2.1 asks for a signed distance):
//! - the distance is the exact distance from `p` to the zero-level segments of the input (an
//!   R-tree of segments), with the sign of the input's P1 interpolant at `p` — so the adapted
//!   mesh's zero level follows the input's, evaluated in the *input* mesh at every new vertex,
//!   never interpolated from an intermediate mesh, and multiplying the field by `c > 0` changes
//!   nothing;
//! - the gradient is the unit vector from the closest point of the zero level to `p`;
//! - the Hessian is the shape operator `P H P` (004 §4.3: `H` recovered by least squares from
//!   the redistanced field at the input vertices, interpolated P1 at `p`; `P = I - n nᵀ`).
//!
//! [`Shape::boundary_samples`] are points of the input's zero level and [`Shape::exact_area`]
//! its enclosed area, so a report measured against this shape gives the two-sided distance
//! between the input's zero level and the output's and their relative area difference.

use crate::error::{Error, Result};
use crate::geom::simplex::p1_gradient;
use crate::geom::DVec2;
use crate::levelset::redistance::redistance_geometric;
use crate::levelset::{enclosed_area, extract_zero_level, interface_length, Shape};
use crate::mesh::{Location, Mesh2};
use crate::metric::Sym2;
use crate::recovery::recover_ls;
use rstar::primitives::Line;
use rstar::{PointDistance, RTree};

/// A P1 level set on a mesh as a shape (module documentation).
pub struct DiscreteLevelSet {
    mesh: Mesh2,
    u: Vec<f64>,
    hessian: Vec<Sym2>,
    segments: RTree<Line<[f64; 2]>>,
    samples: Vec<DVec2>,
    area: f64,
    length: f64,
}

impl DiscreteLevelSet {
    /// The zero level of `u` on `mesh`. Errors: an invalid field, no zero level.
    pub fn new(mesh: Mesh2, u: Vec<f64>) -> Result<Self> {
        let lines = extract_zero_level(&mesh, &u)?;
        let mut segs = Vec::new();
        let mut samples = Vec::new();
        for l in &lines {
            for (a, b) in l.segments() {
                segs.push(Line::new(a.to_array(), b.to_array()));
                samples.extend([a, 0.5 * (a + b)]);
            }
            samples.extend(l.points.last());
        }
        if segs.is_empty() {
            return Err(Error::EmptyLevelSet(
                "the level set has no zero level on its mesh".into(),
            ));
        }
        let d = redistance_geometric(&mesh, &u)?;
        let hessian = recover_ls(&mesh, &d)?.hessian;
        let (area, length) = (enclosed_area(&mesh, &u)?, interface_length(&mesh, &u)?);
        Ok(DiscreteLevelSet {
            mesh,
            u,
            hessian,
            segments: RTree::bulk_load(segs),
            samples,
            area,
            length,
        })
    }

    /// The input mesh.
    pub fn mesh(&self) -> &Mesh2 {
        &self.mesh
    }

    /// The input triangle containing `p` and the barycentric coordinates (the nearest
    /// boundary triangle's, clamped, for a point just outside).
    fn locate(&self, p: DVec2) -> (usize, [f64; 3]) {
        match self
            .mesh
            .locate(p, self.mesh.vert_tri.first().copied().unwrap_or(0))
        {
            Location::Inside { tri, bary } => (tri as usize, bary),
            // The walk can leave a non-convex domain (a hole) before reaching `p`.
            Location::Outside { tri, .. } => match self.mesh.locate_brute_force(p) {
                Some(Location::Inside { tri, bary }) => (tri as usize, bary),
                _ => self.clamped(tri as usize, p),
            },
        }
    }

    /// Barycentric coordinates of `p` in triangle `t`, clamped to the triangle.
    fn clamped(&self, t: usize, p: DVec2) -> (usize, [f64; 3]) {
        let [a, b, c] = self.mesh.tri_points(t);
        let bary = crate::geom::barycentric(a, b, c, p).map(|x| x.clamp(0.0, 1.0));
        let s: f64 = bary.iter().sum();
        (t, bary.map(|x| x / s))
    }

    /// The closest point of the zero level and the distance to it.
    fn closest(&self, p: DVec2) -> (DVec2, f64) {
        let q = p.to_array();
        match self.segments.nearest_neighbor(q) {
            Some(l) => {
                let c = l.nearest_point(&q);
                (DVec2::from_array(c), l.distance_2(&q).sqrt())
            }
            None => (p, 0.0),
        }
    }
}

impl Shape for DiscreteLevelSet {
    fn distance(&self, p: DVec2) -> f64 {
        let (t, bary) = self.locate(p);
        let v = self.mesh.tris[t].map(|i| self.u[i as usize]);
        let value = bary[0] * v[0] + bary[1] * v[1] + bary[2] * v[2];
        let (_, d) = self.closest(p);
        if value < 0.0 {
            -d
        } else {
            d
        }
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        let (c, d) = self.closest(p);
        let s = self.distance(p).signum();
        if d > 0.0 {
            s * (p - c) / d
        } else {
            // On the zero level: the normal of the input's P1 field there.
            let (t, _) = self.locate(p);
            let values = self.mesh.tris[t].map(|i| self.u[i as usize]);
            p1_gradient(&self.mesh.tri_points(t), &values).normalize_or_zero()
        }
    }
    fn hessian(&self, p: DVec2) -> Sym2 {
        let (t, bary) = self.locate(p);
        let [ha, hb, hc] = self.mesh.tris[t].map(|i| self.hessian[i as usize]);
        let h = ha
            .scale(bary[0])
            .add(&hb.scale(bary[1]))
            .add(&hc.scale(bary[2]));
        let n = self.gradient(p);
        if n == DVec2::ZERO {
            return h;
        }
        let tangent = n.perp();
        Sym2::outer(tangent).scale(h.quad(tangent))
    }
    fn exact_area(&self) -> Option<f64> {
        Some(self.area)
    }
    fn exact_perimeter(&self) -> Option<f64> {
        Some(self.length)
    }
    fn boundary_samples(&self, _n: usize) -> Option<Vec<DVec2>> {
        Some(self.samples.clone())
    }
    fn name(&self) -> String {
        "level set".into()
    }
}
