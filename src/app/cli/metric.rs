//! `anisomesh metric --input M.mesh (--sol U.sol | --expr E) [--eps --hmin --hmax --band --grade
//! | --target-vertices N] [--hgrad G] -o METRIC.sol`: the metric of a level set on a user's
//! triangle or tetrahedral mesh, written as a Medit tensor field (what `mmg2d_O3` / `mmg3d_O3
//! -in M.mesh -sol METRIC.sol` read).
//!
//! Level set → metric, 2D: the metric `adapt --input M.mesh --sol U.sol` adapts to, evaluated at
//! the input's vertices by the same library call ([`level_set_metric`]): 004 eq. (6) of the
//! exact distance to the P1 zero level (004 §2.2), its normal and the shape operator of the
//! least-squares Hessian (004 §4.3), with `adapt`'s size bounds, band, growth and gradation (same
//! defaults, same flags); with `--target-vertices`, `adapt`'s multiscale L2 Hessian metric of the
//! field itself. 3D: the metric `adapt --input M.mesh --sol U.sol` (`adapt --dim 3 --expr E`)
//! adapts to, by the same library call ([`shape_metric3`]): eq. (6) of the exact distance to
//! the P1 zero level with the least-squares shape operator (or of the expression's
//! derivatives), with the defaults of `adapt --dim 3` and the same flags, graded by `--hgrad`
//! as `adapt --hgrad` grades it.

use super::measure::print_conformity;
use super::metric_args::MetricArgs;
use super::user_files::{read_scalar, read_user_mesh, UserMesh};
use anisomesh::adapt::{
    level_set_metric, shape_metric3, DiscreteLevelSet3, LevelSetMetric, Run3Options, RunOptions,
};
use anisomesh::io::{self, Sol};
use anisomesh::levelset::{Expr, Variables};
use anisomesh::metric::{complexity, conformity, gradate, predicted_vertices, Sym2, Sym3};
use anisomesh::{Error, Mesh2, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh metric`.
#[derive(Debug, Args)]
pub struct MetricCmdArgs {
    /// The mesh (.mesh 2D or 3D, .msh).
    #[arg(long)]
    pub input: PathBuf,
    /// The level set on the mesh's vertices (.sol, one scalar per vertex).
    #[arg(long, conflicts_with = "expr", required_unless_present = "expr")]
    pub sol: Option<PathBuf>,
    /// The level set as an expression in x, y (and z on a 3D mesh), negative inside.
    #[arg(long)]
    pub expr: Option<String>,
    /// The geometric metric's accuracy, sizes, band and growth (as for `adapt`).
    #[command(flatten)]
    pub metric: MetricArgs,
    /// The multiscale L2 Hessian metric of the field with this many target vertices (2D).
    #[arg(long, conflicts_with = "band")]
    pub target_vertices: Option<usize>,
    /// Grade the metric with this growth factor (> 1, as mmg's -hgrad), as `adapt --hgrad`.
    #[arg(long)]
    pub hgrad: Option<f64>,
    /// Output .sol.
    #[arg(short, long)]
    pub output: PathBuf,
}

/// The level set at the vertices: read from `--sol` or evaluated from `--expr`.
fn level_set(a: &MetricCmdArgs, mesh: &UserMesh) -> Result<Vec<f64>> {
    let u = match (&a.sol, &a.expr, mesh) {
        (Some(p), _, _) => return read_scalar(p, mesh),
        (None, Some(e), UserMesh::Tri { points, .. }) => {
            let e = Expr::parse(e)?;
            points.iter().map(|&p| e.eval(p)).collect::<Vec<f64>>()
        }
        (None, Some(e), UserMesh::Tet { points, .. }) => {
            let e = Expr::parse_with(e, Variables::XYZ)?;
            points.iter().map(|&p| e.eval3(p)).collect()
        }
        (None, None, _) => {
            return Err(Error::InvalidInput(
                "metric: give the level set with --sol or --expr".into(),
            ))
        }
    };
    if let Some(v) = u.iter().position(|x| !x.is_finite()) {
        return Err(Error::InvalidInput(format!(
            "--expr: non-finite value {} at vertex {}",
            u[v],
            v + 1
        )));
    }
    Ok(u)
}

/// The 2D metric field: the metric `adapt --input M.mesh --sol U.sol` adapts to, on the input
/// mesh ([`level_set_metric`]).
pub fn metric2(
    mesh: &Mesh2,
    u: &[f64],
    lm: &LevelSetMetric,
    target: Option<usize>,
) -> Result<Vec<Sym2>> {
    lm.validate()?;
    let opts = RunOptions {
        metric: *lm,
        target_vertices: target,
        ..RunOptions::default()
    };
    level_set_metric(mesh, u, None, &opts)
}

/// The 3D metric field: the metric `adapt --input M.mesh --sol U.sol` (or `adapt --dim 3
/// --expr E`) adapts to, at the input's vertices, by the same library call
/// ([`shape_metric3`] of the input's zero level, [`DiscreteLevelSet3`], or of the expression).
pub fn metric3(
    points: &[anisomesh::DVec3],
    cells: &[[u32; 4]],
    u: &[f64],
    expr: Option<&str>,
    lm: &LevelSetMetric,
    hgrad: Option<f64>,
) -> Result<Vec<Sym3>> {
    match expr {
        Some(e) => {
            let (_, shape) = super::adapt3::shape3(None, Some(e))?;
            shape_metric3(shape.as_ref(), lm, points, cells, hgrad)
        }
        None => {
            let shape = DiscreteLevelSet3::new(points, cells, u)?;
            shape_metric3(&shape, lm, points, cells, hgrad)
        }
    }
}

/// Runs `anisomesh metric`.
pub fn run(a: MetricCmdArgs) -> Result<()> {
    let lm = a.metric.apply(LevelSetMetric::default());
    let mesh = read_user_mesh(&a.input)?;
    let u = level_set(&a, &mesh)?;
    let (lo, hi) = u
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), &x| {
            (l.min(x), h.max(x))
        });
    if lo > 0.0 || hi < 0.0 {
        return Err(Error::EmptyLevelSet(format!(
            "the level set has no zero level on the mesh (values in [{lo:.3e}, {hi:.3e}])"
        )));
    }
    match &mesh {
        UserMesh::Tri {
            points,
            cells,
            mesh,
        } => {
            let mut m = metric2(mesh, &u, &lm, a.target_vertices)?;
            if let Some(g) = a.hgrad {
                gradate(mesh, &mut m, g)?;
            }
            io::write_sol(&a.output, &Sol::metric(m.clone()))?;
            println!(
                "metric of {}: {} ; predicts about {:.0} vertices",
                a.input.display(),
                mesh_kind(&a),
                predicted_vertices(complexity(mesh, &m))
            );
            print_conformity(
                "the input mesh in this metric",
                &conformity(points, cells, &m)?,
            );
        }
        UserMesh::Tet { points, cells } => {
            if a.target_vertices.is_some() {
                return Err(Error::Unsupported(
                    "metric: --target-vertices is 2D only".into(),
                ));
            }
            let lm3 = a.metric.apply_tet(Run3Options::default().metric);
            let m = metric3(points, cells, &u, a.expr.as_deref(), &lm3, a.hgrad)?;
            io::write_sol(&a.output, &Sol::metric3(&m))?;
            println!("metric of {}: {}", a.input.display(), mesh_kind(&a));
            print_conformity(
                "the input mesh in this metric",
                &conformity(points, cells, &m)?,
            );
        }
    }
    println!("wrote {}", a.output.display());
    Ok(())
}

fn mesh_kind(a: &MetricCmdArgs) -> String {
    match a.target_vertices {
        Some(n) => format!("multiscale L2 Hessian metric, target {n} vertices"),
        None => "geometric metric 004 eq. (6) of the distance to the zero level".into(),
    }
}
