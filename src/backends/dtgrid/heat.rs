//! The heat equation on a sphere solved on a narrow band (000 §2.1, Table 2.1): the second
//! spherical harmonic `Y = (z/|x|)² − 1/3` on the sphere of radius `R` decays as `e^{−6t/R²}`;
//! the band carries `Φ = |x| − R` and `U` extended constantly along the normals. The error is
//! `‖U − u‖_{L²(M_h)}` on the discrete surface `[Φ = 0]`.
//!
//! Time stepping ([`band_heat_steps`]): backward Euler, the paper's scheme 000 (2.10),
//! `(M[Φ] + τ L[Φ]) U^{k+1} = M[Φ] U^k (+ τ Γ[U^k])` (transparent conditions with
//! `U_approx = U^k`), or second-order BDF2,
//! `(M + ⅔τ L) U^{k+1} = M (4U^k − U^{k−1})/3 (+ ⅔τ Γ[2U^k − U^{k−1}])`, started by one
//! Crank–Nicolson step; the linear extrapolation `2U^k − U^{k−1}` keeps the defect of the
//! transparent flux at `O(τ²)` (000 §2.2 bounds it by `O(τ)` for `U_approx = U^k`).

use super::band::Band;
use super::fem::{assemble, elements, transparent_vector, BandMatrices, Element, Weight};
use super::ghost::GhostRows;
use super::lattice::{band_around, crossing_cells_of_fn, Lattice, NarrowBand, C3};
use super::scheme::{solve_all, solve_general, system_matrix, Bc};
use super::surface::{surface_integral, zero_level};
use crate::error::{Error, Result};
use crate::fem::Csr;
use crate::geom::DVec3;

/// The time discretisation of the band heat equation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum TimeScheme {
    /// Backward Euler, first order (000 (2.10)).
    Euler,
    /// BDF2, second order, first step Crank–Nicolson.
    Bdf2,
}

impl TimeScheme {
    /// The name used in reports and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            TimeScheme::Euler => "euler",
            TimeScheme::Bdf2 => "bdf2",
        }
    }

    /// Parses `euler` or `bdf2`.
    /// Error: [`Error::InvalidInput`] for another name.
    pub fn parse(s: &str) -> Result<TimeScheme> {
        match s {
            "euler" => Ok(TimeScheme::Euler),
            "bdf2" => Ok(TimeScheme::Bdf2),
            _ => Err(Error::InvalidInput(format!(
                "time scheme {s:?} (euler or bdf2)"
            ))),
        }
    }
}

/// The options of one heat run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatOptions {
    /// Grid nodes per side on `[−½, ½]³`.
    pub n: usize,
    /// The band half-width `j` in cells.
    pub j: usize,
    /// Natural or transparent conditions.
    pub bc: Bc,
    /// The time step (`None`: `h²`, rounded so that the steps end at `t_end`).
    pub tau: Option<f64>,
    /// The final time (000: 0.01).
    pub t_end: f64,
    /// The sphere radius (000: 1/3).
    pub radius: f64,
    /// The time discretisation.
    pub time: TimeScheme,
}

impl HeatOptions {
    /// The paper's problem (R = 1/3, t = 0.01, backward Euler) on `n³` nodes with half-width
    /// `j`.
    pub fn paper(n: usize, j: usize, bc: Bc) -> HeatOptions {
        HeatOptions {
            n,
            j,
            bc,
            tau: None,
            t_end: 0.01,
            radius: 1.0 / 3.0,
            time: TimeScheme::Euler,
        }
    }
}

/// The outcome of one heat run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HeatResult {
    /// `‖U − u‖_{L²(M_h)}` at `t_end`.
    pub error: f64,
    /// Band nodes.
    pub nodes: usize,
    /// Time steps taken.
    pub steps: usize,
    /// The time step used.
    pub tau: f64,
    /// The grid spacing.
    pub h: f64,
}

/// The number of steps of length at most `tau` that end at `t_end`, and the step.
/// Error: [`Error::InvalidInput`] when `tau` or `t_end` is not positive and finite.
pub fn step_count(tau: f64, t_end: f64) -> Result<(usize, f64)> {
    if !(t_end.is_finite() && t_end > 0.0 && tau.is_finite() && tau > 0.0) {
        return Err(Error::InvalidInput(format!(
            "heat: t_end = {t_end} and tau = {tau} must be positive"
        )));
    }
    let steps = (t_end / tau - 1e-9).ceil().max(1.0) as usize;
    Ok((steps, t_end / steps as f64))
}

/// Advances the band field `u` by `steps` steps of `tau` of the surface heat equation with the
/// heat matrices `m` of the band field `phi` on the elements `el` (000 (2.10)), natural or
/// transparent conditions, time discretisation `time`.
/// Errors: [`Error::InvalidInput`] for Dirichlet conditions; solver errors from [`solve_all`].
#[allow(clippy::too_many_arguments)]
pub fn band_heat_steps(
    lat: &Lattice,
    el: &[Element],
    phi: &[f64],
    m: &BandMatrices,
    bc: Bc,
    time: TimeScheme,
    tau: f64,
    steps: usize,
    u: &mut [f64],
) -> Result<()> {
    if matches!(bc, Bc::Dirichlet | Bc::Extrapolated) {
        return Err(Error::InvalidInput(
            "the heat problem takes natural or transparent conditions here".into(),
        ));
    }
    let n = u.len();
    let flux = |v: &[f64]| transparent_vector(lat, el, n, phi, v, Weight::Heat);
    let flux = (bc == Bc::Transparent).then_some(&flux as Flux);
    steps_with(m, flux, time, tau, steps, u, solve_all)
}

/// A lagged boundary vector of the band field.
type Flux<'a> = &'a dyn Fn(&[f64]) -> Vec<f64>;

/// The time steps of [`band_heat_steps`] with the lagged boundary vector `flux` (`None`: natural
/// conditions): the transparent `Γ` of 000 (2.9) or the outside cells' part of the complete
/// boundary rows ([`GhostRows::vector`]).
/// Errors: solver errors from [`solve_all`].
#[allow(clippy::too_many_arguments)]
fn steps_with(
    m: &BandMatrices,
    flux: Option<Flux>,
    time: TimeScheme,
    tau: f64,
    steps: usize,
    u: &mut [f64],
    solve: fn(&Csr, &[f64], &mut [f64]) -> Result<usize>,
) -> Result<()> {
    let n = u.len();
    let mut b = vec![0.0; n];
    if time == TimeScheme::Euler {
        let a = system_matrix(m, tau)?;
        for _ in 0..steps {
            b.iter_mut()
                .zip(&m.mass)
                .zip(u.iter())
                .for_each(|((b, m), u)| *b = m * u);
            if let Some(flux) = flux {
                let g = flux(u);
                b.iter_mut().zip(&g).for_each(|(b, g)| *b += tau * g);
            }
            solve(&a, &b, u)?;
        }
        return Ok(());
    }
    // BDF2: the first step by Crank–Nicolson,
    // (M + τ/2 L) U¹ = (M − τ/2 L) U⁰ + τ Γ[U⁰].
    let mut prev = u.to_vec();
    if steps == 0 {
        return Ok(());
    }
    {
        let a = system_matrix(m, 0.5 * tau)?;
        let lu = m.stiff.mul(u);
        b.iter_mut()
            .zip(&m.mass)
            .zip(u.iter().zip(&lu))
            .for_each(|((b, m), (u, lu))| *b = m * u - 0.5 * tau * lu);
        if let Some(flux) = flux {
            let g = flux(u);
            b.iter_mut().zip(&g).for_each(|(b, g)| *b += tau * g);
        }
        solve(&a, &b, u)?;
    }
    let t2 = 2.0 * tau / 3.0;
    let a = system_matrix(m, t2)?;
    let mut guess = vec![0.0; n];
    for _ in 1..steps {
        b.iter_mut()
            .zip(&m.mass)
            .zip(u.iter().zip(&prev))
            .for_each(|((b, m), (u, p))| *b = m * (4.0 * u - p) / 3.0);
        guess
            .iter_mut()
            .zip(u.iter().zip(&prev))
            .for_each(|(g, (u, p))| *g = 2.0 * u - p);
        if let Some(flux) = flux {
            let g = flux(&guess);
            b.iter_mut().zip(&g).for_each(|(b, g)| *b += t2 * g);
        }
        prev.copy_from_slice(u);
        u.copy_from_slice(&guess);
        solve(&a, &b, u)?;
    }
    Ok(())
}

/// Assembles the heat matrices of the band `nb` for the band field `phi` and advances `u` by
/// `steps` steps of `tau` under natural, transparent (000 (2.9)) or extrapolated conditions
/// ([`GhostRows`]: the boundary rows completed by the cells outside the band, solved implicitly
/// by BiCGStab since the completed matrix is not symmetric).
/// Errors: [`Error::InvalidInput`] for Dirichlet conditions or a band too thin for the ghost
/// extrapolation; solver errors.
#[allow(clippy::too_many_arguments)]
pub fn heat_steps<B: Band<Coord = C3>>(
    lat: &Lattice,
    nb: &NarrowBand<B>,
    phi: &[f64],
    bc: Bc,
    time: TimeScheme,
    tau: f64,
    steps: usize,
    u: &mut [f64],
) -> Result<()> {
    let n = nb.band.len();
    let el = elements(nb);
    let mut m = assemble(lat, &el, n, phi, Weight::Heat)?;
    if bc != Bc::Extrapolated {
        return band_heat_steps(lat, &el, phi, &m, bc, time, tau, steps, u);
    }
    let ghost = GhostRows::new(lat, nb, phi, Weight::Heat)?;
    m.mass
        .iter_mut()
        .zip(&ghost.mass)
        .for_each(|(m, g)| *m += g);
    m.stiff = ghost.complete(&m.stiff)?;
    steps_with(&m, None, time, tau, steps, u, solve_general)
}

/// Runs the heat problem on a band stored as `B`.
/// Errors: [`Error::InvalidInput`] for Dirichlet conditions, a non-positive time or a band that
/// does not fit; solver errors from [`solve_all`].
pub fn sphere_heat<B: Band<Coord = C3>>(o: &HeatOptions) -> Result<HeatResult> {
    if o.bc == Bc::Dirichlet {
        return Err(Error::InvalidInput(
            "the heat problem takes natural or transparent conditions".into(),
        ));
    }
    if !(o.t_end.is_finite() && o.t_end > 0.0 && o.radius.is_finite() && o.radius > 0.0) {
        return Err(Error::InvalidInput(format!(
            "heat: t_end = {} and radius = {} must be positive",
            o.t_end, o.radius
        )));
    }
    let lat = Lattice::unit(o.n)?;
    let r = o.radius;
    let f = |p: DVec3| p.length() - r;
    let cross = crossing_cells_of_fn(&lat, &f)?;
    let nb: NarrowBand<B> = band_around(&lat, &cross, o.j)?;
    let n = nb.band.len();
    let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
    let y = |p: DVec3| {
        let l = p.length().max(1e-300);
        (p.z / l).powi(2) - 1.0 / 3.0
    };
    let mut u: Vec<f64> = nb.band.coords().map(|c| y(lat.pos(c))).collect();
    let (steps, tau) = step_count(o.tau.unwrap_or(lat.h * lat.h), o.t_end)?;
    heat_steps(&lat, &nb, &phi, o.bc, o.time, tau, steps, &mut u)?;
    let z = zero_level(&lat, &nb.band, &phi);
    let decay = (-6.0 * o.t_end / (r * r)).exp();
    let e2 = surface_integral(&lat, &nb.band, &z, &u, |x, ux| (ux - decay * y(x)).powi(2));
    Ok(HeatResult {
        error: e2.sqrt(),
        nodes: n,
        steps,
        tau,
        h: lat.h,
    })
}
