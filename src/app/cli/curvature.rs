//! `anisomesh curvature --expr E [--n N] [--domain X0,Y0,X1,Y1]`: the curvature of the zero
//! level of an expression by local averaging on interface-fitted grids (001 (5.2), §5), against
//! the exact curvature of the expression's zero level, with the observed order.

use super::adapt::parse_domain;
use anisomesh::backends::fitted::interface_curvature;
use anisomesh::io::atomic_write;
use anisomesh::levelset::{Expr, Shape};
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::{DVec2, Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh curvature`.
#[derive(Debug, Args)]
pub struct CurvatureArgs {
    /// The level set, an expression in x and y (negative inside); any normalisation.
    #[arg(long, default_value = "sqrt((x-0.5)^2 + (y-0.5)^2) - 0.25")]
    expr: String,
    /// One grid of N x N cells; without it the sequence 16, 32, 64, 128.
    #[arg(long)]
    n: Option<usize>,
    /// The domain x0,y0,x1,y1 (the unit square by default).
    #[arg(long, value_parser = parse_domain)]
    domain: Option<(DVec2, DVec2)>,
    /// Output directory (curvature.json).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// One grid of the table.
#[derive(Debug, serde::Serialize)]
struct Row {
    n: usize,
    h: f64,
    interface_nodes: usize,
    max_rel_error: f64,
    at_limit: usize,
}

/// The exact curvature `div(∇f/|∇f|)` of the level set of `f` through `p` (derivatives of
/// the expression by differences).
fn exact_curvature(f: &Expr, p: DVec2) -> f64 {
    let g = f.gradient(p);
    let h = f.hessian(p);
    let n2 = g.length_squared();
    ((h.xx + h.yy) * n2 - (g.x * g.x * h.xx + 2.0 * g.x * g.y * h.xy + g.y * g.y * h.yy))
        / (n2 * n2.sqrt())
}

/// Runs the table and writes `curvature.json`.
pub fn run(a: CurvatureArgs) -> Result<()> {
    let f = Expr::parse(&a.expr)?;
    let (lo, hi) = a.domain.unwrap_or((DVec2::ZERO, DVec2::ONE));
    let ns: Vec<usize> = match a.n {
        Some(n) if (2..=4096).contains(&n) => vec![n],
        Some(n) => {
            return Err(Error::InvalidInput(format!(
                "--n {n}: need 2 to 4096 cells per side"
            )))
        }
        None => vec![16, 32, 64, 128],
    };
    println!(
        "curvature of the zero level of {} by local averaging (001 (5.2))",
        a.expr
    );
    println!(
        "{:>6} {:>10} {:>8} {:>14} {:>8} {:>9}",
        "n", "h", "nodes", "max rel error", "order", "at bound"
    );
    let mut rows: Vec<Row> = Vec::new();
    for &n in &ns {
        let mesh = Mesh2::rectangle(lo, hi, n, n, GridPattern::Right)?;
        let u: Vec<f64> = mesh.points.iter().map(|&p| f.eval(p)).collect();
        let (points, kappa, at_limit) = interface_curvature(&mesh, &u)?;
        let exact: Vec<f64> = points.iter().map(|&p| exact_curvature(&f, p)).collect();
        let scale = exact.iter().fold(0.0f64, |m, k| m.max(k.abs()));
        if !(scale.is_finite() && scale > 0.0) {
            return Err(Error::InvalidInput(format!(
                "curvature: the zero level of '{}' has no finite, non-zero curvature to compare with",
                a.expr
            )));
        }
        let err = kappa
            .iter()
            .zip(&exact)
            .map(|(k, e)| (k - e).abs() / scale)
            .fold(0.0f64, f64::max);
        let h = ((hi.x - lo.x) / n as f64).max((hi.y - lo.y) / n as f64);
        let order = rows
            .last()
            .map(|r| format!("{:.2}", (r.max_rel_error / err).ln() / (r.h / h).ln()))
            .unwrap_or_default();
        println!(
            "{n:>6} {h:>10.3e} {:>8} {err:>14.3e} {order:>8} {at_limit:>9}",
            points.len()
        );
        rows.push(Row {
            n,
            h,
            interface_nodes: points.len(),
            max_rel_error: err,
            at_limit,
        });
    }
    let slope = fitted_slope(&rows);
    if let Some(s) = slope {
        println!("fitted slope {s:.3} (001 §5: 2.065 for the circle r = 1/4)");
    }
    if let Some(r) = rows.iter().find(|r| r.at_limit > 0) {
        println!(
            "note: on the {} grid {} vertices reach the bound |κ_h| ≤ ∫|∇N_v| / ∫N_v (unresolved curvature)",
            r.n, r.at_limit
        );
    }
    std::fs::create_dir_all(&a.output).map_err(|e| Error::io(&a.output, e))?;
    let json = serde_json::json!({ "expr": a.expr, "rows": rows, "slope": slope });
    let path = a.output.join("curvature.json");
    let text =
        serde_json::to_string_pretty(&json).map_err(|e| Error::InvalidInput(e.to_string()))?;
    atomic_write(&path, |w| w.write_all(text.as_bytes()))?;
    println!("wrote {}", path.display());
    Ok(())
}

/// The least-squares slope of log(error) against log(h), when there are two grids or more.
fn fitted_slope(rows: &[Row]) -> Option<f64> {
    if rows.len() < 2 {
        return None;
    }
    let n = rows.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = rows
        .iter()
        .map(|r| (r.h.ln(), r.max_rel_error.max(1e-300).ln()))
        .unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = x.iter().map(|x| (x - mx) * (x - mx)).sum();
    Some(sxy / sxx)
}
