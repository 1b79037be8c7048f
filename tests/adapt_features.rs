//! Exact sharp features: `Shape::corners`, the point insertion behind them
//! (`Mesh2::insert_point`) and the corner vertices of `adapt_to_shape`
//! (`ShapeAdaptOptions::features`, `kink_edge`). On the default Zalesak run (004 eq. (6),
//! eps 1e-4, hmin 1e-3, hmax 0.2) the corner vertices and kink edges took the Hausdorff distance
//! from 4.9e-4 to 2.0e-5 and the perimeter error from 4.3e-4 to 5.8e-6; at eps and hmin ±10%
//! from 3.7e-4..7.9e-4 to 1.9e-5..2.2e-5 (corner vertices alone: 2.2e-5..2.0e-4, the rest
//! still cut where the corner's fan straddles the kink of the distance).

use anisomesh::adapt::features::{kink_point, KINK_LABEL};
use anisomesh::adapt::{
    adapt_to_shape, mesh_report, AnalyticLevelSetSource, MeshReport, ShapeAdaptOptions,
};
use anisomesh::error::Error;
use anisomesh::levelset::{Circle, Difference, Rotated, Shape, Zalesak};
use anisomesh::mesh::{GridPattern, Insertion, Mesh2};
use anisomesh::DVec2;

fn unit_square(n: usize) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::UnionJack).unwrap()
}

/// Inserts `p`, checks the mesh, the area and that a vertex sits exactly at `p`.
fn insert_checked(m: &mut Mesh2, p: DVec2) -> Insertion {
    let (area, nt) = (m.area(), m.n_live_tris());
    let r = m.insert_point(p).unwrap();
    m.check().unwrap();
    assert_eq!(m.points[r.vertex() as usize], p);
    assert!(
        (m.area() - area).abs() <= 1e-14 * area,
        "area {} -> {}",
        area,
        m.area()
    );
    let added = match r {
        Insertion::Existing(_) => 0,
        Insertion::OnBoundary(_) => 1,
        Insertion::InTriangle(_) | Insertion::OnEdge(_) => 2,
    };
    assert_eq!(m.n_live_tris(), nt + added, "{r:?}");
    r
}

#[test]
fn insert_point_inside_on_edges_and_at_vertices() {
    let mut m = unit_square(2);
    let np = m.n_points();
    assert!(matches!(
        insert_checked(&mut m, DVec2::new(0.3, 0.1)),
        Insertion::InTriangle(_)
    ));
    // The grid line y = 0.5 is an interior edge; the union-jack diagonal of the first cell too.
    assert!(matches!(
        insert_checked(&mut m, DVec2::new(0.25, 0.5)),
        Insertion::OnEdge(_)
    ));
    assert!(matches!(
        insert_checked(&mut m, DVec2::new(0.875, 0.875)),
        Insertion::OnEdge(_)
    ));
    // A boundary edge: both halves keep the bottom label 1.
    let r = insert_checked(&mut m, DVec2::new(0.75, 0.0));
    assert!(matches!(r, Insertion::OnBoundary(_)), "{r:?}");
    let v = r.vertex();
    let labels: Vec<i32> = m
        .boundary_edges()
        .into_iter()
        .filter(|&(a, b, _)| a == v || b == v)
        .map(|e| e.2)
        .collect();
    assert_eq!(labels, [1, 1]);
    assert_eq!(m.n_points(), np + 4);
    // An existing vertex: nothing changes.
    let before = m.clone();
    assert_eq!(
        m.insert_point(DVec2::new(0.5, 0.5)).unwrap(),
        Insertion::Existing(4)
    );
    assert_eq!(m, before);
}

#[test]
fn insert_point_outside_or_not_finite_is_a_typed_error() {
    let mut m = unit_square(2);
    let before = m.clone();
    for p in [
        DVec2::new(1.5, 0.5),
        DVec2::new(-1e-12, 0.5),
        DVec2::new(f64::NAN, 0.5),
    ] {
        match m.insert_point(p) {
            Err(Error::InvalidInput(msg)) => assert!(msg.contains("insert_point"), "{msg}"),
            other => panic!("{p}: expected InvalidInput, got {other:?}"),
        }
    }
    assert_eq!(m, before);
}

#[test]
fn many_insertions_keep_the_mesh_valid() {
    let mut m = unit_square(3);
    let mut state = 12345u64;
    let mut next = || {
        state = state
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (state >> 11) as f64 / (1u64 << 53) as f64
    };
    let mut kinds = [0usize; 4];
    for k in 0..400 {
        // Every third point snapped to a grid line (x = i/3 or on the boundary).
        let (x, y) = (next(), next());
        let p = match k % 3 {
            0 => DVec2::new((3.0 * x).round() / 3.0, y),
            1 => DVec2::new(x, (y * 2.0).round() / 2.0),
            _ => DVec2::new(x, y),
        };
        let i = match insert_checked(&mut m, p) {
            Insertion::Existing(_) => 0,
            Insertion::InTriangle(_) => 1,
            Insertion::OnEdge(_) => 2,
            Insertion::OnBoundary(_) => 3,
        };
        kinds[i] += 1;
    }
    assert!(
        kinds[1] > 100 && kinds[2] > 10 && kinds[3] > 10,
        "{kinds:?}"
    );
}

#[test]
fn zalesak_corners_are_exact() {
    let z = Zalesak::default();
    let c = z.corners();
    let yb = 0.75 - (0.25f64 - 0.06 * 0.06).sqrt();
    let expected = [
        DVec2::new(-0.06, yb),
        DVec2::new(-0.06, 0.85),
        DVec2::new(0.06, 0.85),
        DVec2::new(0.06, yb),
    ];
    assert_eq!(c, expected);
    for p in &c {
        assert_eq!(z.distance(*p), 0.0, "{p}");
    }
    let circle = Circle {
        centre: DVec2::ZERO,
        radius: 0.5,
    };
    assert!(circle.corners().is_empty());
    let r = Rotated {
        shape: Box::new(Zalesak::default()),
        pivot: DVec2::ZERO,
        angle: 1.0,
    };
    assert_eq!(r.corners().len(), 4);
    for p in r.corners() {
        assert!(r.distance(p).abs() < 1e-15, "{p}: {}", r.distance(p));
    }
    // A combination keeps the corners on its boundary: a far disk removes none, a disk over
    // the slot's top removes the top two.
    let minus = |centre: DVec2, radius: f64| Difference {
        a: Box::new(Zalesak::default()),
        b: Box::new(Circle { centre, radius }),
    };
    assert_eq!(minus(DVec2::new(3.0, 3.0), 0.1).corners().len(), 4);
    assert_eq!(
        minus(DVec2::new(0.0, 0.85), 0.1).corners(),
        expected[..1]
            .iter()
            .chain(&expected[3..])
            .copied()
            .collect::<Vec<_>>()
    );
}

/// The default run with `features` and its measures (hausdorff, relative area and perimeter
/// errors); checks the corner vertices.
fn zalesak_run(eps_scale: f64, hmin_scale: f64, features: bool) -> (usize, f64, f64, f64) {
    zalesak_run_with(eps_scale, hmin_scale, features, Some(2.0))
}

fn zalesak_run_with(
    eps_scale: f64,
    hmin_scale: f64,
    features: bool,
    kink_edge: Option<f64>,
) -> (usize, f64, f64, f64) {
    let shape = Zalesak::default();
    let mut opts = ShapeAdaptOptions {
        features,
        kink_edge,
        ..ShapeAdaptOptions::default()
    };
    // As `anisomesh adapt --eps/--hmin`: the band scales with eps.
    opts.metric.eps *= eps_scale;
    opts.metric.band *= eps_scale;
    opts.metric.hmin *= hmin_scale;
    let domain = (DVec2::splat(-2.0), DVec2::splat(2.0));
    let (mesh, u, rep) = adapt_to_shape(&shape, domain, &opts).unwrap();
    mesh.check().unwrap();
    assert!(rep.converged, "{rep:?}");
    if features {
        for c in shape.corners() {
            let v = (0..mesh.n_points())
                .min_by(|&a, &b| {
                    (mesh.points[a] - c)
                        .length()
                        .total_cmp(&(mesh.points[b] - c).length())
                })
                .unwrap();
            assert!((mesh.points[v] - c).length() < 1e-12, "corner {c}");
            assert!(mesh.required[v] && u[v] == 0.0, "corner {c}: u = {}", u[v]);
            // The kink edge leaves the corner into the convex side.
            if kink_edge.is_none() {
                continue;
            }
            assert!(has_kink_edge(&mesh, v), "no kink edge at corner {c}");
        }
    }
    let r = report_in_graded_metric(&mesh, &u, &shape, &opts);
    let per = (r.perimeter - r.exact_perimeter.unwrap()).abs() / r.exact_perimeter.unwrap();
    eprintln!(
        "eps x{eps_scale} hmin x{hmin_scale} features {features}: {} vertices, d_H {:.3e}, area {:.2e}, perimeter {per:.2e}, in range {:.4}, Q {:.3}/{:.3}",
        r.vertices, r.hausdorff.unwrap(), r.area_rel_error.unwrap(), r.edge_length_in_range,
        r.q_ani_mean, r.q_ani_max
    );
    assert!(r.edge_length_in_range >= 0.95 && r.q_ani_mean <= 1.10 && r.q_ani_max <= 5.0);
    (
        r.vertices,
        r.hausdorff.unwrap(),
        r.area_rel_error.unwrap(),
        per,
    )
}

#[test]
fn zalesak_default_run_has_exact_corners() {
    let (nv, dh, area, per) = zalesak_run(1.0, 1.0, true);
    // Issue targets: <= 5,000 vertices, d_H <= 5e-4, area error <= 5e-5. Measured 4,331,
    // 2.0e-5 (about eps/5, now attained away from the corners), 3.0e-5; the perimeter error
    // 5.8e-6 (4.3e-4 with the corners cut).
    assert!(nv <= 5000, "{nv}");
    assert!(dh <= 6e-5, "{dh:e}");
    assert!(area <= 5e-5, "{area:e}");
    assert!(per <= 5e-5, "{per:e}");
}

/// eps and hmin ±10%: every run at d_H <= 6e-5, an eighth of the target (measured
/// 1.9e-5..2.2e-5; without the corner features 3.7e-4..7.9e-4), and the perimeter error below
/// 5e-5 (without: 2.5e-4..5.2e-4).
#[test]
fn zalesak_nearby_settings_keep_the_margin() {
    for (e, h) in [(0.9, 1.0), (1.1, 1.0), (1.0, 0.9), (1.0, 1.1)] {
        let (nv, dh, area, per) = zalesak_run(e, h, true);
        assert!(nv <= 5000 && dh <= 6e-5 && area <= 5e-5 && per <= 5e-5);
    }
}

#[test]
fn kink_points_lie_on_the_medial_axis() {
    let z = Zalesak::default();
    let r = 2e-3;
    let c = z.corners();
    // Slot top corners: the slot's diagonals.
    let k = kink_point(&z, c[2], r).unwrap();
    assert!((k - (c[2] + r * DVec2::new(-1.0, -1.0).normalize())).length() < 1e-9);
    let k = kink_point(&z, c[1], r).unwrap();
    assert!((k - (c[1] + r * DVec2::new(1.0, -1.0).normalize())).length() < 1e-9);
    // Bottom corners: inside the disk, as far from the wall as from the circle.
    for (corner, wall_x) in [(c[0], -0.06f64), (c[3], 0.06)] {
        let k = kink_point(&z, corner, r).unwrap();
        let to_wall = (k.x - wall_x).abs();
        let to_circle = 0.5 - (k - z.centre).length();
        assert!(
            (to_wall - to_circle).abs() < 1e-12,
            "{k}: {to_wall:e} vs {to_circle:e}"
        );
        assert!(z.distance(k) < -0.5 * r);
    }
    // A smooth boundary point has no kink.
    let circle = Circle {
        centre: DVec2::ZERO,
        radius: 0.5,
    };
    assert!(kink_point(&circle, DVec2::new(0.5, 0.0), r).is_none());
}

#[test]
fn corners_outside_the_domain_are_skipped() {
    // The bottom corners (y = 0.2536) lie below this domain; the top ones are inserted.
    let shape = Zalesak::default();
    let opts = ShapeAdaptOptions {
        max_rounds: 2,
        ..ShapeAdaptOptions::default()
    };
    let domain = (DVec2::new(-0.5, 0.5), DVec2::new(0.5, 1.5));
    let (mesh, _, _) = adapt_to_shape(&shape, domain, &opts).unwrap();
    mesh.check().unwrap();
    let has = |c: DVec2| mesh.points.contains(&c);
    let c = shape.corners();
    assert!(has(c[1]) && has(c[2]));
    assert!(!has(c[0]) && !has(c[3]));
}

/// A rotated disk (corners and kinks off the axes): every corner a required vertex with a kink
/// edge, and the interface error at the level of the axis-aligned run.
#[test]
fn rotated_zalesak_keeps_exact_corners() {
    let shape = Rotated {
        shape: Box::new(Zalesak::default()),
        pivot: DVec2::ZERO,
        angle: 0.7,
    };
    let opts = ShapeAdaptOptions::default();
    let domain = (DVec2::splat(-2.0), DVec2::splat(2.0));
    let (mesh, u, rep) = adapt_to_shape(&shape, domain, &opts).unwrap();
    mesh.check().unwrap();
    assert!(rep.converged);
    for c in shape.corners() {
        let v = mesh
            .points
            .iter()
            .position(|&p| p == c)
            .expect("corner vertex");
        assert!(mesh.required[v] && u[v].abs() < 1e-15);
        assert!(has_kink_edge(&mesh, v), "no kink edge at {c}");
    }
    let r = report_in_graded_metric(&mesh, &u, &shape, &opts);
    eprintln!("rotated: {r:?}");
    assert!(r.vertices <= 5000 && r.hausdorff.unwrap() <= 6e-5, "{r:?}");
}

/// Whether vertex `v` has an edge labelled `KINK_LABEL`.
fn has_kink_edge(mesh: &Mesh2, v: usize) -> bool {
    mesh.vertex_fan(v as u32).iter().any(|&t| {
        (0..3).any(|i| {
            mesh.edge_ref[t as usize][i] == KINK_LABEL
                && mesh.edge_vertices(t as usize, i).contains(&(v as u32))
        })
    })
}

/// The mesh report in the graded eq. (6) metric of `opts` evaluated exactly at the vertices.
fn report_in_graded_metric(
    mesh: &Mesh2,
    u: &[f64],
    shape: &dyn Shape,
    opts: &ShapeAdaptOptions,
) -> MeshReport {
    let src = AnalyticLevelSetSource::new(
        |p| (shape.distance(p), shape.gradient(p), shape.hessian(p)),
        opts.metric,
    );
    let (mut metric, _) = src.evaluate(mesh);
    anisomesh::metric::gradate(mesh, &mut metric, opts.gradation.unwrap()).unwrap();
    mesh_report(mesh, &metric, u, Some(shape)).unwrap()
}
