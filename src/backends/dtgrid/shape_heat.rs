//! The heat equation `∂ₜu − Δ_M u = 0` on the zero level `M` of any implicit function, solved
//! on the narrow band as in 000 §2.1 (the scheme of [`super::heat`], there on a sphere): the
//! band carries the signed distance `Φ` to the marching-tetrahedra zero level, each step solves
//! `(M[Φ] + τ L[Φ]) U^{k+1} = M[Φ] U^k (+ τ Γ[U^k])` with natural or transparent conditions,
//! or with the boundary rows completed by ghost values outside the band (extrapolated
//! conditions, [`super::ghost`]) (backward Euler, [`super::heat::heat_steps`]).

use super::band::Band;
use super::grid::DtGrid;
use super::heat::{heat_steps, step_count, TimeScheme};
use super::lattice::{Lattice, C3};
use super::mcf::McfState;
use super::scheme::Bc;
use super::surface::{surface_integral, zero_level};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::levelset::TriangleSurface;

/// The outcome of a heat run on an implicit surface.
#[derive(Debug, Clone)]
pub struct ShapeHeat {
    /// The band, its grid and the signed distance `Φ` on it.
    pub state: McfState<DtGrid<C3>>,
    /// `U` at the band nodes at `t_end`.
    pub u: Vec<f64>,
    /// The zero level `M_h`.
    pub surface: TriangleSurface,
    /// `U` at the vertices of `surface` (Q1 interpolation).
    pub surface_u: Vec<f64>,
    /// `‖U − u_exact‖_{L²(M_h)}` when an exact solution was given.
    pub error: Option<f64>,
    /// Time steps taken.
    pub steps: usize,
    /// The time step used (`τ` rounded so that the steps end at `t_end`).
    pub tau: f64,
}

/// Runs the heat equation on the zero level of `f` (negative inside) on the grid `lat` with a
/// band of half-width `j`, initial data `u0` at the band nodes (constant extension is the
/// caller's choice), time step `tau` to `t_end`; `exact(x)` is the solution at `t_end` if known.
/// Errors: as [`McfState::new`]; [`Error::InvalidInput`] for Dirichlet conditions or a
/// non-positive time; [`Error::InvalidField`] when `u0` is not finite at a band node.
#[allow(clippy::too_many_arguments)]
pub fn shape_heat(
    lat: Lattice,
    j: usize,
    bc: Bc,
    f: &(impl Fn(DVec3) -> f64 + Sync),
    u0: impl Fn(DVec3) -> f64,
    tau: f64,
    t_end: f64,
    exact: Option<&dyn Fn(DVec3) -> f64>,
) -> Result<ShapeHeat> {
    if bc == Bc::Dirichlet {
        return Err(Error::InvalidInput(
            "the heat problem takes natural, transparent or extrapolated conditions".into(),
        ));
    }
    let (steps, tau) = step_count(tau, t_end)?;
    let state: McfState<DtGrid<C3>> = McfState::new(lat, j, f)?;
    let (nb, phi) = (&state.nb, &state.phi);
    let mut u: Vec<f64> = nb.band.coords().map(|c| u0(lat.pos(c))).collect();
    if let Some(i) = u.iter().position(|v| !v.is_finite()) {
        let c = nb.band.coords().nth(i).unwrap_or_default();
        return Err(Error::InvalidField {
            name: "initial data".into(),
            msg: format!("not finite at {:?}", lat.pos(c)),
        });
    }
    heat_steps(&lat, nb, phi, bc, TimeScheme::Euler, tau, steps, &mut u)?;
    let z = zero_level(&lat, &nb.band, phi);
    let error = exact
        .map(|ex| surface_integral(&lat, &nb.band, &z, &u, |x, ux| (ux - ex(x)).powi(2)).sqrt());
    let mut surface = z.surface;
    surface.weld(1e-7 * lat.h);
    let mut surface_u: Vec<f64> = surface
        .points
        .iter()
        .map(|&p| super::probe::sample(&lat, &nb.band, &u, p).unwrap_or(f64::NAN))
        .collect();
    // A vertex on a face shared with a cell outside the element set takes the mean.
    let finite: Vec<f64> = surface_u
        .iter()
        .copied()
        .filter(|v| v.is_finite())
        .collect();
    let mean = finite.iter().sum::<f64>() / finite.len().max(1) as f64;
    surface_u
        .iter_mut()
        .filter(|v| !v.is_finite())
        .for_each(|v| *v = mean);
    Ok(ShapeHeat {
        u,
        surface,
        surface_u,
        error,
        steps,
        tau,
        state,
    })
}
