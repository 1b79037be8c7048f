//! `anisomesh fit`: cut a mesh along the zero level (or another level) of a P1 level set so the
//! interface is made of mesh edges, labelled as `mmg2d -ls` labels it.

use anisomesh::backends::fitted::{fit, FitOptions, FittedMesh};
use anisomesh::io::{self, SolField};
use anisomesh::levelset::nodal_distance;
use anisomesh::{Error, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `anisomesh fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    /// The base mesh (.mesh, .msh).
    #[arg(long)]
    input: PathBuf,
    /// The level set at its vertices (.sol, one scalar per vertex).
    #[arg(long)]
    sol: PathBuf,
    /// The level to fit.
    #[arg(long, default_value_t = 0.0)]
    iso: f64,
    /// The fitted mesh (.mesh with labels 3 inside, 2 outside, interface edges 10; .msh; .vtu).
    #[arg(short, long)]
    output: PathBuf,
    /// A JSON report (vertices, triangles, area_inside, interface_length, seconds).
    #[arg(long)]
    report: Option<PathBuf>,
}

/// The numbers `anisomesh fit` prints and reports.
#[derive(Debug, serde::Serialize)]
pub struct FitReport {
    /// Vertices of the fitted mesh.
    pub vertices: usize,
    /// Triangles of the fitted mesh.
    pub triangles: usize,
    /// Vertices added on cut edges.
    pub added_vertices: usize,
    /// Base vertices snapped onto the level.
    pub snapped_vertices: usize,
    /// Area of the inside (label 3).
    pub area_inside: f64,
    /// Length of the interface (edges labelled 10).
    pub interface_length: f64,
    /// Wall time of the whole command (reading, fitting, checking, writing), in seconds.
    pub seconds: f64,
}

/// Reads a mesh and a scalar level set, fits the level `iso`, checks the result.
pub fn fit_files(input: &Path, sol: &Path, iso: f64) -> Result<FittedMesh> {
    let mesh = io::read_mesh(input)?;
    let sol_data = io::read_sol_for(sol, mesh.n_points())?;
    let u = match sol_data.fields.into_iter().next() {
        Some(SolField::Scalar(u)) => u,
        _ => {
            return Err(Error::InvalidInput(format!(
                "{}: expected a scalar level set (Medit type 1) as the first field",
                sol.display()
            )))
        }
    };
    let f = fit(
        &mesh,
        &u,
        &FitOptions {
            iso,
            ..FitOptions::default()
        },
    )
    .map_err(|e| match e {
        Error::EmptyLevelSet(m) => Error::EmptyLevelSet(format!("{}: {m}", sol.display())),
        e => e,
    })?;
    f.mesh.check()?;
    Ok(f)
}

/// The report of a fitted mesh, with the command's wall time.
pub fn report_of(f: &FittedMesh, seconds: f64) -> FitReport {
    FitReport {
        vertices: f.mesh.n_points(),
        triangles: f.mesh.n_live_tris(),
        added_vertices: f.cuts.len(),
        snapped_vertices: f.snapped,
        area_inside: f.area_inside(),
        interface_length: f.interface_length(),
        seconds,
    }
}

/// Prints the report and writes it as JSON where asked.
pub fn print_report(r: &FitReport, report: Option<&Path>) -> Result<()> {
    println!(
        "vertices {}  triangles {}  (added {}, snapped {})  area_inside {:.12}  interface_length {:.12}  seconds {:.4}",
        r.vertices,
        r.triangles,
        r.added_vertices,
        r.snapped_vertices,
        r.area_inside,
        r.interface_length,
        r.seconds
    );
    if let Some(path) = report {
        io::atomic_write(path, |w| {
            serde_json::to_writer_pretty(&mut *w, r).map_err(std::io::Error::from)?;
            writeln!(w)
        })?;
        println!("wrote {}", path.display());
    }
    Ok(())
}

/// `anisomesh adapt --fit`: reads `<dir>/<name>.mesh` (the adapted mesh), evaluates the shape
/// (or expression; the Zalesak disk without either) at its vertices, fits its zero level and
/// writes `<dir>/<name>_fitted.mesh`.
pub fn fit_adapted(dir: &Path, name: &str, shape: Option<&str>, expr: Option<&str>) -> Result<()> {
    let start = Instant::now();
    let mesh = io::read_mesh(&dir.join(format!("{name}.mesh")))?;
    let shape_name = match (shape, expr) {
        (None, None) => Some("zalesak"),
        (s, _) => s,
    };
    let shape = super::shape::chosen_shape(shape_name, expr)?;
    let u = nodal_distance(&mesh, shape.as_ref());
    let f = fit(&mesh, &u, &FitOptions::default())?;
    f.mesh.check()?;
    let out = dir.join(format!("{name}_fitted.mesh"));
    io::write_mesh(&out, &f.mesh)?;
    println!("wrote {}", out.display());
    print_report(&report_of(&f, start.elapsed().as_secs_f64()), None)
}

/// Runs `anisomesh fit`.
pub fn run(a: FitArgs) -> Result<()> {
    let start = Instant::now();
    let f = fit_files(&a.input, &a.sol, a.iso)?;
    io::write_mesh(&a.output, &f.mesh)?;
    let r = report_of(&f, start.elapsed().as_secs_f64());
    println!("wrote {}", a.output.display());
    print_report(&r, a.report.as_deref())
}
