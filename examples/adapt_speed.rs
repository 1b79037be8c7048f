//! Adaptation speed on the benchmark: a 100 x 100-vertex grid of [-2, 2]² carrying the
//! geometric metric of 004 eq. (6) of the Zalesak disk with `eps = hmin` (the files that
//! `anisomesh adapt --input BG.mesh --sol M.sol` reads, written by
//! [`anisomesh::bench::peers::write_speed_case`]), adapted by [`anisomesh::adapt::adapt`] with the
//! metric interpolated at new vertices with sizes varying linearly, as mmg2d does with the same
//! files (`ANISOMESH_LOG_INTERP=1`: log-Euclidean, which gives many more vertices;
//! `ANISOMESH_HGRAD=1.3`: the metric graded during the adaptation, as mmg2d's default `-hgrad`). Prints the output size,
//! the time per operator and the vertices per second for each `eps`.
//!
//! Usage: `cargo run --release --example adapt_speed -- [eps ...]` (default 1e-3 1e-4 3e-5 1e-5;
//! `ANISOMESH_QUICK=1`: 1e-3 only). Set `RAYON_NUM_THREADS=1` for one thread.

use anisomesh::adapt::{adapt, MetricInterpolation, PassKind};
use anisomesh::bench::adapt_run::metric_file_options;
use anisomesh::bench::peers::{read_mesh_and_metric, write_speed_case};
use anisomesh::metric::quality_stats;
use std::time::Instant;

fn main() -> anisomesh::Result<()> {
    let mut eps: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    if eps.is_empty() {
        eps = if std::env::var_os("ANISOMESH_QUICK").is_some() {
            vec![1e-3]
        } else {
            vec![1e-3, 1e-4, 3e-5, 1e-5]
        };
    }
    let dir = std::env::temp_dir().join(format!("anisomesh_speed_{}", std::process::id()));
    println!(
        "{:>8} {:>10} {:>10} {:>8} {:>12} {:>8} {:>8} {:>8}",
        "eps", "vertices", "triangles", "seconds", "vertices/s", "in_range", "q_mean", "q_max"
    );
    for e in eps {
        let (bg, sol) = write_speed_case(&dir, 100, e)?;
        let (mut mesh, mut metric) = read_mesh_and_metric(&bg, &sol)?;
        let t0 = Instant::now();
        // As `anisomesh adapt --input BG.mesh --sol M.sol` (and mmg2d): sizes interpolated
        // linearly between the background vertices; `ANISOMESH_LOG_INTERP=1`: log-Euclidean.
        let interp = if std::env::var_os("ANISOMESH_LOG_INTERP").is_some() {
            MetricInterpolation::LogEuclidean
        } else {
            MetricInterpolation::LinearSizes
        };
        // `ANISOMESH_HGRAD=1.3`: grade the metric during the adaptation (as mmg2d -hgrad 1.3).
        let hgrad = std::env::var("ANISOMESH_HGRAD")
            .ok()
            .and_then(|s| s.parse().ok());
        let opts = metric_file_options().interpolation(interp).gradation(hgrad);
        let rep = adapt(&mut mesh, &mut metric, &mut [], None, &opts)?;
        let secs = t0.elapsed().as_secs_f64();
        let q = quality_stats(&mesh, &metric);
        println!(
            "{:>8.0e} {:>10} {:>10} {:>8.2} {:>12.0} {:>8.4} {:>8.3} {:>8.2}",
            e,
            mesh.n_points(),
            mesh.n_tris(),
            secs,
            mesh.n_points() as f64 / secs,
            q.edge_length_in_range,
            q.q_ani_mean,
            q.q_ani_max
        );
        println!(
            "    cycles {} converged {} gradation {:.2} s",
            rep.cycles, rep.converged, rep.gradation_seconds
        );
        if std::env::var_os("ANISOMESH_PASSES").is_some() {
            for p in &rep.passes {
                println!("      {:?} {} {:.3}", p.kind, p.count, p.seconds);
            }
            // A fingerprint of the result: equal runs print equal numbers.
            let mut h: u64 = 0xcbf29ce484222325;
            for p in &mesh.points {
                for x in [p.x.to_bits(), p.y.to_bits()] {
                    h = (h ^ x).wrapping_mul(0x100000001b3);
                }
            }
            for t in &mesh.tris {
                for &v in t {
                    h = (h ^ u64::from(v)).wrapping_mul(0x100000001b3);
                }
            }
            println!("    fingerprint {h:016x}");
        }
        for kind in [
            PassKind::Split,
            PassKind::Collapse,
            PassKind::Flip,
            PassKind::Smooth,
        ] {
            let (passes, n, s) = rep.pass_totals(kind);
            println!("    {kind:?}: {passes} passes, {n} ops, {s:.3} s");
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
    Ok(())
}
