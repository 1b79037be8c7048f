//! Polynomial-preserving recovery (PPR) of the gradient of a P1 or P2 field, 003 §6.2.
//!
//! At a vertex `v` a polynomial `p_v` of degree `k + 1` is fitted in the least-squares sense to the
//! field values at all nodes of the patch `ω(v)` (the cells around `v`), and
//! `(G_h φ_h)(v) = ∇p_v(v)`. For P2 the recovered gradient at the midpoint `m` of the edge
//! `(v_1, v_2)` is `½ (∇p_{v_1}(m) + ∇p_{v_2}(m))`. `G_h φ_h` is then the P_k interpolant of these
//! nodal vectors, eq. (6.3).
//!
//! Fallback for few neighbours (003 §6.2, "fewer than 10 independent conditions"): the patch is
//! first enlarged to the second ring of cells; if the fit is still rank deficient the mixed terms
//! of top degree are dropped, then the degree is lowered. Each fallback is counted.
//!
//! Fits are computed lazily (on first use) and cached per vertex, so only the neighbourhood of the
//! zero level is ever fitted. Coordinates are centred at `v` and scaled by the patch radius.

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::OnceLock;

use nalgebra::{DMatrix, DVector};

use super::simplices::Simplices;
use crate::geom::DVec3;

/// A fitted polynomial in the scaled local coordinates `ξ = (x - centre) / scale`.
#[derive(Debug, Clone)]
pub(crate) struct Poly {
    centre: DVec3,
    scale: f64,
    exps: Vec<[u8; 3]>,
    coef: Vec<f64>,
}

impl Poly {
    /// Gradient (in `x`) at `x`.
    pub(crate) fn grad(&self, x: &DVec3) -> DVec3 {
        let xi = (*x - self.centre) / self.scale;
        let mut g = DVec3::ZERO;
        for (e, &c) in self.exps.iter().zip(&self.coef) {
            for d in 0..3 {
                if e[d] == 0 {
                    continue;
                }
                let mut t = c * e[d] as f64;
                for k in 0..3 {
                    let p = if k == d { e[k] - 1 } else { e[k] };
                    t *= xi[k].powi(p as i32);
                }
                g[d] += t;
            }
        }
        g / self.scale
    }
}

/// Exponents of the monomials of total degree `<= deg` in `dim` variables (ascending degree).
/// With `no_mixed_top`, the mixed monomials of degree exactly `deg` are left out.
fn monomials(dim: usize, deg: usize, no_mixed_top: bool) -> Vec<[u8; 3]> {
    let mut out = Vec::new();
    for total in 0..=deg {
        for a in (0..=total).rev() {
            for b in (0..=total - a).rev() {
                let c = total - a - b;
                if dim == 2 && c > 0 {
                    continue;
                }
                let e = [a as u8, b as u8, c as u8];
                let nonzero = e.iter().filter(|&&x| x > 0).count();
                if no_mixed_top && total == deg && nonzero > 1 {
                    continue;
                }
                out.push(e);
            }
        }
    }
    out
}

/// Least-squares fit of `exps` to `(points, values)`; `None` when rank deficient.
fn lsq(
    centre: &DVec3,
    scale: f64,
    pts: &[DVec3],
    vals: &[f64],
    exps: &[[u8; 3]],
) -> Option<Vec<f64>> {
    let (m, n) = (pts.len(), exps.len());
    if m < n {
        return None;
    }
    let a = DMatrix::from_fn(m, n, |i, j| {
        let xi = (pts[i] - *centre) / scale;
        let e = exps[j];
        xi[0].powi(e[0] as i32) * xi[1].powi(e[1] as i32) * xi[2].powi(e[2] as i32)
    });
    let b = DVector::from_column_slice(vals);
    let qr = a.qr();
    let r = qr.r();
    let dmax = (0..n).map(|i| r[(i, i)].abs()).fold(0.0, f64::max);
    let dmin = (0..n)
        .map(|i| r[(i, i)].abs())
        .fold(f64::INFINITY, f64::min);
    if dmin.is_nan() || dmin <= 1e-8 * dmax {
        return None;
    }
    let qtb = qr.q().transpose() * b;
    let x = r.solve_upper_triangular(&qtb)?;
    Some(x.iter().copied().collect())
}

/// The recovered gradient `G_h φ_h` of one field on one mesh, computed lazily per node.
pub(crate) struct Recovery<'a> {
    sx: &'a Simplices,
    f: &'a [f64],
    polys: Vec<OnceLock<Box<Poly>>>,
    grads: Vec<OnceLock<DVec3>>,
    /// Number of vertex fits that needed the fallback.
    pub fallbacks: AtomicUsize,
}

impl<'a> Recovery<'a> {
    pub(crate) fn new(sx: &'a Simplices, f: &'a [f64]) -> Self {
        Recovery {
            sx,
            f,
            polys: (0..sx.points.len()).map(|_| OnceLock::new()).collect(),
            grads: (0..sx.n_nodes()).map(|_| OnceLock::new()).collect(),
            fallbacks: AtomicUsize::new(0),
        }
    }

    /// A recovery whose nodal gradients are already known (P1: one per vertex), e.g. from
    /// [`crate::recovery::gradient_ppr`].
    pub(crate) fn with_node_grads(sx: &'a Simplices, f: &'a [f64], grads: &[DVec3]) -> Self {
        let r = Self::new(sx, f);
        for (cell, g) in r.grads.iter().zip(grads) {
            let _ = cell.set(*g);
        }
        r
    }

    /// The nodes of the cells around the vertices of `verts` (deduplicated, sorted).
    fn patch_nodes(&self, verts: &[u32]) -> Vec<u32> {
        let mut nodes: Vec<u32> = verts
            .iter()
            .flat_map(|&v| self.sx.cells_of(v).iter())
            .flat_map(|&c| self.sx.nodes(c as usize).iter().copied())
            .collect();
        nodes.sort_unstable();
        nodes.dedup();
        nodes
    }

    fn fit(&self, v: u32) -> Poly {
        let sx = self.sx;
        let deg = sx.degree + 1;
        let centre = sx.points[v as usize];
        let mut nodes = self.patch_nodes(&[v]);
        let mut fallback = false;
        for attempt in 0..2 {
            if attempt == 1 {
                // Second ring: cells around every vertex of the first patch.
                let verts: Vec<u32> = nodes
                    .iter()
                    .copied()
                    .filter(|&n| (n as usize) < sx.points.len())
                    .collect();
                nodes = self.patch_nodes(&verts);
                fallback = true;
            }
            let pts: Vec<DVec3> = nodes.iter().map(|&n| sx.node_points[n as usize]).collect();
            let vals: Vec<f64> = nodes.iter().map(|&n| self.f[n as usize]).collect();
            let scale = pts
                .iter()
                .map(|p| (*p - centre).length())
                .fold(0.0, f64::max)
                .max(f64::MIN_POSITIVE);
            let mut tries = vec![(deg, false)];
            if attempt == 1 {
                tries.extend([(deg, true), (deg - 1, false), (1, false)]);
            }
            for (d, nm) in tries {
                let exps = monomials(sx.dim, d, nm);
                if let Some(coef) = lsq(&centre, scale, &pts, &vals, &exps) {
                    if fallback {
                        self.fallbacks.fetch_add(1, Ordering::Relaxed);
                    }
                    return Poly {
                        centre,
                        scale,
                        exps,
                        coef,
                    };
                }
            }
        }
        // Nothing fits (an isolated vertex): a zero gradient, flagged by the caller's checks.
        self.fallbacks.fetch_add(1, Ordering::Relaxed);
        Poly {
            centre,
            scale: 1.0,
            exps: vec![[0, 0, 0]],
            coef: vec![self.f[v as usize]],
        }
    }

    fn poly(&self, v: u32) -> &Poly {
        self.polys[v as usize].get_or_init(|| Box::new(self.fit(v)))
    }

    /// `(G_h φ_h)` at node `n` (a vertex, or for P2 an edge midpoint).
    pub(crate) fn at_node(&self, n: u32) -> DVec3 {
        *self.grads[n as usize].get_or_init(|| {
            let nvert = self.sx.points.len();
            if (n as usize) < nvert {
                self.poly(n).grad(&self.sx.points[n as usize])
            } else {
                let [a, b] = self.sx.edges[n as usize - nvert];
                let x = self.sx.node_points[n as usize];
                let (ga, gb) = (self.poly(a).grad(&x), self.poly(b).grad(&x));
                (ga + gb) * 0.5
            }
        })
    }

    /// `(G_h φ_h)(x)` for `x` at barycentric coordinates `lam` of cell `c`, eq. (6.3).
    pub(crate) fn at(&self, c: usize, lam: &[f64; 4]) -> DVec3 {
        self.sx.eval_vec(c, lam, |n| self.at_node(n))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn monomial_counts() {
        assert_eq!(monomials(2, 2, false).len(), 6);
        assert_eq!(monomials(2, 3, false).len(), 10);
        assert_eq!(monomials(3, 2, false).len(), 10);
        assert_eq!(monomials(3, 3, false).len(), 20);
        assert_eq!(monomials(3, 2, true).len(), 7);
    }
}
