//! `anisomesh solvation`: molecular solvation by the variational implicit-solvent model on the
//! interface-fitted mesh (001 §7).

use crate::app::repro::solvation::{run, sweep, write, write_sweep};
use anisomesh::backends::fitted::solvation::{RelaxOptions, SystemKind, Wrap, ROD_SPACING};
use anisomesh::backends::fitted::ExtensionKind;
use anisomesh::error::{Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh solvation`.
#[derive(Debug, Args)]
pub struct SolvationArgs {
    /// The system of 001 §7: three (three particles), ring (8 particles on a circle) or rods
    /// (two rods of 9 particles a distance d apart).
    #[arg(long, default_value = "three")]
    system: String,
    /// Distance between the rods in units of sigma (rods; default 3.2).
    #[arg(long)]
    d: Option<f64>,
    /// Spacing of the 9 particles along each rod in units of sigma (rods; 001 does not give it).
    #[arg(long, default_value_t = ROD_SPACING)]
    spacing: f64,
    /// Initial surface: loose, tight or both (default both).
    #[arg(long, default_value = "both")]
    wrap: String,
    /// Cells per side of the base grid on the unit square (default 128; the sweep 64).
    #[arg(long)]
    n: Option<usize>,
    /// Largest number of relaxation steps per run.
    #[arg(long, default_value_t = 4000)]
    steps: usize,
    /// Steady state: the length-weighted mean |V_n| on the interface below this.
    #[arg(long, default_value_t = 2e-5)]
    tol: f64,
    /// Steady state also when G changed by less than this times |G| over the last 50 steps
    /// (0: only the |V_n| test).
    #[arg(long, default_value_t = 1e-6)]
    energy_rtol: f64,
    /// Courant number of the adaptive time step.
    #[arg(long, default_value_t = 0.5)]
    cfl: f64,
    /// Semi-implicit stabilisation factor of the curvature term (0: the explicit step).
    #[arg(long, default_value_t = 1.0)]
    stabilise: f64,
    /// With --stabilise > 0: the curvature limit of the time step in units of the explicit one.
    #[arg(long, default_value_t = 16.0)]
    curvature_steps: f64,
    /// Velocity extension of 001 §3: harmonic or ls (least squares).
    #[arg(long, default_value = "harmonic")]
    extension: String,
    /// Rods only: relax both wraps at d = 1.6, 2.0, ..., 5.6 sigma (or --d-list) and print the
    /// free energy against d (001 Fig. 7.8).
    #[arg(long)]
    sweep: bool,
    /// Distances of the sweep, comma-separated, in units of sigma.
    #[arg(long)]
    d_list: Option<String>,
    /// Output directory (solvation.json or solvation_sweep.json/.csv, figures/).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

fn positive_d(d: f64) -> Result<f64> {
    if d.is_finite() && d > 0.0 {
        Ok(d)
    } else {
        Err(Error::InvalidInput(format!(
            "solvation: --d must be finite and positive (got {d})"
        )))
    }
}

/// Runs the command.
pub fn run_cli(a: SolvationArgs) -> Result<()> {
    let opts = RelaxOptions {
        cfl: a.cfl,
        tol: a.tol,
        energy_rtol: a.energy_rtol,
        max_steps: a.steps,
        stabilise: a.stabilise,
        curvature_steps: a.curvature_steps,
        extension: match a.extension.as_str() {
            "harmonic" => ExtensionKind::Harmonic,
            "ls" => ExtensionKind::LeastSquares,
            e => {
                return Err(Error::InvalidInput(format!(
                    "solvation: unknown --extension '{e}' (harmonic, ls)"
                )))
            }
        },
        ..RelaxOptions::default()
    };
    let kind = match a.system.as_str() {
        "three" => SystemKind::Three,
        "ring" => SystemKind::Ring,
        "rods" => SystemKind::Rods {
            d: positive_d(a.d.unwrap_or(3.2))?,
            spacing: a.spacing,
        },
        s => {
            return Err(Error::InvalidInput(format!(
                "solvation: unknown --system '{s}' (three, ring, rods)"
            )))
        }
    };
    let wraps = match a.wrap.as_str() {
        "loose" => vec![Wrap::Loose],
        "tight" => vec![Wrap::Tight],
        "both" => vec![Wrap::Loose, Wrap::Tight],
        w => {
            return Err(Error::InvalidInput(format!(
                "solvation: unknown --wrap '{w}' (loose, tight, both)"
            )))
        }
    };
    if a.sweep {
        if !matches!(kind, SystemKind::Rods { .. }) {
            return Err(Error::InvalidInput(
                "solvation: --sweep needs --system rods".into(),
            ));
        }
        let ds: Vec<f64> = match &a.d_list {
            Some(list) => list
                .split(',')
                .map(|t| {
                    t.trim().parse::<f64>().map_err(|_| {
                        Error::InvalidInput(format!("solvation: --d-list: '{t}' is not a number"))
                    })
                })
                .map(|d| d.and_then(positive_d))
                .collect::<Result<Vec<f64>>>()?,
            None => (0..=10).map(|k| 1.6 + 0.4 * k as f64).collect(),
        };
        let n = a.n.unwrap_or(64);
        let s = sweep(&ds, a.spacing, n, &opts)?;
        println!("two rods, {n} x {n} cells: relaxed free energy G against d (001 Fig. 7.8)");
        println!(
            "{:>6} {:>12} {:>6} {:>6} {:>12} {:>6} {:>6} {:>9}",
            "d/sig", "G loose", "comp", "steps", "G tight", "comp", "steps", "converged"
        );
        for r in &s.rows {
            println!(
                "{:>6.2} {:>12.5e} {:>6} {:>6} {:>12.5e} {:>6} {:>6} {:>9}",
                r.d,
                r.loose_energy,
                r.loose_components,
                r.loose_steps,
                r.tight_energy,
                r.tight_components,
                r.tight_steps,
                r.converged
            );
        }
        match s.bistable {
            Some((lo, hi)) => println!(
                "different minima from the two wraps for d = {lo:.2} to {hi:.2} sigma \
                 (001: 2.4 to 4 sigma)"
            ),
            None => println!("the two wraps relax to the same minimum at every d"),
        }
        write_sweep(&a.output, &s)?;
        println!("wrote {}", a.output.join("solvation_sweep.csv").display());
        return Ok(());
    }
    let n = a.n.unwrap_or(128);
    let rep = run(kind, &wraps, n, &opts)?;
    print!("{}, {n} x {n} cells", rep.system);
    if let Some(d) = rep.d {
        print!(", d = {d} sigma");
    }
    println!(
        ", gamma = {}, rho_w = {}; free energy 001 (7.1)",
        rep.gamma, rep.rho_w
    );
    println!(
        "{:>6} {:>6} {:>12} {:>12} {:>12} {:>12} {:>5} {:>5} {:>9} {:>9} {:>7}",
        "wrap",
        "steps",
        "G start",
        "surface",
        "vdW",
        "G final",
        "comp",
        "holes",
        "max rise",
        "converged",
        "s"
    );
    for r in &rep.runs {
        let e = r.final_energy;
        println!(
            "{:>6} {:>6} {:>12.5e} {:>12.5e} {:>12.5e} {:>12.5e} {:>5} {:>5} {:>9.1e} {:>9} {:>7.1}",
            r.wrap,
            r.steps,
            r.records[0].energy.total,
            e.surface,
            e.vdw,
            e.total,
            r.components,
            e.holes,
            r.largest_increase,
            r.converged,
            r.seconds
        );
    }
    let name = match kind {
        SystemKind::Rods { d, .. } => format!("rods_d{d}"),
        k => k.name().to_string(),
    };
    write(&a.output, &name, &rep)?;
    println!("wrote {}", a.output.join("solvation.json").display());
    Ok(())
}
