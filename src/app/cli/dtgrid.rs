//! `anisomesh dtgrid heat|mcf`: the band finite element problems of 000 §2. Without `--n` the
//! paper's table (Table 2.1 or 2.2) is run and printed beside the paper's values; with `--n`
//! one run with the given options.

use crate::app::repro::dtgrid as repro;
use anisomesh::backends::dtgrid::heat::{HeatOptions, TimeScheme};
use anisomesh::backends::dtgrid::mcf::McfOptions;
use anisomesh::backends::dtgrid::scheme::Bc;
use anisomesh::Result;
use clap::{Args, Subcommand};
use std::path::PathBuf;

/// The band finite element problems.
#[derive(Debug, Subcommand)]
pub enum DtGrid {
    /// The heat equation on the sphere r = 1/3 (000 Table 2.1).
    Heat(HeatArgs),
    /// A sphere r = 0.25 shrinking by mean curvature (000 Table 2.2).
    Mcf(McfArgs),
    /// A Turing reaction–diffusion texture on a triangulated surface (000 §4.1).
    Texture(super::dtgrid_obj::TextureArgs),
    /// Mean curvature motion of a triangulated surface, frames drawn (000 §2.4).
    ObjMcf(super::dtgrid_obj::ObjMcfArgs),
}

/// Options of `dtgrid heat`.
#[derive(Debug, Args)]
pub struct HeatArgs {
    /// Grid nodes per side (one run); without it, the paper's table.
    #[arg(long)]
    n: Option<usize>,
    /// Band half-width j in cells.
    #[arg(long, default_value_t = 2)]
    band: usize,
    /// natural, transparent (000 (2.9)) or extrapolated (the boundary rows completed by ghost
    /// values outside the band).
    #[arg(long, default_value = "transparent")]
    bc: String,
    /// Time step (default h²).
    #[arg(long)]
    tau: Option<f64>,
    /// Time discretisation of the sphere runs: euler (000 (2.10)) or bdf2 (second order).
    #[arg(long, default_value = "euler", value_parser = ["euler", "bdf2"])]
    time: String,
    /// Final time.
    #[arg(long, default_value_t = 0.01)]
    t_end: f64,
    /// Table on the grids 17³…65³ only.
    #[arg(long)]
    quick: bool,
    /// The finest grid of the table (17, 33, 65, 129, 257 or 513 nodes per side).
    #[arg(long, default_value_t = 129)]
    max_n: usize,
    /// One run on this surface through the band back end: sphere, torus or star, in (−½, ½)³
    /// (writes the zero level as .vtu and pictures).
    #[arg(long, value_parser = ["sphere", "torus", "star"], conflicts_with = "expr")]
    shape: Option<String>,
    /// One run on the zero level of this function of x, y, z (negative inside), in (−½, ½)³.
    #[arg(long)]
    expr: Option<String>,
    /// Output directory.
    #[arg(short, long, default_value = "out/dtgrid")]
    output: PathBuf,
}

/// Options of `dtgrid mcf`.
#[derive(Debug, Args)]
pub struct McfArgs {
    /// Grid nodes per side (one run); without it, the paper's table.
    #[arg(long)]
    n: Option<usize>,
    /// Band half-width j in cells.
    #[arg(long, default_value_t = 1)]
    band: usize,
    /// natural, transparent or dirichlet.
    #[arg(long, default_value = "dirichlet")]
    bc: String,
    /// Most solves per step (1: no inner iteration).
    #[arg(long, default_value_t = 5)]
    inner: usize,
    /// Time step (default h²).
    #[arg(long)]
    tau: Option<f64>,
    /// Final time.
    #[arg(long, default_value_t = 0.0059)]
    t_end: f64,
    /// Time the phases of one step of the sphere r = 1/3 (000 Table 4.1) instead.
    #[arg(long)]
    step_timing: bool,
    /// Table on the grids 17³…65³ only.
    #[arg(long)]
    quick: bool,
    /// The finest grid of the table (17, 33, 65, 129, 257 or 513 nodes per side).
    #[arg(long, default_value_t = 129)]
    max_n: usize,
    /// One run on this surface through the band back end: sphere, torus or star, in (−½, ½)³
    /// (writes the zero level as .vtu and pictures).
    #[arg(long, value_parser = ["sphere", "torus", "star"], conflicts_with = "expr")]
    shape: Option<String>,
    /// One run on the zero level of this function of x, y, z (negative inside), in (−½, ½)³.
    #[arg(long)]
    expr: Option<String>,
    /// A sphere (r = --radius) on a band too large for assembled matrices: f32 values,
    /// matrix-free products, windowed rebuild; prints bytes per node, peak memory, phase times.
    #[arg(long, conflicts_with_all = ["shape", "expr", "step_timing"])]
    matrix_free: bool,
    /// Steps of a --matrix-free run (default: to --t-end).
    #[arg(long, requires = "matrix_free")]
    steps: Option<usize>,
    /// The sphere's radius in a --matrix-free run.
    #[arg(long, default_value_t = 1.0 / 3.0, requires = "matrix_free")]
    radius: f64,
    /// Output directory.
    #[arg(short, long, default_value = "out/dtgrid")]
    output: PathBuf,
}

/// The options of a `--shape`/`--expr` run (33³ nodes unless `--n`).
#[allow(clippy::too_many_arguments)]
fn shape_run<'a>(
    n: Option<usize>,
    band: usize,
    bc: &'a str,
    inner: usize,
    tau: Option<f64>,
    t_end: f64,
    shape: &'a Option<String>,
    expr: &'a Option<String>,
    output: &'a std::path::Path,
) -> super::dtgrid_shape::ShapeRun<'a> {
    super::dtgrid_shape::ShapeRun {
        n: n.unwrap_or(33),
        band,
        bc,
        inner,
        tau,
        t_end,
        shape: shape.as_deref(),
        expr: expr.as_deref(),
        output,
    }
}

/// The grids of a table: 17³ up to `max_n`³ (65³ with `quick`).
/// Error: [`anisomesh::Error::InvalidInput`] when `max_n` is not one of the paper's grids.
fn table_grids(quick: bool, max_n: usize) -> Result<Vec<usize>> {
    const GRIDS: [usize; 6] = [17, 33, 65, 129, 257, 513];
    let max_n = if quick { 65 } else { max_n };
    if !GRIDS.contains(&max_n) {
        return Err(anisomesh::Error::InvalidInput(format!(
            "--max-n {max_n}: one of 17, 33, 65, 129, 257, 513"
        )));
    }
    Ok(GRIDS.iter().copied().filter(|&n| n <= max_n).collect())
}

/// Runs a `dtgrid` subcommand.
pub fn run(cmd: DtGrid) -> Result<()> {
    super::memory::keep_freed_memory();
    match cmd {
        DtGrid::Texture(a) => super::dtgrid_obj::texture(a),
        DtGrid::ObjMcf(a) => super::dtgrid_obj::obj_mcf(a),
        DtGrid::Heat(a) if a.shape.is_some() || a.expr.is_some() => {
            super::dtgrid_shape::heat(&shape_run(
                a.n, a.band, &a.bc, 1, a.tau, a.t_end, &a.shape, &a.expr, &a.output,
            ))
        }
        DtGrid::Mcf(a) if a.shape.is_some() || a.expr.is_some() => {
            super::dtgrid_shape::mcf(&shape_run(
                a.n, a.band, &a.bc, a.inner, a.tau, a.t_end, &a.shape, &a.expr, &a.output,
            ))
        }
        DtGrid::Mcf(a) if a.matrix_free => super::dtgrid_big::run(&super::dtgrid_big::BigRun {
            n: a.n.unwrap_or(1024),
            radius: a.radius,
            steps: a.steps,
            tau: a.tau,
            t_end: a.t_end,
            mcf: McfOptions {
                j: a.band,
                bc: Bc::parse(&a.bc)?,
                inner: a.inner,
                ..McfOptions::default()
            },
            output: &a.output,
        }),
        DtGrid::Heat(a) => {
            let time = TimeScheme::parse(&a.time)?;
            let rows = match a.n {
                Some(n) => vec![repro::heat_row(&HeatOptions {
                    tau: a.tau,
                    t_end: a.t_end,
                    time,
                    ..HeatOptions::paper(n, a.band, Bc::parse(&a.bc)?)
                })?],
                None => {
                    let tau = a.tau;
                    repro::heat_table(&table_grids(a.quick, a.max_n)?, time, |h| {
                        tau.unwrap_or(h * h)
                    })?
                }
            };
            println!(
                "heat equation on the sphere r = 1/3, t = {} (000 Table 2.1)",
                a.t_end
            );
            print!("{}", repro::format_table(&rows));
            repro::write_rows(&a.output, "dtgrid_heat", &rows)
        }
        DtGrid::Mcf(a) => {
            if a.step_timing {
                let n = a.n.unwrap_or(129);
                let r = repro::step_timing(n, a.band)?;
                let t = r.step.times;
                println!(
                    "one mean curvature step, sphere r = 1/3, {n}³, j = {}, tau = h²: {} band \
                     nodes ({} interior unknowns), {} solves, {} CG iterations",
                    a.band, r.nodes, r.interior, r.step.solves, r.step.cg_iterations
                );
                println!("phase        wall s    cpu s   (000 Table 4.1 at 513³, j = 1)");
                for (name, w, c, p) in [
                    ("rebuild", t.rebuild, t.rebuild_cpu, 10.202),
                    ("assembly", t.assembly, t.assembly_cpu, 14.133),
                    ("solve", t.solve, t.solve_cpu, 5.864),
                ] {
                    println!("{name:10} {w:8.3} {c:8.3}   {p:6.3}");
                }
                println!(
                    "{:10} {:8.3} {:8.3}   {:6.3}",
                    "total",
                    t.rebuild + t.assembly + t.solve,
                    t.rebuild_cpu + t.assembly_cpu + t.solve_cpu,
                    30.199
                );
                println!(
                    "CSR product (M + tau L) x on one core: {} entries, {:.3e} band nodes per cpu \
                     s, {:.2} GB/s moved (row pointers, columns, values, x, y)",
                    r.nnz,
                    r.matvec_rate,
                    r.matvec_bandwidth * 1e-9
                );
                return Ok(());
            }
            let rows = match a.n {
                Some(n) => {
                    let h = 1.0 / (n.max(2) - 1) as f64;
                    let o = McfOptions {
                        j: a.band,
                        bc: Bc::parse(&a.bc)?,
                        inner: a.inner,
                        ..McfOptions::default()
                    };
                    let tau = a.tau.unwrap_or(h * h);
                    let block = repro::paper_block(h, tau, a.t_end, &o);
                    vec![repro::mcf_row(n, tau, a.t_end, &o, block)?]
                }
                None => repro::mcf_table(&table_grids(a.quick, a.max_n)?)?,
            };
            println!(
                "sphere r0 = 0.25 by mean curvature to t = {} (000 Table 2.2)",
                a.t_end
            );
            print!("{}", repro::format_table(&rows));
            if let [r] = &rows[..] {
                if let (Some(f), Some(e)) = (r.radius_final, r.radius_exact) {
                    println!("radius_final {f:.6}, radius_exact {e:.6}");
                }
            }
            repro::write_rows(&a.output, "dtgrid_mcf", &rows)
        }
    }
}
