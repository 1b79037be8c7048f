//! The benchmark-flow commands: `zalesak` and `reinit` (thin wrappers over `anisomesh::bench`).

use anisomesh::bench::{reinit, zalesak};
use anisomesh::Result;
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh zalesak` (defaults: 004 §5.1).
#[derive(Debug, Args)]
pub struct ZalesakArgs {
    /// Also run a uniform mesh and an isotropic adapted mesh of similar vertex count.
    #[arg(long)]
    compare: bool,
    /// Restore the initial area after each period (004 §5.1 mass correction).
    #[arg(long)]
    mass_correction: bool,
    /// Periods per revolution (16 = steps of pi/8).
    #[arg(long, default_value_t = 16)]
    periods: usize,
    /// Output directory (zalesak.json, zalesak.csv, figures).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the Zalesak rotation and prints its table.
pub fn zalesak(a: ZalesakArgs) -> Result<()> {
    let opts = zalesak::ZalesakOptions {
        compare: a.compare,
        mass_correction: a.mass_correction,
        periods: a.periods,
        out_dir: Some(a.output.clone()),
        ..zalesak::ZalesakOptions::default()
    };
    let r = zalesak::run(&opts)?;
    print!("{}", r.summary());
    println!("wrote {}", a.output.display());
    Ok(())
}

/// Options of `anisomesh reinit`.
#[derive(Debug, Args)]
pub struct ReinitArgs {
    /// Smaller levels (a run of seconds instead of minutes).
    #[arg(long)]
    quick: bool,
    /// Output directory (reinit.json and plots).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the redistancing experiments of 003 §8 and prints the tables beside the paper's.
pub fn reinit(a: ReinitArgs) -> Result<()> {
    let mut opts = reinit::ReinitOptions {
        out_dir: Some(a.output.clone()),
        ..reinit::ReinitOptions::default()
    };
    if a.quick {
        opts.levels_3d = vec![3];
        opts.levels_2d = (3..=6).collect();
        opts.alphas = vec![1, 10];
        opts.volume_levels = vec![3];
        opts.volume_reps = 10;
    }
    reinit::run(&opts)?;
    println!("wrote {}", a.output.join("reinit.json").display());
    Ok(())
}
