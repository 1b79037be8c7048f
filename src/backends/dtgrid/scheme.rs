//! The linear systems of one semi-implicit band time step (000 (2.5), (2.10), (2.12)):
//! `(M + τ L) U = r` with natural or transparent Neumann conditions (all band nodes unknown), or
//! with Dirichlet values on the boundary layer (000 (2.12): CG updates interior nodes only, the
//! boundary nodes keep their prescribed values). CG with the diagonal preconditioner.

use super::fem::BandMatrices;
use crate::error::{Error, Result};
use crate::fem::solve::pcg;
use crate::fem::{CgOptions, Csr};

/// The boundary condition on the band's boundary.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Bc {
    /// Natural (homogeneous Neumann) conditions of the weak form.
    Natural,
    /// Transparent Neumann conditions: the boundary flux of the last step added (000 (2.9)–(2.11)).
    Transparent,
    /// The heat equation's boundary rows completed by the cells outside the band, with values
    /// extrapolated linearly along the normals ([`super::ghost`]); heat problems only.
    Extrapolated,
    /// Dirichlet values on the boundary layer (000 (2.12)), with the nested inner iteration of
    /// 000 §2.4 where the caller asks for more than one solve per step.
    Dirichlet,
}

impl Bc {
    /// The name used in reports and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Bc::Natural => "natural",
            Bc::Transparent => "transparent",
            Bc::Dirichlet => "dirichlet",
            Bc::Extrapolated => "extrapolated",
        }
    }

    /// Parses `natural`, `transparent` or `dirichlet`.
    /// Error: [`Error::InvalidInput`] for another name.
    pub fn parse(s: &str) -> Result<Bc> {
        match s {
            "natural" => Ok(Bc::Natural),
            "transparent" => Ok(Bc::Transparent),
            "dirichlet" => Ok(Bc::Dirichlet),
            "extrapolated" => Ok(Bc::Extrapolated),
            _ => Err(Error::InvalidInput(format!(
                "boundary condition {s:?} (natural, transparent, extrapolated or dirichlet)"
            ))),
        }
    }
}

/// `M + τ L` as one CSR matrix.
pub fn system_matrix(m: &BandMatrices, tau: f64) -> Result<Csr> {
    let mut a = m.stiff.clone();
    a.val.iter_mut().for_each(|v| *v *= tau);
    for (i, &mi) in m.mass.iter().enumerate() {
        a.add(i, i, mi)?;
    }
    Ok(a)
}

fn cg_options() -> CgOptions {
    CgOptions {
        rtol: 1e-10,
        atol: 1e-300,
        max_iter: 20_000,
        ..CgOptions::default()
    }
}

/// Solves `A x = b` over all nodes (natural or transparent conditions), from the guess in `x`;
/// returns the CG iterations.
/// Error: [`Error::NotConverged`] when CG fails, [`Error::InvalidField`] for a NaN in the result.
pub fn solve_all(a: &Csr, b: &[f64], x: &mut [f64]) -> Result<usize> {
    let d = a.diagonal();
    let rep = pcg(
        |v, y| a.matvec(v, y),
        |r, z| {
            z.iter_mut()
                .zip(r)
                .zip(&d)
                .for_each(|((z, r), d)| *z = r / d)
        },
        b,
        x,
        &cg_options(),
    );
    finish(rep, x)
}

/// Solves `R A E x_int = R (b − A x_bd)`: the nodes with `fixed[i]` keep their values in `x`, the
/// others are solved for (000 (2.12)); returns the CG iterations.
/// Errors: as [`solve_all`].
pub fn solve_dirichlet(a: &Csr, b: &[f64], fixed: &[bool], x: &mut [f64]) -> Result<usize> {
    solve_dirichlet_rtol(a, b, fixed, x, cg_options().rtol)
}

/// [`solve_dirichlet`] stopping at the relative residual `rtol` (relative to the residual of the
/// guess in `x`).
/// Errors: as [`solve_all`].
pub fn solve_dirichlet_rtol(
    a: &Csr,
    b: &[f64],
    fixed: &[bool],
    x: &mut [f64],
    rtol: f64,
) -> Result<usize> {
    let apply = |v: &[f64], out: &mut [f64]| {
        a.matvec(v, out);
        out.iter_mut().zip(fixed).for_each(|(o, &f)| {
            if f {
                *o = 0.0
            }
        });
    };
    solve_dirichlet_with(apply, &a.diagonal(), b, fixed, x, rtol)
}

/// [`solve_dirichlet_rtol`] for the operator `apply` (`out = A v` with zeros on the rows of the
/// `fixed` nodes) with diagonal `diag`.
/// Errors: as [`solve_all`].
pub fn solve_dirichlet_with(
    mut apply: impl FnMut(&[f64], &mut [f64]),
    diag: &[f64],
    b: &[f64],
    fixed: &[bool],
    x: &mut [f64],
    rtol: f64,
) -> Result<usize> {
    let mut r = vec![0.0; x.len()];
    apply(x, &mut r);
    r.iter_mut()
        .zip(b)
        .zip(fixed)
        .for_each(|((r, b), &f)| *r = if f { 0.0 } else { b - *r });
    let mut y = vec![0.0; x.len()];
    let rep = pcg(
        apply,
        |r, z| {
            z.iter_mut()
                .zip(r)
                .zip(diag)
                .zip(fixed)
                .for_each(|(((z, r), d), &f)| *z = if f { 0.0 } else { r / d })
        },
        &r,
        &mut y,
        &CgOptions {
            rtol,
            ..cg_options()
        },
    );
    x.iter_mut().zip(&y).for_each(|(x, y)| *x += y);
    finish(rep, x)
}

/// Solves `A x = b` for a matrix `A` that need not be symmetric (the completed rows of
/// [`super::ghost::GhostRows::complete`]) by BiCGStab with the diagonal preconditioner, from the
/// guess in `x`; returns the iterations.
/// Errors: as [`solve_all`] (also on a breakdown of BiCGStab).
pub fn solve_general(a: &Csr, b: &[f64], x: &mut [f64]) -> Result<usize> {
    let rep = crate::fem::bicgstab::bicgstab(a, b, x, &cg_options())?;
    finish(rep, x)
}

fn finish(rep: crate::fem::CgReport, x: &[f64]) -> Result<usize> {
    if let Some(i) = x.iter().position(|v| !v.is_finite()) {
        return Err(Error::InvalidField {
            name: "band solution".into(),
            msg: format!("not finite at band node {i}"),
        });
    }
    if !rep.converged {
        return Err(Error::NotConverged(format!(
            "band CG: residual {:.2e} after {} iterations",
            rep.residual, rep.iterations
        )));
    }
    Ok(rep.iterations)
}
