//! Lagrange P1 and P2 elements on triangles and tetrahedra (shape functions, gradients, nodes)
//! and the P2 degree-of-freedom numbering of a mesh (vertices, then one dof per edge).
//!
//! Local numbering (the same everywhere in the crate):
//! - P1: the vertices `0..=dim`; the shape functions are the barycentric coordinates `λ_i`.
//! - P2 on a triangle: vertices `0, 1, 2`, then the midpoints of edges [`TRI_EDGES`] = (0,1),
//!   (1,2), (2,0) as local dofs `3, 4, 5`.
//! - P2 on a tetrahedron: vertices `0..4`, then the midpoints of [`TET_EDGES`] = (0,1), (1,2),
//!   (2,0), (0,3), (1,3), (2,3) as local dofs `4..10`.
//! - P2 shape functions: `λ_i (2 λ_i - 1)` at a vertex, `4 λ_i λ_j` at the midpoint of `(i, j)`.
//!
//! The slice-based functions ([`p2_values`], [`p2_grads`]) serve both dimensions; points and
//! gradients are then `[f64; 3]` (z = 0 in 2D).

use std::collections::HashMap;

use crate::geom::{DVec2, DVec3};
use crate::mesh::{Mesh2, NONE};

/// Local edges of a triangle, in P2 dof order.
pub const TRI_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];
/// Local edges of a tetrahedron, in P2 dof order.
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];

/// The local edge table of a simplex with `n_vertices` (3 or 4) vertices.
#[inline]
pub fn simplex_edges(n_vertices: usize) -> &'static [[usize; 2]] {
    if n_vertices == 3 {
        &TRI_EDGES
    } else {
        &TET_EDGES
    }
}

/// Gradients of the barycentric coordinates (the P1 shape functions) of the triangle `p`.
/// A degenerate triangle gives non-finite values.
pub fn bary_grads_tri(p: [DVec2; 3]) -> [DVec2; 3] {
    let det = (p[1] - p[0]).perp_dot(p[2] - p[0]);
    // ∇λ_i is the inward normal of the opposite edge divided by twice the area.
    let g = |a: DVec2, b: DVec2| DVec2::new(a.y - b.y, b.x - a.x) / det;
    [g(p[1], p[2]), g(p[2], p[0]), g(p[0], p[1])]
}

/// Gradients of the barycentric coordinates of the tetrahedron `p`.
pub fn bary_grads_tet(p: [DVec3; 4]) -> [DVec3; 4] {
    let (e1, e2, e3) = (p[1] - p[0], p[2] - p[0], p[3] - p[0]);
    let det = e1.dot(e2.cross(e3));
    let g1 = e2.cross(e3) / det;
    let g2 = e3.cross(e1) / det;
    let g3 = e1.cross(e2) / det;
    [-(g1 + g2 + g3), g1, g2, g3]
}

/// Barycentric coordinates of `x` in the triangle `p`.
pub fn bary_tri(p: [DVec2; 3], x: DVec2) -> [f64; 3] {
    crate::geom::barycentric(p[0], p[1], p[2], x)
}

/// Barycentric coordinates of `x` in the tetrahedron `p`.
pub fn bary_tet(p: [DVec3; 4], x: DVec3) -> [f64; 4] {
    let (e1, e2, e3, r) = (p[1] - p[0], p[2] - p[0], p[3] - p[0], x - p[0]);
    let det = e1.dot(e2.cross(e3));
    let l1 = r.dot(e2.cross(e3)) / det;
    let l2 = e1.dot(r.cross(e3)) / det;
    let l3 = e1.dot(e2.cross(r)) / det;
    [1.0 - l1 - l2 - l3, l1, l2, l3]
}

/// P2 shape function values at barycentric coordinates `lam` (length 3 or 4) into `out`
/// (length 6 or 10).
pub fn p2_values(lam: &[f64], out: &mut [f64]) {
    let nv = lam.len();
    for i in 0..nv {
        out[i] = lam[i] * (2.0 * lam[i] - 1.0);
    }
    for (k, &[i, j]) in simplex_edges(nv).iter().enumerate() {
        out[nv + k] = 4.0 * lam[i] * lam[j];
    }
}

/// P2 shape function gradients at `lam`, given the barycentric gradients `glam`.
pub fn p2_grads(lam: &[f64], glam: &[[f64; 3]], out: &mut [[f64; 3]]) {
    let nv = lam.len();
    for i in 0..nv {
        let c = 4.0 * lam[i] - 1.0;
        out[i] = glam[i].map(|g| c * g);
    }
    for (k, &[i, j]) in simplex_edges(nv).iter().enumerate() {
        out[nv + k] = std::array::from_fn(|d| 4.0 * (lam[i] * glam[j][d] + lam[j] * glam[i][d]));
    }
}

/// P2 shape functions on a triangle at barycentric coordinates `lam`.
pub fn p2_tri_values(lam: [f64; 3]) -> [f64; 6] {
    let mut out = [0.0; 6];
    p2_values(&lam, &mut out);
    out
}

/// P2 shape function gradients on the triangle `p` at barycentric coordinates `lam`.
pub fn p2_tri_grads(p: [DVec2; 3], lam: [f64; 3]) -> [DVec2; 6] {
    let g = bary_grads_tri(p).map(|v| [v.x, v.y, 0.0]);
    let mut out = [[0.0; 3]; 6];
    p2_grads(&lam, &g, &mut out);
    out.map(|v| DVec2::new(v[0], v[1]))
}

/// P2 shape functions on a tetrahedron at barycentric coordinates `lam`.
pub fn p2_tet_values(lam: [f64; 4]) -> [f64; 10] {
    let mut out = [0.0; 10];
    p2_values(&lam, &mut out);
    out
}

/// P2 shape function gradients on the tetrahedron `p` at barycentric coordinates `lam`.
pub fn p2_tet_grads(p: [DVec3; 4], lam: [f64; 4]) -> [DVec3; 10] {
    let g = bary_grads_tet(p).map(|v| v.to_array());
    let mut out = [[0.0; 3]; 10];
    p2_grads(&lam, &g, &mut out);
    out.map(DVec3::from_array)
}

/// P2 nodes of a triangle (vertices, then edge midpoints in [`TRI_EDGES`] order).
pub fn p2_tri_nodes(p: [DVec2; 3]) -> [DVec2; 6] {
    let m = |[i, j]: [usize; 2]| 0.5 * (p[i] + p[j]);
    [
        p[0],
        p[1],
        p[2],
        m(TRI_EDGES[0]),
        m(TRI_EDGES[1]),
        m(TRI_EDGES[2]),
    ]
}

/// P2 nodes of a tetrahedron (vertices, then edge midpoints in [`TET_EDGES`] order).
pub fn p2_tet_nodes(p: [DVec3; 4]) -> [DVec3; 10] {
    std::array::from_fn(|k| {
        if k < 4 {
            p[k]
        } else {
            let [i, j] = TET_EDGES[k - 4];
            0.5 * (p[i] + p[j])
        }
    })
}

/// The P2 dof numbering of a simplicial mesh: dof `v` is vertex `v`, dof `n_vertices + e` is the
/// midpoint of edge `e`. Edges are numbered in order of first appearance (cell by cell, local
/// edges in table order), so the numbering is deterministic.
#[derive(Debug, Clone, PartialEq)]
pub struct P2Dofs {
    /// Number of vertices (= number of vertex dofs).
    pub n_vertices: usize,
    /// Vertices of each edge, smaller index first.
    pub edges: Vec<[u32; 2]>,
    /// Dofs of each cell, `dofs_per_cell` per cell (all [`NONE`] for a deleted cell).
    pub cell_dofs: Vec<u32>,
    /// 6 (triangles) or 10 (tetrahedra).
    pub dofs_per_cell: usize,
    edge_index: HashMap<(u32, u32), u32>,
}

impl P2Dofs {
    fn build<const N: usize>(cells: &[[u32; N]], n_vertices: usize) -> P2Dofs {
        let table = simplex_edges(N);
        let per = N + table.len();
        let mut edges = Vec::new();
        let mut edge_index = HashMap::new();
        let mut cell_dofs = Vec::with_capacity(cells.len() * per);
        for c in cells {
            if c[0] == NONE {
                cell_dofs.resize(cell_dofs.len() + per, NONE);
                continue;
            }
            cell_dofs.extend_from_slice(c);
            for &[i, j] in table {
                let key = (c[i].min(c[j]), c[i].max(c[j]));
                let e = *edge_index.entry(key).or_insert_with(|| {
                    edges.push([key.0, key.1]);
                    (edges.len() - 1) as u32
                });
                cell_dofs.push(n_vertices as u32 + e);
            }
        }
        P2Dofs {
            n_vertices,
            edges,
            cell_dofs,
            dofs_per_cell: per,
            edge_index,
        }
    }

    /// P2 dofs of a triangle list over `n_vertices` vertices.
    pub fn for_triangles(tris: &[[u32; 3]], n_vertices: usize) -> P2Dofs {
        Self::build(tris, n_vertices)
    }

    /// P2 dofs of a tetrahedron list over `n_vertices` vertices.
    pub fn for_tets(tets: &[[u32; 4]], n_vertices: usize) -> P2Dofs {
        Self::build(tets, n_vertices)
    }

    /// P2 dofs of a [`Mesh2`] (tombstones get [`NONE`] dofs).
    pub fn for_mesh2(mesh: &Mesh2) -> P2Dofs {
        Self::build(&mesh.tris, mesh.n_points())
    }

    /// Total number of dofs.
    pub fn n_dofs(&self) -> usize {
        self.n_vertices + self.edges.len()
    }

    /// The dofs of cell `c`.
    pub fn cell(&self, c: usize) -> &[u32] {
        &self.cell_dofs[c * self.dofs_per_cell..(c + 1) * self.dofs_per_cell]
    }

    /// The dof at the midpoint of the edge `(a, b)`, if that edge exists.
    pub fn edge_dof(&self, a: u32, b: u32) -> Option<u32> {
        self.edge_index
            .get(&(a.min(b), a.max(b)))
            .map(|&e| self.n_vertices as u32 + e)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn p2_tet_interpolates_quadratics_and_gradients() {
        let p = [
            DVec3::new(0.1, 0.0, 0.2),
            DVec3::new(1.0, 0.2, 0.0),
            DVec3::new(0.3, 1.1, 0.1),
            DVec3::new(0.2, 0.3, 0.9),
        ];
        let f = |x: DVec3| 1.0 + x.x - 2.0 * x.y * x.z + 3.0 * x.x * x.x;
        let gf = |x: DVec3| DVec3::new(1.0 + 6.0 * x.x, -2.0 * x.z, -2.0 * x.y);
        let nodes = p2_tet_nodes(p);
        let x = DVec3::new(0.35, 0.3, 0.25);
        let lam = bary_tet(p, x);
        let v = p2_tet_values(lam);
        let g = p2_tet_grads(p, lam);
        let val: f64 = (0..10).map(|k| v[k] * f(nodes[k])).sum();
        let grad: DVec3 = (0..10).map(|k| g[k] * f(nodes[k])).sum();
        assert!((val - f(x)).abs() < 1e-13);
        assert!((grad - gf(x)).length() < 1e-12);
        assert!((v.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn p2_tri_interpolates_quadratics_and_gradients() {
        let p = [
            DVec2::new(0.0, 0.1),
            DVec2::new(1.2, 0.0),
            DVec2::new(0.4, 0.9),
        ];
        let f = |x: DVec2| 2.0 - x.x * x.y + 0.5 * x.y * x.y;
        let gf = |x: DVec2| DVec2::new(-x.y, -x.x + x.y);
        let nodes = p2_tri_nodes(p);
        let x = DVec2::new(0.5, 0.3);
        let lam = bary_tri(p, x);
        let v = p2_tri_values(lam);
        let g = p2_tri_grads(p, lam);
        let val: f64 = (0..6).map(|k| v[k] * f(nodes[k])).sum();
        let grad: DVec2 = (0..6).map(|k| g[k] * f(nodes[k])).sum();
        assert!((val - f(x)).abs() < 1e-13);
        assert!((grad - gf(x)).length() < 1e-12);
    }

    #[test]
    fn p2_dofs_share_edges() {
        // Two triangles sharing edge (1, 2).
        let d = P2Dofs::for_triangles(&[[0, 1, 2], [2, 1, 3]], 4);
        assert_eq!(d.n_dofs(), 4 + 5);
        assert_eq!(d.edge_dof(2, 1), Some(d.cell(0)[4]));
        assert_eq!(d.cell(0)[4], d.cell(1)[3]);
        assert_eq!(d.edge_dof(0, 3), None);
    }
}
