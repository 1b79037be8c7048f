//! [`ParametricSurface`]: a closed surface as a mesh of P1 (flat) or isoparametric P2 (curved)
//! triangles in 3D, built from a refined icosahedron projected onto a sphere (002's reference
//! sphere), with its measures: area, enclosed volume and the averaged radius
//! `∫_Γ |x| / ∫_Γ 1` of 002.

use super::element;
use crate::error::{Error, Result};
use crate::fem::lagrange::P2Dofs;
use crate::geom::DVec3;
use crate::levelset::TriangleSurface;
use std::collections::HashMap;

/// The quadrature degree of the measures (002 integrates the averaged radius with degree 4).
const MEASURE_DEGREE: usize = 6;

/// A closed triangulated surface with Lagrange nodes of order 1 or 2.
///
/// `nodes[..n_vertices]` are the triangle vertices; for order 2 the edge nodes follow (one per
/// edge, numbered as [`P2Dofs`]). Triangles are oriented counter-clockwise seen from outside.
#[derive(Debug, Clone, PartialEq)]
pub struct ParametricSurface {
    /// The polynomial order of the parametrisation and of the finite element space (1 or 2).
    pub order: usize,
    /// The node positions.
    pub nodes: Vec<DVec3>,
    /// The number of triangle vertices (the first nodes).
    pub n_vertices: usize,
    /// The vertex triangles.
    pub triangles: Vec<[u32; 3]>,
    /// The nodes of each element: 3 (order 1) or 6 (order 2) per triangle.
    pub cell_nodes: Vec<u32>,
}

impl ParametricSurface {
    /// The icosahedron refined `level` times by splitting every triangle into four, every new
    /// vertex projected onto the sphere of radius `radius` about the origin; for order 2 the
    /// edge nodes are the projected edge midpoints. Vertices: `10·4^level + 2`.
    pub fn icosphere(radius: f64, level: usize, order: usize) -> Result<ParametricSurface> {
        if !(radius.is_finite() && radius > 0.0) || level > 9 {
            return Err(Error::InvalidInput(format!(
                "icosphere: need a positive radius and at most 9 levels (got {radius}, {level})"
            )));
        }
        let base = crate::levelset::icosphere(0);
        let (mut pts, mut tris) = (base.points, base.triangles);
        for _ in 0..level {
            let mut mid: HashMap<(u32, u32), u32> = HashMap::new();
            let mut next = Vec::with_capacity(4 * tris.len());
            for &[a, b, c] in &tris {
                let mut m = |i: u32, j: u32| {
                    *mid.entry((i.min(j), i.max(j))).or_insert_with(|| {
                        pts.push((pts[i as usize] + pts[j as usize]).normalize());
                        (pts.len() - 1) as u32
                    })
                };
                let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
                next.extend([[a, ab, ca], [ab, b, bc], [ca, bc, c], [ab, bc, ca]]);
            }
            tris = next;
        }
        let pts: Vec<DVec3> = pts.iter().map(|p| radius * p.normalize()).collect();
        Self::from_triangles(pts, tris, order, |x| radius * x.normalize())
    }

    /// A surface of order `order` from vertices and counter-clockwise triangles; for order 2
    /// the edge node of each edge is `project` of its midpoint (the identity keeps the flat
    /// triangles). Errors: an order other than 1 or 2, a vertex index out of range.
    pub fn from_triangles(
        points: Vec<DVec3>,
        triangles: Vec<[u32; 3]>,
        order: usize,
        project: impl Fn(DVec3) -> DVec3,
    ) -> Result<ParametricSurface> {
        if order != 1 && order != 2 {
            return Err(Error::InvalidInput(format!(
                "surface elements of order {order}: only 1 and 2 are available"
            )));
        }
        let n = points.len();
        if triangles.iter().flatten().any(|&v| v as usize >= n) || triangles.is_empty() {
            return Err(Error::InvalidInput(
                "surface triangles: empty, or a vertex index out of range".into(),
            ));
        }
        let mut nodes = points;
        let cell_nodes = if order == 1 {
            triangles.iter().flatten().copied().collect()
        } else {
            let dofs = P2Dofs::for_triangles(&triangles, n);
            for &[a, b] in &dofs.edges {
                nodes.push(project(0.5 * (nodes[a as usize] + nodes[b as usize])));
            }
            dofs.cell_dofs
        };
        Ok(ParametricSurface {
            order,
            nodes,
            n_vertices: n,
            triangles,
            cell_nodes,
        })
    }

    /// Nodes per element (3 or 6).
    pub fn nodes_per_cell(&self) -> usize {
        if self.order == 1 {
            3
        } else {
            6
        }
    }

    /// The node indices of element `c`.
    pub fn cell(&self, c: usize) -> &[u32] {
        let k = self.nodes_per_cell();
        &self.cell_nodes[c * k..(c + 1) * k]
    }

    /// The node positions of element `c`.
    pub fn cell_points(&self, c: usize) -> Vec<DVec3> {
        self.cell(c)
            .iter()
            .map(|&i| self.nodes[i as usize])
            .collect()
    }

    /// Moves every node to `f(node)` (the vertices and, for order 2, the edge nodes: an
    /// isoparametric interpolation of the map `f`).
    pub fn map_nodes(&mut self, f: impl Fn(DVec3) -> DVec3) {
        for p in &mut self.nodes {
            *p = f(*p);
        }
    }

    /// `∫_Γ f(x, n) dA` over the (curved) elements, `n` the unit outer normal. Error: a
    /// degenerate element ([`Error::InvalidInput`]).
    pub fn integrate(&self, f: impl Fn(DVec3, DVec3) -> f64) -> Result<f64> {
        let mut s = 0.0;
        for c in 0..self.triangles.len() {
            s += element::integrate(&self.cell_points(c), MEASURE_DEGREE, &f)
                .ok_or_else(|| degenerate(c))?;
        }
        Ok(s)
    }

    /// The surface area.
    pub fn area(&self) -> Result<f64> {
        self.integrate(|_, _| 1.0)
    }

    /// The enclosed volume `⅓ ∫_Γ x · n`.
    pub fn enclosed_volume(&self) -> Result<f64> {
        self.integrate(|x, n| x.dot(n) / 3.0)
    }

    /// The averaged radius `∫_Γ |x| / ∫_Γ 1` about the origin (002's error measure for the
    /// shrinking sphere).
    pub fn mean_radius(&self) -> Result<f64> {
        Ok(self.integrate(|x, _| x.length())? / self.area()?)
    }

    /// The largest `| |x| − r |` over the nodes.
    pub fn max_radius_deviation(&self, r: f64) -> f64 {
        self.nodes
            .iter()
            .map(|p| (p.length() - r).abs())
            .fold(0.0, f64::max)
    }

    /// A flat triangle surface: the triangles themselves (order 1) or each curved triangle
    /// split into four at its edge nodes (order 2).
    pub fn to_triangle_surface(&self) -> TriangleSurface {
        let triangles = if self.order == 1 {
            self.triangles.clone()
        } else {
            self.cell_nodes
                .chunks(6)
                .flat_map(|c| {
                    let [a, b, cc, ab, bc, ca] = [c[0], c[1], c[2], c[3], c[4], c[5]];
                    [[a, ab, ca], [ab, b, bc], [ca, bc, cc], [ab, bc, ca]]
                })
                .collect()
        };
        TriangleSurface {
            points: self.nodes.clone(),
            triangles,
        }
    }

    /// Checks the structure: node indices in range, finite nodes, every element non-degenerate.
    pub fn check(&self) -> Result<()> {
        let k = self.nodes_per_cell();
        if self.cell_nodes.len() != k * self.triangles.len()
            || self
                .cell_nodes
                .iter()
                .any(|&i| i as usize >= self.nodes.len())
            || self.nodes.iter().any(|p| !p.is_finite())
        {
            return Err(Error::InvalidInput(
                "surface: node table inconsistent or a node non-finite".into(),
            ));
        }
        for c in 0..self.triangles.len() {
            let x = self.cell_points(c);
            element::integrate(&x, 2, |_, _| 1.0).ok_or_else(|| degenerate(c))?;
        }
        Ok(())
    }
}

fn degenerate(c: usize) -> Error {
    Error::InvalidInput(format!("surface element {c} has a vanishing area element"))
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn icosphere_counts_orientation_and_measures() {
        for order in [1, 2] {
            let s = ParametricSurface::icosphere(2.0, 3, order).unwrap();
            s.check().unwrap();
            assert_eq!(s.n_vertices, 642);
            let (a, v) = (s.area().unwrap(), s.enclosed_volume().unwrap());
            let (ea, ev) = (16.0 * PI, 32.0 * PI / 3.0);
            let tol = if order == 1 { 2e-2 } else { 2e-4 };
            assert!(
                ((a - ea) / ea).abs() < tol && ((v - ev) / ev).abs() < tol,
                "{a} {v}"
            );
            assert!(v > 0.0);
        }
    }
}
