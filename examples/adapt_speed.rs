//! Adaptation speed: a 100 x 100-vertex grid of [-2, 2]² adapted to the geometric metric of
//! 004 eq. (6) of the Zalesak disk with `eps = hmin`, through `adapt_to_shape` (rounds of exact
//! evaluation at the vertices, gradation 2, adaptation), for `eps = hmin` = 1e-3, 1e-4, 1e-5.
//! Prints the output size, the time and the vertices per second; single-threaded if run with
//! `RAYON_NUM_THREADS=1`. Measured (one thread, busy 2-core machine): 2.5e3 vertices in 0.8 s,
//! 1.4e4 in 3.5 s, 5.1e4 in 17.5 s (eps 3e-5), 2.2e5 in 171 s (eps 1e-5, worst Q_ani 1e3):
//! 1e3–4e3 vertices/s and superlinear, far from the 1.3e5/s target.
//!
//! Usage: `cargo run --release --example adapt_speed -- [eps ...]`

use anisomesh::adapt::{
    adapt_to_shape, AnalyticLevelSetSource, LevelSetMetric, PassKind, ShapeAdaptOptions,
};
use anisomesh::levelset::{Shape, Zalesak};
use anisomesh::metric::quality_stats;
use anisomesh::DVec2;
use std::time::Instant;

fn main() -> anisomesh::Result<()> {
    let mut eps: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    if eps.is_empty() {
        // ANISOMESH_QUICK=1 (CI): one small case only.
        eps = if std::env::var_os("ANISOMESH_QUICK").is_some() {
            vec![1e-3]
        } else {
            vec![1e-3, 1e-4, 1e-5]
        };
    }
    println!(
        "{:>8} {:>10} {:>10} {:>8} {:>12} {:>8} {:>8} {:>8}",
        "eps", "vertices", "triangles", "seconds", "vertices/s", "in_range", "q_mean", "q_max"
    );
    let z = Zalesak::default();
    for e in eps {
        let opts = ShapeAdaptOptions {
            metric: LevelSetMetric {
                eps: e,
                hmin: e,
                ..LevelSetMetric::default()
            },
            coarse_cells: 99,
            ..ShapeAdaptOptions::default()
        };
        let t0 = Instant::now();
        let domain = (DVec2::splat(-2.0), DVec2::splat(2.0));
        let (mesh, _u, rep) = adapt_to_shape(&z, domain, &opts)?;
        let secs = t0.elapsed().as_secs_f64();
        let src = AnalyticLevelSetSource::new(
            |p| (z.distance(p), z.gradient(p), z.hessian(p)),
            opts.metric,
        );
        let (mut metric, _) = src.evaluate(&mesh);
        anisomesh::metric::gradate(&mesh, &mut metric, opts.gradation.unwrap_or(2.0))?;
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
        println!("    cycles {} converged {}", rep.cycles, rep.converged);
        for kind in [
            PassKind::Split,
            PassKind::Collapse,
            PassKind::Flip,
            PassKind::Smooth,
        ] {
            let ps: Vec<_> = rep.passes.iter().filter(|p| p.kind == kind).collect();
            let s: f64 = ps.iter().map(|p| p.seconds).sum();
            let n: usize = ps.iter().map(|p| p.count).sum();
            println!("    {kind:?}: {} passes, {n} ops, {s:.3} s", ps.len());
        }
    }
    Ok(())
}
