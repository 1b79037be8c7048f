//! `anisomesh crosscheck`: every problem through every back end that can take it.

use crate::app::repro::crosscheck::{self, Resolution};
use anisomesh::Result;
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh crosscheck`.
#[derive(Debug, Args)]
pub struct CrosscheckArgs {
    /// Two coarse levels per back end (seconds).
    #[arg(long, conflicts_with = "full")]
    quick: bool,
    /// One more level than the default (a benchmark, minutes).
    #[arg(long)]
    full: bool,
    /// Output directory (crosscheck.json, crosscheck.csv, crosscheck_<problem>.png).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs the cross-check and prints one table per problem.
pub fn run(a: CrosscheckArgs) -> Result<()> {
    let res = if a.quick {
        Resolution::Tiny
    } else if a.full {
        Resolution::Full
    } else {
        Resolution::Quick
    };
    let report = crosscheck::run(res, &mut |line| eprintln!("{line}"))?;
    print!("{}", crosscheck::tables(&report));
    crosscheck::write_outputs(&a.output, &report)?;
    println!("wrote {}", a.output.join("crosscheck.json").display());
    Ok(())
}
