//! `anisomesh stefan`: the Stefan problem on the interface-fitted mesh (001 §6).

use crate::app::repro::stefan::{frank, paper};
use anisomesh::error::Result;
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh stefan`.
#[derive(Debug, Args)]
pub struct StefanArgs {
    /// The case: frank (Frank's expanding circle against the exact solution) or pentagon
    /// (001 §6, no surface tension; defaults n = 128, dt = 2.5e-4, t-end = 0.4).
    #[arg(long, default_value = "frank", value_parser = ["frank", "pentagon"])]
    case: String,
    /// One base mesh of n x n cells instead of the refinement table 32, 64, 128, 256.
    #[arg(long)]
    n: Option<usize>,
    /// End time (frank: from t0 = 0.25; default 0.5 for frank, 0.4 for pentagon).
    #[arg(long)]
    t_end: Option<f64>,
    /// Time step (pentagon; frank uses 0.2 h).
    #[arg(long, default_value_t = 2.5e-4)]
    dt: f64,
    /// Output directory (stefan.json, stefan.csv, figures).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the case, prints its table and writes the report.
pub fn run(a: StefanArgs) -> Result<()> {
    if a.case == "pentagon" {
        return pentagon(&a);
    }
    let t_end = a.t_end.unwrap_or(0.5);
    let ns = match a.n {
        Some(n) => vec![n],
        None => vec![32, 64, 128, 256],
    };
    let rows = frank::run(&ns, t_end)?;
    println!(
        "Frank's circle, S0 = {}, t {} -> {}, (-2, 2)^2, dt ~ 0.2 h",
        frank::S0,
        frank::T0,
        t_end
    );
    println!(
        "{:>5} {:>9} {:>6} {:>11} {:>11} {:>11} {:>6} {:>8} {:>6} {:>8}",
        "n", "dt", "steps", "mean |r-R|", "max |r-R|", "|RA - R|", "order", "fitted", "CG", "s"
    );
    for r in &rows {
        println!(
            "{:>5} {:>9.3e} {:>6} {:>11.3e} {:>11.3e} {:>11.3e} {:>6} {:>8} {:>6.1} {:>8.2}",
            r.n,
            r.dt,
            r.steps,
            r.radius_error,
            r.radius_error_max,
            r.area_radius_error,
            if r.order.is_finite() {
                format!("{:.2}", r.order)
            } else {
                "–".to_string()
            },
            r.fitted_vertices,
            r.cg_iterations,
            r.seconds
        );
    }
    frank::write(&a.output, &rows, t_end)?;
    println!("wrote {}", a.output.join("stefan.json").display());
    Ok(())
}

fn pentagon(a: &StefanArgs) -> Result<()> {
    let n = a.n.unwrap_or(128);
    let rep = paper::run(n, a.dt, a.t_end.unwrap_or(0.4), 8)?;
    println!(
        "pentagon seed (circumradius {}), {n} x {n} cells, dt = {}, no surface tension",
        paper::SEED_RADIUS,
        a.dt
    );
    println!(
        "{:>7} {:>6} {:>10} {:>8} {:>8} {:>4}",
        "t", "step", "area", "fitted", "max vn", "CG"
    );
    for s in &rep.snapshots {
        println!(
            "{:>7.4} {:>6} {:>10.4e} {:>8} {:>8.3} {:>4}",
            s.time, s.step, s.area, s.fitted_vertices, s.max_vn, s.cg_iterations
        );
    }
    println!("{:.1} s", rep.seconds);
    paper::write(&a.output, &rep)?;
    println!("wrote {}", a.output.join("stefan.json").display());
    Ok(())
}
