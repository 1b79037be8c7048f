//! The boundary and interface data of a [`StokesProblem`]: Dirichlet values on the velocity
//! dofs, natural (traction) loads `∫_{Γ_N} s · v` (004 §5.1 eq. (9)) and the surface-tension
//! load on the zero level of the level set (interface condition (8)).

use super::{DirichletData, StokesProblem};
use crate::error::{Error, Result};
use crate::fem::p1::P1Geom;
use crate::geom::DVec2;
use crate::mesh::NONE;

impl StokesProblem<'_> {
    /// Dirichlet mask and values on the `3 n_v` dofs, and whether every boundary edge is
    /// Dirichlet (pressure defined up to a constant). Errors on a non-finite prescribed value.
    pub(super) fn dirichlet_data(&self) -> Result<DirichletData> {
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let mut fixed = vec![false; 3 * nv];
        let mut values = vec![0.0; 3 * nv];
        let mut all = true;
        for t in mesh.live_tris() {
            for i in 0..3 {
                if mesh.neighbours[t][i] != NONE {
                    continue;
                }
                let label = mesh.edge_ref[t][i];
                let Some((_, g)) = self.dirichlet.iter().find(|(l, _)| *l == label) else {
                    all = false;
                    continue;
                };
                for v in mesh.edge_vertices(t, i) {
                    let v = v as usize;
                    let gv = g(mesh.points[v]);
                    if !gv.is_finite() {
                        return Err(Error::InvalidField {
                            name: "Dirichlet velocity".into(),
                            msg: format!("non-finite value at vertex {v}"),
                        });
                    }
                    fixed[v] = true;
                    fixed[nv + v] = true;
                    values[v] = gv.x;
                    values[nv + v] = gv.y;
                }
            }
        }
        Ok(DirichletData {
            fixed,
            values,
            all_dirichlet: all,
        })
    }

    /// Adds `∫_{Γ_N} s · v` on labelled boundary edges that are not Dirichlet (2-point Gauss;
    /// the bubble vanishes there).
    pub(super) fn add_neumann(&self, rhs: &mut [f64]) {
        if self.neumann.is_empty() {
            return;
        }
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let g = 0.5 / 3f64.sqrt();
        for t in mesh.live_tris() {
            for i in 0..3 {
                if mesh.neighbours[t][i] != NONE {
                    continue;
                }
                let label = mesh.edge_ref[t][i];
                if self.dirichlet.iter().any(|(l, _)| *l == label) {
                    continue;
                }
                let Some((_, s)) = self.neumann.iter().find(|(l, _)| *l == label) else {
                    continue;
                };
                let [a, b] = mesh.edge_vertices(t, i);
                let (pa, pb) = (mesh.points[a as usize], mesh.points[b as usize]);
                let len = (pb - pa).length();
                for xi in [0.5 - g, 0.5 + g] {
                    let sv = s(pa + xi * (pb - pa)) * (0.5 * len);
                    for (v, phi) in [(a, 1.0 - xi), (b, xi)] {
                        rhs[v as usize] += phi * sv.x;
                        rhs[nv + v as usize] += phi * sv.y;
                    }
                }
            }
        }
    }

    /// Adds the surface tension `-γ ∫_Γ div_Γ v ds`, `div_Γ v = div v - n·(∇v) n`, on the
    /// straight piece of the zero level of the P1 level set in each cut triangle (P1 velocity
    /// part: the bubble contribution is dropped, it is of higher order).
    pub(super) fn add_surface_tension(&self, rhs: &mut [f64]) {
        let Some(phi) = self.viscosity.level_set() else {
            return;
        };
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let gamma = self.surface_tension;
        for t in mesh.live_tris() {
            let v = mesh.tris[t].map(|i| i as usize);
            let f = v.map(|i| phi[i]);
            let p = mesh.tri_points(t);
            let Some(len) = zero_level_length(p, f) else {
                continue;
            };
            let g = P1Geom::new(p);
            let grad_phi: DVec2 = (0..3).map(|k| f[k] * g.grad[k]).sum();
            let nrm = grad_phi.normalize_or_zero();
            for k in 0..3 {
                // div_Γ(φ_k e_c) = ∂_c φ_k - n_c (n · ∇φ_k)
                let gk = g.grad[k];
                let tang = gk - nrm * nrm.dot(gk);
                rhs[v[k]] -= gamma * len * tang.x;
                rhs[nv + v[k]] -= gamma * len * tang.y;
            }
        }
    }
}

/// Length of the straight zero line of the linear interpolant of `f` on the triangle `p`, when
/// it crosses exactly two edges (sign changes `f < 0` against `f >= 0`).
fn zero_level_length(p: [DVec2; 3], f: [f64; 3]) -> Option<f64> {
    let mut cut = Vec::with_capacity(2);
    for i in 0..3 {
        let (a, b) = ((i + 1) % 3, (i + 2) % 3);
        if (f[a] < 0.0) != (f[b] < 0.0) {
            let s = f[a] / (f[a] - f[b]);
            cut.push(p[a] + s * (p[b] - p[a]));
        }
    }
    (cut.len() == 2).then(|| (cut[1] - cut[0]).length())
}
