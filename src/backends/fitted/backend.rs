//! The interface-fitted mesh of 001 as a level-set back end ([`LevelSetBackend<D2>`]): the level
//! set `u` is a P1 field on a uniform base triangulation of the box (001 §2, right diagonals),
//! and the queries about its zero level are answered on the mesh fitted to it
//! ([`super::fit`]).
//!
//! - **Build**: the base grid with cells of side at most the resolution `h`; `u` the implicit
//!   function at the vertices (`f/|∇f|` when it is not a distance function), redistanced ([`FittedRedistancing`], geometric by default: the
//!   exact distance to the P1 zero level, 004 §2.2) only when it is not close to a distance
//!   ([`FittedOptions::distance_tol`]). A distance is kept as it is: the distance to the P1
//!   polyline has the curvature of its level sets at the polyline's corners, and 001 (5.2) then
//!   errs by about 10% on a circle at every resolution (docs/fitted.md).
//! - **Mean curvature** (`u_t = |∇u| κ`, `κ = div(∇u/|∇u|)`, 000 eq. (2.4)): the speed
//!   `f = |∇u| κ_h` at the vertices, κ_h by 001 (5.2) (the curvature of the level set through
//!   each vertex, so no extension is needed) and `|∇u|` of the area-weighted mean gradient;
//!   the increment `(M_L + dt K) δ = dt M_L f` keeps the stiffness as an implicit smoother;
//!   Heun's predictor–corrector averages the increments at `u^n` and at the predicted
//!   `u^n + δ`. The smoother alone adds `dt² M_L⁻¹K f` per step, an `O(dt)` error of the zero
//!   level (with `dt ∝ h`, order 0.81 / 0.88 on the shrinking circle of the cross-check), so the
//!   step is Richardson-extrapolated: `2 H_{dt/2}(H_{dt/2}(u)) − H_dt(u)` with `H` Heun's
//!   step, second order in `dt` and still damping the stiff modes (each `H` halves the
//!   highest ones, the combination removes them). Measured (circle R0 = 0.5 to T = 0.06,
//!   `dt = 0.4h`): radius error 5.2e-4 / 1.45e-4 / 4.0e-5 at h = 0.02 / 0.01 / 0.005 (orders
//!   1.83, 1.85); with the fixed small `dt = 5e-4` the error is that of the initial P1 zero
//!   level, 7.3e-5 / 1.8e-5 (order 2); the same extrapolation of the plain implicit step
//!   (3 solves instead of 6) is thrown off by the singular speed at a grid vertex on the
//!   circle's centre (4.0e-4 at h = 0.01). Then `u` is redistanced only when it has drifted from
//!   a distance (no redistancing in that run). Tests: tests/backends_fitted.rs,
//!   docs/crosscheck.md.
//! - **Advection**: characteristics, `u^{n+1}(x_i) = u^n(X(x_i))` at every base vertex, with the
//!   foot by classical Runge–Kutta in sub-steps of at most half a cell and P1 interpolation on
//!   the base grid (feet outside the box are moved to
//!   the nearest point of the box: inflow takes the boundary value).
//! - **Redistancing**: geometric (default) or the Poisson reinitialisation of 001 §4
//!   ([`super::poisson_reinit`]), see [`FittedRedistancing`].
//! - **Measures**: the inside area (triangles labelled 3) and the interface length (edges
//!   labelled 10) of the fitted mesh, which are those of the P1 zero level of `u` to round-off.
//! - **Curvature**: 001 (5.2) at the base vertices, interpolated onto the interface nodes of
//!   the fitted mesh (001 §5; [`super::interface_curvature`]).

use super::{fit, interface_curvature, vertex_curvature, FitOptions, FittedMesh, PoissonReinit};
use crate::backends::{
    check_dt, BuildSpec, CurvatureSamples, LevelSetBackend, StepReport, VelocityField, D2,
};
use crate::error::{Error, Result};
use crate::fem::p1::{add_stiffness, gradients, lumped_mass, Coef};
use crate::fem::solve::cg;
use crate::fem::{CgOptions, Csr};
use crate::geom::DVec2;
use crate::levelset::redistance::{redistance_geometric, redistance_ppr, PprOptions};
use crate::levelset::{extract_zero_level, normalized_distance, Polyline};
use crate::mesh::{GridPattern, Mesh2};
use rayon::prelude::*;
use std::time::Instant;

/// How the fitted back end redistances: in [`LevelSetBackend::redistance`], and after building
/// and after a mean curvature step when `u` has drifted from a distance
/// ([`FittedOptions::distance_tol`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum FittedRedistancing {
    /// The exact distance to the P1 zero level (004 §2.2): `|∇u| = 1` near the zero level.
    #[default]
    Geometric,
    /// PPR gradient recovery and oblique projection onto the zero level, fast marching beyond
    /// (003 §6).
    Ppr,
    /// The Poisson reinitialisation of 001 §4 with the gradient-jump rows, solved on the fitted
    /// mesh and restricted to the base grid ([`super::poisson_reinit`]). Its `u` is smooth
    /// across the zero level with `|∇u|` bounded away from 0 and ∞, but not a distance.
    Poisson(PoissonReinit),
}

/// Options of [`FittedBackend`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FittedOptions {
    /// The redistancing.
    pub redistancing: FittedRedistancing,
    /// The build and the mean curvature steps redistance `u` only when the area-weighted mean
    /// of `||∇u_h| − 1|` over the cut triangles exceeds this (module documentation).
    pub distance_tol: f64,
    /// The conjugate-gradient solve of the mean curvature step.
    pub cg: CgOptions,
}

impl Default for FittedOptions {
    fn default() -> Self {
        FittedOptions {
            redistancing: FittedRedistancing::default(),
            distance_tol: 0.3,
            cg: CgOptions {
                rtol: 1e-12,
                ..CgOptions::default()
            },
        }
    }
}

/// The interface-fitted back end (module documentation).
#[derive(Debug, Clone)]
pub struct FittedBackend {
    base: Mesh2,
    lo: DVec2,
    hi: DVec2,
    nx: usize,
    ny: usize,
    u: Vec<f64>,
    time: f64,
    opts: FittedOptions,
}

impl FittedBackend {
    /// Builds the back end for `spec` with options `opts` (module documentation). Errors: a
    /// domain that is not a box, a resolution outside `(0, side)` or finer than 4096 cells per
    /// side, no zero level in the domain.
    pub fn new(spec: &BuildSpec<'_, D2>, opts: FittedOptions) -> Result<FittedBackend> {
        let (lo, hi) = spec.domain;
        if !(lo.is_finite() && hi.is_finite() && lo.x < hi.x && lo.y < hi.y) {
            return Err(Error::InvalidInput(format!(
                "fitted back end: the domain ({lo}, {hi}) is not a box"
            )));
        }
        let side = (hi - lo).max_element();
        let h = spec.resolution;
        if !(h > 0.0 && h < side && side / h <= 4096.0) {
            return Err(Error::InvalidInput(format!(
                "fitted back end: the resolution must lie in [{}, {side}) (got {h})",
                side / 4096.0
            )));
        }
        if !(opts.distance_tol.is_finite() && opts.distance_tol >= 0.0) {
            return Err(Error::InvalidInput(format!(
                "fitted back end: distance_tol must be finite and >= 0 (got {})",
                opts.distance_tol
            )));
        }
        let cells = |l: f64| ((l / h) * (1.0 - 1e-12)).ceil().max(1.0) as usize;
        let (nx, ny) = (cells(hi.x - lo.x), cells(hi.y - lo.y));
        let base = Mesh2::rectangle(lo, hi, nx, ny, GridPattern::Right)?;
        let f = spec.function;
        // A function that is not a distance is seen as `f/|∇f|` (levelset::Normalized): the
        // same zero level with a unit gradient on it, so the curvature of 001 (5.2) is that of
        // the function's own level sets rather than of a distance to the P1 polyline.
        let cap = (hi - lo).length();
        let u0: Vec<f64> = if f.is_distance() {
            base.points.par_iter().map(|&p| f.distance(p)).collect()
        } else {
            base.points
                .par_iter()
                .map(|&p| normalized_distance(f, p, cap))
                .collect()
        };
        if !(u0.iter().any(|&v| v < 0.0) && u0.iter().any(|&v| v > 0.0)) {
            return Err(Error::EmptyLevelSet(format!(
                "the implicit function '{}' has no zero level in the domain ({lo}, {hi}) at \
                 resolution {h}",
                f.name()
            )));
        }
        let mut b = FittedBackend {
            base,
            lo,
            hi,
            nx,
            ny,
            u: u0,
            time: 0.0,
            opts,
        };
        if distance_defect(&b.base, &b.u)? > opts.distance_tol {
            b.u = b.redistanced()?;
        }
        Ok(b)
    }

    /// The base grid.
    pub fn base(&self) -> &Mesh2 {
        &self.base
    }

    /// The level set at the vertices of [`FittedBackend::base`].
    pub fn values(&self) -> &[f64] {
        &self.u
    }

    /// The mesh fitted to the zero level of `u` (labels 3 inside, 2 outside, interface edges
    /// 10).
    pub fn fitted(&self) -> Result<FittedMesh> {
        fit(&self.base, &self.u, &FitOptions::default())
    }

    /// The P1 interpolant of `u` at `p` (`None` outside the box).
    fn value_at(&self, p: DVec2) -> Option<f64> {
        let (lo, hi) = (self.lo, self.hi);
        let tol = 1e-12 * (hi - lo).max_element();
        if !(p.x >= lo.x - tol && p.x <= hi.x + tol && p.y >= lo.y - tol && p.y <= hi.y + tol) {
            return None;
        }
        Some(self.interpolate(p))
    }

    /// The P1 interpolant of `u` at `p`, clamped into the box.
    fn interpolate(&self, p: DVec2) -> f64 {
        let (lo, hi) = (self.lo, self.hi);
        let q = p.clamp(lo, hi);
        let hx = (hi.x - lo.x) / self.nx as f64;
        let hy = (hi.y - lo.y) / self.ny as f64;
        let fx = (q.x - lo.x) / hx;
        let fy = (q.y - lo.y) / hy;
        let i = (fx.floor() as usize).min(self.nx - 1);
        let j = (fy.floor() as usize).min(self.ny - 1);
        let (s, r) = (fx - i as f64, fy - j as f64);
        let id = |i: usize, j: usize| self.u[j * (self.nx + 1) + i];
        let (ua, ub, uc, ud) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
        // GridPattern::Right: triangles [a, b, c] (s >= r) and [a, c, d].
        if s >= r {
            ua + s * (ub - ua) + r * (uc - ub)
        } else {
            ua + r * (ud - ua) + s * (uc - ud)
        }
    }

    fn redistanced(&self) -> Result<Vec<f64>> {
        match self.opts.redistancing {
            FittedRedistancing::Geometric => redistance_geometric(&self.base, &self.u),
            FittedRedistancing::Ppr => {
                redistance_ppr(&self.base, &self.u, &PprOptions::default()).map(|o| o.values)
            }
            FittedRedistancing::Poisson(p) => p.reinitialise(&self.base, &self.u),
        }
    }

    /// The increment `δ` of one mean curvature step from `u`: `(M_L + dt K) δ = dt M_L f` with
    /// the speed `f = |∇u| κ_h` at the vertices, κ_h by 001 (5.2) and `|∇u|` of the
    /// area-weighted mean gradient of the vertex's triangles; `a` is `M_L + dt K`.
    fn mcf_increment(&self, u: &[f64], a: &Csr, dt: f64, rep: &mut StepReport) -> Result<Vec<f64>> {
        let t = Instant::now();
        let m = &self.base;
        let kappa = vertex_curvature(m, u)?;
        let grads = gradients(m, u)?;
        let mut g = vec![DVec2::ZERO; m.n_points()];
        for t in m.live_tris() {
            let at = m.tri_area(t);
            for v in m.tris[t] {
                g[v as usize] += at * grads[t];
            }
        }
        let rhs: Vec<f64> = (0..m.n_points())
            .map(|v| {
                let k = kappa.kappa[v].unwrap_or(0.0);
                // M_L f with |∇u| = |g_v| / (3 m_v): the patch has area 3 m_v.
                dt * k * g[v].length() / 3.0
            })
            .collect();
        rep.phases.assembly += t.elapsed().as_secs_f64();
        let t = Instant::now();
        let mut x = vec![0.0; m.n_points()];
        let r = cg(a, &rhs, &mut x, &self.opts.cg)?;
        rep.phases.solve += t.elapsed().as_secs_f64();
        rep.linear_iterations += r.iterations;
        rep.converged &= r.converged;
        Ok(x)
    }

    /// The smoother `M_L + tau K` of the mean curvature increment.
    fn smoother(&self, tau: f64, rep: &mut StepReport) -> Result<Csr> {
        let t = Instant::now();
        let m = &self.base;
        let ml = lumped_mass(m)?;
        let mut a = Csr::p1_pattern(m)?;
        add_stiffness(&mut a, m, &Coef::Const(tau))?;
        for (i, x) in ml.iter().enumerate() {
            a.add(i, i, *x)?;
        }
        rep.phases.assembly += t.elapsed().as_secs_f64();
        Ok(a)
    }

    /// Heun's predictor–corrector from `u` over `dt` with the smoother `a = M_L + dt K`: the
    /// increments at `u` and at the predicted `u + δ₁`, averaged.
    fn heun(&self, u: &[f64], dt: f64, a: &Csr, rep: &mut StepReport) -> Result<Vec<f64>> {
        let d1 = self.mcf_increment(u, a, dt, rep)?;
        let predicted: Vec<f64> = u.iter().zip(&d1).map(|(u, d)| u + d).collect();
        let d2 = self.mcf_increment(&predicted, a, dt, rep)?;
        Ok(u.iter()
            .zip(d1.iter().zip(&d2))
            .map(|(u, (a, b))| u + 0.5 * (a + b))
            .collect())
    }

    fn finish(&self, mut rep: StepReport, t0: Instant) -> StepReport {
        rep.time = self.time;
        rep.dof = self.base.n_points();
        rep.seconds = t0.elapsed().as_secs_f64();
        rep
    }

    fn check_inside(&self, u: &[f64], what: &str, t: f64) -> Result<()> {
        if u.iter().any(|&v| v < 0.0) && u.iter().any(|&v| v > 0.0) {
            Ok(())
        } else {
            Err(Error::EmptyLevelSet(format!(
                "the zero level vanished by {what} before t = {t}"
            )))
        }
    }
}

impl LevelSetBackend<D2> for FittedBackend {
    fn name(&self) -> &'static str {
        "fitted"
    }

    fn build(spec: &BuildSpec<'_, D2>) -> Result<Self> {
        FittedBackend::new(spec, FittedOptions::default())
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn dof(&self) -> usize {
        self.base.n_points()
    }

    fn advance_mean_curvature(&mut self, dt: f64) -> Result<StepReport> {
        check_dt(dt, "mean curvature step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        // Heun's step with the implicit smoother has a local error `dt² M_L⁻¹K f` (the smoother's
        // bias, an `O(dt)` radius error with dt ∝ h); Richardson extrapolation of one step of
        // dt and two of dt/2 cancels it, and the damping of the stiff modes is kept (module
        // documentation).
        let a_full = self.smoother(dt, &mut rep)?;
        let a_half = self.smoother(0.5 * dt, &mut rep)?;
        let full = self.heun(&self.u, dt, &a_full, &mut rep)?;
        let half = self.heun(&self.u, 0.5 * dt, &a_half, &mut rep)?;
        let half = self.heun(&half, 0.5 * dt, &a_half, &mut rep)?;
        let u: Vec<f64> = half.iter().zip(&full).map(|(h, f)| 2.0 * h - f).collect();
        self.check_inside(&u, "mean curvature", self.time + dt)?;
        self.u = u;
        self.time += dt;
        let t = Instant::now();
        if distance_defect(&self.base, &self.u)? > self.opts.distance_tol {
            self.u = self.redistanced()?;
            rep.inner_iterations += 1;
        }
        rep.phases.redistance += t.elapsed().as_secs_f64();
        Ok(self.finish(rep, t0))
    }

    fn advect(&mut self, velocity: VelocityField<'_, D2>, dt: f64) -> Result<StepReport> {
        check_dt(dt, "advection step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let (ta, tb) = (self.time, self.time + dt);
        let cell =
            ((self.hi - self.lo).x / self.nx as f64).min((self.hi - self.lo).y / self.ny as f64);
        let u: Vec<f64> = self
            .base
            .points
            .par_iter()
            .map(|&x| {
                // The foot of the characteristic through x at tb: classical Runge–Kutta
                // backwards in time, in sub-steps that move at most half a cell each.
                let reach = dt * velocity(tb, x).length();
                let n = ((2.0 * reach / cell).ceil() as usize).clamp(1, 256);
                let s = dt / n as f64;
                let mut p = x;
                for k in 0..n {
                    let t = tb - k as f64 * s;
                    let k1 = velocity(t, p);
                    let k2 = velocity(t - 0.5 * s, p - 0.5 * s * k1);
                    let k3 = velocity(t - 0.5 * s, p - 0.5 * s * k2);
                    let k4 = velocity(t - s, p - s * k3);
                    p -= s / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                }
                self.interpolate(p)
            })
            .collect();
        if u.iter().any(|v| !v.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "advection step at t = {ta}: the velocity is not finite"
            )));
        }
        self.check_inside(&u, "advection", tb)?;
        self.u = u;
        self.time = tb;
        rep.phases.solve += t0.elapsed().as_secs_f64();
        Ok(self.finish(rep, t0))
    }

    fn redistance(&mut self) -> Result<StepReport> {
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        self.u = self.redistanced()?;
        rep.phases.redistance += t0.elapsed().as_secs_f64();
        Ok(self.finish(rep, t0))
    }

    fn enclosed_measure(&self) -> Result<f64> {
        Ok(self.fitted()?.area_inside())
    }

    fn interface_measure(&self) -> Result<f64> {
        Ok(self.fitted()?.interface_length())
    }

    fn interface_curvature(&self) -> Result<CurvatureSamples<D2>> {
        let (points, values, _) = interface_curvature(&self.base, &self.u)?;
        Ok(CurvatureSamples { points, values })
    }

    fn zero_level(&self) -> Result<Vec<Polyline>> {
        extract_zero_level(&self.base, &self.u)
    }

    fn evaluate(&self, points: &[DVec2]) -> Result<Vec<Option<f64>>> {
        Ok(points.iter().map(|&p| self.value_at(p)).collect())
    }
}

/// The area-weighted mean of `||∇u_h| − 1|` over the triangles the zero level cuts (0 when none
/// is cut).
pub(crate) fn distance_defect(mesh: &Mesh2, u: &[f64]) -> Result<f64> {
    let g = gradients(mesh, u)?;
    let (mut sum, mut area) = (0.0, 0.0);
    for t in mesh.live_tris() {
        let neg = mesh.tris[t]
            .iter()
            .filter(|&&v| u[v as usize] < 0.0)
            .count();
        if neg == 0 || neg == 3 {
            continue;
        }
        let a = mesh.tri_area(t);
        sum += a * (g[t].length() - 1.0).abs();
        area += a;
    }
    Ok(if area > 0.0 { sum / area } else { 0.0 })
}
