//! `anisomesh bench star`: accuracy per vertex on the 004 §5 star surface
//! `|x| = 0.45 + 0.3 cos 6θ cos² 3φ` against mmg3d, in the same run and measured by the same
//! code. anisomesh adapts the Kuhn mesh of `[−1, 1]³` to the star with 004 eq. (6)
//! (`adapt --dim 3 --shape star`); mmg3d_O3 gets the Kuhn mesh of `[−1, 1]³` with `n³` cubes
//! and the star's level set at its vertices (`mmg3d_O3 -in cubeN.mesh -sol cubeN.sol -ls
//! -hausd H`). Both discrete surfaces (ours: the P1 zero level of the level set at the
//! vertices; mmg3d's: the faces between its regions 3 and 2) are measured against the exact
//! surface by [`anisomesh::levelset::compare_radial`]: distances both ways (median, 99th
//! percentile, maximum) and the enclosed volume against the exact 0.4805422178.

use super::bench_tet::{cpu_seconds, run_mmg3d};
use super::ugawg::to_medit3;
use crate::app::repro::peers::find_program;
use anisomesh::adapt::{run3, LevelSetMetric, Run3Options, Target3};
use anisomesh::io::{self, atomic_write, Sol};
use anisomesh::levelset::compare_radial::{
    compare_to_radial, interface_triangles, zero_level_triangles, RadialComparison, RadialSurface,
};
use anisomesh::levelset::{Normalized, Shape, StarSurface};
use anisomesh::mesh3::Mesh3;
use anisomesh::{DVec3, Error, Result};
use serde::Serialize;
use std::path::Path;
use std::time::{Duration, Instant};

/// The exact surface is sampled on the icosahedron refined this many times (as `measure`).
const SAMPLING_LEVEL: u32 = 7;

/// One mesher's result.
#[derive(Debug, Clone, Serialize)]
pub struct StarRow {
    /// `anisomesh` or `mmg3d`.
    pub mesher: &'static str,
    /// The setting (`eps`, `hmin` or the input grid and `-hausd`).
    pub setting: String,
    /// Vertices of the result.
    pub vertices: usize,
    /// CPU seconds (this process's adaptation, or the mmg3d child).
    pub cpu: f64,
    /// Wall-clock seconds.
    pub wall: f64,
    /// The distances and the volume.
    pub comparison: RadialComparison,
}

/// What the benchmark runs.
pub struct StarBench<'a> {
    /// 004 eq. (6) for our run.
    pub metric: LevelSetMetric,
    /// Cells per side of mmg3d's Kuhn input meshes (one mmg3d run each).
    pub cubes: &'a [usize],
    /// mmg3d's `-hausd`.
    pub hausd: f64,
    /// Whether to run mmg3d (skipped when it is not installed).
    pub with_mmg3d: bool,
    /// Time limit of each mmg3d run.
    pub timeout: Duration,
    /// Output directory (meshes, `bench_star.json`, `bench_star.csv`).
    pub dir: &'a Path,
}

/// The star's level set as the adaptation and the measurement see it: `u/|∇u|`.
fn level_set(p: DVec3) -> f64 {
    Normalized {
        inner: StarSurface::PAPER,
        cap: 4.0,
    }
    .distance(p)
}

fn exact_star() -> (StarSurface, f64) {
    let star = StarSurface::PAPER;
    (star, star.exact_area().unwrap_or(f64::NAN))
}

fn compare(triangles: &[[DVec3; 3]], volume: f64) -> Result<RadialComparison> {
    let (star, exact_volume) = exact_star();
    let rho = move |d: DVec3| star.radius_towards(d);
    let exact = RadialSurface {
        centre: DVec3::ZERO,
        rho: &rho,
        volume: exact_volume,
    };
    compare_to_radial(triangles, volume, &exact, SAMPLING_LEVEL)
}

/// Runs ours, then mmg3d on each input grid, calling `row` after each; writes the meshes,
/// `bench_star.json` and `bench_star.csv` into `b.dir`.
pub fn run(b: &StarBench<'_>, mut row: impl FnMut(&StarRow)) -> Result<Vec<StarRow>> {
    std::fs::create_dir_all(b.dir).map_err(|e| Error::io(b.dir, e))?;
    let mut rows = Vec::new();
    let opts = Run3Options {
        metric: b.metric,
        ..Run3Options::default()
    };
    let (c0, t0) = (cpu_seconds(libc::RUSAGE_SELF), Instant::now());
    let a = run3(Target3::Shape(&StarSurface::PAPER), None, &opts)?;
    let (cpu, wall) = (
        cpu_seconds(libc::RUSAGE_SELF) - c0,
        t0.elapsed().as_secs_f64(),
    );
    io::write_medit3(&b.dir.join("anisomesh_star.mesh"), &to_medit3(&a.mesh))?;
    let u: Vec<f64> = a.mesh.points.iter().map(|&p| level_set(p)).collect();
    let (t, v) = zero_level_triangles(&a.mesh.points, &a.mesh.tets, &u)?;
    let ours = StarRow {
        mesher: "anisomesh",
        setting: format!("eps {:.0e} hmin {:.0e}", b.metric.eps, b.metric.hmin),
        vertices: a.mesh.n_points(),
        cpu,
        wall,
        comparison: compare(&t, v)?,
    };
    row(&ours);
    rows.push(ours);
    let mmg = if b.with_mmg3d {
        find_program("mmg3d_O3")
    } else {
        None
    };
    if let Some(prog) = &mmg {
        for &n in b.cubes {
            rows.push(mmg3d(prog, n, b)?);
            row(rows.last().expect("pushed"));
        }
    }
    write_reports(&rows, b.dir)?;
    Ok(rows)
}

/// mmg3d_O3 `-ls -hausd` on the Kuhn mesh of `[−1, 1]³` with `n³` cubes.
fn mmg3d(prog: &Path, n: usize, b: &StarBench<'_>) -> Result<StarRow> {
    let start = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [n; 3])?;
    let tag = format!("cube{n}");
    let mesh_in = b.dir.join(format!("{tag}.mesh"));
    let sol_in = b.dir.join(format!("{tag}.sol"));
    let mesh_out = b.dir.join(format!("{tag}_mmg3d.mesh"));
    io::write_medit3(&mesh_in, &to_medit3(&start))?;
    let u: Vec<f64> = start.points.iter().map(|&p| level_set(p)).collect();
    io::write_sol(&sol_in, &Sol::scalar_dim(3, u))?;
    let hausd = b.hausd.to_string();
    let (wall, cpu) = run_mmg3d(
        prog,
        &mesh_in,
        &sol_in,
        &["-ls", "-hausd", &hausd],
        &mesh_out,
        b.timeout,
        b.dir,
        &tag,
    )?;
    let m = io::read_medit3(&mesh_out)?;
    let (t, v) = interface_triangles(&m.points, &m.tets, &m.tet_ref, 3, 2)?;
    Ok(StarRow {
        mesher: "mmg3d",
        setting: format!("{n}^3 cubes, -hausd {:.0e}", b.hausd),
        vertices: m.points.len(),
        cpu,
        wall,
        comparison: compare(&t, v)?,
    })
}

fn write_reports(rows: &[StarRow], dir: &Path) -> Result<()> {
    let json = serde_json::to_string_pretty(&serde_json::json!({
        "shape": "star, 004 §5",
        "exact_volume": exact_star().1,
        "rows": rows,
    }))
    .map_err(|e| Error::InvalidInput(format!("bench_star.json: {e}")))?;
    atomic_write(&dir.join("bench_star.json"), |w| {
        w.write_all(json.as_bytes())
    })?;
    atomic_write(&dir.join("bench_star.csv"), |w| {
        writeln!(
            w,
            "mesher,setting,vertices,cpu_s,wall_s,exact_to_discrete_median,exact_to_discrete_p99,\
             exact_to_discrete_max,discrete_to_exact_median,discrete_to_exact_p99,\
             discrete_to_exact_max,volume,volume_error"
        )?;
        for r in rows {
            let c = &r.comparison;
            let (e, d) = (&c.exact_to_discrete, &c.discrete_to_exact);
            writeln!(
                w,
                "{},{},{},{:.2},{:.2},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.4e},{:.10},{:.4e}",
                r.mesher,
                r.setting,
                r.vertices,
                r.cpu,
                r.wall,
                e.median,
                e.p99,
                e.max,
                d.median,
                d.p99,
                d.max,
                c.volume,
                c.volume_error
            )?;
        }
        Ok(())
    })
}
