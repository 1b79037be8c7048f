//! The fixed point in 3D (004 §5): a tetrahedral mesh adapted to a metric given as a function
//! of position — either a metric field directly, or the geometric metric of 004 eq. (6) of an
//! implicit surface with exact derivatives — starting from the Kuhn mesh of a box (by default
//! `[−1, 1]³`) or from a given mesh. The metric is evaluated exactly at every new or moved
//! vertex, so one run of the split / collapse / swap / smoothing cycle
//! ([`crate::adapt::cycle::run_cycles`]) reaches the fixed point of the metric.

use std::time::Instant;

use serde::Serialize;

use super::stats::{tet_stats, TetStats};
use super::{Ctx, MetricFn3};
use crate::adapt::cycle::run_cycles;
use crate::adapt::{AdaptOptions, AdaptReport, LevelSetMetric};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::levelset::{enclosed_measure, interface_measure, Normalized, Shape};
use crate::mesh3::{EditMesh3, Mesh3};
use crate::metric::sym::bound_eigenvalues;
use crate::metric::{geometric_metric, Sym3};

mod cycle3;
mod stages;
use stages::{coarsened, Scale};
pub use stages::{Continuation3, Stage3};

/// What to adapt to.
pub enum Target3<'a> {
    /// A metric field, evaluated at every vertex.
    Metric(MetricFn3<'a>),
    /// An implicit surface: the metric of 004 eq. (6) from its exact derivatives
    /// ([`level_set_metric3`]).
    Shape(&'a dyn Shape<DVec3>),
}

/// Options of [`run3`].
#[derive(Debug, Clone)]
pub struct Run3Options {
    /// The box of the start mesh (default `[−1, 1]³`).
    pub lo: DVec3,
    /// Upper corner of the box.
    pub hi: DVec3,
    /// Cells per direction of the Kuhn start mesh (default 8).
    pub cells: usize,
    /// The eq. (6) parameters for a shape target (ε, hmin, hmax, band, grade, anisotropy).
    pub metric: LevelSetMetric,
    /// The cycle options (length bounds, cycles, final sweeps, per-pass checks, vertex guard;
    /// gradation is not available on tetrahedra).
    pub adapt: AdaptOptions,
    /// How a shape's metric is reached from the start mesh ([`Continuation3`]).
    pub continuation: Continuation3,
}

impl Default for Run3Options {
    fn default() -> Self {
        Run3Options {
            lo: DVec3::splat(-1.0),
            hi: DVec3::splat(1.0),
            cells: 8,
            metric: LevelSetMetric {
                eps: 1e-3,
                hmin: 1e-2,
                hmax: 0.2,
                max_aniso: 1e3,
                band: 5e-3,
                grade: 1.0,
                analytic: true,
                isotropic: false,
            },
            adapt: AdaptOptions::default().max_vertices(Some(5_000_000)),
            continuation: Continuation3::default(),
        }
    }
}

/// The numbers of a 3D run.
#[derive(Debug, Clone, Serialize)]
pub struct Report3 {
    /// Vertices of the adapted mesh.
    pub vertices: usize,
    /// Tetrahedra.
    pub tetrahedra: usize,
    /// Edge lengths and quality in the final metric.
    pub stats: TetStats,
    /// Fraction of edges with metric length in `[1/√2, √2]` (as in `stats`).
    pub edge_length_in_range: f64,
    /// Worst mean-ratio quality (as in `stats`).
    pub quality_min: f64,
    /// Volume inside the P1 zero level of the shape (shape targets).
    pub volume: Option<f64>,
    /// The shape's exact enclosed volume, when known.
    pub exact_volume: Option<f64>,
    /// Area of the P1 zero level (shape targets).
    pub surface_area: Option<f64>,
    /// Wall-clock seconds of the whole run.
    pub seconds: f64,
    /// The cycle's passes.
    pub adapt: AdaptReport,
    /// The continuation's stages, the target metric last (shape targets; empty for a metric
    /// target).
    pub stages: Vec<Stage3>,
}

/// An adapted mesh with its metric, the level set at its vertices (shape targets) and the
/// report.
#[derive(Debug, Clone)]
pub struct Adapted3 {
    /// The adapted mesh.
    pub mesh: Mesh3,
    /// The vertex metric.
    pub metric: Vec<Sym3>,
    /// The shape's signed distance at the vertices (shape targets; for a level-set function that
    /// is not a distance, its first-order distance `u/|∇u|`).
    pub level_set: Option<Vec<f64>>,
    /// The numbers.
    pub report: Report3,
}

/// A shape as 004 eq. (6) sees it: itself when it is a signed distance
/// ([`Shape::is_distance`]), otherwise its first-order distance `u/|∇u|`, unit normal and shape
/// operator ([`Normalized`]), so that the band, `hmin` and the curvature sizes are lengths and
/// `u` and `c u` give the same mesh (the 2D [`crate::adapt::run`] does the same).
pub enum Seen3<'a> {
    /// A signed distance, used as it is.
    Distance(&'a dyn Shape<DVec3>),
    /// A level-set function that is not a distance, normalised.
    Normalized(Normalized<&'a dyn Shape<DVec3>>),
}

impl<'a> Seen3<'a> {
    /// `shape` as eq. (6) sees it; `cap` bounds `|u/|∇u||` where `∇u` vanishes (the domain's
    /// diameter).
    pub fn new(shape: &'a dyn Shape<DVec3>, cap: f64) -> Seen3<'a> {
        if shape.is_distance() {
            Seen3::Distance(shape)
        } else {
            Seen3::Normalized(Normalized { inner: shape, cap })
        }
    }

    /// The (first-order) signed distance, its gradient and Hessian at `p`.
    pub fn jet(&self, p: DVec3) -> (f64, DVec3, Sym3) {
        match self {
            Seen3::Distance(s) => (s.distance(p), s.gradient(p), s.hessian(p)),
            Seen3::Normalized(n) => n.parts3(p),
        }
    }

    /// The shape whose values are the level set of the adapted mesh.
    pub fn shape(&self) -> &dyn Shape<DVec3> {
        match self {
            Seen3::Distance(s) => *s,
            Seen3::Normalized(n) => n,
        }
    }
}

/// 004 eq. (6) in 3D with the band and bounds of `lm` ([`LevelSetMetric`]): the bounded
/// `∇u ∇uᵀ / hmin² + |D²u| / ε` where `|u| < band`; outside, the same sizes grown linearly
/// with the distance, `h ← min(hmax, h + grade (|u| − band))`.
pub fn level_set_metric3(lm: &LevelSetMetric, u: f64, grad: DVec3, hess: &Sym3) -> Sym3 {
    // One decomposition of the unbounded metric serves the bounds, the isotropic option and the
    // growth outside the band (they all keep the eigenvectors).
    let (l, mut v) = geometric_metric(grad, hess, lm.hmin, lm.eps).eigen();
    let mut l = bound_eigenvalues(l, lm.hmin, lm.hmax, lm.max_aniso);
    if lm.isotropic {
        l = [l[2]; 3];
        v = [DVec3::X, DVec3::Y, DVec3::Z];
    }
    let d = u.abs() - lm.band;
    if d > 0.0 {
        if !lm.grade.is_finite() {
            return Sym3::iso(lm.hmax);
        }
        l = l.map(|l| {
            let h = (1.0 / l.sqrt() + lm.grade * d).min(lm.hmax);
            1.0 / (h * h)
        });
    }
    Sym3::from_eigen(l, v)
}

/// The live vertices of `mesh`.
fn alive_points(mesh: &EditMesh3) -> usize {
    (0..mesh.points.len() as u32)
        .filter(|&v| mesh.alive(v))
        .count()
}

/// Re-evaluates the metric at every vertex of `ctx` from `source` (after the continuation's
/// scale changed), and has every operator look at every vertex again.
fn refresh_metric(ctx: &mut Ctx<'_>, source: MetricFn3<'_>) -> Result<()> {
    use rayon::prelude::*;
    let metric: Vec<Sym3> = ctx.mesh.points.par_iter().map(|&p| source(p)).collect();
    for (v, m) in metric.iter().enumerate() {
        m.validate(v)?;
    }
    ctx.metric = metric;
    ctx.last = [0; 5];
    Ok(())
}

/// Up to three rounds of the quality sweep ([`super::sweep`]), each followed by a swap and a
/// smoothing pass, recorded in `rep` (the sweep's collapses as a collapse pass).
fn final_sweep(ctx: &mut Ctx<'_>, opts: &AdaptOptions, rep: &mut AdaptReport) -> Result<()> {
    use crate::adapt::cycle::Remesher;
    use crate::adapt::options::{PassKind, PassReport};
    for _ in 0..3 {
        let mut changed = 0;
        for kind in [PassKind::Collapse, PassKind::Flip, PassKind::Smooth] {
            let t = Instant::now();
            let n = match kind {
                PassKind::Collapse => super::sweep::pass(ctx),
                k => ctx.run_pass(k),
            };
            match kind {
                PassKind::Collapse => rep.collapses += n,
                PassKind::Flip => rep.flips += n,
                _ => rep.moves += n,
            }
            rep.passes.push(PassReport {
                kind,
                count: n,
                seconds: t.elapsed().as_secs_f64(),
            });
            if opts.check_each_pass {
                ctx.check()?;
            }
            if kind == PassKind::Collapse {
                changed = n;
            }
        }
        if changed == 0 {
            break;
        }
    }
    Ok(())
}

/// Runs the cycles of continuation stage `k` (`k = 0`: the target) on `ctx`, adds them to
/// `rep` and reports the stage (its sizes left for the caller: no ε or band, `hmin` 0).
fn stage(ctx: &mut Ctx<'_>, opts: &AdaptOptions, k: u32, rep: &mut AdaptReport) -> Result<Stage3> {
    let start = alive_points(&ctx.mesh);
    let mut r = AdaptReport::default();
    // A stage's mesh only has to be close to the next stage's metric (`cycle3`).
    let churn = if k == 0 { 200 } else { 50 };
    cycle3::cycles(ctx, opts, churn, opts.max_cycles, &mut r)?;
    let st = Stage3 {
        scale: f64::from(1u32 << k),
        eps: None,
        hmin: 0.0,
        band: None,
        start_vertices: start,
        vertices: alive_points(&ctx.mesh),
        peak_vertices: stages::peak(start, &r),
        complexity: stages::complexity(&ctx.mesh, &ctx.metric),
        passes: r.passes.len(),
        seconds: stages::seconds_by_kind(&r),
    };
    rep.absorb(&r);
    rep.converged = r.converged;
    Ok(st)
}

/// Adapts the Kuhn mesh of the box of `opts` (or `start`, when given) to `target` and reports
/// the result. Errors: invalid options or start mesh, a metric that is not SPD and finite at a
/// vertex, more vertices than `opts.adapt.max_vertices`, a defect found by the per-pass check.
pub fn run3(target: Target3<'_>, start: Option<&Mesh3>, opts: &Run3Options) -> Result<Adapted3> {
    let clock = Instant::now();
    if opts.adapt.gradation.is_some() {
        return Err(Error::InvalidInput(
            "gradation during the adaptation is not available on tetrahedra".into(),
        ));
    }
    let lm = opts.metric;
    let cont = opts.continuation;
    let seen;
    let coarsening = Scale::default();
    let shape_metric;
    let floor = Scale::new(0.0);
    let floored;
    let (source, shape): (MetricFn3<'_>, Option<&dyn Shape<DVec3>>) = match target {
        Target3::Metric(f) => {
            let floor = &floor;
            floored = move |p: DVec3| stages::floored(f(p), floor.get());
            (&floored, None)
        }
        Target3::Shape(s) => {
            lm.validate()?;
            seen = Seen3::new(s, (opts.hi - opts.lo).length());
            let seen = &seen;
            let scale = &coarsening;
            shape_metric = move |p: DVec3| {
                let (u, g, h) = seen.jet(p);
                level_set_metric3(&coarsened(&lm, cont, scale.get()), u, g, &h)
            };
            (&shape_metric, Some(seen.shape()))
        }
    };
    let mesh = match start {
        Some(m) => m.clone(),
        None => Mesh3::kuhn_box(opts.lo, opts.hi, [opts.cells; 3])?,
    };
    let edit = EditMesh3::from_mesh(&mesh)?;
    let metric: Vec<Sym3> = edit.points.iter().map(|&p| source(p)).collect();
    for (v, m) in metric.iter().enumerate() {
        m.validate(v)?;
    }
    let mut ctx = Ctx::new(edit, metric, Some(source));
    ctx.l_min = opts.adapt.l_min;
    ctx.l_max = opts.adapt.l_max;
    let mut rep = AdaptReport::default();
    let mut stage_reports = Vec::new();
    let metric_stages = match shape {
        Some(_) => None,
        None if cont == Continuation3::Off => None,
        None => Some(stages::SizeFloors::new(&mesh, &ctx.metric)),
    };
    if let Some(floors) = metric_stages.filter(|f| f.count > 0) {
        for k in (0..=floors.count).rev() {
            let h = floors.floor(k);
            floor.set(h);
            refresh_metric(&mut ctx, source)?;
            let st = stage(&mut ctx, &opts.adapt, k, &mut rep)?;
            stage_reports.push(Stage3 {
                hmin: if k == 0 { floors.smallest } else { h },
                ..st
            });
        }
    } else if shape.is_some() {
        // Continuation: the eq. (6) metric seen 2^k times coarser, k = K, …, 1, before the
        // metric itself (`stages`).
        for k in (0..=stages::stage_count(&lm, cont)).rev() {
            let s = f64::from(1u32 << k);
            coarsening.set(s);
            if k > 0 || !stage_reports.is_empty() {
                refresh_metric(&mut ctx, source)?;
            }
            let st = stage(&mut ctx, &opts.adapt, k, &mut rep)?;
            let c = coarsened(&lm, cont, s);
            stage_reports.push(Stage3 {
                eps: Some(c.eps),
                hmin: c.hmin,
                band: Some(c.band),
                ..st
            });
        }
    } else {
        run_cycles(&mut ctx, &opts.adapt, &mut rep)?;
    }
    final_sweep(&mut ctx, &opts.adapt, &mut rep)?;
    super::conform::polish(&mut ctx, &opts.adapt, &mut rep)?;
    let (mesh, old) = ctx.mesh.to_mesh();
    let metric: Vec<Sym3> = old.iter().map(|&v| ctx.metric[v as usize]).collect();
    rep.seconds = clock.elapsed().as_secs_f64();
    let stats = tet_stats(&mesh, &metric);
    let (level_set, volume, area) = match shape {
        Some(s) => {
            let u: Vec<f64> = mesh.points.iter().map(|&p| s.distance(p)).collect();
            let vol = enclosed_measure(&mesh.points, &mesh.tets, &u)?;
            let area = interface_measure(&mesh.points, &mesh.tets, &u)?;
            (Some(u), Some(vol), Some(area))
        }
        None => (None, None, None),
    };
    let report = Report3 {
        vertices: mesh.n_points(),
        tetrahedra: mesh.n_tets(),
        stats,
        edge_length_in_range: stats.edge_length_in_range,
        quality_min: stats.quality_min,
        volume,
        exact_volume: shape.and_then(|s| s.exact_area()),
        surface_area: area,
        seconds: clock.elapsed().as_secs_f64(),
        adapt: rep,
        stages: stage_reports,
    };
    Ok(Adapted3 {
        mesh,
        metric,
        level_set,
        report,
    })
}
