//! `anisomesh fit --compare-mmg`: the interface fitting of `anisomesh fit` beside
//! `mmg2d_O3 -ls -noinsert -noswap -nomove` (the same operation: the zero level split into the
//! mesh, no remeshing), both run as commands on the same `.mesh`/`.sol` files, in the same run.
//!
//! Cases: the Zalesak disk on a 100² grid and on a mesh adapted to it (004), a level set whose
//! zeros fall exactly on vertices (a square and a diamond on grid lines), level sets touching
//! the boundary (a disk cut by a side, a quarter disk at a corner), five separate disks, and the
//! Zalesak disk on a 200² grid (201² vertices) for speed. Round-off zeros of the distance
//! functions (`|u| < 1e-14 · max |u|`) are written as exact zeros, so the P1 zero level of every
//! file is well defined.
//!
//! Every output is read back and measured the same way: `check()`, vertices, triangles,
//! interface edges (label 10), the area of the triangles labelled 3 against the area of
//! `{u_h < 0}` of the P1 field as written, wall and CPU time of the command (user + system,
//! from `getrusage(RUSAGE_CHILDREN)`), and mmg2d's own `ELAPSED TIME`.

use super::peers::{find_program, parse_mmg_elapsed, run_with_timeout};
use anisomesh::adapt::{AdaptTarget, RunOptions};
use anisomesh::backends::fitted::{REF_INSIDE, REF_INTERFACE};
use anisomesh::io::{self, Sol};
use anisomesh::levelset::{enclosed_area, nodal_distance, Shape, Zalesak};
use anisomesh::{DVec2, Error, GridPattern, Mesh2, Result};
use serde::Serialize;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Duration;

/// One input of the comparison.
pub struct FitCase {
    /// Short name (file stem).
    pub name: &'static str,
    /// The base mesh.
    pub mesh: Mesh2,
    /// The level set at its vertices.
    pub u: Vec<f64>,
}

/// One tool on one case.
#[derive(Debug, Clone, Serialize)]
pub struct FitRow {
    pub case: String,
    pub tool: String,
    pub vertices: usize,
    pub triangles: usize,
    pub interface_edges: usize,
    pub area_inside: f64,
    /// |area − P1 area| / P1 area.
    pub area_rel_error: f64,
    /// "ok" or the defect `check()` reports.
    pub check: String,
    /// Wall time of the command (best of the repeats).
    pub wall_seconds: f64,
    /// User + system CPU time of the command (the least of the repeats).
    pub cpu_seconds: f64,
    /// mmg2d's own ELAPSED TIME, when printed.
    pub own_seconds: Option<f64>,
}

/// The whole comparison.
#[derive(Debug, Clone, Serialize)]
pub struct FitComparison {
    /// The mmg2d binary run (None when not installed).
    pub mmg2d: Option<String>,
    pub rows: Vec<FitRow>,
    /// mmg2d wall / ours wall and CPU ratios on the speed case.
    pub speed_wall_ratio: Option<f64>,
    pub speed_cpu_ratio: Option<f64>,
}

fn clean_zeros(mut u: Vec<f64>) -> Vec<f64> {
    let scale = u.iter().fold(0.0f64, |m, x| m.max(x.abs()));
    for x in &mut u {
        if x.abs() < 1e-14 * scale {
            *x = 0.0;
        }
    }
    u
}

fn on_grid(lo: DVec2, hi: DVec2, n: usize, f: impl Fn(DVec2) -> f64) -> Result<(Mesh2, Vec<f64>)> {
    let m = Mesh2::rectangle(lo, hi, n, n, GridPattern::Right)?;
    let u = clean_zeros(m.points.iter().map(|&p| f(p)).collect());
    Ok((m, u))
}

/// The cases of the comparison (module documentation); `speed_n` cells per side for the speed
/// case.
pub fn cases(speed_n: usize) -> Result<Vec<FitCase>> {
    let z = Zalesak::default();
    let (zlo, zhi) = (DVec2::new(-1.0, -0.25), DVec2::new(1.0, 1.75));
    let mut out = Vec::new();
    let mut push = |name, (mesh, u): (Mesh2, Vec<f64>)| out.push(FitCase { name, mesh, u });
    push("zalesak_grid", on_grid(zlo, zhi, 100, |p| z.distance(p))?);
    let adapted = anisomesh::adapt::run(
        AdaptTarget::Shape {
            shape: Box::new(Zalesak::default()),
            domain: (DVec2::new(-2.0, -2.0), DVec2::new(2.0, 2.0)),
        },
        &RunOptions::default(),
    )?;
    let u = clean_zeros(nodal_distance(&adapted.mesh, &z));
    push("zalesak_adapted", (adapted.mesh, u));
    let (o, one) = (DVec2::ZERO, DVec2::ONE);
    push(
        "vertex_zeros",
        on_grid(o, one, 50, |p| {
            let sq = (p.x - 0.3).abs().max((p.y - 0.3).abs()) - 0.16;
            let diamond = (p.x - 0.7).abs() + (p.y - 0.7).abs() - 0.2;
            sq.min(diamond)
        })?,
    );
    push(
        "boundary",
        on_grid(o, one, 50, |p| {
            let side = (p - DVec2::new(0.97, 0.52)).length() - 0.17;
            let corner = p.length() - 0.33;
            side.min(corner)
        })?,
    );
    push(
        "components",
        on_grid(o, one, 60, |p| {
            [
                (0.2, 0.2, 0.1),
                (0.55, 0.25, 0.12),
                (0.8, 0.6, 0.13),
                (0.3, 0.7, 0.15),
                (0.62, 0.85, 0.07),
            ]
            .iter()
            .map(|&(x, y, r)| (p - DVec2::new(x, y)).length() - r)
            .fold(f64::INFINITY, f64::min)
        })?,
    );
    push("speed", on_grid(zlo, zhi, speed_n, |p| z.distance(p))?);
    Ok(out)
}

/// The native mmg2d behind a Python entry-point script (mmgpy installs `mmg2d_O3` as a script
/// that starts the binary in `site-packages/mmgpy/bin`), or the program itself.
pub fn native_mmg2d() -> Option<PathBuf> {
    let p = find_program("mmg2d_O3")?;
    let head = std::fs::read(&p).ok()?;
    if !head.starts_with(b"#!") {
        return Some(p);
    }
    let first = String::from_utf8_lossy(&head);
    let interp = first.lines().next()?.trim_start_matches("#!").trim();
    let prefix = Path::new(interp).parent()?.parent()?;
    let lib = prefix.join("lib");
    for e in std::fs::read_dir(&lib).ok()?.flatten() {
        let cand = e.path().join("site-packages/mmgpy/bin/mmg2d_O3");
        if cand.is_file() {
            return Some(cand);
        }
    }
    Some(p)
}

/// CPU time (user + system) of the terminated children of this process, in seconds.
fn children_cpu() -> f64 {
    // SAFETY: getrusage writes into the zeroed struct it is given.
    let mut r: libc::rusage = unsafe { std::mem::zeroed() };
    unsafe { libc::getrusage(libc::RUSAGE_CHILDREN, &mut r) };
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(r.ru_utime) + t(r.ru_stime)
}

/// Measures a fitted mesh read back from `path`.
fn measure(path: &Path, case: &str, tool: &str, reference: f64) -> Result<FitRow> {
    let m = io::read_mesh(path)?;
    let check = match m.check() {
        Ok(()) => "ok".to_string(),
        Err(e) => e.to_string(),
    };
    let area: f64 = m
        .live_tris()
        .filter(|&t| m.tri_ref[t] == REF_INSIDE)
        .map(|t| m.tri_area(t))
        .sum();
    let interface_edges = {
        let mut n = 0;
        for t in m.live_tris() {
            for i in 0..3 {
                let nb = m.neighbours[t][i];
                if m.edge_ref[t][i] == REF_INTERFACE && (nb == anisomesh::NONE || nb as usize > t) {
                    n += 1;
                }
            }
        }
        n
    };
    Ok(FitRow {
        case: case.into(),
        tool: tool.into(),
        vertices: m.n_points(),
        triangles: m.n_live_tris(),
        interface_edges,
        area_inside: area,
        area_rel_error: (area - reference).abs() / reference,
        check,
        wall_seconds: f64::INFINITY,
        cpu_seconds: 0.0,
        own_seconds: None,
    })
}

/// Runs `cmd` `repeats` times; the best wall time, the least CPU time (each of the runs on a
/// shared machine is slowed by other work by a different amount; the least disturbed run is
/// the one closest to the command's own cost), the stdout of the fastest run.
fn timed(
    mut cmd: impl FnMut() -> Command,
    repeats: usize,
    dir: &Path,
    tag: &str,
) -> Result<(f64, f64, String)> {
    let mut best = (f64::INFINITY, f64::INFINITY, String::new());
    for _ in 0..repeats.max(1) {
        let c0 = children_cpu();
        let run = run_with_timeout(&mut cmd(), Duration::from_secs(300), dir, tag)?;
        let cpu = children_cpu() - c0;
        if !run.success {
            return Err(Error::InvalidInput(format!(
                "{tag} failed{}: {}{}",
                if run.timed_out { " (timed out)" } else { "" },
                run.stdout.lines().last().unwrap_or(""),
                run.stderr.lines().last().unwrap_or("")
            )));
        }
        if run.seconds < best.0 {
            best.0 = run.seconds;
            best.2 = run.stdout;
        }
        if cpu < best.1 {
            best.1 = cpu;
        }
    }
    Ok(best)
}

/// Runs every case through `anisomesh fit` (this executable) and mmg2d (when installed),
/// `repeats` times each for the timings; files go to `dir`.
pub fn compare(dir: &Path, speed_n: usize, repeats: usize) -> Result<FitComparison> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let exe = std::env::current_exe().map_err(|e| Error::io(Path::new("anisomesh"), e))?;
    let mmg = native_mmg2d();
    let mut rows = Vec::new();
    let (mut speed_wall, mut speed_cpu) = (None, None);
    for case in cases(speed_n)? {
        let mesh_in = dir.join(format!("{}.mesh", case.name));
        let sol_in = dir.join(format!("{}.sol", case.name));
        io::write_mesh(&mesh_in, &case.mesh)?;
        io::write_sol(&sol_in, &Sol::scalar(case.u.clone()))?;
        let reference = enclosed_area(&case.mesh, &case.u)?;
        let ours_out = dir.join(format!("{}_ours.mesh", case.name));
        let (w, c, _) = timed(
            || {
                let mut cmd = Command::new(&exe);
                cmd.arg("fit")
                    .arg("--input")
                    .arg(&mesh_in)
                    .arg("--sol")
                    .arg(&sol_in)
                    .arg("-o")
                    .arg(&ours_out);
                cmd
            },
            repeats,
            dir,
            "anisomesh",
        )?;
        let mut ours = measure(&ours_out, case.name, "anisomesh", reference)?;
        ours.wall_seconds = w;
        ours.cpu_seconds = c;
        if let Some(mmg) = &mmg {
            let mmg_out = dir.join(format!("{}_mmg2d.mesh", case.name));
            let (w2, c2, stdout) = timed(
                || {
                    let mut cmd = Command::new(mmg);
                    cmd.args(["-ls", "-noinsert", "-noswap", "-nomove", "-in"])
                        .arg(&mesh_in)
                        .arg("-sol")
                        .arg(&sol_in)
                        .arg("-out")
                        .arg(&mmg_out);
                    cmd
                },
                repeats,
                dir,
                "mmg2d",
            )?;
            let mut theirs = measure(&mmg_out, case.name, "mmg2d", reference)?;
            theirs.wall_seconds = w2;
            theirs.cpu_seconds = c2;
            theirs.own_seconds = parse_mmg_elapsed(&stdout);
            if case.name == "speed" {
                speed_wall = Some(w2 / w);
                speed_cpu = Some(c2 / c.max(1e-9));
            }
            rows.push(ours);
            rows.push(theirs);
        } else {
            rows.push(ours);
        }
    }
    Ok(FitComparison {
        mmg2d: mmg.map(|p| p.display().to_string()),
        rows,
        speed_wall_ratio: speed_wall,
        speed_cpu_ratio: speed_cpu,
    })
}
