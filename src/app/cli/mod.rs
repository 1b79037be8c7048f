//! Command definitions (clap) and dispatch. Each command lives in its own file and only calls
//! the library's public API.

mod adapt;
mod adapt3;
mod bench;
mod convert;
mod flows;
mod info;
mod metric_args;
mod progress;
mod shape;

use anisomesh::Result;
use clap::{Parser, Subcommand};
use std::path::PathBuf;

/// Anisotropic mesh adaptation around level-set interfaces.
#[derive(Debug, Parser)]
#[command(name = "anisomesh", version, about, long_about = None)]
pub struct Cli {
    #[command(subcommand)]
    command: Option<Command>,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Adapts a mesh to a shape, an expression, a level set or a metric (default: the Zalesak
    /// disk at the paper's setting); writes .mesh, .vtu, .png and report.json.
    Adapt(adapt::AdaptArgs),
    /// The Zalesak slotted-disk rotation (004 §5.1): area and perimeter after one revolution.
    Zalesak(flows::ZalesakArgs),
    /// The level-set redistancing experiments of 003 §8 (tables 8.1-8.4, volume drift).
    Reinit(flows::ReinitArgs),
    /// Interface error versus vertex count: anisotropic, isotropic-adapted and uniform meshes.
    Convergence(flows::ConvergenceArgs),
    /// The two-phase Couette Stokes flow (004 §5.1) on an adapted (or fitted) mesh.
    Couette(flows::CouetteArgs),
    /// Speed benchmarks, with the peers (mmg2d, FreeFem++ BAMG) beside ours in the same run.
    #[command(subcommand)]
    Bench(bench::Bench),
    /// Counts, bounding box, labels and quality statistics of a mesh file (.mesh, .msh).
    Info {
        /// The mesh file.
        file: PathBuf,
        /// A metric (.sol, symmetric tensors at vertices) to measure edge lengths and Q_ani in.
        #[arg(long)]
        sol: Option<PathBuf>,
    },
    /// Converts a mesh between formats, chosen by extension (.mesh, .msh -> .mesh, .msh, .vtu).
    Convert {
        /// Input mesh (.mesh or .msh).
        input: PathBuf,
        /// Output mesh (.mesh, .msh or .vtu).
        output: PathBuf,
    },
    /// Evaluates a level set on a mesh's vertices and writes it (.sol or .vtu).
    Shape {
        /// A built-in shape: circle, zalesak or flower.
        #[arg(long)]
        name: Option<String>,
        /// A user expression in x and y, e.g. "x^2 + y^2 - 0.25" (negative inside).
        #[arg(long)]
        expr: Option<String>,
        /// The mesh (.mesh or .msh).
        #[arg(long)]
        mesh: PathBuf,
        /// Output file (.sol or .vtu).
        #[arg(short, long)]
        output: PathBuf,
    },
}

/// Runs the parsed command; with no command, the default adaptation job.
pub fn run(cli: Cli) -> Result<()> {
    match cli.command {
        Some(Command::Info { file, sol }) => info::run(&file, sol.as_deref()),
        Some(Command::Convert { input, output }) => convert::run(&input, &output),
        Some(Command::Shape {
            name,
            expr,
            mesh,
            output,
        }) => shape::run(name.as_deref(), expr.as_deref(), &mesh, &output),
        Some(Command::Adapt(a)) => adapt::run(a),
        Some(Command::Zalesak(a)) => flows::zalesak(a),
        Some(Command::Reinit(a)) => flows::reinit(a),
        Some(Command::Convergence(a)) => flows::convergence(a),
        Some(Command::Couette(a)) => flows::couette(a),
        Some(Command::Bench(b)) => bench::run(b),
        None => run(Cli::parse_from(["anisomesh", "adapt"])),
    }
}
