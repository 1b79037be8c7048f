//! Geometric redistancing (004 §2.2): exactness, sign and zero-level guarantees, bad input.

use anisomesh::levelset::redistance::redistance_geometric;
use anisomesh::{DVec2, Error, GridPattern, Mesh2};

fn grid(n: usize) -> Mesh2 {
    Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        n,
        n,
        GridPattern::UnionJack,
    )
    .unwrap()
}

#[test]
fn plane_distance_is_reproduced_to_round_off() {
    let m = grid(40);
    let s = (1.0f64 + 0.09).sqrt();
    let exact: Vec<f64> = m
        .points
        .iter()
        .map(|p| (p.x - 0.3 * p.y - 0.1) / s)
        .collect();
    let u: Vec<f64> = exact.iter().map(|d| 3.0 * d).collect();
    let d = redistance_geometric(&m, &u).unwrap();
    // Only vertices whose foot point on the line lies inside the square (the polyline is finite).
    let n = DVec2::new(1.0, -0.3) / s;
    let err = m
        .points
        .iter()
        .enumerate()
        .filter(|(i, p)| {
            let f = **p - exact[*i] * n;
            f.x.abs() <= 1.0 && f.y.abs() <= 1.0
        })
        .map(|(i, _)| (d[i] - exact[i]).abs())
        .fold(0.0, f64::max);
    assert!(err < 1e-14, "error {err:e}");
}

/// Max distance error to the exact circle, and the max displacement of the zero crossing on cut
/// edges.
fn circle_errors(n: usize) -> (f64, f64) {
    let m = grid(n);
    let u: Vec<f64> = m.points.iter().map(|p| p.length_squared() - 0.25).collect();
    let d = redistance_geometric(&m, &u).unwrap();
    let mut err = 0.0f64;
    for (i, p) in m.points.iter().enumerate() {
        assert_eq!(d[i].signum(), u[i].signum());
        err = err.max((d[i] - (p.length() - 0.5)).abs());
    }
    let mut moved = 0.0f64;
    for (e, _, _) in m.edges() {
        let (a, b) = (e[0] as usize, e[1] as usize);
        if u[a] * u[b] < 0.0 {
            let l = (m.points[b] - m.points[a]).length();
            let t0 = u[a] / (u[a] - u[b]);
            let t1 = d[a] / (d[a] - d[b]);
            moved = moved.max((t1 - t0).abs() * l);
        }
    }
    (err, moved)
}

#[test]
fn circle_distance_is_second_order_and_zero_level_moves_by_o_h2() {
    let (e1, m1) = circle_errors(64);
    let (e2, m2) = circle_errors(128);
    let order = (e1 / e2).log2();
    assert!(
        (order - 2.0).abs() < 0.2,
        "order {order} ({e1:e} -> {e2:e})"
    );
    assert!(m2 < 2e-4, "zero level moved by {m2:e} at h = 1/64");
    let morder = (m1 / m2).log2();
    assert!(
        morder > 1.7,
        "displacement order {morder} ({m1:e} -> {m2:e})"
    );
}

#[test]
fn vertices_on_the_zero_level_stay_zero_and_result_is_thread_independent() {
    let m = grid(50);
    // A line through grid vertices: x = 0.2 exactly representable? use x = 0 (grid vertex column).
    let u: Vec<f64> = m.points.iter().map(|p| p.x * (1.0 + p.y * p.y)).collect();
    let d = redistance_geometric(&m, &u).unwrap();
    for (i, p) in m.points.iter().enumerate() {
        if u[i] == 0.0 {
            assert_eq!(d[i], 0.0);
        }
        assert!((d[i] - p.x).abs() < 1e-14);
    }
    let u2: Vec<f64> = m
        .points
        .iter()
        .map(|p| (p - DVec2::new(0.1, -0.2)).length() - 0.6)
        .collect();
    let a = redistance_geometric(&m, &u2).unwrap();
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .unwrap();
    let b = pool.install(|| redistance_geometric(&m, &u2).unwrap());
    assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
}

#[test]
fn matches_brute_force() {
    let m = grid(24);
    let u: Vec<f64> = m
        .points
        .iter()
        .map(|p| (3.0 * p.x).sin() + (2.0 * p.y).cos() - 0.8)
        .collect();
    let d = redistance_geometric(&m, &u).unwrap();
    // Brute force over all cut edges' crossing segments per triangle.
    let mut segs = Vec::new();
    for t in m.live_tris() {
        let tri = m.tris[t];
        let mut pts = Vec::new();
        for i in 0..3 {
            let (a, b) = (tri[i] as usize, tri[(i + 1) % 3] as usize);
            if u[a] * u[b] < 0.0 {
                let s = u[a] / (u[a] - u[b]);
                pts.push(m.points[a] + s * (m.points[b] - m.points[a]));
            }
        }
        if pts.len() == 2 {
            segs.push((pts[0], pts[1]));
        }
    }
    for (i, p) in m.points.iter().enumerate() {
        let bf = segs
            .iter()
            .map(|&(a, b)| anisomesh::geom::point_segment_distance(*p, a, b).0)
            .fold(f64::INFINITY, f64::min);
        assert!((d[i].abs() - bf).abs() < 1e-14, "vertex {i}");
    }
}

#[test]
fn bad_input_is_a_clear_error() {
    let m = grid(4);
    let mut u = vec![1.0; m.n_points()];
    assert!(matches!(
        redistance_geometric(&m, &u),
        Err(Error::EmptyLevelSet(_))
    ));
    u[3] = f64::NAN;
    match redistance_geometric(&m, &u) {
        Err(Error::InvalidField { msg, .. }) => assert!(msg.contains("vertex 3")),
        other => panic!("expected InvalidField, got {other:?}"),
    }
    assert!(matches!(
        redistance_geometric(&m, &u[..5]),
        Err(Error::InvalidField { .. })
    ));
}
