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

/// The planar entry point is the generic one on the live triangles: same bits.
#[test]
fn mesh_entry_point_equals_the_generic_one() {
    use anisomesh::levelset::redistance::redistance_geometric_cells;
    let m = grid(30);
    let u: Vec<f64> = m
        .points
        .iter()
        .map(|p| 2.0 * ((p.x - 0.1).hypot(p.y + 0.05) - 0.55))
        .collect();
    let a = redistance_geometric(&m, &u).unwrap();
    let b = redistance_geometric_cells(&m.points, &m.tris, &u).unwrap();
    assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
}

/// On tetrahedra: the distance to the piecewise-planar zero level of a torus (003 §8, Example 1)
/// is within O(h²) of the exact distance near the surface, signs are kept, and a plane is
/// reproduced to round-off.
#[test]
fn torus_and_plane_on_tetrahedra() {
    use anisomesh::levelset::redistance::redistance_geometric_cells;
    use anisomesh::levelset::shapes::{Shape, Torus};
    use anisomesh::mesh3::Mesh3;
    use anisomesh::DVec3;
    let torus = Torus::PAPER;
    let mut errs = vec![];
    for n in [12, 24] {
        let m = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [n, n, n]).unwrap();
        let exact: Vec<f64> = m.points.iter().map(|&p| torus.distance(p)).collect();
        // A field with the torus as zero level but far from a distance.
        let u: Vec<f64> = exact
            .iter()
            .zip(&m.points)
            .map(|(d, p)| d * (3.0 + p.x))
            .collect();
        let d = redistance_geometric_cells(&m.points, &m.tets, &u).unwrap();
        assert!(d
            .iter()
            .zip(&u)
            .all(|(d, u)| d.signum() == u.signum() || *u == 0.0));
        let h = 2.0 / n as f64;
        let err = d
            .iter()
            .zip(&exact)
            .filter(|(_, e)| e.abs() < 2.0 * h)
            .map(|(d, e)| (d - e).abs())
            .fold(0.0, f64::max);
        errs.push(err);
    }
    let order = (errs[0] / errs[1]).log2();
    assert!(order > 1.6, "order {order} ({errs:?})");
    let m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [6, 6, 6]).unwrap();
    let nrm = DVec3::new(0.2, -0.3, 1.0).normalize();
    let exact: Vec<f64> = m.points.iter().map(|p| p.dot(nrm) - 0.4).collect();
    let u: Vec<f64> = exact.iter().map(|e| 5.0 * e).collect();
    let d = redistance_geometric_cells(&m.points, &m.tets, &u).unwrap();
    // Vertices whose foot point lies inside the cube (the zero level is a finite polygon).
    let err = m
        .points
        .iter()
        .zip(d.iter().zip(&exact))
        .filter(|(p, (_, e))| {
            let f = **p - **e * nrm;
            f.min_element() >= 0.0 && f.max_element() <= 1.0
        })
        .map(|(_, (d, e))| (d - e).abs())
        .fold(0.0, f64::max);
    assert!(err < 1e-14, "plane error {err:e}");
}
