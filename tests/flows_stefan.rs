//! The Stefan pieces on a mesh: the heat step (001 (6.1)–(6.3)) and the Stefan condition (6.4).

use anisomesh::flows::stefan::{heat_step, stefan_velocity};
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::DVec2;

fn grid(n: usize) -> Mesh2 {
    Mesh2::rectangle(
        DVec2::new(-1.0, -1.0),
        DVec2::new(1.0, 1.0),
        n,
        n,
        GridPattern::UnionJack,
    )
    .unwrap()
}

#[test]
fn the_stefan_condition_is_exact_for_piecewise_linear_temperatures() {
    // Interface y = 0 (a grid line), solid below (label 3), liquid above (label 2).
    let mut mesh = grid(8);
    for t in 0..mesh.tris.len() {
        let c = mesh.tri_points(t).iter().fold(DVec2::ZERO, |s, p| s + *p) / 3.0;
        mesh.tri_ref[t] = if c.y < 0.0 { 3 } else { 2 };
    }
    let on: Vec<bool> = mesh.points.iter().map(|p| p.y.abs() < 1e-12).collect();
    let normals = vec![DVec2::new(0.0, 1.0); mesh.n_points()];
    let (a, b) = (-0.7, 0.2);
    let temp: Vec<f64> = mesh
        .points
        .iter()
        .map(|p| if p.y > 0.0 { a * p.y } else { b * p.y })
        .collect();
    let vn = stefan_velocity(&mesh, 3, &on, &normals, &temp).unwrap();
    for v in 0..mesh.n_points() {
        let want = if on[v] { -(a - b) } else { 0.0 };
        assert!(
            (vn[v] - want).abs() < 1e-12,
            "vertex {v}: {} vs {want}",
            vn[v]
        );
    }
    // A normal that is not a unit vector is refused.
    let bad = vec![DVec2::new(0.0, 2.0); mesh.n_points()];
    assert!(stefan_velocity(&mesh, 3, &on, &bad, &temp).is_err());
}

#[test]
fn heat_step_keeps_a_steady_state_and_converges_at_second_order() {
    // T = x with T prescribed on x = ±1 and insulated y = ±1 walls is steady.
    let mesh = grid(10);
    let on: Vec<bool> = mesh
        .points
        .iter()
        .map(|p| (p.x.abs() - 1.0).abs() < 1e-12)
        .collect();
    let t0: Vec<f64> = mesh.points.iter().map(|p| p.x).collect();
    let (t1, _) = heat_step(&mesh, &on, &t0, &t0, 0.1).unwrap();
    let drift = t0
        .iter()
        .zip(&t1)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(drift < 1e-9, "steady state drifts by {drift}");

    // cos(πx/2)·e^{−π²t/4} with T = 0 held on x = ±1: error O(h² + dt), dt ∝ h².
    let err = |n: usize| {
        let mesh = grid(n);
        let on: Vec<bool> = mesh
            .points
            .iter()
            .map(|p| (p.x.abs() - 1.0).abs() < 1e-12)
            .collect();
        let zero = vec![0.0; mesh.n_points()];
        let k = std::f64::consts::FRAC_PI_2;
        let mut temp: Vec<f64> = mesh.points.iter().map(|p| (k * p.x).cos()).collect();
        let h = 2.0 / n as f64;
        let (t_end, steps) = (0.1, ((0.1 / (h * h)).ceil() as usize).max(1));
        let dt = t_end / steps as f64;
        for _ in 0..steps {
            temp = heat_step(&mesh, &on, &zero, &temp, dt).unwrap().0;
        }
        let decay = (-k * k * t_end).exp();
        mesh.points
            .iter()
            .zip(&temp)
            .map(|(p, t)| (t - decay * (k * p.x).cos()).abs())
            .fold(0.0, f64::max)
    };
    let (e1, e2) = (err(8), err(16));
    let order = (e1 / e2).log2();
    assert!(order > 1.8, "order {order}: {e1:.3e} -> {e2:.3e}");
    // Bad input: a negative step, a NaN interface value.
    assert!(heat_step(&mesh, &on, &t0, &t0, -1.0).is_err());
    let mut nan = t0.clone();
    nan[0] = f64::NAN;
    assert!(heat_step(&mesh, &on, &nan, &t0, 0.1).is_err());
}
