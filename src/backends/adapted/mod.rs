//! The anisotropic adapted mesh of 004 as a level-set back end: a triangulation adapted to the
//! geometric metric of 004 eq. (6) of the level set `u` (a signed distance), re-adapted whenever
//! the zero level moves.
//!
//! - **Build** ([`AdaptedBackend::new`]): [`crate::adapt::adapt_to_shape`] with the implicit
//!   function `f` seen through [`Normalized`] (`f/|∇f|`: the same zero level, a unit gradient
//!   on it, smooth, whether or not `f` is a distance), then a re-adaptation (below), then the
//!   exact values of `f/|∇f|` at the vertices; when `f` is not a distance
//!   ([`Shape::is_distance`]), they are blended into the distance to their zero level beyond
//!   the band. Redistancing a non-distance `f` instead (an
//!   ellipse `x²/a² + y²/b² − 1`) puts the curvature of the piecewise-linear zero level's
//!   distance into `u`: the recovered curvature then does not converge (mean relative error
//!   0.18 at every `h` on the ellipse of half axes 0.5, 0.3).
//! - **Re-adaptation** (after the build and every mean curvature step): when `u` is no longer
//!   close to a signed distance ([`AdaptedOptions::distance_tol`] on `||∇u_h| − 1|` over the cut
//!   triangles), redistancing ([`Redistancing`]); then the metric of eq. (6) from the
//!   least-squares derivatives of `u` (004 §4.3), graded, and [`crate::adapt::adapt`] with the
//!   quadratic reconstruction of `u` (exact for quadratics) evaluated at every new or moved
//!   vertex, so the remeshing does not move a smooth zero level by the P1 interpolation error.
//!   Redistancing only on demand keeps `u` smooth: the exact distance to the piecewise-linear
//!   zero level has its curvature concentrated at the polyline's corners, which biases the
//!   recovered curvature sampled on the zero level (measured on a circle of radius 0.5 at
//!   `h = 0.0025`: mean curvature 1.2% high after redistancing, 0.02% high before).
//! - **Mean curvature** (`u_t = |∇u| div(∇u/|∇u|)`, 000 eq. (2.4)), one implicit P1 step with
//!   natural conditions on the box, then the re-adaptation; two schemes
//!   ([`McfScheme`]). For a signed distance `|∇u| = 1`, so the equation is the heat equation
//!   `u_t = Δu` near the zero level, and [`McfScheme::Heat`] takes
//!   `(M + dt K) u^{n+1} = M u^n`. The P1 stiffness applied to the interpolant of a curved
//!   distance is not a consistent Laplacian on stretched elements (measured on a circle of
//!   radius 0.5 at `h = 0.005`: `−M⁻¹K u` is `1.41/r` at the vertices near the interface, `1.03/r`
//!   on an isotropic mesh of the same `h`), so the default [`McfScheme::RecoveredCurvature`]
//!   takes the speed `f = |∇u| div(∇u/|∇u|)` from the recovered derivatives (the cubic fit of
//!   `cubic.rs` near the zero level) and keeps a stiffness only as an implicit smoother of the
//!   increment: `(M + dt K_t)(u^{n+1} − u^n) = dt M f`, with `K_t` the stiffness of the
//!   diffusion along the level lines of `uⁿ` (coefficient `I − n nᵀ` on each triangle, the
//!   stiff part of the linearised operator). A perturbation of the zero level of wavelength
//!   `λ` is damped by `1/(1 + dt (2π/λ)²)`, as in the implicit heat step. The isotropic
//!   smoother `K` damps as well but adds `dt² M⁻¹K f` per step, and `M⁻¹K` is the inconsistent
//!   Laplacian of the stretched elements: its bias grows like the aspect ratio `~h^{-1/2}`, and
//!   the radius error of the shrinking circle (`R0 = 0.5`, `T = 0.06`, `dt = 0.4h`) fell only
//!   from 2.6e-3 to 1.7e-3 from `h = 0.01` to `0.005` (order 0.65), always too small; with
//!   `K_t` it is 1.4e-3 and 6.6e-4 (order 1.09). [`McfScheme::SemiImplicit`] is 000's scheme
//!   (2.4)–(2.5) for comparison.
//! - **Re-adaptation during the flow** (optional, [`AdaptedOptions::readapt_shift`]): only
//!   when `u` has changed by more than a fraction of `h` at the interface since the last one.
//! - **Advection**: the characteristics-Galerkin step of 004 eq. (2) inside the transient fixed
//!   point of 004 §3.5 ([`crate::advect::advance_period`]), optionally followed by the mass
//!   correction of 004 §5.1.
//! - **Curvature**: `div(∇u/|∇u|)` from the recovered gradient and Hessian, sampled where the
//!   zero level crosses the edges.
//!
//! In 3D, [`AdaptedBackend3`] (`tet.rs`) is the adapted tetrahedral mesh of 004 §5 with 000's
//! semi-implicit mean curvature step (2.4)–(2.5) on it (`mcf3.rs`).

mod cubic;
mod curvature;
mod mcf;
mod mcf3;
mod source;
mod tet;

pub use tet::{Adapted3Options, AdaptedBackend3};

use super::{
    check_dt, BuildSpec, CurvatureSamples, LevelSetBackend, StepReport, VelocityField, D2,
};
use crate::adapt::{adapt, adapt_to_shape, AdaptOptions, LevelSetMetric, ShapeAdaptOptions};
use crate::advect::characteristics::locate_all;
use crate::advect::{advance_period, correct_mass, FixedPointOptions, LevelSetAdapter};
use crate::error::{Error, Result};
use crate::fem::CgOptions;
use crate::levelset::redistance::{redistance_geometric, redistance_ppr, PprOptions};
use crate::levelset::{
    enclosed_area, extract_zero_level, interface_length, Normalized, Polyline, Shape,
};
use crate::mesh::{Location, Mesh2};
use crate::metric::Sym2;
use crate::DVec2;
use source::{distance_defect, QuadraticSource};
use std::time::Instant;

/// The time discretisation of mean curvature motion on the adapted mesh (module
/// documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum McfScheme {
    /// The implicit P1 heat step `(M + dt K) u^{n+1} = M u^n`.
    Heat,
    /// The increment `(M + dt K)(u^{n+1} − u^n) = dt M f` with the recovered speed
    /// `f = |∇u| div(∇u/|∇u|)`.
    #[default]
    RecoveredCurvature,
    /// The semi-implicit scheme of 000 eq. (2.4)–(2.5): `(M[uⁿ] + dt L[uⁿ]) uⁿ⁺¹ = M[uⁿ] uⁿ`
    /// with the lumped mass and the stiffness weighted by `|∇uⁿ|_ε⁻¹` on each element.
    SemiImplicit,
}

/// How the adapted back end redistances.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Redistancing {
    /// The exact distance to the piecewise-linear zero level (004 §2.2).
    #[default]
    Geometric,
    /// PPR gradient recovery and oblique projection onto the zero level, fast marching beyond
    /// (003 §6).
    Ppr,
}

/// Options of [`AdaptedBackend`]. Lengths are given in units of the resolution `h` of the
/// [`BuildSpec`] (`hmin` of 004 eq. (6)), so one set of options serves every resolution.
#[derive(Debug, Clone)]
pub struct AdaptedOptions {
    /// The interface error bound ε of eq. (6), in units of `h`.
    pub eps: f64,
    /// The half-width of the band where eq. (6) applies, in units of `h`.
    pub band: f64,
    /// The largest element size, as a fraction of the longest side of the domain.
    pub hmax: f64,
    /// The largest ratio of element sizes (anisotropy).
    pub max_aniso: f64,
    /// The growth rate of the sizes outside the band ([`LevelSetMetric::grade`]).
    pub grade: f64,
    /// The metric gradation factor of every re-adaptation ([`crate::metric::gradate`]), or
    /// `None`.
    pub gradation: Option<f64>,
    /// The remeshing options of every adaptation.
    pub adapt: AdaptOptions,
    /// Cells per side of the initial grid of the build.
    pub coarse_cells: usize,
    /// Adaptation rounds of the build ([`ShapeAdaptOptions::max_rounds`]).
    pub build_rounds: usize,
    /// Adaptation rounds of each re-adaptation; rounds stop early when the vertex count changes
    /// by less than `readapt_tol`.
    pub readapt_rounds: usize,
    /// See `readapt_rounds`.
    pub readapt_tol: f64,
    /// The transient fixed point of each advection step (004 §3.5).
    pub fixed_point: FixedPointOptions,
    /// Restore the enclosed area after each advection step by a constant shift of `u`
    /// (004 §5.1).
    pub mass_correction: bool,
    /// The redistancing method.
    pub redistancing: Redistancing,
    /// The build and the mean curvature steps redistance `u` when the area-weighted mean of
    /// `||∇u_h| − 1|` over the cut triangles exceeds this; otherwise `u` is kept (module
    /// documentation). Measured on a circle of radius 0.5 shrinking to t = 0.06 (h = 0.005,
    /// dt = 0.002): radius error 3.1e-3 at 0.05, 2.4e-3 at 0.15, 1.6e-3 at 0.3 (no
    /// redistancing needed in that run).
    pub distance_tol: f64,
    /// The scheme of the mean curvature step.
    pub mcf: McfScheme,
    /// The conjugate-gradient solve of the mean curvature step.
    pub cg: CgOptions,
    /// The weight `θ` of the implicit smoother of [`McfScheme::RecoveredCurvature`]:
    /// `(M + θ dt K)(u^{n+1} − u^n) = dt M f`.
    pub smoothing: f64,
    /// The smoother of [`McfScheme::RecoveredCurvature`] diffuses along the level lines of `uⁿ`
    /// only (`K` with the coefficient `I − n nᵀ`) rather than isotropically.
    pub tangential_smoothing: bool,
    /// Two-stage (Heun) recovered-curvature step: the speed is averaged between `uⁿ` and the
    /// predictor.
    pub heun: bool,
    /// The curvature and the speed near the zero level from the cubic fit (`cubic.rs`) rather
    /// than the quadratic one of 004 §4.3.
    pub cubic: bool,
    /// A mean curvature step re-adapts the mesh only when `u` has changed by more than this
    /// (in units of `h`) at a vertex of a cut triangle since the last adaptation; 0 re-adapts
    /// after every step.
    pub readapt_shift: f64,
}

impl Default for AdaptedOptions {
    fn default() -> Self {
        AdaptedOptions {
            eps: 0.1,
            band: 3.0,
            hmax: 0.05,
            max_aniso: 1e4,
            grade: 1.0,
            gradation: Some(2.0),
            adapt: AdaptOptions::default().max_cycles(4),
            coarse_cells: 20,
            build_rounds: 8,
            readapt_rounds: 2,
            readapt_tol: 0.02,
            fixed_point: FixedPointOptions::default(),
            mass_correction: false,
            mcf: McfScheme::default(),
            redistancing: Redistancing::default(),
            distance_tol: 0.3,
            cg: CgOptions {
                rtol: 1e-12,
                ..CgOptions::default()
            },
            smoothing: 1.0,
            tangential_smoothing: true,
            heun: false,
            cubic: true,
            readapt_shift: 0.0,
        }
    }
}

impl AdaptedOptions {
    /// The metric of eq. (6) for resolution `h` on a domain whose longest side is `side`.
    pub fn metric(&self, h: f64, side: f64) -> Result<LevelSetMetric> {
        let m = LevelSetMetric {
            eps: self.eps * h,
            hmin: h,
            hmax: (self.hmax * side).max(h),
            max_aniso: self.max_aniso,
            band: self.band * h,
            grade: self.grade,
            analytic: true,
            isotropic: false,
        };
        m.validate()?;
        let non_negative = |x: f64| x >= 0.0;
        if self.readapt_rounds == 0
            || !non_negative(self.readapt_tol)
            || !non_negative(self.distance_tol)
        {
            return Err(Error::InvalidInput(format!(
                "adapted back end: need readapt_rounds >= 1, readapt_tol >= 0 and \
                 distance_tol >= 0 (got {}, {}, {})",
                self.readapt_rounds, self.readapt_tol, self.distance_tol
            )));
        }
        Ok(m)
    }
}

/// The anisotropic adapted-mesh back end (module documentation): a [`Mesh2`] and a P1 level set
/// on it.
#[derive(Debug, Clone)]
pub struct AdaptedBackend {
    mesh: Mesh2,
    u: Vec<f64>,
    time: f64,
    metric: LevelSetMetric,
    opts: AdaptedOptions,
    /// `u` at the last adaptation of the current mesh.
    u_adapted: Vec<f64>,
}

/// A borrowed implicit function as a [`Shape`] (for [`Normalized`]).
struct ByRef<'a>(&'a dyn Shape);

impl Shape for ByRef<'_> {
    fn distance(&self, p: DVec2) -> f64 {
        self.0.distance(p)
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.0.gradient(p)
    }
    fn hessian(&self, p: DVec2) -> Sym2 {
        self.0.hessian(p)
    }
    fn corners(&self) -> Vec<DVec2> {
        self.0.corners()
    }
    fn name(&self) -> String {
        self.0.name()
    }
}

impl AdaptedBackend {
    /// Builds the back end for `spec` with options `opts` (module documentation). Errors:
    /// invalid options, resolution or domain; no zero level in the domain.
    pub fn new(spec: &BuildSpec<'_, D2>, opts: AdaptedOptions) -> Result<AdaptedBackend> {
        let (lo, hi) = spec.domain;
        if !(lo.is_finite() && hi.is_finite() && lo.x < hi.x && lo.y < hi.y) {
            return Err(Error::InvalidInput(format!(
                "adapted back end: the domain ({lo}, {hi}) is not a box"
            )));
        }
        let side = (hi - lo).max_element();
        if !(spec.resolution > 0.0 && spec.resolution < side) {
            return Err(Error::InvalidInput(format!(
                "adapted back end: the resolution must lie in (0, {side}) (got {})",
                spec.resolution
            )));
        }
        let metric = opts.metric(spec.resolution, side)?;
        let shape_opts = ShapeAdaptOptions {
            metric,
            adapt: opts.adapt.clone(),
            coarse_cells: opts.coarse_cells,
            max_rounds: opts.build_rounds,
            gradation: opts.gradation,
            ..ShapeAdaptOptions::default()
        };
        // `f/|∇f|`: exact zero level, unit gradient on it, smooth (module documentation).
        let normalized = Normalized {
            inner: ByRef(spec.function),
            cap: (hi - lo).length(),
        };
        let (mesh, u, _) = adapt_to_shape(&normalized, spec.domain, &shape_opts)?;
        if !(u.iter().any(|&v| v < 0.0) && u.iter().any(|&v| v >= 0.0)) {
            return Err(Error::EmptyLevelSet(format!(
                "the implicit function '{}' has no zero level in the domain ({lo}, {hi})",
                spec.function.name()
            )));
        }
        let mut b = AdaptedBackend {
            mesh,
            u,
            time: 0.0,
            metric,
            opts,
            u_adapted: Vec::new(),
        };
        b.readapt(&mut StepReport::default())?;
        // The re-adaptation transferred `u` by reconstruction; the function itself is at hand.
        b.u = b
            .mesh
            .points
            .iter()
            .map(|&p| normalized.distance(p))
            .collect();
        if !spec.function.is_distance() {
            b.u = blend_with_distance(&b.mesh, &b.u, b.opts.band * spec.resolution)?;
        }
        b.u_adapted = b.u.clone();
        Ok(b)
    }

    /// The current mesh.
    pub fn mesh(&self) -> &Mesh2 {
        &self.mesh
    }

    /// The level set at the vertices of [`AdaptedBackend::mesh`].
    pub fn values(&self) -> &[f64] {
        &self.u
    }

    /// The metric of eq. (6) the mesh is adapted to.
    pub fn level_set_metric(&self) -> &LevelSetMetric {
        &self.metric
    }

    /// Redistances `u` when it is no longer close to a signed distance (module documentation),
    /// then re-adapts the mesh to it; adds the times and rounds to `rep`.
    fn readapt(&mut self, rep: &mut StepReport) -> Result<()> {
        let t = Instant::now();
        if distance_defect(&self.mesh, &self.u) > self.opts.distance_tol {
            self.u = self.redistanced()?;
        }
        rep.phases.redistance += t.elapsed().as_secs_f64();
        let t = Instant::now();
        let source = QuadraticSource::new(&self.mesh, &self.u)?;
        let mut converged = false;
        for _ in 0..self.opts.readapt_rounds {
            let n0 = self.mesh.n_points();
            let mut metric = self.metric.field_from_p1(&self.mesh, &self.u)?;
            if let Some(beta) = self.opts.gradation {
                crate::metric::gradate(&self.mesh, &mut metric, beta)?;
            }
            let mut fields = vec![std::mem::take(&mut self.u)];
            let r = adapt(
                &mut self.mesh,
                &mut metric,
                &mut fields,
                Some(&source),
                &self.opts.adapt,
            )?;
            self.u = fields.pop().unwrap_or_default();
            rep.inner_iterations += 1;
            let n1 = self.mesh.n_points();
            if r.converged && (n1 as f64 - n0 as f64).abs() <= self.opts.readapt_tol * n1 as f64 {
                converged = true;
                break;
            }
        }
        rep.converged &= converged;
        rep.phases.rebuild += t.elapsed().as_secs_f64();
        self.u_adapted = self.u.clone();
        Ok(())
    }

    /// Whether `u` has changed by more than [`AdaptedOptions::readapt_shift`] × h at a vertex of
    /// a triangle cut by the zero level of `u` or of the `u` of the last adaptation.
    fn moved_out(&self) -> bool {
        let limit = self.opts.readapt_shift * self.metric.hmin;
        if limit <= 0.0 || self.u_adapted.len() != self.u.len() {
            return true;
        }
        let cut = |f: &[f64], t: &[usize; 3]| {
            let neg = t.iter().filter(|&&v| f[v] < 0.0).count();
            neg != 0 && neg != 3
        };
        self.mesh.live_tris().any(|t| {
            let tri = self.mesh.tris[t].map(|v| v as usize);
            (cut(&self.u, &tri) || cut(&self.u_adapted, &tri))
                && tri
                    .iter()
                    .any(|&v| (self.u[v] - self.u_adapted[v]).abs() > limit)
        })
    }

    /// `u` redistanced by the method of the options.
    fn redistanced(&self) -> Result<Vec<f64>> {
        match self.opts.redistancing {
            Redistancing::Geometric => redistance_geometric(&self.mesh, &self.u),
            Redistancing::Ppr => {
                redistance_ppr(&self.mesh, &self.u, &PprOptions::default()).map(|o| o.values)
            }
        }
    }

    fn finish(&self, mut rep: StepReport, t0: Instant) -> StepReport {
        rep.time = self.time;
        rep.dof = self.mesh.n_points();
        rep.seconds = t0.elapsed().as_secs_f64();
        rep
    }
}

/// `f/|∇f|` within `width` of its zero level, the distance `d` to its P1 zero level beyond
/// `2 width`, and `d + χ (f/|∇f| − d)` between, `χ` a smooth step: a signed distance away from
/// the interface, and near it the smooth field whose recovered curvature converges (the
/// distance to a polyline has its curvature at the corners).
fn blend_with_distance(mesh: &Mesh2, n: &[f64], width: f64) -> Result<Vec<f64>> {
    let d = redistance_geometric(mesh, n)?;
    Ok(n.iter()
        .zip(&d)
        .map(|(&n, &d)| {
            let t = (d.abs() / width - 1.0).clamp(0.0, 1.0);
            let chi = 1.0 - t * t * (3.0 - 2.0 * t);
            d + chi * (n - d)
        })
        .collect())
}

impl LevelSetBackend<D2> for AdaptedBackend {
    fn name(&self) -> &'static str {
        "adapted"
    }

    fn build(spec: &BuildSpec<'_, D2>) -> Result<Self> {
        AdaptedBackend::new(spec, AdaptedOptions::default())
    }

    fn time(&self) -> f64 {
        self.time
    }

    fn dof(&self) -> usize {
        self.mesh.n_points()
    }

    fn advance_mean_curvature(&mut self, dt: f64) -> Result<StepReport> {
        check_dt(dt, "mean curvature step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let mut cost = mcf::StepCost::default();
        let width = self.opts.band * self.metric.hmin;
        let u = mcf::step(&self.mesh, &self.u, dt, width, &self.opts, &mut cost)?;
        rep.phases.assembly += cost.assembly;
        rep.phases.solve += cost.solve;
        rep.linear_iterations += cost.iterations;
        rep.converged &= cost.converged;
        if !u.iter().any(|&v| v < 0.0) {
            return Err(Error::EmptyLevelSet(format!(
                "the inside vanished by mean curvature before t = {}",
                self.time + dt
            )));
        }
        self.u = u;
        self.time += dt;
        if self.moved_out() {
            self.readapt(&mut rep)?;
        }
        Ok(self.finish(rep, t0))
    }

    fn advect(&mut self, velocity: VelocityField<'_, D2>, dt: f64) -> Result<StepReport> {
        check_dt(dt, "advection step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let area = if self.opts.mass_correction {
            Some(enclosed_area(&self.mesh, &self.u)?)
        } else {
            None
        };
        let mut adapter = LevelSetAdapter::new(self.metric, self.opts.adapt.clone())?;
        let period = advance_period(
            &self.mesh,
            &self.u,
            &velocity,
            self.time,
            self.time + dt,
            &mut adapter,
            &self.opts.fixed_point,
        )?;
        rep.phases.rebuild += period.adapt_seconds;
        rep.phases.solve += period.advect_seconds;
        rep.inner_iterations += period.iterations;
        rep.converged &= period.converged;
        self.mesh = period.mesh;
        self.u = period.u;
        self.u_adapted = self.u.clone();
        self.time += dt;
        if let Some(target) = area {
            correct_mass(&self.mesh, &mut self.u, target, 1e-13)?;
        }
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
        enclosed_area(&self.mesh, &self.u)
    }

    fn interface_measure(&self) -> Result<f64> {
        interface_length(&self.mesh, &self.u)
    }

    fn interface_curvature(&self) -> Result<CurvatureSamples<D2>> {
        curvature::curvature_samples(&self.mesh, &self.u, self.opts.cubic)
    }

    fn zero_level(&self) -> Result<Vec<Polyline>> {
        extract_zero_level(&self.mesh, &self.u)
    }

    fn evaluate(&self, points: &[DVec2]) -> Result<Vec<Option<f64>>> {
        let locs = locate_all(&self.mesh, points, None)?;
        Ok(locs
            .iter()
            .map(|l| match *l {
                Location::Inside { tri, bary } => {
                    let t = self.mesh.tris[tri as usize];
                    Some((0..3).map(|k| bary[k] * self.u[t[k] as usize]).sum())
                }
                Location::Outside { .. } => None,
            })
            .collect())
    }
}
