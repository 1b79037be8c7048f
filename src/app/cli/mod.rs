//! Command definitions (clap) and dispatch. Each command lives in its own file and only calls
//! the library's public API.

mod adapt;
mod adapt3;
mod advect;
mod bench;
mod bench_star;
mod bench_tet;
mod convert;
mod crosscheck;
mod curvature;
mod dtgrid;
mod dtgrid_big;
mod dtgrid_obj;
mod dtgrid_shape;
mod fit;
mod flows;
mod info;
mod measure;
mod measure_shape;
mod memory;
mod metric;
mod metric_args;
mod progress;
mod redistance;
mod shape;
mod solvation;
mod stefan;
mod surface;
mod triangulate;
mod ugawg;
mod user_files;

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
    /// Any shape in any velocity field, or the single vortex / deformation / Zalesak cases.
    Advect(advect::AdvectArgs),
    /// The Zalesak slotted-disk rotation (004 §5.1): area and perimeter after one revolution.
    Zalesak(flows::ZalesakArgs),
    /// The level-set redistancing experiments of 003 §8 (tables 8.1-8.4, volume drift).
    Reinit(flows::ReinitArgs),
    /// Interface error versus vertex count: anisotropic, isotropic-adapted and uniform meshes.
    Convergence(flows::ConvergenceArgs),
    /// The two-phase Couette Stokes flow (004 §5.1) on an adapted (or fitted) mesh.
    Couette(flows::CouetteArgs),
    /// Cuts a mesh along the zero level of a P1 level set (001 §2): interface edges labelled
    /// 10, inside 3, outside 2, as mmg2d -ls.
    Fit(fit::FitArgs),
    /// The Stefan problem on the interface-fitted mesh (001 §6): Frank's circle.
    Stefan(stefan::StefanArgs),
    /// Molecular solvation on the interface-fitted mesh (001 §7): relaxed solute surfaces and
    /// their free energy; the two-rod sweep over the distance d.
    Solvation(solvation::SolvationArgs),
    /// Speed benchmarks, with the peers (mmg2d, FreeFem++ BAMG) beside ours in the same run.
    #[command(subcommand)]
    Bench(bench::Bench),
    /// Each problem (shrinking circle and sphere, interface curvature) through every back end
    /// that can take it: error, order and time per back end; crosscheck.json, .csv, figures.
    Crosscheck(crosscheck::CrosscheckArgs),
    /// Parametric surfaces moved by Dziuk's surface finite elements (002).
    #[command(subcommand)]
    Surface(surface::Surface),
    /// Band finite elements (000 §2): the heat equation and mean curvature motion on a band.
    #[command(subcommand)]
    Dtgrid(dtgrid::DtGrid),
    /// The curvature of an expression's zero level by local averaging on interface-fitted
    /// grids (001 (5.2)), against the exact curvature, with the observed order.
    Curvature(curvature::CurvatureArgs),
    /// Counts, bounding box, labels and quality statistics of a mesh file (.mesh, .msh).
    Info {
        /// The mesh file.
        file: PathBuf,
        /// A metric (.sol, symmetric tensors at vertices) to measure edge lengths and Q_ani in.
        #[arg(long)]
        sol: Option<PathBuf>,
    },
    /// Edge lengths, Q_ani and mean ratio of a triangle or tetrahedral mesh in a metric (.sol or
    /// a UGAWG analytic field).
    Measure(measure::MeasureArgs),
    /// The metric of a user's level set (.sol or expression) on a triangle or tetrahedral
    /// mesh, written as a Medit tensor field (.sol) for mmg2d/mmg3d or `adapt --sol`.
    Metric(metric::MetricCmdArgs),
    /// Signed distance to the zero level of a user's level set (.sol) on a triangle or
    /// tetrahedral mesh: geometric (exact), PPR or fast marching.
    Redistance(redistance::RedistanceArgs),
    /// A UGAWG benchmark case (cube-linear, cube-polar-1): the Kuhn starting mesh of [0,1]^3,
    /// its metric (.sol) and its statistics in that metric.
    Ugawg(ugawg::UgawgArgs),
    /// Converts a mesh between formats, chosen by extension (.mesh, .msh -> .mesh, .msh, .vtu).
    Convert {
        /// Input mesh (.mesh or .msh).
        input: PathBuf,
        /// Output mesh (.mesh, .msh or .vtu).
        output: PathBuf,
    },
    /// Writes a closed triangulation (OBJ) of a built-in surface: star, sphere or torus.
    Triangulate(triangulate::TriangulateArgs),
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
        Some(Command::Advect(a)) => advect::run(a),
        Some(Command::Zalesak(a)) => flows::zalesak(a),
        Some(Command::Reinit(a)) => flows::reinit(a),
        Some(Command::Convergence(a)) => flows::convergence(a),
        Some(Command::Couette(a)) => flows::couette(a),
        Some(Command::Fit(a)) => fit::run(a),
        Some(Command::Stefan(a)) => stefan::run(a),
        Some(Command::Solvation(a)) => solvation::run_cli(a),
        Some(Command::Bench(b)) => bench::run(b),
        Some(Command::Measure(a)) => measure::run(a),
        Some(Command::Metric(a)) => metric::run(a),
        Some(Command::Redistance(a)) => redistance::run(a),
        Some(Command::Ugawg(a)) => ugawg::run(a),
        Some(Command::Triangulate(a)) => triangulate::run(a),
        Some(Command::Surface(s)) => surface::run(s),
        Some(Command::Crosscheck(a)) => crosscheck::run(a),
        Some(Command::Curvature(a)) => curvature::run(a),
        Some(Command::Dtgrid(d)) => dtgrid::run(d),
        None => run(Cli::parse_from(["anisomesh", "adapt"])),
    }
}
