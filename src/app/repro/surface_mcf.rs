//! The shrinking-sphere experiment of 002: Dziuk's θ-scheme on icosahedral spheres of radius
//! `R0 = 2` up to `T = 0.1`, error `|R̄ − √(R0² − 4T)|` of the averaged radius `R̄ = ∫|x| / ∫1`,
//! EOC with respect to the mesh size `h ∝ V^{-1/2}` (`V` vertices), beside 002's P2 table.
//!
//! 002 refines by bisection (`h` divided by √2 per level) and halves `τ` per level, so its
//! `τ` falls like `h²`; icosahedral refinement halves `h`, so the default divides `τ` by 4 per
//! level to keep 002's coupling (`tau_factor = 2` halves it instead). The scheme is first order
//! in `τ`, so with `τ ∝ h²` the P2 error (whose spatial part is far smaller) falls like `h²`.
//!
//! Also the perturbed sphere `x (1 + ½ sin(2π(x + y)) cos(¼πz))` of 002 flowing, written as
//! `.vtu` frames.

use crate::app::plot::surface::{render_surfaces, SurfacePanel, View};
use anisomesh::backends::surface::{theta_step, ParametricSurface};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec3;
use anisomesh::levelset::TriangleSurface;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// 002's P2 table: (vertices, error of the averaged radius at T = 0.1).
pub const PAPER_P2: [(usize, f64); 3] = [(318, 1.060e-3), (766, 6.05e-4), (1745, 2.75e-4)];

/// Options of [`run`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceMcfOptions {
    /// Element orders to run (1, 2).
    pub orders: Vec<usize>,
    /// θ of the scheme (002: 0.5).
    pub theta: f64,
    /// The first icosahedral level (vertices `10·4^level + 2`).
    pub first_level: usize,
    /// The number of levels.
    pub levels: usize,
    /// The time step on the first level.
    pub tau0: f64,
    /// The division of `τ` per level.
    pub tau_factor: f64,
    /// The initial radius.
    pub r0: f64,
    /// The final time.
    pub t_end: f64,
}

impl Default for SurfaceMcfOptions {
    fn default() -> Self {
        SurfaceMcfOptions {
            orders: vec![1, 2],
            theta: 0.5,
            first_level: 2,
            levels: 3,
            tau0: 0.02,
            tau_factor: 4.0,
            r0: 2.0,
            t_end: 0.1,
        }
    }
}

/// One row of the table.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceMcfRow {
    /// Element order.
    pub order: usize,
    /// Icosahedral level.
    pub level: usize,
    /// Triangle vertices (002's "size").
    pub vertices: usize,
    /// Finite element nodes per coordinate.
    pub dofs: usize,
    /// The time step.
    pub tau: f64,
    /// `|R̄(T) − R(T)|`.
    pub error: f64,
    /// The averaged radius `R̄(T)`.
    pub mean_radius: f64,
    /// EOC against the previous row of the same order, in `h ∝ V^{-1/2}`.
    pub eoc: Option<f64>,
    /// On P2 rows, 002's P2 error at this vertex count (log-log interpolation inside its table,
    /// the nearest row outside); `None` on P1 rows (002 reports P2 only).
    pub paper_error: Option<f64>,
    /// CG iterations of the run.
    pub iterations: usize,
    /// Wall-clock seconds.
    pub seconds: f64,
}

/// The report written as `surface_mcf.json`.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SurfaceMcfReport {
    /// The options.
    pub options: SurfaceMcfOptions,
    /// The rows, by order then level.
    pub rows: Vec<SurfaceMcfRow>,
}

/// 002's P2 error at `vertices` (see [`SurfaceMcfRow::paper_error`]).
pub fn paper_error(vertices: usize) -> f64 {
    let v = vertices as f64;
    let (first, last) = (PAPER_P2[0], PAPER_P2[2]);
    if vertices <= first.0 {
        return first.1;
    }
    if vertices >= last.0 {
        return last.1;
    }
    let w = PAPER_P2
        .windows(2)
        .find(|w| vertices <= w[1].0)
        .unwrap_or(&PAPER_P2[1..]);
    let (v0, e0, v1, e1) = (w[0].0 as f64, w[0].1, w[1].0 as f64, w[1].1);
    let s = (v / v0).ln() / (v1 / v0).ln();
    (e0.ln() + s * (e1 / e0).ln()).exp()
}

/// Runs one order at one level: the error of the averaged radius at `t_end`.
pub fn run_one(
    opts: &SurfaceMcfOptions,
    order: usize,
    level: usize,
    tau: f64,
) -> Result<SurfaceMcfRow> {
    let start = Instant::now();
    let mut s = ParametricSurface::icosphere(opts.r0, level, order)?;
    let steps = (opts.t_end / tau).round().max(1.0) as usize;
    let tau = opts.t_end / steps as f64;
    let mut iterations = 0;
    for _ in 0..steps {
        iterations += theta_step(&mut s, tau, opts.theta)?.iterations;
    }
    let exact = (opts.r0 * opts.r0 - 4.0 * opts.t_end).sqrt();
    let mean_radius = s.mean_radius()?;
    Ok(SurfaceMcfRow {
        order,
        level,
        vertices: s.n_vertices,
        dofs: s.nodes.len(),
        tau,
        error: (mean_radius - exact).abs(),
        mean_radius,
        eoc: None,
        paper_error: (order == 2).then(|| paper_error(s.n_vertices)),
        iterations,
        seconds: start.elapsed().as_secs_f64(),
    })
}

/// Runs every order and level; `progress` hears of each row as it finishes.
pub fn run(
    opts: &SurfaceMcfOptions,
    mut progress: impl FnMut(&SurfaceMcfRow),
) -> Result<SurfaceMcfReport> {
    if opts.levels == 0
        || opts.first_level + opts.levels > 8
        || opts.tau_factor.is_nan()
        || opts.tau_factor < 1.0
    {
        return Err(Error::InvalidInput(format!(
            "surface mcf: need 1 to 8 levels in all and τ factor ≥ 1 (got levels {}..{}, \
             factor {})",
            opts.first_level,
            opts.first_level + opts.levels,
            opts.tau_factor
        )));
    }
    let mut rows: Vec<SurfaceMcfRow> = Vec::new();
    for &order in &opts.orders {
        let mut prev: Option<(usize, f64)> = None;
        for k in 0..opts.levels {
            let tau = opts.tau0 / opts.tau_factor.powi(k as i32);
            let mut row = run_one(opts, order, opts.first_level + k, tau)?;
            if let Some((v0, e0)) = prev {
                let h_ratio = (row.vertices as f64 / v0 as f64).sqrt();
                row.eoc = Some((e0 / row.error).ln() / h_ratio.ln());
            }
            prev = Some((row.vertices, row.error));
            progress(&row);
            rows.push(row);
        }
    }
    Ok(SurfaceMcfReport {
        options: opts.clone(),
        rows,
    })
}

/// The table of `report` beside 002's P2 errors, as text.
pub fn table(report: &SurfaceMcfReport) -> String {
    let mut s = format!(
        "{:>5} {:>5} {:>8} {:>8} {:>9} {:>10} {:>6} {:>12} {:>8}\n",
        "order", "level", "vertices", "dofs", "tau", "error", "eoc", "002 P2 error", "seconds"
    );
    for r in &report.rows {
        let eoc = r.eoc.map_or("-".to_string(), |e| format!("{e:.2}"));
        s += &format!(
            "{:>5} {:>5} {:>8} {:>8} {:>9.2e} {:>10.3e} {:>6} {:>12} {:>8.2}\n",
            r.order,
            r.level,
            r.vertices,
            r.dofs,
            r.tau,
            r.error,
            eoc,
            r.paper_error
                .map_or("-".to_string(), |e| format!("{e:.3e}")),
            r.seconds
        );
    }
    s += "002 (P2, bisection refinement, tau 0.02 halved per level): 318 / 766 / 1745 vertices \
          -> 1.06e-3 / 6.05e-4 / 2.75e-4 (EOC 1.62, 2.28)\n";
    s
}

/// Writes `surface_mcf.json` into `dir`.
pub fn write_report(dir: &Path, report: &SurfaceMcfReport) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    anisomesh::io::atomic_write(&dir.join("surface_mcf.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, report).map_err(std::io::Error::from)?;
        writeln!(w)
    })
}

/// 002's perturbed initial surface: the point `x` of the unit sphere mapped to
/// `x (1 + ½ sin(2π(x + y)) cos(¼πz))`.
pub fn perturbed(x: DVec3) -> DVec3 {
    use std::f64::consts::PI;
    x * (1.0 + 0.5 * (2.0 * PI * (x.x + x.y)).sin() * (0.25 * PI * x.z).cos())
}

/// Flows 002's perturbed sphere (unit icosphere at `level`, order `order`) with `steps` steps
/// of `tau` and writes `frame_NNN.vtu` every `every` steps into `dir`, and four of the frames
/// shaded side by side as `perturbed.png` beside `dir`; returns the paths.
pub fn perturbed_frames(
    dir: &Path,
    order: usize,
    level: usize,
    tau: f64,
    steps: usize,
    every: usize,
    theta: f64,
) -> Result<Vec<std::path::PathBuf>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let mut s = ParametricSurface::icosphere(1.0, level, order)?;
    s.map_nodes(perturbed);
    let mut paths = Vec::new();
    let mut shots = Vec::new();
    for n in 0..=steps {
        if n % every.max(1) == 0 || n == steps {
            let path = dir.join(format!("frame_{n:03}.vtu"));
            let surface = s.to_triangle_surface();
            write_surface_vtu(&path, &surface)?;
            paths.push(path);
            shots.push((n as f64 * tau, surface));
        }
        if n < steps {
            theta_step(&mut s, tau, theta)?;
        }
    }
    let picks: Vec<usize> = if shots.len() <= 4 {
        (0..shots.len()).collect()
    } else {
        (0..4).map(|k| k * (shots.len() - 1) / 3).collect()
    };
    let panels: Vec<SurfacePanel> = picks
        .iter()
        .map(|&k| SurfacePanel {
            surface: &shots[k].1,
            scalars: None,
            title: format!("t = {:.4}", shots[k].0),
        })
        .collect();
    let png = dir.with_extension("png");
    render_surfaces(&png, &panels, &View::default())?;
    paths.push(png);
    Ok(paths)
}

/// Writes a triangle surface as a `.vtu` unstructured grid (triangles, 3D points).
pub fn write_surface_vtu(path: &Path, s: &TriangleSurface) -> Result<()> {
    write_surface_fields(path, s, &[])
}

/// Writes a triangle surface with per-vertex fields as a `.vtu` unstructured grid.
/// Error: [`Error::InvalidField`] for a field of the wrong length or a non-finite value.
pub fn write_surface_fields(
    path: &Path,
    s: &TriangleSurface,
    fields: &[(&str, &[f64])],
) -> Result<()> {
    for (name, f) in fields {
        if f.len() != s.points.len() || f.iter().any(|v| !v.is_finite()) {
            return Err(Error::InvalidField {
                name: (*name).into(),
                msg: format!(
                    "{} values for {} vertices, or a non-finite value",
                    f.len(),
                    s.points.len()
                ),
            });
        }
    }
    anisomesh::io::atomic_write(path, |w| {
        writeln!(w, "<?xml version=\"1.0\"?>")?;
        writeln!(w, "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\">")?;
        writeln!(w, "<UnstructuredGrid>")?;
        writeln!(
            w,
            "<Piece NumberOfPoints=\"{}\" NumberOfCells=\"{}\">",
            s.points.len(),
            s.triangles.len()
        )?;
        if !fields.is_empty() {
            writeln!(w, "<PointData>")?;
        }
        for (name, f) in fields {
            writeln!(
                w,
                "<DataArray type=\"Float64\" Name=\"{name}\" format=\"ascii\">"
            )?;
            for v in *f {
                writeln!(w, "{v}")?;
            }
            writeln!(w, "</DataArray>")?;
        }
        if !fields.is_empty() {
            writeln!(w, "</PointData>")?;
        }
        writeln!(
            w,
            "<Points><DataArray type=\"Float64\" NumberOfComponents=\"3\" format=\"ascii\">"
        )?;
        for p in &s.points {
            writeln!(w, "{} {} {}", p.x, p.y, p.z)?;
        }
        writeln!(w, "</DataArray></Points><Cells>")?;
        writeln!(
            w,
            "<DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">"
        )?;
        for t in &s.triangles {
            writeln!(w, "{} {} {}", t[0], t[1], t[2])?;
        }
        writeln!(
            w,
            "</DataArray><DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">"
        )?;
        for i in 0..s.triangles.len() {
            writeln!(w, "{}", 3 * (i + 1))?;
        }
        writeln!(
            w,
            "</DataArray><DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">"
        )?;
        for _ in &s.triangles {
            writeln!(w, "5")?;
        }
        writeln!(
            w,
            "</DataArray></Cells></Piece></UnstructuredGrid></VTKFile>"
        )
    })
}
