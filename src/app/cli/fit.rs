//! `anisomesh fit`: cut a mesh along the zero level (or another level) of a P1 level set so the
//! interface is made of mesh edges, labelled as `mmg2d -ls` labels it; `--compare-mmg` runs the
//! same files through `mmg2d_O3 -ls -noinsert -noswap -nomove` beside it.

use crate::app::repro::peers_fit;
use anisomesh::advect::characteristics::locate_all;
use anisomesh::backends::fitted::{fit, FitOptions, FittedMesh};
use anisomesh::io::{self, SolField};
use anisomesh::levelset::{enclosed_area, nodal_distance};
use anisomesh::mesh::{check_p1_field, Location};
use anisomesh::{Error, Result};
use clap::Args;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Options of `anisomesh fit`.
#[derive(Debug, Args)]
pub struct FitArgs {
    /// The base mesh (.mesh, .msh).
    #[arg(long, required_unless_present = "compare_mmg", requires = "sol")]
    input: Option<PathBuf>,
    /// The level set at its vertices (.sol, one scalar per vertex).
    #[arg(long, requires = "input")]
    sol: Option<PathBuf>,
    /// The level to fit.
    #[arg(long, default_value_t = 0.0)]
    iso: f64,
    /// The fitted mesh (.mesh with labels 3 inside, 2 outside, interface edges 10; .msh; .vtu).
    #[arg(short, long, required_unless_present = "compare_mmg")]
    output: Option<PathBuf>,
    /// A JSON report (vertices, triangles, area_inside, interface_length, seconds).
    #[arg(long)]
    report: Option<PathBuf>,
    /// Run the comparison with mmg2d on the built-in cases (Zalesak on a grid and on an adapted
    /// mesh, zeros at vertices, boundary contacts, several components, a speed case); files
    /// and fit_compare.json go to --dir.
    #[arg(long, conflicts_with_all = ["input", "output"])]
    compare_mmg: bool,
    /// Cells per side of the speed case of --compare-mmg.
    #[arg(long, default_value_t = 200)]
    speed_n: usize,
    /// Runs of each command in --compare-mmg (the best wall time and the least CPU time are
    /// kept).
    #[arg(long, default_value_t = 3)]
    repeats: usize,
    /// Directory of --compare-mmg.
    #[arg(long, default_value = "out/fit_compare")]
    dir: PathBuf,
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

/// Whether the input is read without its final `check()` (a Medit `.mesh`; see
/// [`fit_unchecked`]).
fn unchecked_input(input: &Path) -> bool {
    input
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mesh"))
}

/// The error to report when the fitted mesh (or the fit) of `input` failed: the input's own
/// error where the input is not a valid mesh (as `io::read_mesh` reports it), else `e`.
fn input_error_or(input: &Path, e: Error) -> Error {
    if unchecked_input(input) {
        if let Err(input_error) = io::read_mesh(input) {
            return input_error;
        }
    }
    e
}

/// Reads a mesh and a scalar level set (the `.sol` is read and parsed on a second thread while
/// the mesh is read; a mesh error is reported first, as when read one after the other) and fits
/// the level `iso`.
///
/// **One check.** A Medit input is read with every validation except the final `check()`
/// (elements, orientation, adjacency and labels are validated while reading); the fitted mesh
/// gets the full `check()` instead ([`write_checked`]). The fit keeps the base vertices with
/// their indices and splits every triangle into triangles that tile it, so a defect of the input
/// that check() looks for (duplicate vertices, overlapping fans, hanging vertices) is also one
/// of the fitted mesh; when the fitted mesh (or the fit) fails, the input is read again with its
/// check, and its error, naming the input's line, is the one reported ([`input_error_or`]).
fn fit_unchecked(input: &Path, sol: &Path, iso: f64) -> Result<FittedMesh> {
    let (mesh, sol_data) = std::thread::scope(|s| {
        let sol_thread = s.spawn(|| io::read_sol(sol));
        let mesh = if unchecked_input(input) {
            io::read_medit2_unchecked(input).map_err(|e| input_error_or(input, e))
        } else {
            io::read_mesh(input)
        };
        (mesh, sol_thread.join())
    });
    let mesh = mesh?;
    let n = mesh.n_points();
    let u = match sol_data {
        Ok(Ok(data)) if data.n_vertices() == n => scalar_field(sol, data, n),
        // Any error or another vertex count: read again with the count, for its message.
        _ => read_scalar(sol, n),
    }
    .map_err(|e| input_error_or(input, e))?;
    fit(
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
    })
    .map_err(|e| input_error_or(input, e))
}

/// The scalar level set of a `.sol` with `n` vertices; NaN and infinite values are refused
/// with the vertex named.
fn read_scalar(sol: &Path, n: usize) -> Result<Vec<f64>> {
    scalar_field(sol, io::read_sol_for(sol, n)?, n)
}

/// The first field of `sol_data` (read from `sol`) as the scalar level set of `n` vertices.
fn scalar_field(sol: &Path, sol_data: io::Sol, n: usize) -> Result<Vec<f64>> {
    let u = match sol_data.fields.into_iter().next() {
        Some(SolField::Scalar(u)) => u,
        _ => {
            return Err(Error::InvalidInput(format!(
                "{}: expected a scalar level set (Medit type 1) as the first field",
                sol.display()
            )))
        }
    };
    check_p1_field(n, &u, &sol.display().to_string())?;
    Ok(u)
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

/// `anisomesh adapt --input M --sol U --fit`: reads `<dir>/<name>.mesh` (the mesh adapted to
/// the zero level of `U`), takes the input's P1 level set at its vertices (located in the input
/// mesh), fits its zero level and writes `<dir>/<name>_fitted.mesh`; the inside area is printed
/// beside the input's.
pub fn fit_adapted_input(dir: &Path, name: &str, input: &Path, sol: &Path) -> Result<()> {
    let start = Instant::now();
    let mesh_in = io::read_mesh(input)?;
    let u_in = read_scalar(sol, mesh_in.n_points())?;
    let mesh = io::read_mesh(&dir.join(format!("{name}.mesh")))?;
    let locs = locate_all(&mesh_in, &mesh.points, None)?;
    let u: Vec<f64> = locs
        .iter()
        .zip(&mesh.points)
        .map(|(l, p)| match *l {
            Location::Inside { tri, bary } => {
                let t = mesh_in.tris[tri as usize];
                Ok((0..3).map(|k| bary[k] * u_in[t[k] as usize]).sum())
            }
            Location::Outside { .. } => Err(Error::InvalidInput(format!(
                "adapt --fit: the adapted vertex {p} lies outside the input mesh {}",
                input.display()
            ))),
        })
        .collect::<Result<_>>()?;
    let f = fit(&mesh, &u, &FitOptions::default())?;
    f.mesh.check()?;
    let out = dir.join(format!("{name}_fitted.mesh"));
    io::write_mesh(&out, &f.mesh)?;
    println!("wrote {}", out.display());
    let area_in = enclosed_area(&mesh_in, &u_in)?;
    println!(
        "input inside area {area_in:.12}, fitted {:.12} (relative difference {:.2e})",
        f.area_inside(),
        (f.area_inside() - area_in).abs() / area_in
    );
    print_report(&report_of(&f, start.elapsed().as_secs_f64()), None)
}

/// Runs `anisomesh fit`.
pub fn run(a: FitArgs) -> Result<()> {
    if a.compare_mmg {
        return compare_mmg(&a.dir, a.speed_n, a.repeats);
    }
    let (Some(input), Some(sol), Some(output)) = (&a.input, &a.sol, &a.output) else {
        return Err(Error::InvalidInput(
            "fit: --input, --sol and -o are required".into(),
        ));
    };
    let start = Instant::now();
    super::memory::reserve_heap_in_large_pages();
    let f = fit_unchecked(input, sol, a.iso)?;
    write_checked(output, &f.mesh).map_err(|e| input_error_or(input, e))?;
    let r = report_of(&f, start.elapsed().as_secs_f64());
    println!("wrote {}", output.display());
    print_report(&r, a.report.as_deref())
}

/// Checks the fitted mesh and writes it; a Medit output is formatted while `check()` runs on a
/// second thread and is committed only when the check passes (the file is then never written).
fn write_checked(output: &Path, mesh: &anisomesh::Mesh2) -> Result<()> {
    if !output
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("mesh"))
    {
        mesh.check()?;
        return io::write_mesh(output, mesh);
    }
    let mut checked = None;
    let written = std::thread::scope(|s| {
        let check = s.spawn(|| mesh.check());
        io::atomic_write(output, |w| {
            io::write_medit2_to(w, mesh)?;
            let result = check.join().unwrap_or_else(|_| {
                Err(Error::InvalidInput("fit: the mesh check panicked".into()))
            });
            let failed = result.is_err();
            checked = Some(result);
            if failed {
                return Err(std::io::Error::other("the fitted mesh failed check()"));
            }
            Ok(())
        })
    });
    match checked {
        Some(Err(e)) => Err(e),
        _ => written,
    }
}

/// `anisomesh fit --compare-mmg`: the comparison table and `fit_compare.json`.
fn compare_mmg(dir: &Path, speed_n: usize, repeats: usize) -> Result<()> {
    if !(2..=4096).contains(&speed_n) || repeats == 0 {
        return Err(Error::InvalidInput(format!(
            "--speed-n must be 2..=4096 and --repeats at least 1 (got {speed_n}, {repeats})"
        )));
    }
    let c = peers_fit::compare(dir, speed_n, repeats)?;
    match &c.mmg2d {
        Some(p) => println!("mmg2d: {p} -ls -noinsert -noswap -nomove"),
        None => println!("mmg2d_O3 not on PATH: our rows only"),
    }
    println!(
        "{:<16} {:<10} {:>8} {:>9} {:>7} {:>16} {:>9} {:>5} {:>8} {:>8} {:>8}",
        "case",
        "tool",
        "vertices",
        "triangles",
        "Γ edges",
        "area inside",
        "area err",
        "check",
        "wall s",
        "cpu s",
        "own s"
    );
    for r in &c.rows {
        println!(
            "{:<16} {:<10} {:>8} {:>9} {:>7} {:>16.12} {:>9.1e} {:>5} {:>8.3} {:>8.3} {:>8}",
            r.case,
            r.tool,
            r.vertices,
            r.triangles,
            r.interface_edges,
            r.area_inside,
            r.area_rel_error,
            if r.check == "ok" { "ok" } else { "FAIL" },
            r.wall_seconds,
            r.cpu_seconds,
            r.own_seconds.map(|s| format!("{s:.3}")).unwrap_or_default()
        );
        if r.check != "ok" {
            println!("  {} on {}: check() {}", r.tool, r.case, r.check);
        }
    }
    if let (Some(w), Some(cpu)) = (c.speed_wall_ratio, c.speed_cpu_ratio) {
        println!(
            "speed case ({} vertices): mmg2d / anisomesh = {w:.2}x wall, {cpu:.2}x CPU \
             (whole commands, best of {repeats} runs each)",
            (speed_n + 1) * (speed_n + 1)
        );
    }
    let path = dir.join("fit_compare.json");
    io::atomic_write(&path, |w| {
        serde_json::to_writer_pretty(&mut *w, &c).map_err(std::io::Error::from)?;
        writeln!(w)
    })?;
    println!("wrote {}", path.display());
    Ok(())
}
