//! The `anisomesh adapt` job: adapt a mesh to an implicit shape, to a P1 level set read from a
//! file, or to a given metric field, and write the mesh (`.mesh`, `.vtu`), a picture (`.png`,
//! triangles coloured by `Q_ani`) and `report.json`.
//!
//! Metric sources (issue 3 item 3): the geometric metric of 004 eq. (6) (default), the
//! Hessian-based multiscale `L^p` metric with a target vertex count (`target_vertices`), their
//! isotropic variants (`iso`), or a metric read from a `.sol` file (conform to it, as mmg2d does).

use crate::adapt::{
    adapt, adapt_to_shape, mesh_report, AdaptOptions, AdaptReport, AnalyticLevelSetSource,
    CycleSmoothing, HessianMetric, LevelSetMetric, MeshReport, MetricInterpolation,
    ShapeAdaptOptions,
};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::io::{self, FieldRef};
use crate::levelset::{extract_zero_level, Shape};
use crate::mesh::Mesh2;
use crate::metric::{gradate, q_ani, Sym2};
use crate::plot::{mesh_png, Corner, Inset, MeshPlot, RGBColor};
use serde::Serialize;
use std::path::{Path, PathBuf};

/// The adaptation options of "conform to this metric" (`anisomesh adapt --input M --sol S` with a
/// tensor field): sizes interpolated linearly between the given vertices, as mmg2d does with the
/// same files, and one smoothing sweep per cycle over what the cycle changed
/// ([`CycleSmoothing::Touched`]: these inputs are typically large).
pub fn metric_file_options() -> AdaptOptions {
    AdaptOptions::default()
        .interpolation(MetricInterpolation::LinearSizes)
        .cycle_smoothing(CycleSmoothing::Touched)
}

/// What to adapt to.
pub enum AdaptInput {
    /// An implicit shape (exact signed distance) on the rectangle `domain`.
    Shape {
        shape: Box<dyn Shape>,
        domain: (DVec2, DVec2),
    },
    /// A P1 level set `u` given on `mesh` (adapt to its zero level; derivatives are recovered).
    LevelSet { mesh: Mesh2, u: Vec<f64> },
    /// A metric field given on `mesh` (conform to it).
    Metric { mesh: Mesh2, metric: Vec<Sym2> },
}

/// Options of [`run`]. `Default` is the paper's Zalesak setting (004 §5.1): eps 1e-4,
/// hmin 0.001, hmax 0.2 (stretching 200).
#[derive(Debug, Clone)]
pub struct AdaptRunOptions {
    /// Interface accuracy ε of eq. (6).
    pub eps: f64,
    pub hmin: f64,
    pub hmax: f64,
    /// Half-width of the band around the zero level where eq. (6) applies; `None` (default):
    /// `5 ε`.
    pub band: Option<f64>,
    /// Use the multiscale Hessian metric with this many target vertices instead of eq. (6).
    pub target_vertices: Option<usize>,
    /// Isotropic variant of the chosen metric.
    pub iso: bool,
    /// Output directory and base name of the files written there.
    pub out_dir: PathBuf,
    pub name: String,
    /// Whether to draw the PNG.
    pub picture: bool,
    /// For a metric read from a file: grade it during the adaptation with this growth factor
    /// ([`crate::adapt::AdaptOptions::gradation`], mmg2d's `-hgrad`); `None` (default): as given.
    pub hgrad: Option<f64>,
}

impl Default for AdaptRunOptions {
    fn default() -> Self {
        AdaptRunOptions {
            eps: LevelSetMetric::default().eps,
            hmin: 1e-3,
            hmax: 0.2,
            band: None,
            target_vertices: None,
            iso: false,
            out_dir: PathBuf::from("out"),
            name: "zalesak".into(),
            picture: true,
            hgrad: None,
        }
    }
}

/// What [`run`] measured, written as `report.json`.
#[derive(Debug, Clone, Serialize)]
pub struct AdaptRunReport {
    #[serde(flatten)]
    pub mesh: MeshReport,
    pub metric_source: String,
    pub cycles: usize,
    pub splits: usize,
    pub collapses: usize,
    pub flips: usize,
    pub moves: usize,
    pub converged: bool,
    pub files: Vec<PathBuf>,
}

/// The default domain of a built-in shape: `[-2, 2]²` for the Zalesak disk (004 §5.1),
/// `[-1, 1]²` otherwise.
pub fn default_domain(shape_name: &str) -> (DVec2, DVec2) {
    if shape_name.eq_ignore_ascii_case("zalesak") {
        (DVec2::splat(-2.0), DVec2::splat(2.0))
    } else {
        (DVec2::splat(-1.0), DVec2::splat(1.0))
    }
}

fn level_set_metric(opts: &AdaptRunOptions) -> LevelSetMetric {
    let d = LevelSetMetric::default();
    LevelSetMetric {
        eps: opts.eps,
        hmin: opts.hmin,
        hmax: opts.hmax,
        // By default the band of eq. (6) scales with eps (5 eps).
        band: opts.band.unwrap_or(d.band / d.eps * opts.eps),
        isotropic: opts.iso,
        ..d
    }
}

fn hessian_metric(opts: &AdaptRunOptions, n: usize) -> HessianMetric {
    HessianMetric {
        target_vertices: n,
        hmin: opts.hmin,
        hmax: opts.hmax,
        isotropic: opts.iso,
        ..HessianMetric::default()
    }
}

/// Runs the job and writes `<out_dir>/<name>.mesh`, `.vtu`, `.png` and `<out_dir>/report.json`.
pub fn run(input: AdaptInput, opts: &AdaptRunOptions) -> Result<AdaptRunReport> {
    if !(opts.eps > 0.0 && opts.hmin > 0.0 && opts.hmax >= opts.hmin) {
        return Err(Error::InvalidInput(format!(
            "need eps > 0 and 0 < hmin <= hmax (got eps {}, hmin {}, hmax {})",
            opts.eps, opts.hmin, opts.hmax
        )));
    }
    if let Some(b) = opts.band.filter(|b| !(b.is_finite() && *b > 0.0)) {
        return Err(Error::InvalidInput(format!(
            "need a finite band half-width > 0 (got {b})"
        )));
    }
    let t0 = std::time::Instant::now();
    let (mesh, metric, u, shape, rep, source) = match input {
        AdaptInput::Shape { shape, domain } => {
            let (mesh, metric, u, rep, source) = adapt_shape(shape.as_ref(), domain, opts)?;
            (mesh, metric, Some(u), Some(shape), rep, source)
        }
        AdaptInput::LevelSet { mut mesh, u } => {
            let mut metric = match opts.target_vertices {
                Some(n) => hessian_metric(opts, n).field(&mesh, &u)?,
                None => level_set_metric(opts).field_from_p1(&mesh, &u)?,
            };
            let mut fields = vec![u];
            let rep = adapt(
                &mut mesh,
                &mut metric,
                &mut fields,
                None,
                &AdaptOptions::default(),
            )?;
            let u = fields.pop().unwrap_or_default();
            let source = describe(opts, "recovered from the P1 level set");
            (mesh, metric, Some(u), None, rep, source)
        }
        AdaptInput::Metric {
            mut mesh,
            mut metric,
        } => {
            let rep = adapt(
                &mut mesh,
                &mut metric,
                &mut [],
                None,
                &metric_file_options().gradation(opts.hgrad),
            )?;
            (
                mesh,
                metric,
                None,
                None,
                rep,
                match opts.hgrad {
                    Some(b) => format!("metric read from file, graded with factor {b}"),
                    None => "metric read from file".to_string(),
                },
            )
        }
    };
    let mut report = match &u {
        // Interface distances only against shapes whose exact interface is known.
        Some(u) => {
            let exact = shape
                .as_deref()
                .filter(|s| s.boundary_samples(16).is_some());
            mesh_report(&mesh, &metric, u, exact)?
        }
        None => metric_only_report(&mesh, &metric),
    };
    report.seconds = t0.elapsed().as_secs_f64();
    report.phases = vec![("adapt".into(), rep.seconds)];
    let files = write_outputs(&mesh, &metric, u.as_deref(), opts)?;
    let out = AdaptRunReport {
        mesh: report,
        metric_source: source,
        cycles: rep.cycles,
        splits: rep.splits,
        collapses: rep.collapses,
        flips: rep.flips,
        moves: rep.moves,
        converged: rep.converged,
        files,
    };
    let json = serde_json::to_string_pretty(&out)
        .map_err(|e| Error::InvalidInput(format!("report serialisation: {e}")))?;
    let path = opts.out_dir.join("report.json");
    io::atomic_write(&path, |w| w.write_all(json.as_bytes()))?;
    Ok(out)
}

fn describe(opts: &AdaptRunOptions, derivatives: &str) -> String {
    let kind = match opts.target_vertices {
        Some(n) => format!("multiscale L2 Hessian metric, target {n} vertices"),
        None => format!("geometric metric 004 eq. (6), eps {:e}", opts.eps),
    };
    let iso = if opts.iso { "isotropic " } else { "" };
    format!("{iso}{kind}, {derivatives}")
}

type Adapted = (Mesh2, Vec<Sym2>, Vec<f64>, AdaptReport, String);

/// Adapts to an exact shape: eq. (6) through [`adapt_to_shape`], or the Hessian metric of the
/// nodal distance re-evaluated exactly on each new mesh (a few rounds).
fn adapt_shape(
    shape: &dyn Shape,
    domain: (DVec2, DVec2),
    opts: &AdaptRunOptions,
) -> Result<Adapted> {
    let lm = level_set_metric(opts);
    match opts.target_vertices {
        None => {
            let so = ShapeAdaptOptions {
                metric: lm,
                ..ShapeAdaptOptions::default()
            };
            let (mesh, u, rep) = adapt_to_shape(shape, domain, &so)?;
            // The metric the last round adapted to, at the final vertices, for the report.
            let src = AnalyticLevelSetSource::new(
                |p| (shape.distance(p), shape.gradient(p), shape.hessian(p)),
                lm,
            );
            let (mut metric, _) = src.evaluate(&mesh);
            if let Some(beta) = so.gradation {
                gradate(&mesh, &mut metric, beta)?;
            }
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
                let rep = adapt(
                    &mut mesh,
                    &mut metric,
                    &mut [],
                    None,
                    &AdaptOptions::default(),
                )?;
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

fn metric_only_report(mesh: &Mesh2, metric: &[Sym2]) -> MeshReport {
    let q = crate::metric::quality_stats(mesh, metric);
    MeshReport {
        vertices: mesh.n_points(),
        triangles: mesh.n_live_tris(),
        edge_length_in_range: q.edge_length_in_range,
        q_ani_mean: q.q_ani_mean,
        q_ani_max: q.q_ani_max,
        ..MeshReport::default()
    }
}

/// Per-triangle `Q_ani` in the element metric (log-Euclidean mean of the vertex metrics).
fn triangle_quality(mesh: &Mesh2, metric: &[Sym2]) -> Vec<f64> {
    (0..mesh.n_tris())
        .map(|t| {
            let [a, b, c] = mesh.tris[t].map(|v| &metric[v as usize]);
            q_ani(
                mesh.tri_points(t),
                &crate::metric::element_metric([a, b, c]),
            )
        })
        .collect()
}

fn write_outputs(
    mesh: &Mesh2,
    metric: &[Sym2],
    u: Option<&[f64]>,
    opts: &AdaptRunOptions,
) -> Result<Vec<PathBuf>> {
    std::fs::create_dir_all(&opts.out_dir).map_err(|e| Error::io(&opts.out_dir, e))?;
    let path = |ext: &str| opts.out_dir.join(format!("{}.{ext}", opts.name));
    let quality = triangle_quality(mesh, metric);
    let mut files = Vec::new();
    io::write_mesh(&path("mesh"), mesh)?;
    files.push(path("mesh"));
    let mut point_fields = vec![("metric", FieldRef::TensorComponents(metric))];
    if let Some(u) = u {
        point_fields.push(("levelset", FieldRef::Scalar(u)));
    }
    io::write_vtu(&path("vtu"), mesh, &point_fields, &[("q_ani", &quality)])?;
    files.push(path("vtu"));
    if opts.picture {
        draw(&path("png"), mesh, u, quality, opts)?;
        files.push(path("png"));
    }
    Ok(files)
}

/// The mesh coloured by `Q_ani` with the interface drawn and a zoomed inset: at the upper right
/// corner of the slot for the Zalesak disk, else where the interface turns most sharply.
fn draw(
    path: &Path,
    mesh: &Mesh2,
    u: Option<&[f64]>,
    quality: Vec<f64>,
    opts: &AdaptRunOptions,
) -> Result<()> {
    let mut plot = MeshPlot {
        tri_colour: Some(quality),
        colour_range: Some((1.0, 2.0)),
        colour_label: "Q_ani (1 = ideal)".into(),
        title: format!("{}: {} vertices", opts.name, mesh.n_points()),
        ..MeshPlot::default()
    };
    if let Some(u) = u {
        if let Ok(lines) = extract_zero_level(mesh, u) {
            let focus = if opts.name.eq_ignore_ascii_case("zalesak") {
                Some(DVec2::new(0.06, 0.85))
            } else {
                sharpest_turn(&lines)
            };
            plot.polylines = lines
                .iter()
                .map(|l| (l.points.clone(), RGBColor(220, 30, 30), 1))
                .collect();
            if let Some(c) = focus {
                let half = DVec2::splat(0.02);
                plot.insets.push(Inset {
                    view: (c - half, c + half),
                    placement: Corner::TopRight,
                });
            }
        }
        // Show the shape, not the whole domain, when it is much smaller than the domain.
        if let Some((lo, hi)) = mesh.bounding_box() {
            let inside: Vec<DVec2> = mesh
                .points
                .iter()
                .zip(u)
                .filter(|(_, &v)| v <= 0.0)
                .map(|(p, _)| *p)
                .collect();
            if let Some(&first) = inside.first() {
                let (a, b) = inside
                    .iter()
                    .fold((first, first), |(a, b), &p| (a.min(p), b.max(p)));
                let margin = 0.25 * (b - a).max_element();
                plot.view = Some(((a - margin).max(lo), (b + margin).min(hi)));
            }
        }
    }
    mesh_png(path, mesh, &plot)
}

fn sharpest_turn(lines: &[crate::levelset::Polyline]) -> Option<DVec2> {
    let mut best = (0.0, None);
    for l in lines {
        for w in l.points.windows(3) {
            let (d1, d2) = (
                (w[1] - w[0]).normalize_or_zero(),
                (w[2] - w[1]).normalize_or_zero(),
            );
            let turn = d1.perp_dot(d2).abs();
            if turn > best.0 {
                best = (turn, Some(w[1]));
            }
        }
    }
    best.1
}
