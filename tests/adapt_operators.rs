//! The adaptation driver on small meshes, with `check()` after every pass: interfaces and
//! sub-domain labels preserved, metric interpolation rules, thread-count independence, cycle
//! smoothing and gradation. The single operators are tested in the library
//! (`src/adapt/tests/`).

use anisomesh::adapt::AdaptOptions;
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2, NONE};

fn square(n: usize) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::UnionJack).unwrap()
}

/// Anisotropic metric with sizes `hx`, `hy` along the axes.
fn aniso(hx: f64, hy: f64) -> Sym2 {
    Sym2::new(1.0 / (hx * hx), 0.0, 1.0 / (hy * hy))
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

#[test]
fn interface_edges_and_subdomain_labels_are_preserved() {
    // Two sub-domains: x < 0.5 (label 1) and x > 0.5 (label 2), interface edges labelled 2.
    let grid = square(4);
    let tri_ref: Vec<i32> = (0..grid.n_tris())
        .map(|t| {
            let c = grid.tri_points(t).iter().fold(DVec2::ZERO, |s, &p| s + p) / 3.0;
            if c.x < 0.5 {
                1
            } else {
                2
            }
        })
        .collect();
    let mut mesh = Mesh2::from_parts(grid.points.clone(), grid.tris.clone(), tri_ref).unwrap();
    let area = |m: &Mesh2, r: i32| -> f64 {
        m.live_tris()
            .filter(|&t| m.tri_ref[t] == r)
            .map(|t| m.tri_area(t))
            .sum()
    };
    let (a1, a2) = (area(&mesh, 1), area(&mesh, 2));
    let mut metric: Vec<Sym2> = mesh
        .points
        .iter()
        .map(|p| aniso(0.02 + 0.3 * p.y, 0.08 + 0.1 * p.x))
        .collect();
    let mut f: Vec<Vec<f64>> = vec![];
    let opts = AdaptOptions::default().check_each_pass(true);
    anisomesh::adapt::adapt(&mut mesh, &mut metric, &mut f, None, &opts).unwrap();
    assert!(rel(area(&mesh, 1), a1) < 1e-12);
    assert!(rel(area(&mesh, 2), a2) < 1e-12);
    // Every interface edge lies on x = 0.5.
    let mut n_iface = 0;
    for t in mesh.live_tris() {
        for i in 0..3 {
            if mesh.neighbours[t][i] != NONE && mesh.edge_ref[t][i] == 2 {
                let [a, b] = mesh.edge_vertices(t, i);
                assert_eq!(mesh.points[a as usize].x, 0.5);
                assert_eq!(mesh.points[b as usize].x, 0.5);
                n_iface += 1;
            }
        }
    }
    assert!(n_iface >= 2 * 6, "{n_iface} interface half-edges");
}

/// A metric known only on a coarse background (fine along the line x = 0.5, coarse elsewhere):
/// both interpolation rules give a valid, conforming mesh; linear sizes (mmg2d's rule) give far
/// fewer vertices than log-Euclidean, which keeps fine sizes over the whole background cell.
#[test]
fn metric_interpolation_rules_on_a_coarse_background() {
    use anisomesh::adapt::{adapt, MetricInterpolation};
    let mut counts = Vec::new();
    for rule in [
        MetricInterpolation::LogEuclidean,
        MetricInterpolation::LinearSizes,
    ] {
        let mut mesh = square(10);
        let mut metric: Vec<Sym2> = mesh
            .points
            .iter()
            .map(|p| {
                if (p.x - 0.5).abs() < 1e-9 {
                    aniso(1e-4, 0.05)
                } else {
                    aniso(0.1, 0.1)
                }
            })
            .collect();
        let opts = AdaptOptions::default()
            .interpolation(rule)
            .check_each_pass(true);
        let rep = adapt(&mut mesh, &mut metric, &mut [], None, &opts).unwrap();
        mesh.check().unwrap();
        let q = anisomesh::metric::quality_stats(&mesh, &metric);
        println!(
            "{rule:?}: {} vertices, {:.1}% in range, Q mean {:.3} max {:.2}, converged {}",
            mesh.n_points(),
            100.0 * q.edge_length_in_range,
            q.q_ani_mean,
            q.q_ani_max,
            rep.converged
        );
        assert!(rep.converged, "{rule:?}");
        assert!(q.edge_length_in_range >= 0.9, "{rule:?}: {q:?}");
        counts.push(mesh.n_points());
    }
    assert!(
        2 * counts[1] < counts[0],
        "linear sizes {} vs log-Euclidean {}",
        counts[1],
        counts[0]
    );
}

/// The passes evaluate their checks in parallel when there are several threads and enough work,
/// but use a result only where the sequential check would see the same state: the adapted mesh
/// is bit-identical for 1 and 2 threads (a case large enough for the parallel paths).
#[test]
fn adaptation_is_identical_for_one_and_two_threads() {
    use anisomesh::adapt::{adapt, MetricInterpolation};
    let run = |threads: usize| {
        let pool = rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap();
        pool.install(|| {
            let mut mesh = square(30);
            // Fine and stretched along the circle of radius 0.3 about the centre.
            let mut metric: Vec<Sym2> = mesh
                .points
                .iter()
                .map(|p| {
                    let d = *p - DVec2::splat(0.5);
                    let r = d.length();
                    let h_n = 0.0005 + 0.1 * (r - 0.3).abs();
                    let n = d.try_normalize().unwrap_or(DVec2::X);
                    Sym2::from_eigen([1.0 / (h_n * h_n), 1.0 / 0.01f64.powi(2)], [n, n.perp()])
                })
                .collect();
            let opts = AdaptOptions::default().interpolation(MetricInterpolation::LinearSizes);
            let rep = adapt(&mut mesh, &mut metric, &mut [], None, &opts).unwrap();
            (mesh, rep)
        })
    };
    let (m1, r1) = run(1);
    let (m2, r2) = run(2);
    println!(
        "{} vertices, {} flips, {} moves",
        m1.n_points(),
        r1.flips,
        r1.moves
    );
    assert!(
        m1.n_points() > 5000,
        "{} vertices: too small to exercise the parallel paths",
        m1.n_points()
    );
    assert_eq!(
        (r1.splits, r1.collapses, r1.flips, r1.moves),
        (r2.splits, r2.collapses, r2.flips, r2.moves)
    );
    assert_eq!(m1.tris, m2.tris);
    assert!(m1
        .points
        .iter()
        .zip(&m2.points)
        .all(|(a, b)| a.x.to_bits() == b.x.to_bits() && a.y.to_bits() == b.y.to_bits()));
}

/// `CycleSmoothing::Touched` (one sweep per cycle over what the cycle changed) conforms as well
/// as the relaxing default on a coarse-background metric, with fewer smoothing moves.
#[test]
fn touched_cycle_smoothing_conforms_with_fewer_moves() {
    use anisomesh::adapt::{adapt, CycleSmoothing, MetricInterpolation};
    let mut out = Vec::new();
    for mode in [CycleSmoothing::Relaxing, CycleSmoothing::Touched] {
        let mut mesh = square(12);
        let mut metric: Vec<Sym2> = mesh
            .points
            .iter()
            .map(|p| {
                let d = (p.y - 0.3 - 0.4 * p.x * p.x).abs();
                aniso(0.05, 0.001 + 0.3 * d)
            })
            .collect();
        let opts = AdaptOptions::default()
            .interpolation(MetricInterpolation::LinearSizes)
            .cycle_smoothing(mode)
            .check_each_pass(true);
        let rep = adapt(&mut mesh, &mut metric, &mut [], None, &opts).unwrap();
        let q = anisomesh::metric::quality_stats(&mesh, &metric);
        println!(
            "{mode:?}: {} vertices, {} moves, {:.1}% in range, Q mean {:.3}",
            mesh.n_points(),
            rep.moves,
            100.0 * q.edge_length_in_range,
            q.q_ani_mean
        );
        assert!(rep.converged, "{mode:?}");
        assert!(q.edge_length_in_range >= 0.95, "{mode:?}: {q:?}");
        assert!(q.q_ani_mean <= 1.10, "{mode:?}: {q:?}");
        out.push((rep.moves, mesh.n_points()));
    }
    assert!(
        out[1].0 < out[0].0,
        "moves: touched {} vs relaxing {}",
        out[1].0,
        out[0].0
    );
}
