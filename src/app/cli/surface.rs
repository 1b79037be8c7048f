//! `anisomesh surface mcf`: Dziuk's parametric mean curvature flow of a sphere (002) with its
//! EOC table beside 002's, and the perturbed sphere's frames.

use crate::app::repro::surface_mcf::{self, SurfaceMcfOptions};
use anisomesh::Result;
use clap::{Args, Subcommand};
use std::path::PathBuf;

/// Parametric surface commands.
#[derive(Debug, Subcommand)]
pub enum Surface {
    /// The shrinking sphere R(t) = sqrt(R0^2 - 4t) (002): error of the averaged radius, EOC,
    /// 002's P2 table beside; frames of the perturbed sphere as .vtu.
    Mcf(McfArgs),
}

/// Options of `anisomesh surface mcf`.
#[derive(Debug, Args)]
pub struct McfArgs {
    /// Element order (1 or 2); both when absent.
    #[arg(long)]
    order: Option<usize>,
    /// θ of the scheme.
    #[arg(long, default_value_t = 0.5)]
    theta: f64,
    /// Number of refinement levels.
    #[arg(long, default_value_t = 3)]
    levels: usize,
    /// The first icosahedral level (10·4^level + 2 vertices).
    #[arg(long, default_value_t = 2)]
    first_level: usize,
    /// Division of the time step per level (4 keeps 002's τ ∝ h²; 2 halves it).
    #[arg(long, default_value_t = 4.0)]
    tau_factor: f64,
    /// Steps of the perturbed-sphere flow written as frames (0: none).
    #[arg(long, default_value_t = 40)]
    frames: usize,
    /// Output directory (surface_mcf.json, perturbed/frame_NNN.vtu).
    #[arg(short, long, default_value = "out")]
    output: PathBuf,
}

/// Runs a surface command.
pub fn run(s: Surface) -> Result<()> {
    match s {
        Surface::Mcf(a) => mcf(a),
    }
}

fn mcf(a: McfArgs) -> Result<()> {
    let opts = SurfaceMcfOptions {
        orders: a.order.map_or(vec![1, 2], |o| vec![o]),
        theta: a.theta,
        first_level: a.first_level,
        levels: a.levels,
        tau_factor: a.tau_factor,
        ..SurfaceMcfOptions::default()
    };
    let report = surface_mcf::run(&opts, |r| {
        eprintln!(
            "P{} level {}: {} vertices, error {:.3e} ({:.1} s)",
            r.order, r.level, r.vertices, r.error, r.seconds
        )
    })?;
    print!("{}", surface_mcf::table(&report));
    surface_mcf::write_report(&a.output, &report)?;
    if a.frames > 0 {
        let order = a.order.unwrap_or(2);
        let dir = a.output.join("perturbed");
        let paths = surface_mcf::perturbed_frames(
            &dir,
            order,
            3,
            0.05 / a.frames as f64,
            a.frames,
            4,
            a.theta,
        )?;
        eprintln!(
            "{} frames of the perturbed sphere in {}",
            paths.len(),
            dir.display()
        );
    }
    println!("wrote {}", a.output.join("surface_mcf.json").display());
    Ok(())
}
