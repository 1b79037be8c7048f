//! The tips of the arms of the pentagon seed without surface tension (001 §6, Fig. 6.1): with the
//! P1-mean one-sided gradients of the Stefan condition (6.4) the arm along the y axis sharpens to
//! a needle a few cells wide; with the least-squares quadratic gradients it stays broad (and
//! splits later, as 001 shows).

use anisomesh::backends::fitted::{
    fit, pentagon_seed, stefan_step, FitOptions, StefanFlux, StefanOptions, StefanState,
};
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::DVec2;

const N: usize = 128;
const HALF: f64 = 1.5;

/// The regular pentagon of circumradius 0.1 (a vertex on the positive y axis) on the 129² base
/// mesh of (−1.5, 1.5)², T = 0 inside and −½ outside; `steps` steps of Δt = 2.5e-4 with insulated
/// walls, ε_C = ε_V = 0, redistancing that keeps the interface. Returns the base mesh and φ.
fn run(flux: StefanFlux, steps: usize) -> (Mesh2, Vec<f64>) {
    let base = Mesh2::rectangle(
        DVec2::new(-HALF, -HALF),
        DVec2::new(HALF, HALF),
        N,
        N,
        GridPattern::UnionJack,
    )
    .unwrap();
    let phi = pentagon_seed(&base, 0.1).unwrap();
    let temperature = phi
        .iter()
        .map(|&f| if f < 0.0 { 0.0 } else { -0.5 })
        .collect();
    let mut st = StefanState::new(phi, temperature, 0.0);
    let mut o = StefanOptions::new(2.5e-4, 2.0 * HALF / N as f64);
    o.keep_interface = true;
    o.flux = flux;
    for _ in 0..steps {
        let r = stefan_step(&base, &mut st, &o).unwrap();
        assert!(r.max_vn.is_finite());
    }
    (base, st.phi)
}

/// The tip of the arm along the positive y axis: its height `y_tip` (the highest interface point
/// with |x| < 0.15) and the radius `w² / (8 d)` of the parabola through the arm's width `w` at the
/// depth `d` below the tip.
fn tip(base: &Mesh2, phi: &[f64], d: f64) -> (f64, f64) {
    let fm = fit(base, phi, &FitOptions::default()).unwrap();
    let segs: Vec<(DVec2, DVec2)> = fm
        .interface_edges()
        .into_iter()
        .map(|[a, b]| (fm.mesh.points[a as usize], fm.mesh.points[b as usize]))
        .collect();
    let y_tip = segs
        .iter()
        .flat_map(|&(a, b)| [a, b])
        .filter(|p| p.x.abs() < 0.15)
        .fold(f64::NEG_INFINITY, |m, p| m.max(p.y));
    let y = y_tip - d;
    let xs: Vec<f64> = segs
        .iter()
        .filter(|(a, b)| (a.y - y) * (b.y - y) <= 0.0 && a.y != b.y)
        .map(|&(a, b)| a.x + (y - a.y) / (b.y - a.y) * (b.x - a.x))
        .filter(|x| x.abs() < 0.4)
        .collect();
    let lo = xs.iter().fold(f64::INFINITY, |m, &x| m.min(x));
    let hi = xs.iter().fold(f64::NEG_INFINITY, |m, &x| m.max(x));
    (y_tip, (hi - lo).powi(2) / (8.0 * d))
}

#[test]
fn quadratic_gradients_keep_the_tip_of_a_zero_surface_tension_arm_broad() {
    // 200 steps (t = 0.05). Measured: P1 mean tip at y = 0.463, radius 1.6 h (width 0.12 at
    // 2h below the tip); quadratic tip at y = 0.370, radius 6.6 h (width 0.24).
    let h = 2.0 * HALF / N as f64;
    let d = 2.0 * h;
    let (base, phi_p1) = run(StefanFlux::P1Mean, 200);
    let (y_p1, r_p1) = tip(&base, &phi_p1, d);
    let (_, phi_q) = run(StefanFlux::Quadratic, 200);
    let (y_q, r_q) = tip(&base, &phi_q, d);
    eprintln!(
        "P1 mean: tip y = {y_p1:.3}, radius {:.2} h; quadratic: tip y = {y_q:.3}, radius {:.2} h",
        r_p1 / h,
        r_q / h
    );
    assert!(y_p1 > 0.3 && y_q > 0.3, "the arms grow: {y_p1}, {y_q}");
    assert!(r_q > 4.0 * h, "quadratic tip radius {:.2} h", r_q / h);
    assert!(r_p1 < 2.5 * h, "P1-mean tip radius {:.2} h", r_p1 / h);
    assert!(r_q > 2.5 * r_p1);
}
