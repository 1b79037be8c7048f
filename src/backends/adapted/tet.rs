//! The anisotropic adapted tetrahedral mesh of 004 §5 as a 3D level-set back end
//! ([`AdaptedBackend3`]).
//!
//! - **Build**: [`crate::adapt::run3`] adapts the Kuhn mesh of the box to the geometric metric of
//!   004 eq. (6) of the implicit function, seen through `u/|∇u|` (derivatives by central
//!   differences: the 3D contract gives values only); `u` is `u/|∇u|` at the vertices (the
//!   signed distance for a distance function).
//! - **Volume restoration** ([`Adapted3Options::restore_volume`], on by default): the P1 zero
//!   level of the interpolant is inscribed in a convex zero level and loses `O(ε)` of the
//!   enclosed volume (the error of the shrinking sphere, 4.1e-3 / 3.1e-3 / 2.1e-3 in the radius
//!   at h = 0.2 / 0.141 / 0.1, with a constant that varies with how the adaptation realises ε).
//!   The build therefore shifts `u` by the constant that gives `{u < 0}` the volume of
//!   `{f < 0}`, that volume measured on the mesh with the tetrahedra near the zero level
//!   refined `k` times ([`implicit_volume`]; error divided by about `4^k`): 004 §5.1's mass
//!   correction, with the function's own volume as the target. A re-adaptation likewise keeps
//!   the volume of the P1 zero level it re-adapts to.
//! - **Mean curvature**: the semi-implicit P1 scheme of 000 eq. (2.4)–(2.5) on the tetrahedra
//!   (`mcf3.rs`), natural conditions on the box.
//! - **Re-adaptation on motion**: after a step, the mesh is re-adapted only when `u` has changed
//!   by more than [`Adapted3Options::readapt_shift`] × h at a vertex of a tetrahedron cut by the
//!   zero level now or at the last adaptation, i.e. when the zero level may leave the part of
//!   the band of eq. (6) where the mesh resolves it. The re-adaptation is [`run3`] from the
//!   current mesh to eq. (6) of the P1 zero level ([`DiscreteLevelSet3`]: the exact distance to
//!   it, the recovered shape operator), and the new `u` is that distance: a re-adaptation also
//!   redistances. With the default band of 2h and shift of 1.5h, a zero level that moves less
//!   than 1.5h in all is never re-adapted: one mesh adapted at the start carries the flow.
//! - **Defaults** (ε = 0.2h, band 2h, hmax a tenth of the box): on the sphere of radius 2 in
//!   `[−2.5, 2.5]³`, 5,890 / 8,952 / 12,832 vertices at h = 0.2 / 0.141 / 0.1 (ε = 0.1h with a
//!   band of 3h: 15,980 / 24,223).
//! - **Advection**: semi-Lagrangian, `u(x) ← u(X)` at the foot `X` of the characteristic by the
//!   midpoint rule in sub-steps moving no point by more than h, P1 interpolation on the
//!   current mesh; then the re-adaptation test above.
//! - **Curvature**: `div(∇u/|∇u|) = (tr D²u − n·D²u n)/|∇u|` from the least-squares gradient and
//!   Hessian of the redistanced `u` (004 §4.3), interpolated to the centroids of the pieces of
//!   the P1 zero level.

use super::mcf::StepCost;
use super::mcf3::semi_implicit_step;
use crate::adapt::{
    run3, AdaptOptions, Adapted3, Continuation3, DiscreteLevelSet3, LevelSetMetric, Run3Options,
    Target3,
};
use crate::advect::correct_volume;
use crate::backends::{
    advection_substeps, check_dt, BuildSpec, CurvatureSamples, LevelSetBackend, StepReport,
    VelocityField, D3,
};
use crate::error::{Error, Result};
use crate::fem::CgOptions;
use crate::geom::DVec3;
use crate::levelset::compare3::TetLocator;
use crate::levelset::implicit_volume::MAX_DEPTH;
use crate::levelset::redistance::redistance_geometric_cells;
use crate::levelset::{
    enclosed_measure, implicit_volume, interface_measure, Shape, TriangleSurface,
};
use crate::mesh3::Mesh3;
use crate::recovery::recover_ls3;
use rayon::prelude::*;
use std::time::Instant;

/// Options of [`AdaptedBackend3`]. Lengths are in units of the resolution `h` of the
/// [`BuildSpec`] (`hmin` of 004 eq. (6)), so one set of options serves every resolution.
#[derive(Debug, Clone)]
pub struct Adapted3Options {
    /// The interface error bound ε of eq. (6), in units of `h`.
    pub eps: f64,
    /// The half-width of the band where eq. (6) applies, in units of `h`.
    pub band: f64,
    /// The largest element size, as a fraction of the longest side of the box.
    pub hmax: f64,
    /// The largest ratio of element sizes.
    pub max_aniso: f64,
    /// Cells per side of the Kuhn start mesh of the build.
    pub cells: usize,
    /// A mean curvature or advection step re-adapts when `u` has changed by more than this
    /// (in units of `h`) at a vertex of a cut tetrahedron since the last adaptation.
    pub readapt_shift: f64,
    /// The regularisation ε of `|∇u|_ε = √(ε² + |∇u|²)` in 000 eq. (2.5).
    pub grad_eps: f64,
    /// The conjugate-gradient solve of the mean curvature step.
    pub cg: CgOptions,
    /// The largest vertex count an adaptation may reach.
    pub max_vertices: usize,
    /// Restore the enclosed volume (module documentation): `Some(k)` shifts the built `u` so
    /// that `{u < 0}` has the volume of `{f < 0}` measured with the tetrahedra near the zero
    /// level refined `k` times (at most [`crate::levelset::implicit_volume::MAX_DEPTH`]), and
    /// keeps the volume of the P1 zero level through each re-adaptation; `None` keeps the
    /// interpolant as built. Default `Some(3)`.
    pub restore_volume: Option<u32>,
}

impl Default for Adapted3Options {
    fn default() -> Self {
        Adapted3Options {
            eps: 0.2,
            band: 2.0,
            hmax: 0.1,
            max_aniso: 1e3,
            cells: 8,
            readapt_shift: 1.5,
            grad_eps: 1e-3,
            cg: CgOptions {
                rtol: 1e-10,
                ..CgOptions::default()
            },
            max_vertices: 2_000_000,
            restore_volume: Some(3),
        }
    }
}

/// The adapted tetrahedral mesh back end (module documentation): a [`Mesh3`] and a P1 level
/// set on it.
#[derive(Debug, Clone)]
pub struct AdaptedBackend3 {
    mesh: Mesh3,
    u: Vec<f64>,
    /// `u` at the last adaptation.
    u_adapted: Vec<f64>,
    time: f64,
    h: f64,
    run: Run3Options,
    opts: Adapted3Options,
    /// Adaptations so far (the build's included).
    adaptations: usize,
}

/// An implicit function given by its values as a 3D shape (derivatives by differences).
struct Implicit<'a>(&'a (dyn Fn(DVec3) -> f64 + Send + Sync + 'a));

impl Shape<DVec3> for Implicit<'_> {
    fn distance(&self, p: DVec3) -> f64 {
        (self.0)(p)
    }
    fn is_distance(&self) -> bool {
        false
    }
    fn name(&self) -> String {
        "implicit function".into()
    }
}

impl AdaptedBackend3 {
    /// Builds the back end for `spec` with options `opts` (module documentation). Errors:
    /// invalid options, resolution or box; no zero level in the box; an adaptation over the
    /// vertex limit.
    pub fn new(spec: &BuildSpec<'_, D3>, opts: Adapted3Options) -> Result<AdaptedBackend3> {
        let (lo, hi) = spec.domain;
        if !(lo.is_finite() && hi.is_finite() && lo.cmplt(hi).all()) {
            return Err(Error::InvalidInput(format!(
                "adapted 3D back end: the domain ({lo}, {hi}) is not a box"
            )));
        }
        let side = (hi - lo).max_element();
        let h = spec.resolution;
        if !(h > 0.0 && h < side) {
            return Err(Error::InvalidInput(format!(
                "adapted 3D back end: the resolution must lie in (0, {side}) (got {h})"
            )));
        }
        if !(opts.readapt_shift > 0.0 && opts.grad_eps > 0.0 && opts.cells > 0) {
            return Err(Error::InvalidInput(format!(
                "adapted 3D back end: need readapt_shift > 0, grad_eps > 0 and cells > 0 \
                 (got {}, {}, {})",
                opts.readapt_shift, opts.grad_eps, opts.cells
            )));
        }
        if let Some(depth) = opts.restore_volume.filter(|&k| k > MAX_DEPTH) {
            return Err(Error::InvalidInput(format!(
                "adapted 3D back end: restore_volume depth {depth} exceeds {MAX_DEPTH}"
            )));
        }
        let metric = LevelSetMetric {
            eps: opts.eps * h,
            hmin: h,
            hmax: (opts.hmax * side).max(h),
            max_aniso: opts.max_aniso,
            band: opts.band * h,
            grade: 1.0,
            analytic: true,
            isotropic: false,
        };
        metric.validate()?;
        let run = Run3Options {
            lo,
            hi,
            cells: opts.cells,
            metric,
            adapt: AdaptOptions::default().max_vertices(Some(opts.max_vertices)),
            // Stages with hmin and the band doubled at the target's ε: the sphere's tangential
            // sizes are the target's from the first stage.
            continuation: Continuation3::Normal,
        };
        let a = run3(Target3::Shape(&Implicit(spec.function)), None, &run)?;
        let mut u = a.level_set.unwrap_or_default();
        if !(u.iter().any(|&v| v < 0.0) && u.iter().any(|&v| v >= 0.0)) {
            return Err(Error::EmptyLevelSet(format!(
                "the implicit function has no zero level in the box ({lo}, {hi})"
            )));
        }
        if let Some(depth) = opts.restore_volume {
            let target = implicit_volume(&a.mesh.points, &a.mesh.tets, spec.function, depth)?;
            correct_volume(&a.mesh.points, &a.mesh.tets, &mut u, target, 1e-12)?;
        }
        Ok(AdaptedBackend3 {
            mesh: a.mesh,
            u_adapted: u.clone(),
            u,
            time: 0.0,
            h,
            run,
            opts,
            adaptations: 1,
        })
    }

    /// The current mesh.
    pub fn mesh(&self) -> &Mesh3 {
        &self.mesh
    }

    /// The level set at the vertices of [`AdaptedBackend3::mesh`].
    pub fn values(&self) -> &[f64] {
        &self.u
    }

    /// The number of adaptations so far, the build's included.
    pub fn adaptations(&self) -> usize {
        self.adaptations
    }

    /// Whether `u` has moved by more than the re-adaptation shift at a vertex of a tetrahedron
    /// cut by the zero level of `u` or of the `u` of the last adaptation.
    fn moved_out(&self) -> bool {
        let limit = self.opts.readapt_shift * self.h;
        let cut = |f: &[f64], t: &[u32; 4]| {
            let neg = t.iter().filter(|&&v| f[v as usize] < 0.0).count();
            neg != 0 && neg != 4
        };
        self.mesh.tets.par_iter().any(|t| {
            (cut(&self.u, t) || cut(&self.u_adapted, t))
                && t.iter()
                    .any(|&v| (self.u[v as usize] - self.u_adapted[v as usize]).abs() > limit)
        })
    }

    /// Re-adapts the mesh to eq. (6) of the current P1 zero level; `u` becomes the distance
    /// to it (module documentation).
    fn readapt(&mut self, rep: &mut StepReport) -> Result<()> {
        let t = Instant::now();
        let volume = match self.opts.restore_volume {
            Some(_) => Some(enclosed_measure(
                &self.mesh.points,
                &self.mesh.tets,
                &self.u,
            )?),
            None => None,
        };
        let a: Adapted3 = {
            let zero = DiscreteLevelSet3::new(&self.mesh.points, &self.mesh.tets, &self.u)?;
            run3(Target3::Shape(&zero), Some(&self.mesh), &self.run)?
        };
        rep.converged &= a.report.adapt.converged;
        rep.inner_iterations += 1;
        self.mesh = a.mesh;
        self.u = a.level_set.unwrap_or_default();
        if let Some(target) = volume {
            correct_volume(
                &self.mesh.points,
                &self.mesh.tets,
                &mut self.u,
                target,
                1e-12,
            )?;
        }
        self.u_adapted = self.u.clone();
        self.adaptations += 1;
        rep.phases.rebuild += t.elapsed().as_secs_f64();
        Ok(())
    }

    fn check_not_empty(&self, what: &str) -> Result<()> {
        if self.u.iter().any(|&v| v < 0.0) && self.u.iter().any(|&v| v >= 0.0) {
            Ok(())
        } else {
            Err(Error::EmptyLevelSet(format!(
                "the zero level left the box or vanished by {what} before t = {}",
                self.time
            )))
        }
    }

    fn finish(&self, mut rep: StepReport, t0: Instant) -> StepReport {
        rep.time = self.time;
        rep.dof = self.mesh.n_points();
        rep.seconds = t0.elapsed().as_secs_f64();
        rep
    }
}

impl LevelSetBackend<D3> for AdaptedBackend3 {
    fn name(&self) -> &'static str {
        "adapted"
    }

    fn build(spec: &BuildSpec<'_, D3>) -> Result<Self> {
        AdaptedBackend3::new(spec, Adapted3Options::default())
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
        let mut cost = StepCost {
            converged: true,
            ..StepCost::default()
        };
        self.u = semi_implicit_step(
            &self.mesh.points,
            &self.mesh.tets,
            &self.u,
            dt,
            self.opts.grad_eps,
            &self.opts.cg,
            &mut cost,
        )?;
        self.time += dt;
        rep.phases.assembly += cost.assembly;
        rep.phases.solve += cost.solve;
        rep.linear_iterations += cost.iterations;
        rep.converged &= cost.converged;
        self.check_not_empty("mean curvature")?;
        if self.moved_out() {
            self.readapt(&mut rep)?;
        }
        Ok(self.finish(rep, t0))
    }

    fn advect(&mut self, velocity: VelocityField<'_, D3>, dt: f64) -> Result<StepReport> {
        check_dt(dt, "advection step")?;
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        let (ta, tb) = (self.time, self.time + dt);
        let n =
            advection_substeps::<D3>(&self.mesh.points, velocity, (ta, tb), self.h, "advection")?;
        let tau = dt / n as f64;
        let loc = TetLocator::new(&self.mesh.points, &self.mesh.tets)?;
        for k in 0..n {
            let t = ta + k as f64 * tau;
            // The foot of the characteristic through x at t + τ, by the midpoint rule.
            let u = &self.u;
            self.u = self
                .mesh
                .points
                .par_iter()
                .map(|&x| {
                    let mid = x - 0.5 * tau * velocity(t + tau, x);
                    loc.interpolate(u, x - tau * velocity(t + 0.5 * tau, mid))
                })
                .collect();
        }
        rep.phases.solve += t0.elapsed().as_secs_f64();
        self.time = tb;
        self.check_not_empty("advection")?;
        if self.moved_out() {
            self.readapt(&mut rep)?;
        }
        Ok(self.finish(rep, t0))
    }

    fn redistance(&mut self) -> Result<StepReport> {
        let t0 = Instant::now();
        let mut rep = StepReport::begin();
        self.u = redistance_geometric_cells(&self.mesh.points, &self.mesh.tets, &self.u)?;
        rep.phases.redistance += t0.elapsed().as_secs_f64();
        Ok(self.finish(rep, t0))
    }

    fn enclosed_measure(&self) -> Result<f64> {
        enclosed_measure(&self.mesh.points, &self.mesh.tets, &self.u)
    }

    fn interface_measure(&self) -> Result<f64> {
        interface_measure(&self.mesh.points, &self.mesh.tets, &self.u)
    }

    fn interface_curvature(&self) -> Result<CurvatureSamples<D3>> {
        let (points, tets) = (&self.mesh.points, &self.mesh.tets);
        let d = redistance_geometric_cells(points, tets, &self.u)?;
        let r = recover_ls3(points, tets, &d)?;
        let kappa: Vec<f64> = r
            .gradient
            .iter()
            .zip(&r.hessian)
            .map(|(g, h)| {
                let len = g.length().max(1e-12);
                let n = *g / len;
                (h.trace() - h.quad(n)) / len
            })
            .collect();
        let mut out = CurvatureSamples {
            points: Vec::new(),
            values: Vec::new(),
        };
        for t in tets {
            let p = t.map(|v| points[v as usize]);
            let mut piece = TriangleSurface::default();
            piece.add_tet_zero_level(p, t.map(|v| self.u[v as usize]));
            for tri in &piece.triangles {
                let x = tri.map(|i| piece.points[i as usize]);
                let c = (x[0] + x[1] + x[2]) / 3.0;
                let w = crate::geom::simplex::barycentric(&p, c);
                out.points.push(c);
                out.values
                    .push((0..4).map(|k| w[k] * kappa[t[k] as usize]).sum());
            }
        }
        Ok(out)
    }

    fn zero_level(&self) -> Result<TriangleSurface> {
        let mut s = TriangleSurface::default();
        for t in &self.mesh.tets {
            s.add_tet_zero_level(
                t.map(|v| self.mesh.points[v as usize]),
                t.map(|v| self.u[v as usize]),
            );
        }
        s.weld(1e-9 * self.h);
        Ok(s)
    }

    fn evaluate(&self, points: &[DVec3]) -> Result<Vec<Option<f64>>> {
        let loc = TetLocator::new(&self.mesh.points, &self.mesh.tets)?;
        let tol = 1e-9 * self.h;
        let (lo, hi) = (self.run.lo, self.run.hi);
        Ok(points
            .iter()
            .map(|&p| {
                let inside = (p - lo).min_element() >= -tol && (hi - p).min_element() >= -tol;
                inside.then(|| loc.interpolate(&self.u, p))
            })
            .collect())
    }
}
