//! The Zalesak rotation, step by step: the initial mesh, one period (transport by the fixed point
//! of 004 §3.5 or on a fixed mesh, optional redistancing and mass correction), the measures after
//! each period, the final report, the comparison runs and the output files.

use std::time::Instant;

use super::exact::interface_distances;
use super::figures::write_figures;
use super::output::write_outputs;
use super::sources::ErrorSources;
use super::types::{
    Snapshot, ZalesakFrames, ZalesakMesh, ZalesakOptions, ZalesakReport, ZalesakSample,
};
use anisomesh::adapt::LevelSetMetric;
use anisomesh::advect::adapter::LevelSetAdapter;
use anisomesh::advect::fixed_point::{advance_period, Adapter, FixedPointOptions};
use anisomesh::advect::{self, Rotation};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::levelset::redistance::redistance_geometric;
use anisomesh::levelset::shapes::{Shape, Zalesak};
use anisomesh::mesh::{GridPattern, Mesh2};

/// Runs the Zalesak rotation: on a fixed uniform mesh, or with anisotropic (or isotropic)
/// adaptation and the transient fixed point of 004 §3.5 ([`LevelSetAdapter`]).
pub fn run(opts: &ZalesakOptions) -> Result<ZalesakReport> {
    run_keep(opts, opts.out_dir.is_some())
}

/// [`run`], keeping the figure frames when `keep`.
fn run_keep(opts: &ZalesakOptions, keep: bool) -> Result<ZalesakReport> {
    match opts.mesh {
        ZalesakMesh::Uniform { .. } => run_inner(opts, None, keep),
        ZalesakMesh::Adapted {
            hmin,
            stretching,
            isotropic,
        } => {
            let metric = LevelSetMetric {
                hmin,
                hmax: hmin * stretching,
                isotropic,
                ..opts.metric
            };
            let mut a = LevelSetAdapter::new(metric, opts.adapt.clone())?;
            let mut r = run_inner(opts, Some(&mut a), keep)?;
            r.adaptations = a.reports.len();
            r.adapt_cycles = a.reports.iter().map(|x| x.cycles).sum();
            Ok(r)
        }
    }
}

/// The initial mesh: a uniform grid, adapted `rounds` times to the exact level set when an
/// adapter is given (the level set is re-evaluated exactly at the vertices after each round).
fn initial_mesh(
    n: usize,
    shape: &Zalesak,
    adapter: Option<&mut (dyn Adapter + '_)>,
    rounds: usize,
) -> Result<Mesh2> {
    let lo = DVec2::splat(-2.0);
    let mut mesh = Mesh2::rectangle(lo, -lo, n, n, GridPattern::UnionJack)?;
    if let Some(a) = adapter {
        for _ in 0..rounds {
            let u: Vec<f64> = mesh.points.iter().map(|&p| shape.distance(p)).collect();
            mesh = a.adapt(&mesh, &[u])?;
        }
    }
    Ok(mesh)
}

/// Whether period `k` (of `steps` per revolution) ends at a multiple of a quarter turn.
fn quarter_turn(k: usize, steps: usize, dt: f64) -> bool {
    let q = k as f64 * dt / std::f64::consts::FRAC_PI_2;
    (q - q.round()).abs() < 1e-9 || k == steps
}

/// The time stepping of a run: `steps` periods of length `dt` over the angle `total`.
struct Clock {
    total: f64,
    steps: usize,
    dt: f64,
    /// The period whose adapted mesh is drawn: the one ending at 3π/8 (or the first).
    shown_period: usize,
}

impl Clock {
    /// The periods of `opts` (errors: no period, or a non-positive number of revolutions).
    fn new(opts: &ZalesakOptions) -> Result<Clock> {
        if opts.periods == 0 || opts.revolutions.is_nan() || opts.revolutions <= 0.0 {
            return Err(Error::InvalidInput(format!(
                "zalesak: need periods >= 1 and revolutions > 0 (got {}, {})",
                opts.periods, opts.revolutions
            )));
        }
        let total = 2.0 * std::f64::consts::PI * opts.revolutions;
        let steps = (opts.periods as f64 * opts.revolutions).round().max(1.0) as usize;
        Ok(Clock {
            total,
            steps,
            dt: total / steps as f64,
            shown_period: (steps * 3 / 16).max(1),
        })
    }
}

/// A run between two periods: the current mesh and level set, the measures so far and the
/// frames kept for the figures.
struct State {
    shape: Zalesak,
    start: Instant,
    mesh: Mesh2,
    u: Vec<f64>,
    area_initial: f64,
    perimeter_initial: f64,
    adapt_seconds: f64,
    advect_seconds: f64,
    series: Vec<ZalesakSample>,
    fp_iters: Vec<usize>,
    verts: Vec<usize>,
    frames: ZalesakFrames,
    sources: Option<ErrorSources>,
    keep: bool,
}

impl State {
    /// The initial mesh (adapted to the exact level set when `adapter` is given), the exact
    /// level set on it, its area and perimeter, and the first sample and frame.
    fn start(
        opts: &ZalesakOptions,
        clock: &Clock,
        adapter: Option<&mut (dyn Adapter + '_)>,
        keep: bool,
    ) -> Result<State> {
        let start = Instant::now();
        let shape = Zalesak::default();
        let n = match opts.mesh {
            ZalesakMesh::Uniform { n } => n,
            ZalesakMesh::Adapted { .. } => 40,
        };
        let mesh = initial_mesh(n, &shape, adapter, opts.initial_rounds)?;
        let adapt_seconds = start.elapsed().as_secs_f64();
        let u: Vec<f64> = mesh.points.iter().map(|&p| shape.distance(p)).collect();
        let area_initial = advect::enclosed_area(&mesh, &u)?;
        let perimeter_initial = advect::interface_length(&mesh, &u)?;
        let mut frames = ZalesakFrames::default();
        if keep {
            frames.snapshots.push(Snapshot {
                period: 0,
                time: 0.0,
                mesh: mesh.clone(),
                u: u.clone(),
            });
        }
        let mut series = Vec::with_capacity(clock.steps + 1);
        series.push(ZalesakSample {
            period: 0,
            time: 0.0,
            area: area_initial,
            perimeter: perimeter_initial,
            vertices: mesh.n_points(),
            fixed_point_iterations: 0,
            l1_change: 0.0,
            seconds: start.elapsed().as_secs_f64(),
        });
        Ok(State {
            verts: vec![mesh.n_points()],
            shape,
            start,
            mesh,
            u,
            area_initial,
            perimeter_initial,
            adapt_seconds,
            advect_seconds: 0.0,
            series,
            fp_iters: Vec::with_capacity(clock.steps),
            frames,
            sources: opts.sources.then(ErrorSources::default),
            keep,
        })
    }

    /// Transports the level set over `[t0, t1]`: the fixed point of 004 §3.5 with `adapter`
    /// (new mesh and level set), or one advection on the fixed mesh. Returns the fixed-point
    /// iterations and the last mean L1 change.
    fn transport(
        &mut self,
        opts: &ZalesakOptions,
        adapter: Option<&mut (dyn Adapter + '_)>,
        t0: f64,
        t1: f64,
    ) -> Result<(usize, f64)> {
        let v = Rotation { omega: 1.0 };
        match adapter {
            Some(a) => {
                let fp = FixedPointOptions {
                    max_iterations: opts.fixed_point_iterations.max(1),
                    tol: opts.fixed_point_tol,
                    advect: opts.advect.clone(),
                    ..FixedPointOptions::default()
                };
                let res = advance_period(&self.mesh, &self.u, &v, t0, t1, a, &fp)?;
                self.adapt_seconds += res.adapt_seconds;
                self.advect_seconds += res.advect_seconds;
                self.mesh = res.mesh;
                self.u = res.u;
                Ok((
                    res.iterations,
                    res.l1_changes.last().copied().unwrap_or(0.0),
                ))
            }
            None => {
                let ta = Instant::now();
                self.u = advect::advect(&self.mesh, &self.u, &self.mesh, &v, t0, t1, &opts.advect)?;
                self.advect_seconds += ta.elapsed().as_secs_f64();
                Ok((1, 0.0))
            }
        }
    }

    /// Geometric redistancing (004 §2.2) of the level set, with its change of area and perimeter
    /// recorded as an error source.
    fn redistance(&mut self) -> Result<()> {
        let ta = Instant::now();
        let r = redistance_geometric(&self.mesh, &self.u)?;
        if let Some(src) = self.sources.as_mut() {
            src.redistance(&self.mesh, &self.u, &r)?;
        }
        self.u = r;
        self.advect_seconds += ta.elapsed().as_secs_f64();
        Ok(())
    }

    /// Period `k` of `clock`: transport, error sources, redistancing and mass correction as
    /// `opts` asks, the frames of the figures, and the sample at its end.
    fn period(
        &mut self,
        opts: &ZalesakOptions,
        clock: &Clock,
        adapter: Option<&mut (dyn Adapter + '_)>,
        k: usize,
    ) -> Result<()> {
        let (t0, t1) = (k as f64 * clock.dt, (k + 1) as f64 * clock.dt);
        let (old_mesh, old_u) = (self.mesh.clone(), self.u.clone());
        let (iters, l1_change) = self.transport(opts, adapter, t0, t1)?;
        if let Some(src) = self.sources.as_mut() {
            src.period(&self.shape, &old_mesh, &self.mesh, t0, t1, &opts.advect)?;
        }
        if opts.redistance {
            self.redistance()?;
        }
        if opts.mass_correction {
            advect::correct_mass(&self.mesh, &mut self.u, self.area_initial, 1e-13)?;
        }
        if self.keep && k + 1 == clock.shown_period {
            let snap = |period, time, mesh: &Mesh2, u: &[f64]| Snapshot {
                period,
                time,
                mesh: mesh.clone(),
                u: u.to_vec(),
            };
            self.frames.period = Some((
                snap(k, t0, &old_mesh, &old_u),
                snap(k + 1, t1, &self.mesh, &self.u),
            ));
        }
        if self.keep && quarter_turn(k + 1, clock.steps, clock.dt) {
            self.frames.snapshots.push(Snapshot {
                period: k + 1,
                time: t1,
                mesh: self.mesh.clone(),
                u: self.u.clone(),
            });
        }
        self.fp_iters.push(iters);
        self.verts.push(self.mesh.n_points());
        self.series.push(ZalesakSample {
            period: k + 1,
            time: t1,
            area: advect::enclosed_area(&self.mesh, &self.u)?,
            perimeter: advect::interface_length(&self.mesh, &self.u)?,
            vertices: self.mesh.n_points(),
            fixed_point_iterations: iters,
            l1_change,
            seconds: self.start.elapsed().as_secs_f64(),
        });
        Ok(())
    }

    /// The report after the last period: the final measures, the distance to the exact
    /// interface (after a whole number of revolutions) and the accumulated error sources.
    fn finish(mut self, opts: &ZalesakOptions, clock: &Clock) -> Result<ZalesakReport> {
        let seconds = self.start.elapsed().as_secs_f64();
        // After a whole number of revolutions the exact interface is the initial one.
        let turns = opts.revolutions.fract().abs() < 1e-12;
        let (imax, back) = if turns {
            let e = interface_distances(&self.mesh, &self.u, &self.shape)?;
            (e.to_exact_max, e.from_exact_max)
        } else {
            (f64::NAN, f64::NAN)
        };
        if let Some(src) = self.sources.as_mut() {
            src.finish(
                &self.shape,
                &self.mesh,
                &self.u,
                clock.total,
                self.area_initial,
                self.perimeter_initial,
            )?;
        }
        let last = self
            .series
            .last()
            .cloned()
            .unwrap_or_else(|| self.series[0].clone());
        let verts = &self.verts;
        Ok(ZalesakReport {
            mesh: opts.mesh,
            area_initial: self.area_initial,
            area_final: last.area,
            perimeter_initial: self.perimeter_initial,
            perimeter_final: last.perimeter,
            interface_to_exact_max: imax,
            exact_to_interface_max: back,
            vertices_mean: verts.iter().sum::<usize>() as f64 / verts.len() as f64,
            vertices_max: verts.iter().copied().max().unwrap_or(0),
            fixed_point_iterations: self.fp_iters,
            seconds,
            adapt_seconds: self.adapt_seconds,
            advect_seconds: self.advect_seconds,
            adaptations: 0,
            adapt_cycles: 0,
            series: self.series,
            sources: self.sources,
            compare_uniform: None,
            compare_isotropic: None,
            frames: self.frames,
        })
    }
}

/// One run on the mesh family of `opts` (adapted when `adapter` is given): the periods, the
/// report, the comparison runs (`opts.compare`) and the files (`opts.out_dir`).
fn run_inner(
    opts: &ZalesakOptions,
    mut adapter: Option<&mut dyn Adapter>,
    keep: bool,
) -> Result<ZalesakReport> {
    let clock = Clock::new(opts)?;
    let mut state = State::start(opts, &clock, adapter.as_deref_mut(), keep)?;
    for k in 0..clock.steps {
        state.period(opts, &clock, adapter.as_deref_mut(), k)?;
    }
    let mut report = state.finish(opts, &clock)?;
    if opts.compare {
        compare(&mut report, opts, keep)?;
    }
    if let Some(dir) = &opts.out_dir {
        write_outputs(dir, &report)?;
        write_figures(dir, &report)?;
    }
    Ok(report)
}

/// The comparison runs of `report`: a uniform mesh with about its mean vertex count and, for
/// an adapted run, the isotropic variant matched on the vertex count of the initial mesh.
fn compare(report: &mut ZalesakReport, opts: &ZalesakOptions, keep: bool) -> Result<()> {
    let m = ((report.vertices_mean.sqrt() - 1.0).round() as usize).max(2);
    let cmp = ZalesakOptions {
        mesh: ZalesakMesh::Uniform { n: m },
        compare: false,
        out_dir: None,
        ..opts.clone()
    };
    report.compare_uniform = Some(Box::new(run_inner(&cmp, None, keep)?));
    if let ZalesakMesh::Adapted {
        hmin, stretching, ..
    } = opts.mesh
    {
        // Matched on the initial mesh (one position of the disk; the meshes of the periods
        // carry two), so that the mean counts over the revolution are comparable.
        let target = report.series[0].vertices as f64;
        let h = isotropic_hmin_for(target, hmin, stretching, opts)?;
        let iso = ZalesakOptions {
            mesh: ZalesakMesh::Adapted {
                hmin: h,
                stretching: hmin * stretching / h,
                isotropic: true,
            },
            compare: false,
            out_dir: None,
            ..opts.clone()
        };
        report.compare_isotropic = Some(Box::new(run_keep(&iso, keep)?));
    }
    Ok(())
}

/// The `hmin` of the isotropic variant whose initial adapted mesh has about `target` vertices
/// (a few secant steps on `log(vertices)` against `log(hmin)`; only initial meshes are built).
fn isotropic_hmin_for(
    target: f64,
    hmin: f64,
    stretching: f64,
    opts: &ZalesakOptions,
) -> Result<f64> {
    let shape = Zalesak::default();
    let count = |h: f64| -> Result<f64> {
        let metric = LevelSetMetric {
            hmin: h,
            hmax: (hmin * stretching).max(2.0 * h),
            isotropic: true,
            ..opts.metric
        };
        let mut a = LevelSetAdapter::new(metric, opts.adapt.clone())?;
        Ok(initial_mesh(40, &shape, Some(&mut a), opts.initial_rounds)?.n_points() as f64)
    };
    // Isotropic meshes need about ten times more vertices at equal hmin (004 §5.1).
    let mut h0 = hmin * 10.0;
    let mut n0 = count(h0)?;
    let mut h1 = h0 * (n0 / target).sqrt();
    for _ in 0..3 {
        let n1 = count(h1)?;
        if ((n1 - target) / target).abs() < 0.1 || (n1 - n0).abs() < 1.0 {
            break;
        }
        let slope = (n1.ln() - n0.ln()) / (h1.ln() - h0.ln());
        let h2 = (h1.ln() + (target.ln() - n1.ln()) / slope.min(-0.1)).exp();
        (h0, n0, h1) = (h1, n1, h2.clamp(h1 / 4.0, h1 * 4.0));
    }
    Ok(h1)
}
