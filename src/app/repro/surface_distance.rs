//! The speed of the exact signed distance to a triangulated surface (`TriangulatedShape`):
//! building the bounding-volume hierarchy of an icosphere and answering random queries in a box
//! and in a thin shell around the surface, checked against `|p| − 1` within the chord error.

use anisomesh::error::{Error, Result};
use anisomesh::levelset::{icosphere, TriangulatedShape};
use anisomesh::DVec3;
use clap::Args;
use std::time::Instant;

/// Options of `anisomesh bench surface-distance`.
#[derive(Debug, Args)]
pub struct SurfaceDistanceArgs {
    /// Icosphere refinement level (20·4^L triangles; 6 gives 81,920).
    #[arg(long, default_value_t = 6)]
    level: u32,
    /// Number of queries in each set.
    #[arg(long, default_value_t = 1_000_000)]
    queries: usize,
}

/// Deterministic points uniformly in `[−s, s]³`.
fn points(n: usize, s: f64, mut seed: u64) -> Vec<DVec3> {
    let mut rnd = move || {
        seed = seed
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        ((seed >> 11) as f64 / (1u64 << 53) as f64) * 2.0 - 1.0
    };
    (0..n)
        .map(|_| s * DVec3::new(rnd(), rnd(), rnd()))
        .collect()
}

/// Runs the benchmark and prints one line per phase.
pub fn run(a: SurfaceDistanceArgs) -> Result<()> {
    if a.level > 8 || a.queries == 0 {
        return Err(Error::InvalidInput(format!(
            "bench surface-distance: need --level at most 8 and --queries > 0 (got {} and {})",
            a.level, a.queries
        )));
    }
    let s = icosphere(a.level);
    // The Hausdorff distance between the inscribed polyhedron and the unit sphere (the chord
    // error): one minus the smallest distance from the centre to a face's plane.
    let tol = s
        .triangles
        .iter()
        .map(|t| {
            let [a, b, c] = t.map(|v| s.points[v as usize]);
            1.0 - (b - a).cross(c - a).normalize().dot(a).abs()
        })
        .fold(0.0, f64::max)
        + 1e-12;
    let t0 = Instant::now();
    let shape = TriangulatedShape::new(s.points.clone(), s.triangles.clone())?;
    let build = t0.elapsed().as_secs_f64();
    println!(
        "{} triangles: hierarchy built in {build:.3} s ({} threads)",
        s.triangles.len(),
        rayon::current_num_threads()
    );
    let boxed = points(a.queries, 1.5, 5);
    let shell: Vec<DVec3> = boxed
        .iter()
        .map(|&p| p.normalize_or(DVec3::X) * (1.0 + 0.2 * (p.x / 1.5)))
        .collect();
    for (name, pts) in [
        ("box [-1.5, 1.5]^3", &boxed),
        ("shell 0.8 < |p| < 1.2", &shell),
    ] {
        let t0 = Instant::now();
        let d = shape.distances(pts);
        let secs = t0.elapsed().as_secs_f64();
        let worst = pts
            .iter()
            .zip(&d)
            .map(|(p, dp)| (dp - (p.length() - 1.0)).abs())
            .fold(0.0, f64::max);
        println!(
            "{} queries in the {name}: {secs:.3} s ({:.2} µs per query), largest |d − (|p| − 1)| {worst:.2e}",
            pts.len(),
            1e6 * secs / pts.len() as f64
        );
        if worst > tol {
            return Err(Error::InvalidInput(format!(
                "bench surface-distance: distance error {worst:.3e} above the chord error {tol:.3e}"
            )));
        }
    }
    Ok(())
}
