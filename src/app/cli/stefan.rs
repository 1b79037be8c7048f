//! `anisomesh stefan`: the Stefan problem on the interface-fitted mesh (001 §6).

use crate::app::repro::stefan::frank;
use anisomesh::error::{Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh stefan`.
#[derive(Debug, Args)]
pub struct StefanArgs {
    /// The case: frank (Frank's expanding circle against the exact solution).
    #[arg(long, default_value = "frank", value_parser = ["frank"])]
    case: String,
    /// One base mesh of n x n cells instead of the refinement table 32, 64, 128, 256.
    #[arg(long)]
    n: Option<usize>,
    /// End time (frank: from t0 = 0.25).
    #[arg(long, default_value_t = 0.5)]
    t_end: f64,
    /// Output directory (stefan.json, stefan.csv, figures).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the case, prints its table and writes the report.
pub fn run(a: StefanArgs) -> Result<()> {
    if a.case != "frank" {
        return Err(Error::InvalidInput(format!(
            "unknown Stefan case {}",
            a.case
        )));
    }
    let ns = match a.n {
        Some(n) => vec![n],
        None => vec![32, 64, 128, 256],
    };
    let rows = frank::run(&ns, a.t_end)?;
    println!(
        "Frank's circle, S0 = {}, t {} -> {}, (-2, 2)^2, dt ~ 0.2 h",
        frank::S0,
        frank::T0,
        a.t_end
    );
    println!(
        "{:>5} {:>9} {:>6} {:>11} {:>11} {:>11} {:>6} {:>8} {:>6} {:>8}",
        "n", "dt", "steps", "mean |r-R|", "max |r-R|", "|RA - R|", "order", "fitted", "CG", "s"
    );
    for r in &rows {
        println!(
            "{:>5} {:>9.3e} {:>6} {:>11.3e} {:>11.3e} {:>11.3e} {:>6.2} {:>8} {:>6.1} {:>8.2}",
            r.n,
            r.dt,
            r.steps,
            r.radius_error,
            r.radius_error_max,
            r.area_radius_error,
            r.order,
            r.fitted_vertices,
            r.cg_iterations,
            r.seconds
        );
    }
    frank::write(&a.output, &rows, a.t_end)?;
    println!("wrote {}", a.output.join("stefan.json").display());
    Ok(())
}
