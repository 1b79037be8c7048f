//! Adaptation speed: a 100 x 100-vertex grid of [-2, 2]² adapted to the geometric metric of
//! 004 eq. (6) with `eps = hmin` (the metric and the level set re-evaluated exactly at new
//! vertices), for `eps = hmin` = 1e-3, 1e-4, 1e-5 (about 1e4, 1e5, 1e6 output vertices). Prints
//! the output size, the time and the vertices per second; single-threaded if run with
//! `RAYON_NUM_THREADS=1`.
//!
//! Usage: `cargo run --release --example adapt_speed -- [eps ...]`

use anisomesh::adapt::{adapt, AdaptOptions, AnalyticLevelSetSource, LevelSetMetric, PassKind};
use anisomesh::metric::quality_stats;
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};
use std::time::Instant;

/// Circle of radius 0.5 (replaced by the Zalesak disk once `levelset::shapes` is available).
fn shape(p: DVec2) -> (f64, DVec2, Sym2) {
    let c = DVec2::new(0.0, 0.75);
    let q = p - c;
    let r = q.length().max(1e-12);
    let n = q / r;
    let h = Sym2::IDENTITY
        .add(&Sym2::outer(n).scale(-1.0))
        .scale(1.0 / r);
    (r - 0.5, n, h)
}

fn main() -> anisomesh::Result<()> {
    let mut eps: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    if eps.is_empty() {
        eps = vec![1e-3, 1e-4, 1e-5];
    }
    println!(
        "{:>8} {:>10} {:>10} {:>8} {:>12} {:>8} {:>8}",
        "eps", "vertices", "triangles", "seconds", "vertices/s", "in_range", "q_max"
    );
    for e in eps {
        let lm = LevelSetMetric {
            eps: e,
            hmin: e,
            ..LevelSetMetric::default()
        };
        let src = AnalyticLevelSetSource::new(shape, lm);
        let mut mesh = Mesh2::rectangle(
            DVec2::splat(-2.0),
            DVec2::splat(2.0),
            99,
            99,
            GridPattern::UnionJack,
        )?;
        let t0 = Instant::now();
        let (mut metric, u) = src.evaluate(&mesh);
        let mut fields = vec![u];
        let rep = adapt(
            &mut mesh,
            &mut metric,
            &mut fields,
            Some(&src),
            &AdaptOptions::default(),
        )?;
        let secs = t0.elapsed().as_secs_f64();
        let q = quality_stats(&mesh, &metric);
        println!(
            "{:>8.0e} {:>10} {:>10} {:>8.2} {:>12.0} {:>8.4} {:>8.2}",
            e,
            mesh.n_points(),
            mesh.n_tris(),
            secs,
            mesh.n_points() as f64 / secs,
            q.edge_length_in_range,
            q.q_ani_max
        );
        println!("    cycles {} converged {}", rep.cycles, rep.converged);
        if std::env::var("ADAPT_TRACE").is_ok() {
            for p in &rep.passes {
                print!("{:?}:{} ", p.kind, p.count);
            }
            println!();
        }
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
