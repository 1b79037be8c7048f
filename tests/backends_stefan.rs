//! The Stefan loop on a fitted mesh (001 §6) against Frank's expanding circle.

use anisomesh::backends::fitted::{circle_deviation, stefan_step, StefanState};
use anisomesh::flows::stefan::FrankCircle;
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::DVec2;

/// Runs Frank's circle (S0 = 1.56) in (−2, 2)² from t = 0.25 to 0.5 on an n × n grid with
/// Δt ≈ 0.2 h; returns the mean and max radius error at the end and the error of √(A/π).
fn frank(n: usize) -> (f64, f64, f64) {
    let base = Mesh2::rectangle(
        DVec2::new(-2.0, -2.0),
        DVec2::new(2.0, 2.0),
        n,
        n,
        GridPattern::UnionJack,
    )
    .unwrap();
    let fc = FrankCircle::new(1.56).unwrap();
    let (t0, t1) = (0.25, 0.5);
    let h = 4.0 / n as f64;
    let steps = ((t1 - t0) / (0.2 * h)).ceil() as usize;
    let dt = (t1 - t0) / steps as f64;
    let r0 = fc.radius(t0);
    let mut state = StefanState {
        phi: base.points.iter().map(|p| p.length() - r0).collect(),
        temperature: base
            .points
            .iter()
            .map(|p| fc.temperature(p.length(), t0))
            .collect(),
        time: t0,
    };
    let bc = |p: DVec2, t: f64| fc.temperature(p.length(), t);
    for _ in 0..steps {
        let rep = stefan_step(&base, &mut state, dt, 3.0 * h, 3.0 * h, Some(&bc)).unwrap();
        assert!(rep.max_vn.is_finite() && rep.cg_iterations > 0);
    }
    let r = fc.radius(state.time);
    let (mean, max, ra) = circle_deviation(&base, &state.phi, r).unwrap();
    (mean, max, (ra - r).abs())
}

#[test]
fn frank_circle_converges_at_first_order() {
    // Measured mean radius errors: 0.050 (n = 32), 0.028 (64), 0.015 (128): order 0.85, 0.89.
    let errs: Vec<(f64, f64, f64)> = [32, 64, 128].into_iter().map(frank).collect();
    eprintln!("{errs:?}");
    let order = (errs[0].0 / errs[2].0).log2() / 2.0;
    assert!(order > 0.8, "mean radius error order {order}: {errs:?}");
    let order_area = (errs[0].2 / errs[2].2).log2() / 2.0;
    assert!(
        order_area > 0.8,
        "area radius error order {order_area}: {errs:?}"
    );
    for e in &errs {
        assert!(
            e.1 < 1.3 * e.0 + 0.01,
            "max error far above the mean: {e:?}"
        );
    }
}

#[test]
fn bad_input_is_a_typed_error() {
    let base = Mesh2::rectangle(
        DVec2::new(-1.0, -1.0),
        DVec2::new(1.0, 1.0),
        8,
        8,
        GridPattern::UnionJack,
    )
    .unwrap();
    let n = base.n_points();
    let good = StefanState {
        phi: base.points.iter().map(|p| p.length() - 0.5).collect(),
        temperature: vec![-0.5; n],
        time: 0.0,
    };
    for dt in [0.0, -1.0, f64::NAN] {
        assert!(stefan_step(&base, &mut good.clone(), dt, 0.5, 0.25, None).is_err());
    }
    assert!(stefan_step(&base, &mut good.clone(), 0.01, f64::INFINITY, 0.25, None).is_err());
    assert!(stefan_step(&base, &mut good.clone(), 0.01, 0.5, f64::NAN, None).is_err());
    let mut no_level = StefanState {
        phi: vec![1.0; n],
        ..good.clone()
    };
    assert!(stefan_step(&base, &mut no_level, 0.01, 0.5, 0.25, None).is_err());
    let mut nan_t = good.clone();
    nan_t.temperature[3] = f64::NAN;
    assert!(stefan_step(&base, &mut nan_t, 0.01, 0.5, 0.25, None).is_err());
    let mut ok = good;
    let rep = stefan_step(&base, &mut ok, 0.01, 0.5, 0.25, None).unwrap();
    assert!(rep.fitted_vertices > n && rep.max_vn > 0.0);
}
