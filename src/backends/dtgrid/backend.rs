//! The DT-Grid narrow band behind the level-set back-end contract
//! ([`crate::backends::LevelSetBackend`] for [`D3`]): a signed distance stored on the band of
//! half-width `j` cells around its zero level in a uniform grid (000 §2.3, §3).
//!
//! - **Build**: the grid covers the cube spanned by the domain's longest side with spacing at
//!   most `resolution`; the band is `I^{j+1}` around the cells the zero level crosses, carrying
//!   the signed distance to the marching-tetrahedra zero level ([`super::mcf::McfState::new`]).
//! - **Mean curvature**: sub-steps of at most `tau_per_h2 · h²` of 000 (2.5) with Dirichlet
//!   conditions and the nested inner iteration of 000 §2.4 ([`super::mcf::McfState::step`]).
//! - **Advection**: semi-Lagrangian sub-steps moving the zero level at most `cfl ≤ j` cells:
//!   the band dilated by that many cells takes `u(t, X)` at the foot `X` of its characteristic
//!   (classical Runge–Kutta backwards in time; tricubic Catmull–Rom interpolation in the old
//!   band, Q1 near its edge), the band is rebuilt around the new zero level, and nodes whose
//!   foot left the old band take the signed distance to it.
//! - **Redistance**: the signed distance to the zero level on the band rebuilt around it.
//! - **Measures**: volume and area of the marching-tetrahedra zero level.
//! - **Curvature**: `div(∇u/|∇u|)` by central differences at the nodes, smoothed by a
//!   binomial filter, Q1-interpolated to the triangle centroids of the zero level
//!   ([`super::probe`]).
//! - **Evaluate**: the Q1 interpolant in cells whose corners are all band nodes, `None`
//!   elsewhere.

use super::band::Band;
use super::grid::DtGrid;
use super::lattice::{band_around, crossing_cells_of_band, Lattice, NarrowBand, C3};
use super::mcf::{rebuild, McfOptions, McfState};
use super::probe::{curvature_at, sample, sample_cubic};
use super::surface::{signed_distance, zero_level};
use crate::backends::{
    advection_substeps, check_dt, BuildSpec, CurvatureSamples, LevelSetBackend, StepReport,
    VelocityField, D3,
};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::levelset::TriangleSurface;
use rayon::prelude::*;
use std::collections::HashMap;
use std::time::Instant;

/// The band storage of the back end.
pub type Grid3 = DtGrid<C3>;

/// The options of the DT-Grid back end.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct DtGridOptions {
    /// The mean curvature scheme: band half-width `j`, boundary condition, solves per step.
    pub mcf: McfOptions,
    /// The longest mean curvature sub-step in units of `h²` (000 Table 2.2's best: 1).
    pub tau_per_h2: f64,
    /// The largest displacement of an advection sub-step, in cells (at most `j` are used).
    pub cfl: f64,
}

impl Default for DtGridOptions {
    /// `j = 2`, Dirichlet conditions with up to 5 solves per step, `τ ≤ h²`, 2 cells per
    /// advection sub-step.
    fn default() -> DtGridOptions {
        DtGridOptions {
            mcf: McfOptions {
                j: 2,
                ..McfOptions::default()
            },
            tau_per_h2: 1.0,
            cfl: 2.0,
        }
    }
}

/// A level-set function on a DT-Grid narrow band (see the module documentation).
#[derive(Debug, Clone)]
pub struct DtGridBackend {
    state: McfState<Grid3>,
    /// World position of the grid's local origin: `x_world = x_local + shift`.
    shift: DVec3,
    /// The domain's upper corner in local coordinates.
    top: DVec3,
    time: f64,
    opts: DtGridOptions,
}

impl DtGridBackend {
    /// Builds the band from `spec` with options `opts`.
    /// Errors: [`Error::InvalidInput`] for a bad domain, resolution or options, a band wider than
    /// the grid, or a zero level whose band does not fit in the domain;
    /// [`Error::InvalidField`] for a NaN of the function at a grid node;
    /// [`Error::EmptyLevelSet`] when no grid cell is crossed by the zero level.
    pub fn new(spec: &BuildSpec<'_, D3>, opts: DtGridOptions) -> Result<DtGridBackend> {
        let (lo, hi) = spec.domain;
        let ext = hi - lo;
        if !(lo.is_finite() && hi.is_finite() && ext.min_element() > 0.0) {
            return Err(Error::InvalidInput(format!(
                "dtgrid: the domain {lo:?}..{hi:?} must be a finite box of positive size"
            )));
        }
        let res = spec.resolution;
        if !(res.is_finite() && res > 0.0) {
            return Err(Error::InvalidInput(format!(
                "dtgrid: the resolution must be finite and positive (got {res})"
            )));
        }
        let j = opts.mcf.j;
        if j == 0 || !(opts.tau_per_h2 > 0.0 && opts.tau_per_h2.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "dtgrid: band half-width j = {j} and tau/h² = {} must be positive",
                opts.tau_per_h2
            )));
        }
        if !(opts.cfl > 0.0 && opts.cfl.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "dtgrid: the advection sub-step of {} cells must be positive",
                opts.cfl
            )));
        }
        let side = ext.max_element();
        let cells = (side / res - 1e-9).ceil().max(1.0);
        if cells > (1u64 << 30) as f64 {
            return Err(Error::TooLarge(format!(
                "dtgrid: {cells} cells per side (resolution {res} on a side of {side})"
            )));
        }
        let cells = cells as usize;
        if 2 * (j + 1) >= cells {
            return Err(Error::InvalidInput(format!(
                "dtgrid: a band of half-width j = {j} is wider than the grid of {cells} cells per \
                 side (resolution {res})"
            )));
        }
        let lat = Lattice {
            n: cells + 1,
            h: side / cells as f64,
            lo: 0.0,
        };
        let f = spec.function;
        let local = |p: DVec3| f(p + lo);
        let state = McfState::new(lat, j, &local)?;
        let b = DtGridBackend {
            state,
            shift: lo,
            top: ext,
            time: 0.0,
            opts,
        };
        b.check_fit("the initial zero level")?;
        Ok(b)
    }

    /// The displacement bound of an advection sub-step in cells: `cfl`, at most `j`.
    fn cfl(&self) -> f64 {
        self.opts.cfl.min(self.state.nb.j as f64)
    }

    /// The options.
    pub fn options(&self) -> &DtGridOptions {
        &self.opts
    }

    /// The grid (local coordinates: world = local + [`DtGridBackend::shift`]).
    pub fn lattice(&self) -> &Lattice {
        &self.state.lat
    }

    /// The world position of the grid's local origin.
    pub fn shift(&self) -> DVec3 {
        self.shift
    }

    /// The band nodes.
    pub fn band(&self) -> &Grid3 {
        &self.state.nb.band
    }

    /// The values of `u` at the band nodes, in storage order.
    pub fn values(&self) -> &[f64] {
        &self.state.phi
    }

    /// The world position of grid node `c`.
    pub fn node_position(&self, c: C3) -> DVec3 {
        self.state.lat.pos(c) + self.shift
    }

    /// Error unless every band node lies in the domain box.
    fn check_fit(&self, what: &str) -> Result<()> {
        let tol = 1e-9 * self.state.lat.h;
        let lat = self.state.lat;
        if let Some(c) = self.state.nb.band.coords().find(|&c| {
            let p = lat.pos(c);
            p.x > self.top.x + tol || p.y > self.top.y + tol || p.z > self.top.z + tol
        }) {
            return Err(Error::InvalidInput(format!(
                "dtgrid: the narrow band of {what} leaves the domain at {:?} (the shape does not \
                 fit in the domain with this band width)",
                lat.pos(c) + self.shift
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

    /// The zero level in local coordinates with its cells; [`Error::EmptyLevelSet`] when empty.
    fn local_zero_level(&self) -> Result<super::surface::ZeroLevel> {
        let z = zero_level(&self.state.lat, &self.state.nb.band, &self.state.phi);
        if z.surface.triangles.is_empty() {
            return Err(Error::EmptyLevelSet(
                "dtgrid: the band field has no zero level".into(),
            ));
        }
        Ok(z)
    }

    /// One semi-Lagrangian sub-step `[t1 − k, t1]` (see the module documentation).
    fn advect_substep(&mut self, v: VelocityField<'_, D3>, t1: f64, k: f64) -> Result<()> {
        let lat = self.state.lat;
        let j = self.state.nb.j;
        let (old, phi) = (&self.state.nb.band, &self.state.phi);
        let reach = self.cfl().ceil() as u32;
        let cand = old.dilate(reach, lat.n - 1)?;
        let coords: Vec<C3> = cand.coords().collect();
        let shift = self.shift;
        let vals: Vec<Option<f64>> = coords
            .par_iter()
            .map(|&c| {
                let x = lat.pos(c) + shift;
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
                Ok(sample_cubic(&lat, old, phi, foot - shift))
            })
            .collect::<Result<_>>()?;
        let known: Vec<(C3, f64)> = coords
            .iter()
            .zip(&vals)
            .filter_map(|(&c, v)| v.map(|v| (c, v)))
            .collect();
        let def_band = Grid3::from_sorted(known.iter().map(|k| k.0))?;
        let def_vals: Vec<f64> = known.iter().map(|k| k.1).collect();
        let cross = crossing_cells_of_band(&def_band, &def_vals);
        let nb: NarrowBand<Grid3> = band_around(&lat, &cross, j).map_err(|e| match e {
            Error::EmptyLevelSet(_) => Error::EmptyLevelSet(format!(
                "dtgrid: the zero level vanished during advection at t = {t1}"
            )),
            Error::InvalidInput(m) => {
                Error::InvalidInput(format!("dtgrid: advection to t = {t1}: {m}"))
            }
            e => e,
        })?;
        let z = zero_level(&lat, &def_band, &def_vals);
        let hint: Vec<Option<f64>> = nb
            .band
            .coords()
            .map(|c| def_band.index(c).map(|i| def_vals[i]))
            .collect();
        let d = signed_distance(&lat, &nb.band, &z, 2 * j as i32 + 4, |i| hint[i]);
        self.state.phi = hint.iter().zip(&d).map(|(h, d)| h.unwrap_or(*d)).collect();
        self.state.nb = nb;
        self.check_fit("the advected zero level")
    }
}

impl LevelSetBackend<D3> for DtGridBackend {
    fn name(&self) -> &'static str {
        "dtgrid"
    }

    fn build(spec: &BuildSpec<'_, D3>) -> Result<Self> {
        DtGridBackend::new(spec, DtGridOptions::default())
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn dof(&self) -> usize {
        self.state.nb.band.len()
    }

    fn advance_mean_curvature(&mut self, dt: f64) -> Result<StepReport> {
        check_dt(dt, "dtgrid mean curvature step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let h = self.state.lat.h;
        let steps = (dt / (self.opts.tau_per_h2 * h * h) - 1e-9).ceil().max(1.0);
        if steps > 1e9 {
            return Err(Error::InvalidInput(format!(
                "dtgrid mean curvature step: dt = {dt} needs {steps} sub-steps of h² = {}",
                h * h
            )));
        }
        let steps = steps as usize;
        let tau = dt / steps as f64;
        let o = self.opts.mcf;
        for s in 0..steps {
            let r = self.state.step(tau, &o).map_err(|e| match e {
                Error::EmptyLevelSet(m) => Error::EmptyLevelSet(format!(
                    "dtgrid: {m} by t = {:.6}",
                    self.time + (s + 1) as f64 * tau
                )),
                e => e,
            })?;
            rep.phases.rebuild += r.times.rebuild;
            rep.phases.assembly += r.times.assembly;
            rep.phases.solve += r.times.solve;
            rep.linear_iterations += r.cg_iterations;
            rep.inner_iterations += r.solves;
            if o.bc == super::scheme::Bc::Dirichlet && o.inner > 1 && r.solves >= o.inner {
                rep.converged = false;
            }
            self.check_fit("the moving zero level")?;
        }
        self.time += dt;
        Ok(self.finish(rep, t0))
    }

    fn advect(&mut self, velocity: VelocityField<'_, D3>, dt: f64) -> Result<StepReport> {
        check_dt(dt, "dtgrid advection step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let lat = self.state.lat;
        let shift = self.shift;
        let (ta, tb) = (self.time, self.time + dt);
        let points: Vec<DVec3> = self
            .state
            .nb
            .band
            .coords()
            .map(|c| lat.pos(c) + shift)
            .collect();
        let steps = advection_substeps::<D3>(
            &points,
            velocity,
            (ta, tb),
            self.cfl() * lat.h,
            "dtgrid advection",
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
        let (nb, d) = rebuild(&self.state.lat, &self.state.nb, &self.state.phi)?;
        self.state.nb = nb;
        self.state.phi = d;
        rep.phases.redistance = t0.elapsed().as_secs_f64();
        self.check_fit("the redistanced zero level")?;
        Ok(self.finish(rep, t0))
    }

    fn enclosed_measure(&self) -> Result<f64> {
        Ok(self.local_zero_level()?.surface.enclosed_volume())
    }

    fn interface_measure(&self) -> Result<f64> {
        Ok(self.local_zero_level()?.surface.area())
    }

    fn interface_curvature(&self) -> Result<CurvatureSamples<D3>> {
        let z = self.local_zero_level()?;
        let (lat, band, phi) = (&self.state.lat, &self.state.nb.band, &self.state.phi);
        let mut cache = HashMap::new();
        let mut out = CurvatureSamples {
            points: Vec::new(),
            values: Vec::new(),
        };
        for (t, &cell) in z.surface.triangles.iter().zip(&z.cell) {
            let [a, b, c] = t.map(|i| z.surface.points[i as usize]);
            if (b - a).cross(c - a).length() <= 1e-12 * lat.h * lat.h {
                continue;
            }
            let x = (a + b + c) / 3.0;
            if let Some(k) = curvature_at(lat, band, phi, cell, x, &mut cache) {
                out.points.push(x + self.shift);
                out.values.push(k);
            }
        }
        if out.is_empty() {
            return Err(Error::EmptyLevelSet(
                "dtgrid: no curvature sample on the zero level".into(),
            ));
        }
        Ok(out)
    }

    fn zero_level(&self) -> Result<TriangleSurface> {
        let mut s = self.local_zero_level()?.surface;
        for p in &mut s.points {
            *p += self.shift;
        }
        s.weld(1e-7 * self.state.lat.h);
        Ok(s)
    }

    fn evaluate(&self, points: &[DVec3]) -> Result<Vec<Option<f64>>> {
        let tol = 1e-9 * self.state.lat.h;
        Ok(points
            .iter()
            .map(|&p| {
                let x = p - self.shift;
                let inside = x.min_element() >= -tol && (self.top - x).min_element() >= -tol;
                if !inside {
                    return None;
                }
                sample(&self.state.lat, &self.state.nb.band, &self.state.phi, x)
            })
            .collect())
    }
}
