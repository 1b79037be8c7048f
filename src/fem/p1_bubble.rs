//! The MINI element (Arnold–Brezzi–Fortin): P1 + cubic bubble velocity, P1 pressure, for the
//! Stokes operator in stress form `-div(2μ ε(u)) + ∇p = f`, `div u = 0` (004 eqs. (7)–(9); in
//! each sub-domain `div(2μ ε(u)) = μ Δu` since `div u = 0`, and the stress form gives the
//! interface condition (8) and the Neumann condition `σ n = s_N` of (9) naturally).
//!
//! The bubble `b = 27 λ0 λ1 λ2` is internal to the element, so it is eliminated element by
//! element (static condensation). The condensed element matrix acts on the 9 dofs
//! `[ux0, ux1, ux2, uy0, uy1, uy2, p0, p1, p2]` and has the symmetric saddle-point form
//! `[[A, Bᵀ], [B, -C]]` with `C = B_b A_bb⁻¹ B_bᵀ` positive semi-definite (the stabilisation the
//! bubble induces on P1–P1). Signs: `B[m][(c,k)] = -∫ λ_m ∂_c φ_k`.
//!
//! The viscosity may vary inside an element: it is sampled at the points of the degree-5 rule
//! (exact integration for constant viscosity).

#![allow(clippy::needless_range_loop)] // dense index algebra on 11x11 element matrices

use super::p1::{bary_point, P1Geom};
use super::quadrature::tri_rule;
use crate::geom::DVec2;

/// Size of the uncondensed element system: 6 P1 velocity + 2 bubble + 3 pressure dofs.
const NFULL: usize = 11;
/// Positions of the bubble dofs in the uncondensed system.
const BX: usize = 6;
const BY: usize = 7;

/// The condensed MINI element and the data needed to recover its bubble coefficients.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MiniElement {
    /// Condensed matrix on `[ux0..2, uy0..2, p0..2]`.
    pub k: [[f64; 9]; 9],
    /// Condensed right-hand side (body force) on the same dofs.
    pub f: [f64; 9],
    /// `A_bb⁻¹` (2x2, bubble x / bubble y).
    abb_inv: [[f64; 2]; 2],
    /// Rows of the uncondensed system belonging to the bubbles, on the 9 condensed dofs.
    m_b: [[f64; 9]; 2],
    /// Bubble part of the uncondensed right-hand side.
    f_b: [f64; 2],
}

/// Map from uncondensed index (0..11, bubbles excluded) to condensed index (0..9).
#[inline]
fn cond_index(i: usize) -> Option<usize> {
    match i {
        0..=5 => Some(i),
        BX | BY => None,
        _ => Some(i - 2),
    }
}

/// Gradient of the bubble `27 λ0 λ1 λ2` at barycentric point `l`.
#[inline]
fn bubble_grad(g: &P1Geom, l: &[f64; 3]) -> DVec2 {
    27.0 * (l[1] * l[2] * g.grad[0] + l[0] * l[2] * g.grad[1] + l[0] * l[1] * g.grad[2])
}

impl MiniElement {
    /// Builds the condensed element on the triangle `p` with viscosity `mu(λ)` sampled at the
    /// quadrature points (barycentric argument) and body force `force(x)`.
    pub fn new(
        p: [DVec2; 3],
        mu: impl Fn(&[f64; 3]) -> f64,
        force: impl Fn(DVec2) -> DVec2,
    ) -> MiniElement {
        let g = P1Geom::new(p);
        let rule = tri_rule(5);
        let mut m = [[0.0; NFULL]; NFULL];
        let mut rhs = [0.0; NFULL];
        // Velocity basis (c, k): component c, shape k in {λ0, λ1, λ2, b}; uncondensed index.
        let vidx = |c: usize, k: usize| if k == 3 { BX + c } else { 3 * c + k };
        for (l, w) in rule.points.iter().zip(&rule.weights) {
            let wq = w * g.area;
            let mu_q = mu(l);
            let grads = [g.grad[0], g.grad[1], g.grad[2], bubble_grad(&g, l)];
            let shape = [l[0], l[1], l[2], 27.0 * l[0] * l[1] * l[2]];
            let fq = force(bary_point(&p, l));
            for c in 0..2 {
                for k in 0..4 {
                    let i = vidx(c, k);
                    let gk = grads[k];
                    for d in 0..2 {
                        for (n, gn) in grads.iter().enumerate() {
                            let j = vidx(d, n);
                            let delta = if c == d { gk.dot(*gn) } else { 0.0 };
                            // 2μ ε(φ e_c) : ε(ψ e_d) = μ (δ_cd ∇φ·∇ψ + ∂_d φ ∂_c ψ)
                            m[i][j] += wq * mu_q * (delta + gk[d] * gn[c]);
                        }
                    }
                    // B[p_m][(c,k)] = -∫ λ_m ∂_c φ_k, and its transpose.
                    for mm in 0..3 {
                        let v = -wq * l[mm] * gk[c];
                        m[8 + mm][i] += v;
                        m[i][8 + mm] += v;
                    }
                    rhs[i] += wq * fq[c] * shape[k];
                }
            }
        }
        // Static condensation of the two bubble dofs.
        let (a, b, d) = (m[BX][BX], m[BX][BY], m[BY][BY]);
        let det = a * d - b * b;
        let abb_inv = [[d / det, -b / det], [-b / det, a / det]];
        let mut m_b = [[0.0; 9]; 2];
        for (r, row) in [BX, BY].iter().enumerate() {
            for j in 0..NFULL {
                if let Some(cj) = cond_index(j) {
                    m_b[r][cj] = m[*row][j];
                }
            }
        }
        let f_b = [rhs[BX], rhs[BY]];
        let mut k = [[0.0; 9]; 9];
        let mut f = [0.0; 9];
        for i in 0..NFULL {
            let Some(ci) = cond_index(i) else { continue };
            // s_i = M[i][b] A_bb⁻¹ (row vector over the two bubbles)
            let mib = [m[i][BX], m[i][BY]];
            let s = [
                mib[0] * abb_inv[0][0] + mib[1] * abb_inv[1][0],
                mib[0] * abb_inv[0][1] + mib[1] * abb_inv[1][1],
            ];
            for j in 0..NFULL {
                let Some(cj) = cond_index(j) else { continue };
                k[ci][cj] = m[i][j] - s[0] * m[BX][j] - s[1] * m[BY][j];
            }
            f[ci] = rhs[i] - s[0] * f_b[0] - s[1] * f_b[1];
        }
        // Exact symmetry (round-off of the two sides of the condensation).
        for i in 0..9 {
            for j in 0..i {
                let v = 0.5 * (k[i][j] + k[j][i]);
                k[i][j] = v;
                k[j][i] = v;
            }
        }
        MiniElement {
            k,
            f,
            abb_inv,
            m_b,
            f_b,
        }
    }

    /// The bubble coefficients `(b_x, b_y)` from the element's condensed dof values
    /// `[ux0..2, uy0..2, p0..2]`: `u_b = A_bb⁻¹ (f_b - M_b x)`.
    pub fn bubble(&self, x: &[f64; 9]) -> [f64; 2] {
        self.bubble_recovery().bubble(x)
    }

    /// The part of the element needed to recover the bubble after the solve (24 numbers
    /// instead of the 114 of the element, to keep for every element of a large mesh).
    pub fn bubble_recovery(&self) -> BubbleRecovery {
        BubbleRecovery {
            abb_inv: self.abb_inv,
            m_b: self.m_b,
            f_b: self.f_b,
        }
    }
}

/// The bubble-recovery data of a [`MiniElement`] ([`MiniElement::bubble_recovery`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BubbleRecovery {
    abb_inv: [[f64; 2]; 2],
    m_b: [[f64; 9]; 2],
    f_b: [f64; 2],
}

impl BubbleRecovery {
    /// As [`MiniElement::bubble`].
    pub fn bubble(&self, x: &[f64; 9]) -> [f64; 2] {
        let r: [f64; 2] = std::array::from_fn(|b| {
            self.f_b[b] - (0..9).map(|j| self.m_b[b][j] * x[j]).sum::<f64>()
        });
        [
            self.abb_inv[0][0] * r[0] + self.abb_inv[0][1] * r[1],
            self.abb_inv[1][0] * r[0] + self.abb_inv[1][1] * r[1],
        ]
    }
}

/// The velocity of a MINI field at barycentric point `l` of an element with P1 vertex values
/// `u` and bubble coefficients `bubble`.
#[inline]
pub fn mini_velocity(u: &[DVec2; 3], bubble: DVec2, l: &[f64; 3]) -> DVec2 {
    l[0] * u[0] + l[1] * u[1] + l[2] * u[2] + 27.0 * l[0] * l[1] * l[2] * bubble
}
