//! Speed of geometric redistancing (004 §2.2): a 1001 x 1001 grid of the square [-1, 1]^2
//! (1,002,001 vertices) and four circles whose piecewise-linear zero level has about 10,000
//! segments.
//! Every vertex gets its exact distance to the polyline through a bounding-volume hierarchy:
//! O((m + n) log m). Run with `cargo run --release --example redistance_speed [n]`.

use std::time::Instant;

use anisomesh::levelset::redistance::redistance_geometric;
use anisomesh::{DVec2, GridPattern, Mesh2};

fn main() -> anisomesh::Result<()> {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|s| s.parse().ok())
        // ANISOMESH_QUICK=1 (CI): a 200 x 200 grid instead of 1000 x 1000.
        .unwrap_or(if std::env::var_os("ANISOMESH_QUICK").is_some() {
            200
        } else {
            1000
        });
    let mesh = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        n,
        n,
        GridPattern::Right,
    )?;
    // Four circles of radius 0.37 centred at (±0.5, ±0.5): about 10,000 cut triangles at n = 1000.
    let r = 0.37;
    let exact = |p: &DVec2| {
        let q = DVec2::new(p.x.abs() - 0.5, p.y.abs() - 0.5);
        q.length() - r
    };
    let u: Vec<f64> = mesh.points.iter().map(exact).collect();
    let cut = mesh
        .tris
        .iter()
        .filter(|t| {
            let s = t.map(|v| u[v as usize]);
            s.iter().any(|&x| x < 0.0) && s.iter().any(|&x| x > 0.0)
        })
        .count();
    let mut best = f64::INFINITY;
    let mut best_cpu = f64::INFINITY;
    let mut d = Vec::new();
    for _ in 0..3 {
        let (t0, c0) = (Instant::now(), cpu_seconds());
        d = redistance_geometric(&mesh, &u)?;
        best = best.min(t0.elapsed().as_secs_f64());
        best_cpu = best_cpu.min(cpu_seconds() - c0);
    }
    let err = d
        .iter()
        .zip(&mesh.points)
        .map(|(d, p)| (d - exact(p)).abs())
        .fold(0.0, f64::max);
    println!(
        "{} vertices, {} interface segments, {} threads: best of 3 = {:.3} s wall, {:.2} s CPU \
         (max |d - d_exact| = {:.2e})",
        mesh.n_points(),
        cut,
        rayon::current_num_threads(),
        best,
        best_cpu,
        err
    );
    Ok(())
}

/// CPU time (user + system) of this process so far, from `/proc/self/stat` (0 where unavailable):
/// on a loaded machine it says what the wall time would be with the cores to ourselves.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return 0.0;
    };
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let rest = stat.rsplit_once(')').map(|(_, r)| r).unwrap_or("");
    let f: Vec<&str> = rest.split_whitespace().collect();
    let ticks = |i: usize| f.get(i).and_then(|s| s.parse::<f64>().ok()).unwrap_or(0.0);
    (ticks(11) + ticks(12)) / 100.0
}
