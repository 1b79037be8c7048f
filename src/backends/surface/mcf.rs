//! Dziuk's θ-scheme for mean curvature flow of a parametric surface (002):
//!
//! `∫_{Γⁿ} (Uⁿ⁺¹ − id)·φ + τ ∫_{Γⁿ} (θ ∇_Γ Uⁿ⁺¹ + (1 − θ) I) : ∇_Γ φ = 0` for all `φ`,
//!
//! with `Uⁿ⁺¹` the new node positions over `Γⁿ`. On the discrete surface the identity is in the
//! finite element space and `∫ I : ∇_Γ φ = ∫ ∇_Γ id : ∇_Γ φ`, so each coordinate `k` solves
//! `(M + τθA) U_k = M x_k − τ(1 − θ) A x_k` with the mass and stiffness matrices `M`, `A` of
//! `Γⁿ`: one symmetric positive definite matrix, three right-hand sides, solved by
//! IC(0)-preconditioned conjugate gradients.

use super::element;
use super::ParametricSurface;
use crate::error::{Error, Result};
use crate::fem::solve::{cg_with, Preconditioner};
use crate::fem::{CgOptions, Csr};
use crate::geom::DVec3;

/// The quadrature degree of the element matrices (exact for P2 mass on a flat triangle; the
/// curved-element error of a degree-6 rule is far below the scheme's).
const MATRIX_DEGREE: usize = 6;

/// What one θ-step did.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ThetaStepStats {
    /// Conjugate-gradient iterations, summed over the coordinates.
    pub iterations: usize,
    /// Whether every solve reached its tolerance.
    pub converged: bool,
}

/// Checks `θ ∈ [0, 1]` and a finite positive `τ`.
pub(crate) fn check_theta_tau(theta: f64, tau: f64) -> Result<()> {
    if !((0.0..=1.0).contains(&theta) && tau.is_finite() && tau > 0.0) {
        return Err(Error::InvalidInput(format!(
            "θ-scheme: need θ in [0, 1] and a finite positive time step (got θ = {theta}, \
             τ = {tau})"
        )));
    }
    Ok(())
}

/// Solves `(M + τθA) U_k = M x_k − τ(1 − θ) A x_k` for every coordinate column `x[k]` (in
/// place), given the assembled `M` and `A` on one pattern.
pub fn theta_solve(
    m: &Csr,
    a: &Csr,
    tau: f64,
    theta: f64,
    x: &mut [Vec<f64>],
) -> Result<ThetaStepStats> {
    let mut s = m.clone();
    for (v, av) in s.val.iter_mut().zip(&a.val) {
        *v += tau * theta * av;
    }
    let opts = CgOptions {
        rtol: 1e-12,
        ..CgOptions::default()
    };
    let pre = Preconditioner::new(&s, opts.precond)?;
    let mut stats = ThetaStepStats {
        iterations: 0,
        converged: true,
    };
    for xk in x.iter_mut() {
        let mx = m.mul(xk);
        let ax = a.mul(xk);
        let b: Vec<f64> = mx
            .iter()
            .zip(&ax)
            .map(|(mv, av)| mv - tau * (1.0 - theta) * av)
            .collect();
        let rep = cg_with(&s, &pre, &b, xk, &opts)?;
        stats.iterations += rep.iterations;
        stats.converged &= rep.converged;
    }
    Ok(stats)
}

/// Assembles the mass and stiffness matrices of `surface` (one CSR pattern).
pub fn assemble_surface(surface: &ParametricSurface) -> Result<(Csr, Csr)> {
    let k = surface.nodes_per_cell();
    let mut m = Csr::from_element_iter(surface.nodes.len(), surface.cell_nodes.chunks(k))?;
    let mut a = m.clone();
    for c in 0..surface.triangles.len() {
        let dofs = surface.cell(c);
        let (me, ae) =
            element::mass_stiffness(&surface.cell_points(c), MATRIX_DEGREE).ok_or_else(|| {
                Error::InvalidInput(format!("surface element {c} degenerated during the flow"))
            })?;
        for i in 0..k {
            for j in 0..k {
                let (r, col) = (dofs[i] as usize, dofs[j] as usize);
                m.add(r, col, me[i * k + j])?;
                a.add(r, col, ae[i * k + j])?;
            }
        }
    }
    Ok((m, a))
}

/// One θ-step of mean curvature flow with time step `tau`: moves the nodes of `surface` to
/// `Uⁿ⁺¹` (002). Errors: θ outside `[0, 1]`, a bad time step, a degenerate element.
pub fn theta_step(surface: &mut ParametricSurface, tau: f64, theta: f64) -> Result<ThetaStepStats> {
    check_theta_tau(theta, tau)?;
    let (m, a) = assemble_surface(surface)?;
    let mut x: Vec<Vec<f64>> = (0..3)
        .map(|d| surface.nodes.iter().map(|p| p[d]).collect())
        .collect();
    let stats = theta_solve(&m, &a, tau, theta, &mut x)?;
    for (i, p) in surface.nodes.iter_mut().enumerate() {
        *p = DVec3::new(x[0][i], x[1][i], x[2][i]);
    }
    if surface.nodes.iter().any(|p| !p.is_finite()) {
        return Err(Error::NotConverged(
            "θ-step produced non-finite node positions".into(),
        ));
    }
    Ok(stats)
}
