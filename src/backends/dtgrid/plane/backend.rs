//! The planar DT-Grid narrow band behind the level-set back-end contract
//! ([`LevelSetBackend`] for [`D2`]): a signed distance stored on the band of half-width `j`
//! cells around its zero level in a square grid (000 §2.3, §3 in two dimensions).
//!
//! - **Build**: the grid covers the square spanned by the domain's longest side with spacing at
//!   most `resolution`; the band is `I^{j+1}` around the cells the zero level crosses, carrying
//!   the signed distance to the bicubic zero level of the function's nodal values
//!   ([`super::mcf::PlaneMcf::new`]), so a function that is not a distance becomes one.
//! - **Mean curvature**: sub-steps of at most `min(tau_per_h2 · h², tau_per_h · h)` of
//!   000 (2.5) with Dirichlet conditions and the nested inner iteration of 000 §2.4 (by
//!   default; the first data of a step predicted from the zero level's curvature), natural or
//!   transparent conditions ([`super::mcf::PlaneMcf::step`]).
//! - **Advection**: semi-Lagrangian sub-steps moving the zero level at most `cfl ≤ j` cells:
//!   the band dilated by that many cells takes `u(t, X)` at the foot `X` of its characteristic
//!   (classical Runge–Kutta backwards in time; bicubic interpolation in the old band,
//!   [`super::cubic::Patch`], bilinear near its edge), the band is rebuilt around the new zero level, and nodes
//!   whose foot left the old band take the signed distance to it.
//! - **Redistance**: the signed distance to the zero level on the band rebuilt around it.
//! - **Measures**: area and length of the zero level ([`super::level`]).
//! - **Curvature**: `div(∇u/|∇u|)` by central differences at the nodes, bilinearly
//!   interpolated to one point per cut cell on the zero level.
//! - **Evaluate**: the Q1 interpolant in cells whose corners are all band nodes, `None`
//!   elsewhere.

use super::cubic::{locate, node_curvature, Field};
use super::distance::{extend_distance, Keep};
use super::lattice::{band_around, crossing_cells_of_band, Plane};
use super::level::{zero_level, ZeroLevel};
use super::mcf::{rebuild, PlaneMcf};
use super::{Grid2, C2};
use crate::backends::dtgrid::band::{Band, GridCoord};
use crate::backends::dtgrid::mcf::McfOptions;
use crate::backends::dtgrid::scheme::Bc;
use crate::backends::{
    advection_substeps, check_dt, BuildSpec, CurvatureSamples, LevelSetBackend, StepReport,
    VelocityField, D2,
};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::levelset::Polyline;
use rayon::prelude::*;
use std::time::Instant;

/// The options of the planar DT-Grid back end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DtGrid2Options {
    /// The mean curvature scheme: band half-width `j`, boundary condition (Dirichlet,
    /// natural or transparent), solves per step.
    pub mcf: McfOptions,
    /// The longest mean curvature sub-step in units of `h²`.
    pub tau_per_h2: f64,
    /// The longest mean curvature sub-step in units of `h`.
    pub tau_per_h: f64,
    /// The largest displacement of an advection sub-step, in cells (at most `j` are used).
    pub cfl: f64,
}

impl Default for DtGrid2Options {
    /// `j = 2`, Dirichlet conditions with up to 5 solves per step, `τ ≤ h/8` (first order in
    /// time and cheap; `tau_per_h2 = 1` with `tau_per_h = ∞` is 000's second-order scheme), 2
    /// cells per advection sub-step.
    fn default() -> DtGrid2Options {
        DtGrid2Options {
            mcf: McfOptions {
                j: 2,
                ..McfOptions::default()
            },
            tau_per_h2: f64::INFINITY,
            tau_per_h: 0.125,
            cfl: 2.0,
        }
    }
}

/// A planar level-set function on a DT-Grid narrow band (see the module documentation).
#[derive(Debug, Clone)]
pub struct DtGrid2Backend {
    state: PlaneMcf,
    /// World position of the grid's local origin: `x_world = x_local + shift`.
    shift: DVec2,
    /// The domain's upper corner in local coordinates.
    top: DVec2,
    time: f64,
    opts: DtGrid2Options,
}

fn positive(x: f64) -> bool {
    x.is_finite() && x > 0.0
}

impl DtGrid2Backend {
    /// Builds the band from `spec` with options `opts`.
    /// Errors: [`Error::InvalidInput`] for a bad domain, resolution or options (no solve per
    /// step), a band wider than the grid, or a zero level
    /// whose band does not fit in the domain; [`Error::InvalidField`] for a NaN of the function
    /// at a grid node; [`Error::EmptyLevelSet`] when no grid cell is crossed by the zero level.
    pub fn new(spec: &BuildSpec<'_, D2>, opts: DtGrid2Options) -> Result<DtGrid2Backend> {
        let (lo, hi) = spec.domain;
        let ext = hi - lo;
        if !(lo.is_finite() && hi.is_finite() && ext.min_element() > 0.0) {
            return Err(Error::InvalidInput(format!(
                "planar band: the domain {lo:?}..{hi:?} must be a finite box of positive size"
            )));
        }
        let res = spec.resolution;
        if !positive(res) {
            return Err(Error::InvalidInput(format!(
                "planar band: the resolution must be finite and positive (got {res})"
            )));
        }
        let j = opts.mcf.j;
        let rates = [opts.tau_per_h2, opts.tau_per_h, opts.cfl, opts.mcf.eps];
        if j == 0 || !rates.iter().all(|&x| positive(x) || x == f64::INFINITY) {
            return Err(Error::InvalidInput(format!(
                "planar band: half-width j = {j}, tau/h² = {}, tau/h = {}, advection sub-step {} \
                 cells and eps = {} must be positive",
                opts.tau_per_h2, opts.tau_per_h, opts.cfl, opts.mcf.eps
            )));
        }
        if opts.mcf.inner == 0 {
            return Err(Error::InvalidInput(
                "planar band: at least one solve per mean curvature step".into(),
            ));
        }
        let side = ext.max_element();
        let cells = (side / res - 1e-9).ceil().max(1.0);
        if cells > 16384.0 {
            return Err(Error::TooLarge(format!(
                "planar band: {cells} cells per side (resolution {res} on a side of {side}; at \
                 most 16384)"
            )));
        }
        let cells = cells as usize;
        if 2 * (j + 1) >= cells {
            return Err(Error::InvalidInput(format!(
                "planar band: a band of half-width j = {j} is wider than the grid of {cells} \
                 cells per side (resolution {res})"
            )));
        }
        let plane = Plane::new(cells + 1, side / cells as f64)?;
        let f = spec.function;
        let local = |p: DVec2| f.distance(p + lo);
        let state = PlaneMcf::new(plane, j, &local)?;
        let b = DtGrid2Backend {
            state,
            shift: lo,
            top: ext,
            time: 0.0,
            opts,
        };
        b.check_fit("the initial zero level")?;
        Ok(b)
    }

    /// The options.
    pub fn options(&self) -> &DtGrid2Options {
        &self.opts
    }

    /// The grid (local coordinates: world = local + [`DtGrid2Backend::shift`]).
    pub fn plane(&self) -> &Plane {
        &self.state.plane
    }

    /// The world position of the grid's local origin.
    pub fn shift(&self) -> DVec2 {
        self.shift
    }

    /// The band nodes.
    pub fn band(&self) -> &Grid2 {
        &self.state.nb.band
    }

    /// The values of `u` at the band nodes, in storage order.
    pub fn values(&self) -> &[f64] {
        &self.state.phi
    }

    fn field(&self) -> Field<'_> {
        Field {
            plane: &self.state.plane,
            band: &self.state.nb.band,
            u: &self.state.phi,
        }
    }

    /// The displacement bound of an advection sub-step in cells: `cfl`, at most `j`.
    fn cfl(&self) -> f64 {
        self.opts.cfl.min(self.state.nb.j as f64)
    }

    /// Error unless every band node lies in the domain box.
    fn check_fit(&self, what: &str) -> Result<()> {
        let plane = self.state.plane;
        let tol = 1e-9 * plane.h;
        if let Some(c) = self.state.nb.band.coords().find(|&c| {
            let p = plane.pos(c);
            p.x > self.top.x + tol || p.y > self.top.y + tol
        }) {
            return Err(Error::InvalidInput(format!(
                "planar band: the narrow band of {what} leaves the domain at {:?} (the shape does \
                 not fit in the domain with this band width)",
                plane.pos(c) + self.shift
            )));
        }
        Ok(())
    }

    fn finish(&self, mut rep: StepReport, t0: Instant) -> StepReport {
        rep.time = self.time;
        rep.dof = self.dof();
        rep.seconds = t0.elapsed().as_secs_f64();
        rep
    }

    /// The zero level in local coordinates; [`Error::EmptyLevelSet`] when empty.
    fn local_zero_level(&self) -> Result<ZeroLevel> {
        let z = zero_level(&self.field());
        if z.is_empty() {
            return Err(Error::EmptyLevelSet(
                "planar band: the band field has no zero level".into(),
            ));
        }
        Ok(z)
    }

    /// One semi-Lagrangian sub-step `[t1 − k, t1]` (see the module documentation).
    fn advect_substep(&mut self, v: VelocityField<'_, D2>, t1: f64, k: f64) -> Result<()> {
        let plane = self.state.plane;
        let j = self.state.nb.j;
        let old = self.field();
        let reach = self.cfl().ceil() as u32;
        let cand = old.band.dilate(reach, plane.n - 1)?;
        let coords: Vec<C2> = cand.coords().collect();
        let shift = self.shift;
        let vals: Vec<Option<f64>> = coords
            .par_iter()
            .map(|&c| {
                let x = plane.pos(c) + shift;
                // Classical Runge–Kutta backwards along dX/ds = v(s, X), X(t1) = x.
                let k1 = v(t1, x);
                let k2 = v(t1 - 0.5 * k, x - 0.5 * k * k1);
                let k3 = v(t1 - 0.5 * k, x - 0.5 * k * k2);
                let k4 = v(t1 - k, x - k * k3);
                let foot = x - k / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
                if !foot.is_finite() {
                    return Err(Error::InvalidField {
                        name: "velocity".into(),
                        msg: format!("non-finite near {x:?} at t = {t1}"),
                    });
                }
                let y = foot - shift;
                Ok(locate(&plane, y)
                    .and_then(|cell| super::cubic::Patch::of(&old, cell))
                    .map(|p| p.jet(y).value))
            })
            .collect::<Result<_>>()?;
        let known: Vec<(C2, f64)> = coords
            .iter()
            .zip(&vals)
            .filter_map(|(&c, v)| v.map(|v| (c, v)))
            .collect();
        let def_band = Grid2::from_sorted(known.iter().map(|k| k.0))?;
        let def_vals: Vec<f64> = known.iter().map(|k| k.1).collect();
        let cross: Vec<C2> = crossing_cells_of_band(&def_band, &def_vals)
            .into_iter()
            .map(|(c, _)| c)
            .collect();
        let nb = band_around(&plane, &cross, j).map_err(|e| match e {
            Error::EmptyLevelSet(_) => Error::EmptyLevelSet(format!(
                "planar band: the zero level vanished during advection at t = {t1}"
            )),
            Error::InvalidInput(m) => {
                Error::InvalidInput(format!("planar band: advection to t = {t1}: {m}"))
            }
            e => e,
        })?;
        let reach = (2 * j + 4) as f64 * plane.h;
        self.state.phi =
            extend_distance(&plane, &def_band, &def_vals, &nb.band, Keep::OldBand, reach);
        self.state.nb = nb;
        self.check_fit("the advected zero level")
    }
}

impl LevelSetBackend<D2> for DtGrid2Backend {
    fn name(&self) -> &'static str {
        "dtgrid"
    }

    fn build(spec: &BuildSpec<'_, D2>) -> Result<Self> {
        DtGrid2Backend::new(spec, DtGrid2Options::default())
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn dof(&self) -> usize {
        self.state.nb.band.len()
    }

    fn advance_mean_curvature(&mut self, dt: f64) -> Result<StepReport> {
        check_dt(dt, "planar band mean curvature step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let h = self.state.plane.h;
        let tau_max = (self.opts.tau_per_h2 * h * h).min(self.opts.tau_per_h * h);
        let steps = (dt / tau_max - 1e-9).ceil().max(1.0);
        if steps > 1e9 {
            return Err(Error::InvalidInput(format!(
                "planar band mean curvature step: dt = {dt} needs {steps} sub-steps of {tau_max}"
            )));
        }
        let steps = steps as usize;
        let tau = dt / steps as f64;
        let o = self.opts.mcf;
        for s in 0..steps {
            let r = self.state.step(tau, &o).map_err(|e| match e {
                Error::EmptyLevelSet(m) => Error::EmptyLevelSet(format!(
                    "planar band: {m} by t = {:.6}",
                    self.time + (s + 1) as f64 * tau
                )),
                e => e,
            })?;
            rep.phases.rebuild += r.times.rebuild;
            rep.phases.assembly += r.times.assembly;
            rep.phases.solve += r.times.solve;
            rep.linear_iterations += r.cg_iterations;
            rep.inner_iterations += r.solves;
            if o.bc == Bc::Dirichlet && o.inner > 1 && r.solves >= o.inner {
                rep.converged = false;
            }
            self.check_fit("the moving zero level")?;
        }
        self.time += dt;
        Ok(self.finish(rep, t0))
    }

    fn advect(&mut self, velocity: VelocityField<'_, D2>, dt: f64) -> Result<StepReport> {
        check_dt(dt, "planar band advection step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let plane = self.state.plane;
        let shift = self.shift;
        let (ta, tb) = (self.time, self.time + dt);
        let points: Vec<DVec2> = self
            .state
            .nb
            .band
            .coords()
            .map(|c| plane.pos(c) + shift)
            .collect();
        let steps = advection_substeps::<D2>(
            &points,
            velocity,
            (ta, tb),
            self.cfl() * plane.h,
            "planar band advection",
        )?;
        let k = dt / steps as f64;
        for s in 0..steps {
            self.advect_substep(velocity, ta + (s + 1) as f64 * k, k)?;
        }
        rep.phases.solve = t0.elapsed().as_secs_f64();
        rep.inner_iterations = steps;
        self.time = tb;
        Ok(self.finish(rep, t0))
    }

    fn redistance(&mut self) -> Result<StepReport> {
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let (nb, d) = rebuild(
            &self.state.plane,
            &self.state.nb,
            &self.state.phi,
            Keep::Nothing,
        )?;
        self.state.nb = nb;
        self.state.phi = d;
        rep.phases.redistance = t0.elapsed().as_secs_f64();
        self.check_fit("the redistanced zero level")?;
        Ok(self.finish(rep, t0))
    }

    fn enclosed_measure(&self) -> Result<f64> {
        Ok(self.local_zero_level()?.enclosed_area())
    }

    fn interface_measure(&self) -> Result<f64> {
        Ok(self.local_zero_level()?.length())
    }

    fn interface_curvature(&self) -> Result<CurvatureSamples<D2>> {
        let z = self.local_zero_level()?;
        let f = self.field();
        let h = self.state.plane.h;
        let samples: Vec<(DVec2, f64)> = z
            .segments
            .par_iter()
            .filter_map(|s| {
                let patch = &z.cells[s.cell as usize];
                let x = s.mid;
                let p0 = f.plane.pos(patch.cell);
                let xi = [(x.x - p0.x) / h, (x.y - p0.y) / h].map(|t| t.clamp(0.0, 1.0));
                let mut k = 0.0;
                for c in 0..4 {
                    let w = (if c & 1 == 1 { xi[0] } else { 1.0 - xi[0] })
                        * (if c & 2 == 2 { xi[1] } else { 1.0 - xi[1] });
                    match node_curvature(&f, patch.cell.corner(c)) {
                        Some(kc) => k += w * kc,
                        None => return patch.jet(x).curvature().map(|k| (x + self.shift, k)),
                    }
                }
                Some((x + self.shift, k))
            })
            .collect();
        if samples.is_empty() {
            return Err(Error::EmptyLevelSet(
                "planar band: no curvature sample on the zero level".into(),
            ));
        }
        Ok(CurvatureSamples {
            points: samples.iter().map(|s| s.0).collect(),
            values: samples.iter().map(|s| s.1).collect(),
        })
    }

    fn zero_level(&self) -> Result<Vec<Polyline>> {
        Ok(self.local_zero_level()?.shifted(self.shift))
    }

    fn evaluate(&self, points: &[DVec2]) -> Result<Vec<Option<f64>>> {
        let tol = 1e-9 * self.state.plane.h;
        let f = self.field();
        Ok(points
            .iter()
            .map(|&p| {
                let x = p - self.shift;
                let inside = x.min_element() >= -tol && (self.top - x).min_element() >= -tol;
                if !inside || !x.is_finite() {
                    return None;
                }
                let cell = locate(f.plane, x)?;
                let mut c = [0.0; 4];
                for (k, ck) in c.iter_mut().enumerate() {
                    *ck = f.at(cell.corner(k))?;
                }
                let patch = super::cubic::Patch::linear(f.plane, cell, c);
                Some(patch.jet(x).value)
            })
            .collect())
    }
}
