//! `anisomesh crosscheck`: every problem through every back end that can take it.

use crate::app::repro::crosscheck::{self, table41, Resolution};
use anisomesh::Result;
use clap::Args;
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
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
    /// Also 000 Table 4.1: one mean curvature step of the sphere r = 1/3 on the thinnest
    /// DT-Grid band of the n³ grid against the parametric sphere of the same edge length.
    #[arg(long)]
    table41: bool,
    /// Grid nodes per side for --table41 (000: 513).
    #[arg(long, default_value_t = 513)]
    table41_n: usize,
    /// Output directory (crosscheck.json, crosscheck.csv, crosscheck_<problem>.png,
    /// table41.json).
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
    let bar = ProgressBar::with_draw_target(
        Some(crosscheck::planned_runs(res) as u64),
        ProgressDrawTarget::stderr(),
    );
    bar.set_style(
        ProgressStyle::with_template("{bar:30} {pos}/{len} {elapsed} {msg}")
            .unwrap_or_else(|_| ProgressStyle::default_bar()),
    );
    let report = crosscheck::run(res, &mut |line| {
        if bar.is_hidden() {
            eprintln!("{line}");
        } else {
            bar.println(line);
        }
        bar.set_message(line.to_string());
        bar.inc(1);
    })?;
    bar.finish_and_clear();
    print!("{}", crosscheck::tables(&report));
    crosscheck::write_outputs(&a.output, &report)?;
    println!("wrote {}", a.output.join("crosscheck.json").display());
    if a.table41 {
        let rows = table41::run(a.table41_n)?;
        print!("{}", table41::table(&rows));
        let path = a.output.join("table41.json");
        anisomesh::io::atomic_write(&path, |w| {
            serde_json::to_writer_pretty(&mut *w, &rows).map_err(std::io::Error::from)?;
            writeln!(w)
        })?;
        println!("wrote {}", path.display());
    }
    Ok(())
}
