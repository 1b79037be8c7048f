//! Adapts a coarse grid of [-2, 2]² to the geometric metric (004 eq. (6)) of a circle of radius
//! 0.5, with the metric and the level set re-evaluated exactly at every new vertex, and prints
//! the quality statistics (edge lengths in [1/sqrt2, sqrt2], mean and worst `Q_ani`).
//!
//! Usage: `cargo run --release --example adapt_circle -- [eps] [hmin] [band]`

use anisomesh::adapt::{adapt, AdaptOptions, AnalyticLevelSetSource, LevelSetMetric, PassKind};
use anisomesh::metric::quality_stats;
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};

fn circle(p: DVec2) -> (f64, DVec2, Sym2) {
    let r = p.length().max(1e-12);
    let n = p / r;
    let h = Sym2::IDENTITY
        .add(&Sym2::outer(n).scale(-1.0))
        .scale(1.0 / r);
    (r - 0.5, n, h)
}

fn main() -> anisomesh::Result<()> {
    let args: Vec<f64> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    let lm = LevelSetMetric {
        eps: *args.first().unwrap_or(&1e-4),
        hmin: *args.get(1).unwrap_or(&1e-3),
        band: *args.get(2).unwrap_or(&4e-3),
        ..LevelSetMetric::default()
    };
    let src = AnalyticLevelSetSource::new(circle, lm);
    let mut mesh = Mesh2::rectangle(
        DVec2::splat(-2.0),
        DVec2::splat(2.0),
        20,
        20,
        GridPattern::UnionJack,
    )?;
    let (mut metric, u) = src.evaluate(&mesh);
    let mut fields = vec![u];
    let rep = adapt(
        &mut mesh,
        &mut metric,
        &mut fields,
        Some(&src),
        &AdaptOptions::default().insertion(std::env::var("ADAPT_INSERT").is_ok()),
    )?;
    let q = quality_stats(&mesh, &metric);
    println!(
        "vertices {} tris {} cycles {} converged {} splits {} collapses {} flips {} moves {} time {:.3}s",
        mesh.n_points(),
        mesh.n_tris(),
        rep.cycles,
        rep.converged,
        rep.splits,
        rep.collapses,
        rep.flips,
        rep.moves,
        rep.seconds
    );
    println!(
        "in range {:.4} q mean {:.4} q max {:.3} lmin {:.3} lmax {:.3}",
        q.edge_length_in_range, q.q_ani_mean, q.q_ani_max, q.edge_length_min, q.edge_length_max
    );
    println!("hist {:?}", q.q_ani_histogram);
    for kind in [
        PassKind::Split,
        PassKind::Collapse,
        PassKind::Flip,
        PassKind::Smooth,
    ] {
        let (passes, _, secs) = rep.pass_totals(kind);
        println!("{kind:?}: {passes} passes, {secs:.3}s");
    }
    Ok(())
}
