//! The cross-check at its tiny resolution: every back end converges towards the exact radius
//! or curvature at its expected order, and the outputs are written.

use crate::app::repro::crosscheck::{self, CrossReport, Problem, Resolution};

fn problem<'a>(r: &'a CrossReport, name: &str) -> &'a Problem {
    r.problems.iter().find(|p| p.name == name).unwrap()
}

/// The (order, finest error) of a back end in a problem.
fn finest(p: &Problem, backend: &str) -> (f64, f64) {
    let rows: Vec<_> = p.rows_of(backend).collect();
    assert_eq!(rows.len(), 2, "{} {backend}", p.name);
    assert!(rows
        .iter()
        .all(|r| r.dof > 0 && r.seconds >= 0.0 && r.error.is_finite()));
    (rows[1].order.unwrap(), rows[1].error)
}

/// The least order a back end must show on the shrinking circle and sphere: 1, less a margin
/// of 0.05 for the interface-fitted mesh (measured 5.18e-4 -> 1.45e-4 on these two levels,
/// order 1.83; its Richardson-extrapolated step leaves the `O(dt²)` and `O(h²)` errors).
fn expected_flow_order(backend: &str) -> f64 {
    if backend == "fitted" {
        0.95
    } else {
        1.0
    }
}

#[test]
fn tiny_crosscheck_converges_and_writes() {
    let mut lines = 0;
    let report = crosscheck::run(Resolution::Tiny, &mut |_| lines += 1).unwrap();
    eprintln!("{}", crosscheck::tables(&report));
    assert_eq!(report.problems.len(), 6);
    // One line per run; a Zalesak run fills two problems.
    let rows = report.problems.iter().map(|p| p.rows.len()).sum::<usize>();
    assert_eq!(lines, rows - problem(&report, "zalesak_area").rows.len());
    assert_eq!(lines, crosscheck::planned_runs(Resolution::Tiny));

    // The back ends agree with each other within their own error estimates (the change of
    // the final radius between their two levels), and each is within its Richardson estimate
    // of the exact radius at its expected order p (the change divided by 2^p − 1).
    for name in ["circle_mcf", "sphere_mcf"] {
        let p = problem(&report, name);
        let pairs = crosscheck::agreement(p);
        assert!(!pairs.is_empty(), "{name}");
        for (a, b, diff, est) in pairs {
            assert!(diff <= est, "{name}: {a} vs {b}: {diff:.2e} > {est:.2e}");
        }
        for b in p.backends() {
            let v: Vec<&crosscheck::Row> = p.rows_of(b).collect();
            let p = expected_flow_order(b);
            let est = (v[1].value.unwrap() - v[0].value.unwrap()).abs() / (2f64.powf(p) - 1.0);
            assert!(
                v[1].error <= est,
                "{name} {b}: error {:.2e} > estimate {est:.2e}",
                v[1].error
            );
        }
    }

    // Circle by curvature: every level-set back end at its expected order. Measured: adapted
    // 2.1e-3 -> 9.6e-4 (order 1.15), fitted 5.18e-4 -> 1.45e-4 (1.83), the band at h = 0.04,
    // 0.02 with τ = (2h)² 2.44e-3 -> 5.47e-4 (2.16), polygon 2.4e-3 -> 5.4e-4 (2.12),
    // quadratic arcs 6.2e-3 -> 1.7e-3 (1.90).
    let c = problem(&report, "circle_mcf");
    for (b, _) in crosscheck::level_set_backends() {
        let (o, e) = finest(c, b);
        assert!(o >= expected_flow_order(b) && e < 2e-3, "{b} {o} {e}");
    }
    // The band at τ ∝ h² is second order (000 §2.3).
    let (o, _) = finest(c, "dtgrid");
    assert!(o >= 1.5, "dtgrid circle order {o}");
    for b in ["parametric P1", "parametric P2"] {
        let (o, e) = finest(c, b);
        assert!(o > 1.7 && e < 2e-3, "{b} {o} {e}");
    }

    // Sphere (002). Measured: P1 2.29e-2 -> 5.79e-3 (2.00), P2 9.89e-4 -> 2.70e-4 (1.89).
    let s = problem(&report, "sphere_mcf");
    let (o1, e1) = finest(s, "parametric P1");
    let (o2, e2) = finest(s, "parametric P2");
    assert!((1.8..2.2).contains(&o1) && (1.6..2.4).contains(&o2));
    assert!(e2 < 0.1 * e1 && e2 < 6.05e-4);
    // The 3D level-set back ends at order at least 1. Measured: the adapted tetrahedral mesh
    // (ε = 0.2h, τ = h²/4, volume restored) at h = 0.2, 0.141 1.10e-3 -> 8.2e-5 (the error of
    // the flow alone; its sign changes), the band at h = 0.2, 0.1 6.73e-3 -> 1.21e-3 (2.47).
    for (b, _) in crosscheck::level_set_backends_3d() {
        let (o, e) = finest(s, b);
        assert!(
            o >= expected_flow_order(b) && e < 2e-3,
            "sphere {b} {o} {e}"
        );
    }

    // Curvature of a circle and of the ellipse from a non-distance function: every back end
    // converges at order at least 1. Measured: circle adapted (quartic fit) 2.3e-4 -> 6.8e-5
    // (1.79), band 2.64e-4 -> 6.57e-5 (2.00), polygon 2.6e-2 -> 6.4e-3 (2.03), arcs 8.8e-3 ->
    // 2.4e-3 (1.91); ellipse adapted 1.9e-3 -> 5.2e-4 (1.88), band 1.74e-3 -> 4.40e-4 (1.98),
    // polygon 2.25, arcs 1.80. The band's nodal curvature reads the signed distance to its
    // O(h⁴) Hermite zero level by central differences: second order.
    for name in ["curvature_circle", "curvature_ellipse"] {
        let k = problem(&report, name);
        for b in k.backends() {
            let (o, e) = finest(k, b);
            assert!(o >= 1.0 && e < 2e-2, "{name} {b} {o} {e}");
        }
        let (o, _) = finest(k, "dtgrid");
        assert!(o >= 1.5, "{name} dtgrid {o}");
    }

    // Zalesak, one revolution. Measured: area 2.1e-4 / 6.4e-4 (the signed errors of the P1
    // zero level cancel unevenly), perimeter 6.2e-3 -> 3.1e-3 (order 1.00).
    let (_, area) = finest(problem(&report, "zalesak_area"), "adapted");
    let (o, perimeter) = finest(problem(&report, "zalesak_perimeter"), "adapted");
    assert!(
        area < 2e-3 && perimeter < 5e-3 && o > 0.6,
        "{area} {perimeter} {o}"
    );

    let dir = std::env::temp_dir().join(format!("anisomesh_crosscheck_{}", std::process::id()));
    crosscheck::write_outputs(&dir, &report).unwrap();
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(dir.join("crosscheck.json")).unwrap())
            .unwrap();
    assert_eq!(json["problems"].as_array().unwrap().len(), 6);
    assert!(json["problems"][0]["rows"][0]["backend"].is_string());
    let csv = std::fs::read_to_string(dir.join("crosscheck.csv")).unwrap();
    assert_eq!(
        csv.lines().count(),
        1 + report.problems.iter().map(|p| p.rows.len()).sum::<usize>()
    );
    assert!(dir.join("crosscheck_circle_mcf.png").exists());
    std::fs::remove_dir_all(&dir).ok();
}

#[test]
fn cost_at_error_interpolates_between_bracketing_rows() {
    use crate::app::repro::crosscheck::Row;
    let row = |dof: usize, error: f64, seconds: f64| Row {
        backend: "b".into(),
        resolution: 1.0,
        dof,
        error,
        value: None,
        order: None,
        seconds,
    };
    let p = Problem {
        name: "p".into(),
        error_measure: String::new(),
        rows: vec![row(100, 1e-2, 1.0), row(400, 1e-3, 16.0)],
    };
    let (dof, sec) = p.cost_at_error(10f64.powf(-2.5))[0].1.unwrap();
    assert!((dof - 200.0).abs() < 1e-9 && (sec - 4.0).abs() < 1e-9);
    assert!(p.cost_at_error(1e-4)[0].1.is_none());
}
