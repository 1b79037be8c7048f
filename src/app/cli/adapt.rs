//! `anisomesh adapt`: adapt a mesh to a shape, an expression, a level set or a metric file.

use super::adapt3::Sol3;
use super::metric_args::MetricArgs;
use super::progress::Spinner;
use super::shape::chosen_shape;
use super::user_files::{check_metric, check_sizes, read_input_mesh, read_sol_checked, InputMesh};
use crate::app::repro::adapt_run::{self, AdaptRunOptions};
use anisomesh::adapt::{AdaptTarget, LevelSetMetric, RunOptions, DEFAULT_MAX_VERTICES};
use anisomesh::io::{self, SolField};
use anisomesh::metric::Sym2;
use anisomesh::{DVec2, Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh adapt` (defaults: the Zalesak disk at the paper's setting).
#[derive(Debug, Args)]
pub struct AdaptArgs {
    /// A built-in shape: zalesak (default), circle or flower.
    #[arg(long, conflicts_with_all = ["expr", "input"])]
    shape: Option<String>,
    /// A level-set expression in x and y, negative inside, e.g. "x^2 + y^2 - 0.25".
    #[arg(long, conflicts_with = "input")]
    expr: Option<String>,
    /// An input mesh (.mesh in 2D or 3D, .msh); with --sol. A tetrahedral mesh is adapted in 3D.
    #[arg(long, requires = "sol")]
    input: Option<PathBuf>,
    /// A .sol on the input mesh: a scalar field means "adapt to its zero level" (sizes with
    /// --sizes); a symmetric tensor field (Medit type 3; six entries in 3D) means "conform to
    /// this metric" (as mmg2d / mmg3d do).
    #[arg(long, requires = "input")]
    sol: Option<PathBuf>,
    /// The rectangle to mesh for --shape/--expr, as "x0,y0,x1,y1".
    #[arg(long)]
    domain: Option<String>,
    /// The geometric metric's accuracy, sizes, band and growth.
    #[command(flatten)]
    metric: MetricArgs,
    /// Use the multiscale Hessian (interpolation-error) metric with this many target vertices.
    #[arg(long, conflicts_with = "band")]
    target_vertices: Option<usize>,
    /// Isotropic version of the metric (for comparison).
    #[arg(long)]
    iso: bool,
    /// Grade the metric with this growth factor (> 1; as mmg's -hgrad, e.g. 1.3). 2D: a metric
    /// given with --sol, during the adaptation. 3D: any metric (shape, level set, metric or
    /// sizes file), over the tetrahedra. Default: the metric as given.
    #[arg(long)]
    hgrad: Option<f64>,
    /// With --sol holding a scalar field: read it as element sizes (an isotropic size map, as
    /// mmg reads a scalar .sol without -ls) instead of a level set.
    #[arg(long, requires = "sol")]
    sizes: bool,
    /// Refuse a run whose metric asks for more vertices than this (estimated from its
    /// complexity before adapting).
    #[arg(long, default_value_t = DEFAULT_MAX_VERTICES)]
    max_vertices: f64,
    /// Output directory.
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
    /// A tetrahedral --input: boundary edges whose triangles' normals differ by more than this
    /// angle (degrees; as mmg3d's -ar) are ridges, kept with the corners by the adaptation
    /// (besides edges between differently labelled triangles and the file's Edges, Corners,
    /// RequiredVertices).
    #[arg(long, default_value_t = anisomesh::mesh3::DEFAULT_RIDGE_ANGLE)]
    ridge_angle: f64,
    /// Also cut the adapted mesh along the shape's zero level (interface edges labelled 10,
    /// inside 3, outside 2) and write it beside the adapted mesh as `<name>_fitted.mesh`; with
    /// --input/--sol, the zero level of the input's P1 level set.
    #[arg(long)]
    fit: bool,
    /// Dimension: 2 (triangles) or 3 (tetrahedra in [-1, 1]^3 around --shape star|sphere|torus
    /// or an --expr in x, y, z).
    #[arg(long, default_value_t = 2, value_parser = clap::value_parser!(u8).range(2..=3))]
    dim: u8,
    /// 3D: reach a shape's metric through stages with every size doubled ("sizes", default),
    /// with only hmin and the band doubled ("normal"), or directly ("off"); a 3D metric file's
    /// through stages with its smallest sizes raised (any but "off").
    #[arg(long, value_parser = ["sizes", "normal", "off"])]
    continuation: Option<String>,
}

pub(crate) fn parse_domain(s: &str) -> Result<(DVec2, DVec2)> {
    let v: Vec<f64> = s
        .split(',')
        .map(|x| x.trim().parse::<f64>())
        .collect::<std::result::Result<_, _>>()
        .map_err(|e| Error::InvalidInput(format!("--domain '{s}': {e}")))?;
    match v[..] {
        [x0, y0, x1, y1] if x1 > x0 && y1 > y0 => Ok((DVec2::new(x0, y0), DVec2::new(x1, y1))),
        _ => Err(Error::InvalidInput(format!(
            "--domain '{s}': expected x0,y0,x1,y1 with x1 > x0 and y1 > y0"
        ))),
    }
}

/// Runs the job and prints the report.
pub fn run(a: AdaptArgs) -> Result<()> {
    let (metric3, iso) = (a.metric.clone(), a.iso);
    let metric3 = move |b| LevelSetMetric {
        isotropic: iso,
        ..metric3.apply_tet(b)
    };
    let input = match &a.input {
        Some(p) => Some(read_input_mesh(p, a.ridge_angle)?),
        None => None,
    };
    if let (Some(InputMesh::Tet(mesh)), Some(mesh_path), Some(sol_path)) =
        (&input, &a.input, &a.sol)
    {
        if a.target_vertices.is_some() || a.fit || a.domain.is_some() {
            return Err(Error::InvalidInput(
                "--target-vertices, --fit and --domain are 2D options; this mesh is tetrahedral"
                    .into(),
            ));
        }
        let sol = read_sol_checked(sol_path, mesh.n_points(), 3)?;
        let sol = match sol.fields.into_iter().next() {
            Some(SolField::Tensor3(_)) if a.metric.has_band() => {
                return Err(Error::InvalidInput(format!(
                    "{}: --band sets the band of the geometric metric; this file holds a metric",
                    sol_path.display()
                )));
            }
            Some(SolField::Tensor3(m)) => Sol3::Metric(check_metric(
                sol_path,
                m.iter().map(io::sym3_from_file).collect(),
            )?),
            Some(SolField::Scalar(h)) if a.sizes => {
                check_sizes(sol_path, &h)?;
                Sol3::Sizes(h)
            }
            Some(SolField::Scalar(u)) => {
                if let Some(v) = u.iter().position(|x| !x.is_finite()) {
                    return Err(Error::InvalidField {
                        name: sol_path.display().to_string(),
                        msg: format!("non-finite value {} at vertex {}", u[v], v + 1),
                    });
                }
                Sol3::LevelSet(u)
            }
            _ => {
                return Err(Error::InvalidInput(format!(
                    "{}: expected a scalar level set, sizes (--sizes) or a 3D metric (symmetric \
                     tensor, six entries) field",
                    sol_path.display()
                )))
            }
        };
        let stem = mesh_path
            .file_stem()
            .map(|s| s.to_string_lossy().into_owned())
            .unwrap_or_else(|| "input".into());
        return super::adapt3::run_files(
            mesh,
            &stem,
            sol,
            &super::adapt3::options(metric3, a.continuation.as_deref(), a.max_vertices)?,
            a.hgrad,
            &a.output,
        );
    }
    if a.dim == 3 {
        if a.input.is_some() {
            return Err(Error::InvalidInput(format!(
                "--dim 3: {} is a 2D mesh",
                a.input
                    .as_deref()
                    .unwrap_or(std::path::Path::new(""))
                    .display()
            )));
        }
        if a.domain.is_some() || a.target_vertices.is_some() {
            return Err(Error::InvalidInput(
                "--dim 3 adapts [-1, 1]^3 to --shape or --expr; --domain and --target-vertices \
                 are 2D options"
                    .into(),
            ));
        }
        return super::adapt3::run(
            a.shape.as_deref(),
            a.expr.as_deref(),
            &super::adapt3::options(metric3, a.continuation.as_deref(), a.max_vertices)?,
            a.hgrad,
            &a.output,
        );
    }
    if a.hgrad.is_some() && a.sol.is_none() {
        return Err(Error::InvalidInput(
            "--hgrad: in 2D it grades a metric given with --input/--sol (shapes are graded \
             already)"
                .into(),
        ));
    }
    let mut opts = AdaptRunOptions {
        run: RunOptions {
            metric: LevelSetMetric {
                isotropic: a.iso,
                ..a.metric.apply(LevelSetMetric::default())
            },
            target_vertices: a.target_vertices,
            hgrad: a.hgrad,
            max_vertices: a.max_vertices,
        },
        out_dir: a.output.clone(),
        ..AdaptRunOptions::default()
    };
    let input = if let (Some(InputMesh::Tri(mesh)), Some(mesh_path), Some(sol_path)) =
        (input, &a.input, &a.sol)
    {
        let mesh = *mesh;
        let sol = read_sol_checked(sol_path, mesh.n_points(), 2)?;
        opts.name = mesh_path
            .file_stem()
            .map(|s| format!("{}_adapted", s.to_string_lossy()))
            .unwrap_or_else(|| "adapted".into());
        match sol.fields.into_iter().next() {
            Some(SolField::Scalar(_)) if a.hgrad.is_some() && !a.sizes => {
                return Err(Error::InvalidInput(format!(
                    "{}: --hgrad grades a metric; this file holds a scalar level set",
                    sol_path.display()
                )))
            }
            Some(SolField::Tensor2(_)) if a.metric.has_band() => {
                return Err(Error::InvalidInput(format!(
                    "{}: --band sets the band of the geometric metric; this file holds a metric",
                    sol_path.display()
                )))
            }
            Some(SolField::Scalar(h)) if a.sizes => {
                check_sizes(sol_path, &h)?;
                AdaptTarget::Metric {
                    mesh,
                    metric: h.iter().map(|&h| Sym2::iso(h)).collect(),
                }
            }
            Some(SolField::Scalar(u)) => AdaptTarget::LevelSet { mesh, u },
            Some(SolField::Tensor2(metric)) => AdaptTarget::Metric { mesh, metric },
            _ => {
                return Err(Error::InvalidInput(format!(
                    "{}: expected a scalar level set or a 2D metric (symmetric tensor) field",
                    sol_path.display()
                )))
            }
        }
    } else {
        let name = match (&a.shape, &a.expr) {
            (None, None) => Some("zalesak".to_string()),
            (s, _) => s.clone(),
        };
        let shape = chosen_shape(name.as_deref(), a.expr.as_deref())?;
        opts.name = name.unwrap_or_else(|| "expr".into());
        let domain = match &a.domain {
            Some(d) => parse_domain(d)?,
            None => adapt_run::default_domain(&opts.name),
        };
        AdaptTarget::Shape { shape, domain }
    };
    let spinner = Spinner::start("adapting");
    let r = adapt_run::run(input, &opts);
    spinner.finish();
    let r = r?;
    for w in &r.run.warnings {
        eprintln!("anisomesh: warning: {w}");
    }
    let (m, r) = (&r.run.mesh, &r);
    // A level-set input is measured against its own P1 zero level.
    let reference = if a.input.is_some() { "input" } else { "exact" };
    println!(
        "estimated from the metric: {:.0} vertices",
        r.run.estimated_vertices
    );
    println!("metric: {}", r.run.metric_source);
    println!(
        "vertices {}  triangles {}  edges in [1/sqrt2, sqrt2] {:.2}%  Q_ani mean {:.4} max {:.3}",
        m.vertices,
        m.triangles,
        100.0 * m.edge_length_in_range,
        m.q_ani_mean,
        m.q_ani_max
    );
    if m.perimeter > 0.0 {
        print!("area {:.10}  perimeter {:.10}", m.area, m.perimeter);
        if let (Some(ea), Some(ep)) = (m.exact_area, m.exact_perimeter) {
            print!(
                "  ({reference} {ea:.10}, {ep:.10}: relative errors {:.2e}, {:.2e})",
                (m.area - ea).abs() / ea,
                (m.perimeter - ep).abs() / ep
            );
        }
        println!();
    }
    if let Some(h) = m.hausdorff {
        println!("two-sided distance to the {reference} interface (Hausdorff) {h:.3e}");
    }
    println!(
        "{:.2} s, {:.0} vertices/s ({} cycles, {} splits, {} collapses, {} flips, {} moves{})",
        m.seconds,
        m.vertices as f64 / m.seconds.max(1e-9),
        r.run.cycles,
        r.run.splits,
        r.run.collapses,
        r.run.flips,
        r.run.moves,
        if r.run.converged {
            ""
        } else {
            ", not converged"
        }
    );
    for f in &r.files {
        println!("wrote {}", f.display());
    }
    println!("wrote {}", opts.out_dir.join("report.json").display());
    if let (true, Some(input), Some(sol)) = (a.fit, &a.input, &a.sol) {
        super::fit::fit_adapted_input(&opts.out_dir, &opts.name, input, sol)?;
    } else if a.fit {
        super::fit::fit_adapted(
            &opts.out_dir,
            &opts.name,
            a.shape.as_deref(),
            a.expr.as_deref(),
        )?;
    }
    Ok(())
}
