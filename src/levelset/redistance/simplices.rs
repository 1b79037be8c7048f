//! A dimension-generic read-only view of a conforming simplicial mesh (triangles or tetrahedra)
//! carrying a P1 or P2 field: face neighbours, vertex-to-cell adjacency, nodes, point location and
//! evaluation of finite element functions. Points are `DVec3` (z = 0 in 2D); the per-cell
//! geometry is that of [`crate::geom::simplex`].

use std::collections::HashMap;

use crate::error::{Error, Result};
use crate::fem::lagrange::{self, P2Dofs};
use crate::geom::simplex::{self, simplex_edges};
use crate::geom::{DVec2, DVec3};
use crate::mesh::NONE;

/// The view. `nv = dim + 1` vertices per cell.
#[derive(Debug, Clone)]
pub(crate) struct Simplices {
    pub dim: usize,
    pub nv: usize,
    /// Polynomial degree of the field (1 or 2).
    pub degree: usize,
    pub points: Vec<DVec3>,
    pub cells: Vec<u32>,
    pub nbr: Vec<u32>,
    pub v2c_off: Vec<usize>,
    pub v2c: Vec<u32>,
    /// Dofs per cell: `nv` (P1) or `nv + edges` (P2).
    pub npc: usize,
    pub cell_nodes: Vec<u32>,
    pub node_points: Vec<DVec3>,
    /// For P2: the two vertices of each edge node (`node - n_vertices`).
    pub edges: Vec<[u32; 2]>,
}

impl Simplices {
    /// Build from a cell list (stride `dim + 1`) over `points`. Cells must be live (no tombstones).
    pub(crate) fn new(
        dim: usize,
        points: Vec<DVec3>,
        cells: Vec<u32>,
        degree: usize,
    ) -> Result<Self> {
        if degree != 1 && degree != 2 {
            return Err(Error::InvalidInput(format!(
                "polynomial degree must be 1 or 2 (got {degree})"
            )));
        }
        let nv = dim + 1;
        let nc = cells.len() / nv;
        let n = points.len();
        // Vertex -> cells (CSR).
        let mut v2c_off = vec![0usize; n + 1];
        for &v in &cells {
            v2c_off[v as usize + 1] += 1;
        }
        for i in 0..n {
            v2c_off[i + 1] += v2c_off[i];
        }
        let mut fill = v2c_off.clone();
        let mut v2c = vec![0u32; cells.len()];
        for (c, cell) in cells.chunks(nv).enumerate() {
            for &v in cell {
                v2c[fill[v as usize]] = c as u32;
                fill[v as usize] += 1;
            }
        }
        // Face neighbours: the face opposite local vertex i, keyed by its sorted vertices.
        let mut nbr = vec![NONE; cells.len()];
        let mut faces: HashMap<[u32; 3], u32> = HashMap::with_capacity(cells.len());
        for (c, cell) in cells.chunks(nv).enumerate() {
            for i in 0..nv {
                let mut key = [NONE; 3];
                let mut k = 0;
                for (j, &v) in cell.iter().enumerate() {
                    if j != i {
                        key[k] = v;
                        k += 1;
                    }
                }
                key[..dim].sort_unstable();
                let slot = (c * nv + i) as u32;
                if let Some(other) = faces.remove(&key) {
                    nbr[slot as usize] = other / nv as u32;
                    nbr[other as usize] = c as u32;
                } else {
                    faces.insert(key, slot);
                }
            }
        }
        let (npc, cell_nodes, node_points, edges) = if degree == 1 {
            (nv, cells.clone(), points.clone(), Vec::new())
        } else {
            let dofs = if dim == 2 {
                let t: Vec<[u32; 3]> = cells.chunks(3).map(|c| [c[0], c[1], c[2]]).collect();
                P2Dofs::for_triangles(&t, n)
            } else {
                let t: Vec<[u32; 4]> = cells.chunks(4).map(|c| [c[0], c[1], c[2], c[3]]).collect();
                P2Dofs::for_tets(&t, n)
            };
            let mut np = points.clone();
            for &[a, b] in &dofs.edges {
                let (pa, pb) = (points[a as usize], points[b as usize]);
                np.push(DVec3::from_array(std::array::from_fn(|k| {
                    0.5 * (pa[k] + pb[k])
                })));
            }
            (dofs.dofs_per_cell, dofs.cell_dofs, np, dofs.edges)
        };
        let _ = nc;
        Ok(Simplices {
            dim,
            nv,
            degree,
            points,
            cells,
            nbr,
            v2c_off,
            v2c,
            npc,
            cell_nodes,
            node_points,
            edges,
        })
    }

    pub(crate) fn n_cells(&self) -> usize {
        self.cells.len() / self.nv
    }
    pub(crate) fn n_nodes(&self) -> usize {
        self.node_points.len()
    }
    pub(crate) fn nodes(&self, c: usize) -> &[u32] {
        &self.cell_nodes[c * self.npc..(c + 1) * self.npc]
    }
    pub(crate) fn cells_of(&self, v: u32) -> &[u32] {
        &self.v2c[self.v2c_off[v as usize]..self.v2c_off[v as usize + 1]]
    }
    fn corner(&self, c: usize, i: usize) -> DVec3 {
        self.points[self.cells[c * self.nv + i] as usize]
    }

    /// The corners of triangle `c` in the plane.
    fn tri(&self, c: usize) -> [DVec2; 3] {
        std::array::from_fn(|i| self.corner(c, i).truncate())
    }

    /// The corners of tetrahedron `c`.
    fn tet(&self, c: usize) -> [DVec3; 4] {
        std::array::from_fn(|i| self.corner(c, i))
    }

    /// Barycentric coordinates of `x` in cell `c` (first `nv` entries used).
    pub(crate) fn bary(&self, c: usize, x: &DVec3) -> [f64; 4] {
        if self.dim == 2 {
            let l = simplex::barycentric(&self.tri(c), x.truncate());
            [l[0], l[1], l[2], 0.0]
        } else {
            simplex::barycentric(&self.tet(c), *x)
        }
    }

    /// Gradients of the barycentric coordinates of cell `c`.
    pub(crate) fn bary_grads(&self, c: usize) -> [DVec3; 4] {
        if self.dim == 2 {
            let g = simplex::p1_gradients(&self.tri(c));
            [
                g[0].extend(0.0),
                g[1].extend(0.0),
                g[2].extend(0.0),
                DVec3::ZERO,
            ]
        } else {
            simplex::p1_gradients(&self.tet(c))
        }
    }

    /// Longest edge of cell `c`.
    pub(crate) fn diameter(&self, c: usize) -> f64 {
        simplex_edges(self.nv)
            .iter()
            .map(|&[i, j]| (self.corner(c, j) - self.corner(c, i)).length())
            .fold(0.0, f64::max)
    }

    /// Shape function values at barycentric coordinates `lam` (P1 or P2), into `out[..npc]`.
    pub(crate) fn shape(&self, lam: &[f64; 4], out: &mut [f64; 10]) {
        if self.degree == 1 {
            out[..self.nv].copy_from_slice(&lam[..self.nv]);
        } else {
            lagrange::p2_values(&lam[..self.nv], &mut out[..self.npc]);
        }
    }

    /// Gradient of the field with nodal values `f` in cell `c` at barycentric coordinates `lam`.
    pub(crate) fn grad_in(&self, c: usize, lam: &[f64; 4], f: &[f64]) -> DVec3 {
        let g = self.bary_grads(c);
        let nodes = self.nodes(c);
        let mut out = DVec3::ZERO;
        if self.degree == 1 {
            for i in 0..self.nv {
                out += g[i] * f[nodes[i] as usize];
            }
        } else {
            let ga = g.map(|v| v.to_array());
            let mut sg = [[0.0; 3]; 10];
            lagrange::p2_grads(&lam[..self.nv], &ga[..self.nv], &mut sg[..self.npc]);
            for k in 0..self.npc {
                out += DVec3::from_array(sg[k]) * f[nodes[k] as usize];
            }
        }
        out
    }

    /// The cell containing `x` (and its barycentric coordinates), by a straight walk from `start`;
    /// `None` when `x` is outside the mesh. Falls back to a scan when the walk cycles.
    pub(crate) fn locate(&self, x: &DVec3, start: u32) -> Option<(u32, [f64; 4])> {
        const EPS: f64 = 1e-12;
        let mut c = start as usize;
        for _ in 0..4096 {
            let lam = self.bary(c, x);
            let (mut imin, mut lmin) = (0, lam[0]);
            for (i, &l) in lam.iter().enumerate().take(self.nv).skip(1) {
                if l < lmin {
                    imin = i;
                    lmin = l;
                }
            }
            if lmin >= -EPS {
                return Some((c as u32, lam));
            }
            let n = self.nbr[c * self.nv + imin];
            if n == NONE {
                return None;
            }
            c = n as usize;
        }
        (0..self.n_cells()).find_map(|c| {
            let lam = self.bary(c, x);
            (lam[..self.nv].iter().all(|&l| l >= -EPS)).then_some((c as u32, lam))
        })
    }

    /// Value at barycentric coordinates `lam` of cell `c` of the field with nodal values `f`
    /// (scalar per node).
    pub(crate) fn eval(&self, c: usize, lam: &[f64; 4], f: &[f64]) -> f64 {
        let mut s = [0.0; 10];
        self.shape(lam, &mut s);
        self.nodes(c)
            .iter()
            .zip(&s[..self.npc])
            .map(|(&n, &w)| w * f[n as usize])
            .sum()
    }

    /// Value of a vector field with nodal values `g` at `lam` in cell `c`.
    pub(crate) fn eval_vec(&self, c: usize, lam: &[f64; 4], g: impl Fn(u32) -> DVec3) -> DVec3 {
        let mut s = [0.0; 10];
        self.shape(lam, &mut s);
        let mut out = DVec3::ZERO;
        for (k, &n) in self.nodes(c).iter().enumerate() {
            out += g(n) * s[k];
        }
        out
    }

    /// The P1 sub-mesh on the nodes: the cells themselves for P1; for P2 each triangle split in 4
    /// and each tetrahedron in 8 through its edge midpoints (used by fast marching).
    pub(crate) fn node_cells(&self) -> Vec<u32> {
        if self.degree == 1 {
            return self.cells.clone();
        }
        let mut out = Vec::with_capacity(self.cell_nodes.len() * 4);
        for c in 0..self.n_cells() {
            let d = self.nodes(c);
            if self.dim == 2 {
                // d = [v0, v1, v2, m01, m12, m20]
                let (v0, v1, v2, m01, m12, m20) = (d[0], d[1], d[2], d[3], d[4], d[5]);
                out.extend_from_slice(&[v0, m01, m20, m01, v1, m12, m20, m12, v2, m01, m12, m20]);
            } else {
                // d = [v0, v1, v2, v3, m01, m12, m20, m03, m13, m23]
                let (v0, v1, v2, v3) = (d[0], d[1], d[2], d[3]);
                let (m01, m12, m02, m03, m13, m23) = (d[4], d[5], d[6], d[7], d[8], d[9]);
                out.extend_from_slice(&[v0, m01, m02, m03, m01, v1, m12, m13]);
                out.extend_from_slice(&[m02, m12, v2, m23, m03, m13, m23, v3]);
                // Octahedron split around the diagonal m02-m13.
                out.extend_from_slice(&[m02, m13, m01, m12, m02, m13, m12, m23]);
                out.extend_from_slice(&[m02, m13, m23, m03, m02, m13, m03, m01]);
            }
        }
        out
    }
}
