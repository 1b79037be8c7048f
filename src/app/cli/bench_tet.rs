//! `anisomesh bench tet`: the speed of the tetrahedral adaptation against mmg3d on the same
//! metric, in the same run. The metric is UGAWG cube-linear scaled by `s²` (all sizes divided
//! by `s`, so the vertex count grows as `s³`) for each requested vertex count; the start mesh is
//! the Kuhn mesh of `[0,1]³` with 10 cubes per side. anisomesh evaluates the analytic field at
//! every new or moved vertex; mmg3d_O3 reads the same field at the start mesh's vertices
//! (`CASE.mesh`, `CASE.sol`). Both results are measured by the same conformity statistics in
//! the analytic field. Times are CPU seconds of this process (our adaptation) and of the
//! finished child (mmg3d), from `getrusage`.

use super::ugawg::to_medit3;
use crate::app::repro::peers::{find_program, run_with_timeout};
use anisomesh::adapt::{run3, Run3Options, Target3};
use anisomesh::io::{self, Sol};
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::ugawg::UgawgCase;
use anisomesh::metric::{conformity_analytic, conformity_ugawg};
use anisomesh::{DVec3, Error, Result};
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// The vertex count of the adapted mesh at scale 1 (cube-linear, h0 = 1e-3), about.
const BASE_VERTICES: f64 = 1.0e4;

/// One mesher's result on one scale.
#[derive(Debug, Clone)]
pub struct TetSpeedRow {
    /// `anisomesh` or `mmg3d`.
    pub mesher: &'static str,
    /// The requested vertex count.
    pub target: f64,
    /// Vertices of the result.
    pub vertices: usize,
    /// CPU seconds.
    pub cpu: f64,
    /// Wall-clock seconds.
    pub wall: f64,
    /// Share of edges with metric length in `[1/√2, √2]`, lengths integrated along the edges.
    pub in_range: f64,
    /// The same share by the UGAWG measures (end-point rule, field at the vertices).
    pub in_range_ugawg: f64,
    /// Worst mean ratio.
    pub quality_min: f64,
}

/// CPU seconds used so far by this process (`who = RUSAGE_SELF`) or by its finished children
/// (`RUSAGE_CHILDREN`).
pub(super) fn cpu_seconds(who: i32) -> f64 {
    // SAFETY: getrusage writes into the zeroed struct we own.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    if unsafe { libc::getrusage(who, &mut u) } != 0 {
        return f64::NAN;
    }
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

/// Runs `prog -in MESH -sol SOL [extra] -out OUT` with a time limit (logs in `dir`, named
/// `tag`); returns the outcome's wall-clock seconds and the child's CPU seconds. Errors: the
/// run failed or timed out.
#[allow(clippy::too_many_arguments)]
pub(super) fn run_mmg3d(
    prog: &Path,
    mesh_in: &Path,
    sol_in: &Path,
    extra: &[&str],
    mesh_out: &Path,
    timeout: Duration,
    dir: &Path,
    tag: &str,
) -> Result<(f64, f64)> {
    let c0 = cpu_seconds(libc::RUSAGE_CHILDREN);
    let out = run_with_timeout(
        Command::new(prog)
            .arg("-in")
            .arg(mesh_in)
            .arg("-sol")
            .arg(sol_in)
            .args(extra)
            .arg("-out")
            .arg(mesh_out),
        timeout,
        dir,
        tag,
    )?;
    let cpu = cpu_seconds(libc::RUSAGE_CHILDREN) - c0;
    if !out.success {
        return Err(Error::InvalidInput(format!(
            "{} on {} failed{}",
            prog.display(),
            mesh_in.display(),
            if out.timed_out { " (time limit)" } else { "" }
        )));
    }
    Ok((out.seconds, cpu))
}

/// Runs every scale of `targets` (vertex counts), calling `row` after each mesher; mmg3d is
/// skipped when `with_mmg3d` is false or it is not installed (a row is not printed then).
pub fn run(
    targets: &[f64],
    with_mmg3d: bool,
    timeout: Duration,
    dir: &Path,
    mut row: impl FnMut(&TetSpeedRow),
) -> Result<Vec<TetSpeedRow>> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let case = UgawgCase::CubeLinear;
    let start = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [10; 3])?;
    let mmg = if with_mmg3d {
        find_program("mmg3d_O3")
    } else {
        None
    };
    let mut rows = Vec::new();
    for &n in targets {
        if !(n.is_finite() && (1e3..=1e7).contains(&n)) {
            return Err(Error::InvalidInput(format!(
                "--vertices {n}: expected counts from 1e3 to 1e7"
            )));
        }
        let s2 = (n / BASE_VERTICES).powf(2.0 / 3.0);
        let metric = move |p: DVec3| case.metric(p).scale(s2);
        let (c0, t0) = (cpu_seconds(libc::RUSAGE_SELF), Instant::now());
        let opts = Run3Options::default();
        let a = run3(Target3::Metric(&metric), Some(&start), &opts)?;
        let (cpu, wall) = (
            cpu_seconds(libc::RUSAGE_SELF) - c0,
            t0.elapsed().as_secs_f64(),
        );
        let c = conformity_analytic(&a.mesh.points, &a.mesh.tets, &metric)?;
        let u = ugawg_share(&a.mesh.points, &a.mesh.tets, &metric)?;
        let ours = TetSpeedRow {
            mesher: "anisomesh",
            target: n,
            vertices: a.mesh.n_points(),
            cpu,
            wall,
            in_range: c.edge_length_in_range,
            in_range_ugawg: u,
            quality_min: c.mean_ratio_min,
        };
        row(&ours);
        rows.push(ours);
        let tag = format!("cube-linear-{n:.0e}");
        io::write_medit3(
            &dir.join(format!("{tag}_anisomesh.mesh")),
            &to_medit3(&a.mesh),
        )?;
        let Some(prog) = &mmg else {
            continue;
        };
        let mesh_in = dir.join(format!("{tag}.mesh"));
        let sol_in = dir.join(format!("{tag}.sol"));
        let mesh_out = dir.join(format!("{tag}_mmg3d.mesh"));
        io::write_medit3(&mesh_in, &to_medit3(&start))?;
        let field: Vec<_> = start.points.iter().map(|&p| metric(p)).collect();
        io::write_sol(&sol_in, &Sol::metric3(&field))?;
        let (wall_mmg, cpu) =
            run_mmg3d(prog, &mesh_in, &sol_in, &[], &mesh_out, timeout, dir, &tag)?;
        let m = io::read_medit3(&mesh_out)?;
        let c = conformity_analytic(&m.points, &m.tets, &metric)?;
        let u = ugawg_share(&m.points, &m.tets, &metric)?;
        let theirs = TetSpeedRow {
            mesher: "mmg3d",
            target: n,
            vertices: m.points.len(),
            cpu,
            wall: wall_mmg,
            in_range: c.edge_length_in_range,
            in_range_ugawg: u,
            quality_min: c.mean_ratio_min,
        };
        row(&theirs);
        rows.push(theirs);
    }
    Ok(rows)
}

/// The share of edges in `[1/√2, √2]` by the UGAWG measures: the field at the vertices, lengths
/// by the study's end-point rule.
fn ugawg_share(
    points: &[DVec3],
    tets: &[[u32; 4]],
    metric: &(impl Fn(DVec3) -> anisomesh::metric::Sym3 + Sync),
) -> Result<f64> {
    let at: Vec<_> = points.iter().map(|&p| metric(p)).collect();
    Ok(conformity_ugawg(points, tets, &at)?.edge_length_in_range)
}
