//! The library's entry point: adapt a mesh to an implicit shape, to a P1 level set given on a
//! mesh, or to a metric field given on a mesh ([`run`]).
//!
//! - [`AdaptTarget::Shape`]: the geometric metric of 004 eq. (6) with exact derivatives,
//!   re-evaluated at every new vertex ([`super::adapt_to_shape`]); a shape that is not a
//!   distance ([`Shape::is_distance`], e.g. an expression) is seen through
//!   [`Normalized`], so that `f` and `c f` give the same mesh; or with
//!   [`RunOptions::target_vertices`] the multiscale Hessian metric of the nodal distance.
//! - [`AdaptTarget::LevelSet`]: eq. (6) (or the Hessian metric) with derivatives recovered from
//!   the P1 field (004 §4.3); the field is carried to the new vertices.
//! - [`AdaptTarget::Metric`]: conform to the given metric, sizes interpolated linearly between
//!   the given vertices as mmg2d does ([`metric_file_options`]), optionally graded.
//!
//! Before adapting, the size of the requested mesh is estimated from the metric's complexity
//! ([`super::estimate`]) and a request above [`RunOptions::max_vertices`] is refused.

use super::discrete::DiscreteLevelSet;
use super::estimate;
use super::{
    adapt, adapt_mesh_to_shape, adapt_to_shape, mesh_report, AdaptOptions, AdaptReport,
    AnalyticLevelSetSource, CycleSmoothing, HessianMetric, LevelSetMetric, MeshReport,
    MetricInterpolation, ShapeAdaptOptions,
};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::levelset::{Normalized, Shape};
use crate::mesh::Mesh2;
use crate::metric::{gradate, quality_stats, Sym2};
use serde::Serialize;

/// What to adapt to.
pub enum AdaptTarget {
    /// An implicit shape (a signed distance, negative inside) on the rectangle `domain`.
    Shape {
        /// The shape.
        shape: Box<dyn Shape>,
        /// The rectangle `(lower-left, upper-right)` to mesh.
        domain: (DVec2, DVec2),
    },
    /// A P1 level set `u` given at the vertices of `mesh` (adapt to its zero level).
    LevelSet {
        /// The mesh carrying the level set.
        mesh: Mesh2,
        /// One value per vertex, negative inside.
        u: Vec<f64>,
    },
    /// A metric field given at the vertices of `mesh` (conform to it).
    Metric {
        /// The mesh carrying the metric.
        mesh: Mesh2,
        /// One SPD tensor per vertex.
        metric: Vec<Sym2>,
    },
}

impl AdaptTarget {
    /// A shape on a rectangle.
    pub fn shape(shape: impl Shape + 'static, domain: (DVec2, DVec2)) -> AdaptTarget {
        AdaptTarget::Shape {
            shape: Box::new(shape),
            domain,
        }
    }
}

/// Options of [`run`]. `Default` is the setting of 004 §5.1: eq. (6) with ε = 1e-4, hmin 0.001,
/// hmax 0.2, a band of 5 ε.
#[derive(Debug, Clone)]
pub struct RunOptions {
    /// The geometric metric of eq. (6): ε, hmin, hmax, band, grade, isotropic variant. For a
    /// metric target only `hmin`/`hmax` are unused; the metric is taken as given.
    pub metric: LevelSetMetric,
    /// Use the multiscale Hessian (interpolation-error) metric with this many target vertices
    /// instead of eq. (6) (shape and level-set targets).
    pub target_vertices: Option<usize>,
    /// For a metric target: grade the metric during the adaptation with this growth factor
    /// (> 1; mmg2d's `-hgrad`). `None`: as given.
    pub hgrad: Option<f64>,
    /// Refuse a request whose estimated vertex count exceeds this.
    pub max_vertices: f64,
}

impl Default for RunOptions {
    fn default() -> Self {
        RunOptions {
            metric: LevelSetMetric::default(),
            target_vertices: None,
            hgrad: None,
            max_vertices: DEFAULT_MAX_VERTICES,
        }
    }
}

/// The default limit of [`RunOptions::max_vertices`]: ten million vertices, about 4 GB of
/// adaptation state (mesh, metric and pass workspace take about 400 bytes per vertex).
pub const DEFAULT_MAX_VERTICES: f64 = 1e7;

/// What [`run`] measured.
#[derive(Debug, Clone, Serialize)]
pub struct RunReport {
    /// Vertices, quality, and for a level set the interface measures.
    #[serde(flatten)]
    pub mesh: MeshReport,
    /// The metric the mesh was adapted to, in words.
    pub metric_source: String,
    /// The vertex count estimated from the metric's complexity before adapting.
    pub estimated_vertices: f64,
    /// Split/collapse cycles of the last adaptation.
    pub cycles: usize,
    /// Operations of all adaptation rounds.
    pub splits: usize,
    /// Edge collapses.
    pub collapses: usize,
    /// Edge flips.
    pub flips: usize,
    /// Vertex moves.
    pub moves: usize,
    /// Whether the adaptation settled (edge lengths in range, no more changes).
    pub converged: bool,
    /// Things the user should know about the result (one sentence each).
    pub warnings: Vec<String>,
}

/// The adapted mesh, its metric, the level set on it (shape and level-set targets) and the
/// report.
pub struct Adapted {
    /// The adapted mesh.
    pub mesh: Mesh2,
    /// The metric at its vertices.
    pub metric: Vec<Sym2>,
    /// The level set at its vertices (none for a metric target).
    pub level_set: Option<Vec<f64>>,
    /// What was measured.
    pub report: RunReport,
}

/// The adaptation options for "conform to this metric": sizes interpolated linearly between the
/// given vertices ([`MetricInterpolation::LinearSizes`], as mmg2d does with the same files) and
/// one smoothing sweep per cycle over what the cycle changed ([`CycleSmoothing::Touched`]).
pub fn metric_file_options() -> AdaptOptions {
    AdaptOptions::default()
        .interpolation(MetricInterpolation::LinearSizes)
        .cycle_smoothing(CycleSmoothing::Touched)
}

/// Adapts a mesh to `target` (module documentation).
///
/// Errors: invalid options (ε, sizes, band, hgrad), an invalid input mesh or field, a request
/// whose estimated size exceeds [`RunOptions::max_vertices`], a level set with no zero level.
pub fn run(target: AdaptTarget, opts: &RunOptions) -> Result<Adapted> {
    let lm = &opts.metric;
    if !(lm.eps > 0.0 && lm.hmin > 0.0 && lm.hmax >= lm.hmin) {
        return Err(Error::InvalidInput(format!(
            "need eps > 0 and 0 < hmin <= hmax (got eps {}, hmin {}, hmax {})",
            lm.eps, lm.hmin, lm.hmax
        )));
    }
    if !(lm.band.is_finite() && lm.band > 0.0) {
        return Err(Error::InvalidInput(format!(
            "need a finite band half-width > 0 (got {})",
            lm.band
        )));
    }
    let t0 = std::time::Instant::now();
    let mut warnings = Vec::new();
    let (mesh, metric, u, shape, rep, source, estimated) = match target {
        AdaptTarget::Shape { shape, domain } => {
            // eq. (6) needs a distance: a plain level-set function is seen through its
            // scale-free first-order distance, normal and shape operator.
            let shape: Box<dyn Shape> = if shape.is_distance() {
                shape
            } else {
                Box::new(Normalized {
                    inner: shape,
                    cap: (domain.1 - domain.0).length(),
                })
            };
            let estimated = match opts.target_vertices {
                Some(n) => n as f64,
                None => estimate::shape_vertices(shape.as_ref(), lm, domain).0,
            };
            refuse_above(estimated, opts.max_vertices)?;
            // A guard well above the estimate, for a run that grows far past it.
            let cap = (GROWTH_GUARD * estimated)
                .max(GUARD_FLOOR)
                .min(opts.max_vertices);
            let (mesh, metric, u, rep, source) = adapt_shape(shape.as_ref(), domain, opts, cap)?;
            (mesh, metric, Some(u), Some(shape), rep, source, estimated)
        }
        AdaptTarget::LevelSet { mesh, u } if opts.target_vertices.is_none() => {
            // The input's P1 zero level is the interface, evaluated in the input mesh.
            let shape = DiscreteLevelSet::new(mesh, u)?;
            let domain = shape.mesh().bounding_box().unwrap_or_default();
            let estimated = estimate::shape_vertices(&shape, lm, domain).0;
            refuse_above(estimated, opts.max_vertices)?;
            let cap = (GROWTH_GUARD * estimated)
                .max(GUARD_FLOOR)
                .min(opts.max_vertices);
            let so = ShapeAdaptOptions {
                metric: *lm,
                adapt: AdaptOptions::default().max_vertices(Some(cap as usize)),
                ..ShapeAdaptOptions::default()
            };
            let (mesh, u, rep) = adapt_mesh_to_shape(shape.mesh(), &shape, &so)?;
            let metric = final_metric(&shape, &mesh, opts)?;
            let source = describe(opts, "of the distance to the input's zero level");
            let shape: Box<dyn Shape> = Box::new(shape);
            (mesh, metric, Some(u), Some(shape), rep, source, estimated)
        }
        AdaptTarget::LevelSet { mut mesh, u } => {
            // The Hessian metric (`target_vertices` is set here).
            let mut metric = level_set_metric(&mesh, &u, None, opts)?;
            let estimated = estimate::field_vertices(&mesh, &metric);
            refuse_above(estimated, opts.max_vertices)?;
            let mut fields = vec![u];
            let rep = adapt(
                &mut mesh,
                &mut metric,
                &mut fields,
                None,
                &AdaptOptions::default().max_vertices(Some(opts.max_vertices as usize)),
            )?;
            let u = fields.pop().unwrap_or_default();
            let source = describe(opts, "recovered from the P1 level set");
            (mesh, metric, Some(u), None, rep, source, estimated)
        }
        AdaptTarget::Metric {
            mut mesh,
            mut metric,
        } => {
            crate::metric::validate_field(&metric, mesh.n_points())?;
            let estimated = estimate::field_vertices(&mesh, &metric);
            refuse_above(estimated, opts.max_vertices)?;
            let rep = adapt(
                &mut mesh,
                &mut metric,
                &mut [],
                None,
                &metric_file_options()
                    .gradation(opts.hgrad)
                    .max_vertices(Some(opts.max_vertices as usize)),
            )?;
            let source = match opts.hgrad {
                Some(b) => format!("metric read from file, graded with factor {b}"),
                None => "metric read from file".to_string(),
            };
            (mesh, metric, None, None, rep, source, estimated)
        }
    };
    let mut report = match &u {
        Some(u) => {
            check_zero_level(u)?;
            // Interface distances only against shapes whose exact interface is known.
            let exact = shape
                .as_deref()
                .filter(|s| s.boundary_samples(16).is_some());
            mesh_report(&mesh, &metric, u, exact)?
        }
        None => metric_only_report(&mesh, &metric),
    };
    report.seconds = t0.elapsed().as_secs_f64();
    report.phases = vec![("adapt".into(), rep.seconds)];
    if let Some(n) = opts.target_vertices {
        let got = mesh.n_points() as f64;
        if !(0.5..=2.0).contains(&(got / n as f64)) {
            warnings.push(format!(
                "{} vertices for a target of {n}: the sizes are bounded by hmin {} and hmax {}, \
                 which {} the mesh",
                mesh.n_points(),
                lm.hmin,
                lm.hmax,
                if got > n as f64 { "enlarge" } else { "limit" }
            ));
        }
    }
    if !rep.converged {
        warnings.push(format!(
            "not converged: {:.1}% of the edges have metric length in [1/sqrt2, sqrt2] after {} \
             cycles",
            100.0 * report.edge_length_in_range,
            rep.cycles
        ));
    }
    let report = RunReport {
        mesh: report,
        metric_source: source,
        estimated_vertices: estimated,
        cycles: rep.cycles,
        splits: rep.splits,
        collapses: rep.collapses,
        flips: rep.flips,
        moves: rep.moves,
        converged: rep.converged,
        warnings,
    };
    Ok(Adapted {
        mesh,
        metric,
        level_set: u,
        report,
    })
}

/// The growth guard of a shape adaptation: this many times the estimated vertex count, and at
/// least [`GUARD_FLOOR`] vertices.
const GROWTH_GUARD: f64 = 8.0;
/// The smallest growth guard.
const GUARD_FLOOR: f64 = 5e4;

fn refuse_above(estimated: f64, limit: f64) -> Result<()> {
    if estimated > limit {
        return Err(Error::TooLarge(format!(
            "the metric asks for about {estimated:.2e} vertices (complexity estimate), above the \
             limit of {limit:.2e}: raise eps or hmin, or the limit (--max-vertices)"
        )));
    }
    Ok(())
}

/// An error when the level set does not change sign: there is no interface to adapt to.
fn check_zero_level(u: &[f64]) -> Result<()> {
    let (lo, hi) = u
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
            (a.min(x), b.max(x))
        });
    if lo <= 0.0 && hi >= 0.0 {
        return Ok(());
    }
    Err(Error::EmptyLevelSet(format!(
        "the level set has no zero level in the domain: its values lie in [{lo:.3e}, {hi:.3e}] \
         at all {} vertices",
        u.len()
    )))
}

fn hessian_metric(opts: &RunOptions, n: usize) -> HessianMetric {
    HessianMetric {
        target_vertices: n,
        hmin: opts.metric.hmin,
        hmax: opts.metric.hmax,
        isotropic: opts.metric.isotropic,
        ..HessianMetric::default()
    }
}

fn describe(opts: &RunOptions, derivatives: &str) -> String {
    let kind = match opts.target_vertices {
        Some(n) => format!("multiscale L2 Hessian metric, target {n} vertices"),
        None => format!("geometric metric 004 eq. (6), eps {:e}", opts.metric.eps),
    };
    let iso = if opts.metric.isotropic {
        "isotropic "
    } else {
        ""
    };
    format!("{iso}{kind}, {derivatives}")
}

type ShapeAdapted = (Mesh2, Vec<Sym2>, Vec<f64>, AdaptReport, String);

/// Adapts to an exact shape: eq. (6) through [`adapt_to_shape`], or the Hessian metric of the
/// nodal distance re-evaluated exactly on each new mesh (a few rounds).
fn adapt_shape(
    shape: &dyn Shape,
    domain: (DVec2, DVec2),
    opts: &RunOptions,
    cap: f64,
) -> Result<ShapeAdapted> {
    let lm = opts.metric;
    let guarded = AdaptOptions::default().max_vertices(Some(cap as usize));
    match opts.target_vertices {
        None => {
            let so = ShapeAdaptOptions {
                metric: lm,
                adapt: guarded,
                ..ShapeAdaptOptions::default()
            };
            let (mesh, u, rep) = adapt_to_shape(shape, domain, &so)?;
            let metric = final_metric(shape, &mesh, opts)?;
            Ok((mesh, metric, u, rep, describe(opts, "exact derivatives")))
        }
        Some(n) => {
            let hm = hessian_metric(opts, n);
            let mut mesh = Mesh2::rectangle(domain.0, domain.1, 20, 20, Default::default())?;
            let mut total = AdaptReport::default();
            let mut metric = Vec::new();
            for _round in 0..6 {
                let u: Vec<f64> = mesh.points.iter().map(|&p| shape.distance(p)).collect();
                metric = hm.field(&mesh, &u)?;
                let before = mesh.n_points();
                let rep = adapt(&mut mesh, &mut metric, &mut [], None, &guarded)?;
                total.absorb(&rep);
                total.converged = rep.converged;
                let change = (mesh.n_points() as f64 - before as f64).abs() / before as f64;
                if change < 0.02 {
                    break;
                }
            }
            let u: Vec<f64> = mesh.points.iter().map(|&p| shape.distance(p)).collect();
            Ok((mesh, metric, u, total, describe(opts, "recovered Hessian")))
        }
    }
}

/// The metric a shape adaptation of [`run`] adapts to, at the vertices of `mesh`: 004 eq. (6)
/// of `opts.metric` with the shape's distance, normal and Hessian at every vertex
/// ([`AnalyticLevelSetSource::evaluate`]), graded as the adaptation rounds grade it
/// ([`ShapeAdaptOptions::gradation`], default factor 2). [`run`] returns this metric on the
/// adapted mesh for shape and level-set targets (without `target_vertices`); on the input mesh
/// of a level-set target it is the metric of the first round.
pub fn final_metric(shape: &dyn Shape, mesh: &Mesh2, opts: &RunOptions) -> Result<Vec<Sym2>> {
    let src = AnalyticLevelSetSource::new(
        |p| (shape.distance(p), shape.gradient(p), shape.hessian(p)),
        opts.metric,
    );
    let (mut metric, _) = src.evaluate(mesh);
    if let Some(beta) = ShapeAdaptOptions::default().gradation {
        gradate(mesh, &mut metric, beta)?;
    }
    Ok(metric)
}

/// The metric [`run`] adapts the P1 level set `u` on `mesh` to ([`AdaptTarget::LevelSet`]), at
/// the vertices of `at` (`None`: of `mesh`, the metric of the first round): [`final_metric`] of
/// the input's zero level (the exact distance to the P1 zero level, its normal, and the shape
/// operator of the Hessian recovered by least squares, 004 §2.2, §4.3), evaluated in the input
/// mesh; [`run`] returns it with `at` = the adapted mesh. With `opts.target_vertices`, the
/// multiscale L2 Hessian metric of `u` on `mesh` ([`HessianMetric::field`]; `at` must be
/// `None`). Errors: an invalid mesh or field, no zero level, invalid options.
pub fn level_set_metric(
    mesh: &Mesh2,
    u: &[f64],
    at: Option<&Mesh2>,
    opts: &RunOptions,
) -> Result<Vec<Sym2>> {
    match (opts.target_vertices, at) {
        (Some(n), None) => hessian_metric(opts, n).field(mesh, u),
        (Some(_), Some(_)) => Err(Error::Unsupported(
            "the Hessian metric of a level set lives on the level set's own mesh".into(),
        )),
        (None, _) => {
            opts.metric.validate()?;
            let shape = DiscreteLevelSet::new(mesh.clone(), u.to_vec())?;
            final_metric(&shape, at.unwrap_or(mesh), opts)
        }
    }
}

fn metric_only_report(mesh: &Mesh2, metric: &[Sym2]) -> MeshReport {
    let q = quality_stats(mesh, metric);
    MeshReport {
        vertices: mesh.n_points(),
        triangles: mesh.n_live_tris(),
        edge_length_in_range: q.edge_length_in_range,
        q_ani_mean: q.q_ani_mean,
        q_ani_max: q.q_ani_max,
        ..MeshReport::default()
    }
}
