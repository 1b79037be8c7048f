//! Interface fitting (001 §2): the fitted mesh is valid, its inside has the exact area of the P1
//! zero level, its interface edges have the P1 zero level's length, zeros at vertices and
//! boundary contacts are handled, and bad input is refused with a typed error.

use anisomesh::backends::fitted::{
    fit, interface_curvature, snapped_values, vertex_curvature, FitOptions, FittedMesh, REF_INSIDE,
    REF_INTERFACE,
};
use anisomesh::levelset::{enclosed_area, interface_length, nodal_distance, Circle, Zalesak};
use anisomesh::{DVec2, Error, GridPattern, Mesh2};

fn grid(lo: DVec2, hi: DVec2, n: usize, pattern: GridPattern) -> Mesh2 {
    Mesh2::rectangle(lo, hi, n, n, pattern).unwrap()
}

fn unit(n: usize, pattern: GridPattern) -> Mesh2 {
    grid(DVec2::ZERO, DVec2::ONE, n, pattern)
}

/// Fits and checks everything a fitted mesh must satisfy against its base and level set.
fn fit_and_check(base: &Mesh2, u: &[f64]) -> FittedMesh {
    let f = fit(base, u, &FitOptions::default()).unwrap();
    f.mesh.check().unwrap();
    let (snapped, _) = snapped_values(u, &FitOptions::default());
    let exact = enclosed_area(base, &snapped).unwrap();
    let area = f.area_inside();
    assert!(
        (area - exact).abs() <= 1e-12 * exact.max(1e-300),
        "area {area} vs P1 {exact}"
    );
    assert!((f.mesh.area() - base.area()).abs() <= 1e-12 * base.area());
    let len = interface_length(base, &snapped).unwrap();
    let fl = f.interface_length();
    assert!((fl - len).abs() <= 1e-11 * len, "length {fl} vs P1 {len}");
    // Every fitted triangle is on one side: the snapped level set has no sign change in it.
    for t in f.mesh.live_tris() {
        let vals = f.mesh.tris[t].map(|v| f.u[v as usize]);
        let inside = f.mesh.tri_ref[t] == REF_INSIDE;
        for x in vals {
            assert!(
                if inside { x <= 0.0 } else { x >= 0.0 },
                "triangle {t}: {vals:?}"
            );
        }
    }
    // Interface edges join vertices on the level.
    for [a, b] in f.interface_edges() {
        assert_eq!(f.u[a as usize], 0.0);
        assert_eq!(f.u[b as usize], 0.0);
    }
    // The base vertices are kept in place, with their labels.
    assert_eq!(&f.mesh.points[..base.n_points()], &base.points[..]);
    assert_eq!(&f.mesh.vert_ref[..base.n_points()], &base.vert_ref[..]);
    f
}

#[test]
fn circle_on_every_grid_pattern() {
    let c = Circle {
        centre: DVec2::new(0.503, 0.487),
        radius: 0.3,
    };
    for pattern in [
        GridPattern::Right,
        GridPattern::Left,
        GridPattern::UnionJack,
        GridPattern::CrissCross,
    ] {
        let base = unit(37, pattern);
        let u = nodal_distance(&base, &c);
        let f = fit_and_check(&base, &u);
        assert!(!f.cuts.is_empty());
        assert!((f.area_inside() - std::f64::consts::PI * 0.09).abs() < 5e-3);
    }
}

#[test]
fn zalesak_on_a_100_grid_and_a_jittered_mesh() {
    let z = Zalesak::default();
    let (lo, hi) = (DVec2::new(-1.0, -0.25), DVec2::new(1.0, 1.75));
    let base = grid(lo, hi, 100, GridPattern::Right);
    let u = nodal_distance(&base, &z);
    fit_and_check(&base, &u);
    // An unstructured-like mesh: interior vertices moved by a deterministic jitter.
    let mut m = grid(lo, hi, 60, GridPattern::UnionJack);
    let h = 2.0 / 60.0;
    for (k, p) in m.points.iter_mut().enumerate() {
        if p.x > lo.x + 1e-9 && p.x < hi.x - 1e-9 && p.y > lo.y + 1e-9 && p.y < hi.y - 1e-9 {
            let s = (k as f64 * 0.7548776662).fract() - 0.5;
            let r = (k as f64 * 0.5698402910).fract() - 0.5;
            *p += DVec2::new(s, r) * (0.5 * h);
        }
    }
    m.check().unwrap();
    let u = nodal_distance(&m, &z);
    fit_and_check(&m, &u);
}

#[test]
fn zeros_at_vertices_are_snapped_and_never_cut_twice() {
    let base = unit(10, GridPattern::Right);
    // A straight level through grid vertices, with round-off noise at the vertices on it.
    let u: Vec<f64> = base
        .points
        .iter()
        .map(|p| (p.x - 0.5) + if (p.x - 0.5).abs() < 1e-9 { 1e-17 } else { 0.0 })
        .collect();
    let f = fit_and_check(&base, &u);
    assert!(
        f.cuts.is_empty(),
        "no new vertex on a level through vertices"
    );
    assert_eq!(f.snapped, 11);
    assert!((f.area_inside() - 0.5).abs() < 1e-14);
    assert!((f.interface_length() - 1.0).abs() < 1e-14);
    // The diagonal through vertices (and two domain corners), then across the other diagonal:
    // a zero vertex with the opposite edge cut splits into two.
    let u: Vec<f64> = base.points.iter().map(|p| p.y - p.x).collect();
    let f = fit_and_check(&base, &u);
    assert!(f.cuts.is_empty());
    let u: Vec<f64> = base.points.iter().map(|p| p.x + p.y - 1.0).collect();
    let f = fit_and_check(&base, &u);
    assert!(!f.cuts.is_empty());
    assert!((f.area_inside() - 0.5).abs() < 1e-14);
    assert!((f.interface_length() - 2f64.sqrt()).abs() < 1e-13);
}

#[test]
fn level_touching_the_boundary_and_several_components() {
    let base = unit(40, GridPattern::UnionJack);
    // A quarter disk at a corner: the interface ends on the boundary.
    let c = Circle {
        centre: DVec2::new(0.0, 0.0),
        radius: 0.61,
    };
    let u = nodal_distance(&base, &c);
    let f = fit_and_check(&base, &u);
    // Boundary pieces keep the base labels (1..4), never the interface label.
    for t in f.mesh.live_tris() {
        for i in 0..3 {
            if f.mesh.neighbours[t][i] == anisomesh::mesh::NONE {
                assert!((1..=4).contains(&f.mesh.edge_ref[t][i]));
            }
        }
    }
    // Three disjoint disks.
    let centres = [(0.25, 0.25, 0.15), (0.7, 0.3, 0.2), (0.45, 0.75, 0.18)];
    let u: Vec<f64> = base
        .points
        .iter()
        .map(|&p| {
            centres
                .iter()
                .map(|&(x, y, r)| (p - DVec2::new(x, y)).length() - r)
                .fold(f64::INFINITY, f64::min)
        })
        .collect();
    let f = fit_and_check(&base, &u);
    let n_if = f
        .mesh
        .live_tris()
        .flat_map(|t| f.mesh.edge_ref[t])
        .filter(|&r| r == REF_INTERFACE)
        .count();
    assert_eq!(n_if, 2 * f.interface_edges().len());
}

#[test]
fn base_fields_extend_and_restrict() {
    let base = unit(20, GridPattern::Right);
    let c = Circle {
        centre: DVec2::new(0.41, 0.52),
        radius: 0.27,
    };
    let u = nodal_distance(&base, &c);
    let f = fit(&base, &u, &FitOptions::default()).unwrap();
    let lin = |p: DVec2| 2.0 * p.x - 3.0 * p.y + 0.5;
    let g: Vec<f64> = base.points.iter().map(|&p| lin(p)).collect();
    let e = f.extend_from_base(&g).unwrap();
    for (p, x) in f.mesh.points.iter().zip(&e) {
        assert!((lin(*p) - x).abs() < 1e-13);
    }
    assert_eq!(f.restrict_to_base(&e).unwrap(), g);
    // A different level: iso shifts the fitted level.
    let opts = FitOptions {
        iso: 0.05,
        ..FitOptions::default()
    };
    let f2 = fit(&base, &u, &opts).unwrap();
    let shifted: Vec<f64> = u.iter().map(|x| x - 0.05).collect();
    let exact = enclosed_area(&base, &shifted).unwrap();
    assert!((f2.area_inside() - exact).abs() < 1e-12 * exact);
}

#[test]
fn bad_input_is_refused() {
    let base = unit(8, GridPattern::Right);
    let pos: Vec<f64> = base.points.iter().map(|p| p.x + 1.0).collect();
    let e = fit(&base, &pos, &FitOptions::default()).unwrap_err();
    assert!(matches!(e, Error::EmptyLevelSet(_)), "{e}");
    // Zero only at the corner (0, 0), positive elsewhere: no inside.
    let corner: Vec<f64> = base.points.iter().map(|p| p.x + p.y).collect();
    assert!(matches!(
        fit(&base, &corner, &FitOptions::default()),
        Err(Error::EmptyLevelSet(_))
    ));
    let mut nan = pos.clone();
    nan[3] = f64::NAN;
    nan[0] = -1.0;
    assert!(matches!(
        fit(&base, &nan, &FitOptions::default()),
        Err(Error::InvalidField { .. })
    ));
    assert!(matches!(
        fit(&base, &pos[1..], &FitOptions::default()),
        Err(Error::InvalidField { .. })
    ));
}

/// Max relative curvature error on the interface nodes of the fitted mesh (001 §5: the vertex
/// curvatures interpolated linearly onto the cut points), for `phi` with zero level the circle
/// of radius 1/4 about (1/2, 1/2) on an `n x n` grid of the unit square.
fn interface_curvature_error(n: usize, phi: &dyn Fn(DVec2) -> f64) -> f64 {
    let base = unit(n, GridPattern::Right);
    let u: Vec<f64> = base.points.iter().map(|&p| phi(p)).collect();
    let (points, kappa, at_limit) = interface_curvature(&base, &u).unwrap();
    assert_eq!(at_limit, 0);
    assert!(
        points.len() > 4 * n / 2,
        "{} interface nodes on the {n} grid",
        points.len()
    );
    kappa
        .iter()
        .map(|k| (k - 4.0).abs() / 4.0)
        .fold(0.0f64, f64::max)
}

fn slope(h: &[f64], e: &[f64]) -> f64 {
    let n = h.len() as f64;
    let (x, y): (Vec<f64>, Vec<f64>) = h.iter().zip(e).map(|(h, e)| (h.ln(), e.ln())).unzip();
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxy: f64 = x.iter().zip(&y).map(|(x, y)| (x - mx) * (y - my)).sum();
    let sxx: f64 = x.iter().map(|x| (x - mx) * (x - mx)).sum();
    sxy / sxx
}

#[test]
fn curvature_by_local_averaging_is_second_order_for_any_normalisation() {
    let c = DVec2::new(0.5, 0.5);
    let cone = |p: DVec2| (p - c).length() - 0.25;
    let tilted = |p: DVec2| 7.3 * ((p - c).length() - 0.25) * (1.0 + 0.4 * (p.x - 0.2 * p.y));
    let ns = [16usize, 32, 64, 128];
    let h: Vec<f64> = ns.iter().map(|&n| 1.0 / n as f64).collect();
    for (name, phi) in [
        ("cone", &cone as &dyn Fn(DVec2) -> f64),
        ("tilted", &tilted),
    ] {
        let e: Vec<f64> = ns
            .iter()
            .map(|&n| interface_curvature_error(n, phi))
            .collect();
        let s = slope(&h, &e);
        eprintln!("{name}: errors {e:?}, slope {s:.3}");
        assert!(s >= 1.9, "{name}: slope {s} (errors {e:?})");
    }
    // At the cone's apex, where the level sets are tiny circles, κ_h is of the order of its bound.
    let base = unit(16, GridPattern::Right);
    let u: Vec<f64> = base.points.iter().map(|&p| cone(p)).collect();
    let k = vertex_curvature(&base, &u).unwrap();
    let v = base
        .points
        .iter()
        .position(|p| (*p - c).length() < 1e-12)
        .unwrap();
    // The exact bound on the right-diagonal grid is (2 + √2)/h, below 001's 3√2/h.
    assert!((k.limit[v] - (2.0 + 2f64.sqrt()) * 16.0).abs() < 1e-9);
    assert!(k.limit[v] < 3.0 * 2f64.sqrt() * 16.0);
    let kv = k.kappa[v].unwrap();
    assert!(kv > 0.5 * k.limit[v] && kv <= k.limit[v], "{kv}");
}

// ---- The back-end contract (backends::LevelSetBackend<D2>) on the fitted base grid ----

use anisomesh::backends::fitted::FittedBackend;
use anisomesh::backends::{BuildSpec, FnShape, LevelSetBackend, D2};

fn circle_backend(centre: DVec2, r0: f64, h: f64) -> FittedBackend {
    let f = FnShape::new("circle", move |p: DVec2| (p - centre).length() - r0);
    let spec = BuildSpec::<D2> {
        function: &f,
        domain: (DVec2::splat(-0.5), DVec2::splat(0.5)),
        resolution: h,
    };
    FittedBackend::build(&spec).unwrap()
}

/// Radius of the enclosed area of a back end.
fn area_radius(b: &FittedBackend) -> f64 {
    (b.enclosed_measure().unwrap() / std::f64::consts::PI).sqrt()
}

#[test]
fn backend_circle_shrinks_by_curvature_at_order_two() {
    // R(t) = √(R0² − 2t), dt ∝ h², to T = 0.02. The Richardson-extrapolated step and the P1 zero
    // level are both second order.
    let (r0, t_end) = (0.3f64, 0.02f64);
    let exact = (r0 * r0 - 2.0 * t_end).sqrt();
    let centre = DVec2::new(0.013, -0.021);
    let mut errors = Vec::new();
    for n in [32usize, 64] {
        let h = 1.0 / n as f64;
        let steps = n * n / 256;
        let dt = t_end / steps as f64;
        let mut b = circle_backend(centre, r0, h);
        for _ in 0..steps {
            let rep = b.advance_mean_curvature(dt).unwrap();
            assert!(rep.converged);
        }
        assert!((b.time() - t_end).abs() < 1e-14);
        b.base().check().unwrap();
        let r = area_radius(&b);
        // The perimeter radius agrees with the area radius.
        let rl = b.interface_measure().unwrap() / (2.0 * std::f64::consts::PI);
        assert!((rl - r).abs() < 0.02 * r, "{rl} vs {r}");
        errors.push((r - exact).abs());
        eprintln!(
            "n {n}: dt {dt:.3e}, radius {r:.6} (exact {exact:.6}), error {:.3e}",
            (r - exact).abs()
        );
    }
    let order = (errors[0] / errors[1]).log2();
    eprintln!("order {order:.2}");
    assert!(order >= 1.8, "order {order} (errors {errors:?})");
    assert!(errors[1] < 2e-3, "{errors:?}");
    // With dt ∝ h the extrapolated step is still second order in dt.
    let mut b = circle_backend(centre, r0, 1.0 / 64.0);
    for _ in 0..16 {
        b.advance_mean_curvature(t_end / 16.0).unwrap();
    }
    let e16 = (area_radius(&b) - exact).abs();
    let mut b = circle_backend(centre, r0, 1.0 / 128.0);
    for _ in 0..32 {
        b.advance_mean_curvature(t_end / 32.0).unwrap();
    }
    let e32 = (area_radius(&b) - exact).abs();
    eprintln!(
        "dt ∝ h: errors {e16:.3e}, {e32:.3e}, order {:.2}",
        (e16 / e32).log2()
    );
    assert!((e16 / e32).log2() >= 1.6, "{e16} {e32}");
}

#[test]
fn backend_rotation_keeps_the_area() {
    let (r0, c) = (0.15, DVec2::new(0.2, 0.03));
    let rot = |_t: f64, p: DVec2| DVec2::new(-p.y, p.x);
    let mut drift = Vec::new();
    for n in [64usize, 128] {
        let mut b = circle_backend(c, r0, 1.0 / n as f64);
        let a0 = b.enclosed_measure().unwrap();
        // A semi-Lagrangian step loses O(h²) of the P1 interpolation: few large steps.
        let steps = 8;
        let dt = std::f64::consts::FRAC_PI_2 / steps as f64;
        for _ in 0..steps {
            b.advect(&rot, dt).unwrap();
        }
        b.redistance().unwrap();
        let a1 = b.enclosed_measure().unwrap();
        // The disk's centre has turned a quarter: (x, y) -> (-y, x).
        let zl = b.zero_level().unwrap();
        assert_eq!(zl.len(), 1);
        let m = zl[0].points.iter().fold(DVec2::ZERO, |s, &p| s + p) / zl[0].points.len() as f64;
        assert!((m - DVec2::new(-c.y, c.x)).length() < 2.0 / n as f64, "{m}");
        let rel = (a1 - a0).abs() / a0;
        eprintln!("n {n}: area {a0:.6} -> {a1:.6}, relative change {rel:.2e}");
        drift.push(rel);
    }
    assert!(drift[1] < 1e-2, "{drift:?}");
    assert!((drift[0] / drift[1]).log2() >= 1.0, "{drift:?}");
}

#[test]
fn backend_curvature_of_a_circle_and_contract_errors() {
    let (r0, c) = (0.25, DVec2::new(0.011, 0.007));
    let b = circle_backend(c, r0, 1.0 / 64.0);
    let k = b.interface_curvature().unwrap();
    assert!(k.len() > 50);
    let e = k.max_rel_error(1.0 / r0);
    eprintln!("curvature: mean {:.5}, max rel error {e:.2e}", k.mean());
    assert!(e < 5e-3, "{e}");
    // u is a signed distance after building: values at points against the exact distance.
    let pts = [
        DVec2::new(0.2, 0.1),
        DVec2::new(-0.05, 0.0),
        DVec2::new(0.7, 0.0),
    ];
    let v = b.evaluate(&pts).unwrap();
    for (p, x) in pts.iter().zip(&v).take(2) {
        let d = (*p - c).length() - r0;
        assert!((x.unwrap() - d).abs() < 2e-3, "{p}: {x:?} vs {d}");
    }
    assert_eq!(v[2], None);
    // No zero level, bad time steps.
    let f = FnShape::new("far", |p: DVec2| (p - DVec2::splat(3.0)).length() - 0.1);
    let spec = BuildSpec::<D2> {
        function: &f,
        domain: (DVec2::splat(-0.5), DVec2::splat(0.5)),
        resolution: 0.05,
    };
    assert!(matches!(
        FittedBackend::build(&spec),
        Err(Error::EmptyLevelSet(_))
    ));
    let mut b = circle_backend(c, 0.05, 0.05);
    assert!(b.advance_mean_curvature(f64::NAN).is_err());
    // Shrinking a small circle until it vanishes is an error, not a panic.
    let mut vanished = false;
    for _ in 0..20 {
        if let Err(e) = b.advance_mean_curvature(0.002) {
            assert!(matches!(e, Error::EmptyLevelSet(_)), "{e}");
            vanished = true;
            break;
        }
    }
    assert!(vanished);
}

#[test]
fn curvature_bound_binds_on_an_unresolved_region() {
    // The smallest region the grid holds: one vertex inside (u = -1), all others outside
    // (u = 1). Its zero level joins the midpoints of the vertex's edges; every normal on the
    // patch is parallel to ∇N_v, so κ_h(v) is the bound (2 + √2)/h of (5.2) on this grid, and
    // the vertex is reported at the bound.
    let n = 32;
    let base = unit(n, GridPattern::Right);
    let h = 1.0 / n as f64;
    let v = base
        .points
        .iter()
        .position(|p| (*p - DVec2::splat(0.5)).length() < 1e-12)
        .unwrap();
    let mut u = vec![1.0; base.n_points()];
    u[v] = -1.0;
    let (_, kappa, at_limit) = interface_curvature(&base, &u).unwrap();
    assert!(at_limit >= 1, "{at_limit}");
    let k = vertex_curvature(&base, &u).unwrap();
    let bound = (2.0 + 2f64.sqrt()) / h;
    assert!((k.kappa[v].unwrap() - bound).abs() < 1e-9 * bound);
    assert!(
        kappa.iter().all(|x| *x <= bound * (1.0 + 1e-9)),
        "{kappa:?}"
    );
    // A resolved circle (radius 8h) reports none.
    let c = DVec2::new(0.5 + 0.3 * h, 0.5 + 0.4 * h);
    let u: Vec<f64> = base
        .points
        .iter()
        .map(|&p| (p - c).length() - 8.0 * h)
        .collect();
    assert_eq!(interface_curvature(&base, &u).unwrap().2, 0);
}
