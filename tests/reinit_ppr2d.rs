//! PPR redistancing on triangles (003 §6, the 2D analogue of Tables 8.1/8.2): measured orders of
//! e_inf (band nodes against the exact distance) and e_grad for P1 and P2.

use anisomesh::fem::lagrange::P2Dofs;
use anisomesh::levelset::redistance::{redistance_ppr, PprOptions};
use anisomesh::{DVec2, Error, GridPattern, Mesh2};

const R: f64 = 0.5;

fn exact(p: DVec2) -> f64 {
    (p - DVec2::new(0.03, -0.02)).length() - R
}

/// 003 §8: phi = d * (9 + 4 cos(alpha x1 x2 / |x|)).
fn phi(p: DVec2, alpha: f64) -> f64 {
    exact(p) * (9.0 + 4.0 * (alpha * p.x * p.y / p.length().max(1e-300)).cos())
}

/// Node positions (vertices, then P2 edge midpoints).
fn nodes(m: &Mesh2, k: usize) -> Vec<DVec2> {
    let mut pts = m.points.clone();
    if k == 2 {
        let d = P2Dofs::for_mesh2(m);
        pts.extend(
            d.edges
                .iter()
                .map(|&[a, b]| 0.5 * (m.points[a as usize] + m.points[b as usize])),
        );
    }
    pts
}

fn errors(n: usize, k: usize, alpha: f64) -> (f64, f64, f64) {
    let m = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        n,
        n,
        GridPattern::UnionJack,
    )
    .unwrap();
    let x = nodes(&m, k);
    let f: Vec<f64> = x.iter().map(|&p| phi(p, alpha)).collect();
    let opts = PprOptions {
        degree: k,
        ..PprOptions::default()
    };
    let out = redistance_ppr(&m, &f, &opts).unwrap();
    assert_eq!(out.report.not_converged, 0, "{:?}", out.report);
    let e_inf = x
        .iter()
        .enumerate()
        .filter(|(i, _)| out.band[*i])
        .map(|(i, &p)| (out.values[i] - exact(p)).abs())
        .fold(0.0, f64::max);
    // Extension: everywhere within 0.3 of the circle, first-order accurate.
    let e_ext = x
        .iter()
        .enumerate()
        .filter(|(_, &p)| exact(p).abs() < 0.3)
        .map(|(i, &p)| (out.values[i] - exact(p)).abs())
        .fold(0.0, f64::max);
    (e_inf, out.report.e_grad, e_ext)
}

fn check_orders(k: usize, alpha: f64, levels: &[usize]) {
    let e: Vec<_> = levels.iter().map(|&n| errors(n, k, alpha)).collect();
    for w in 0..e.len() - 1 {
        let oi = (e[w].0 / e[w + 1].0).log2();
        let og = (e[w].1 / e[w + 1].1).log2();
        eprintln!("k={k} alpha={alpha} n={}: e_inf {:.3e} (order {oi:.2}) e_grad {:.3e} (order {og:.2}) ext {:.2e}", levels[w + 1], e[w + 1].0, e[w + 1].1, e[w + 1].2);
        if w + 2 == e.len() {
            assert!(
                (oi - (k + 1) as f64).abs() < 0.2,
                "e_inf order {oi} for k = {k}"
            );
            assert!((og - k as f64).abs() < 0.2, "e_grad order {og} for k = {k}");
        }
    }
    let last = e.last().unwrap();
    assert!(last.2 < 0.02, "extension error {}", last.2);
}

#[test]
fn p1_orders_alpha_1() {
    check_orders(1, 1.0, &[64, 128, 256]);
}

#[test]
fn p1_orders_alpha_10() {
    check_orders(1, 10.0, &[64, 128, 256]);
}

#[test]
fn p2_orders_alpha_1() {
    check_orders(2, 1.0, &[64, 128, 256]);
}

#[test]
fn p2_orders_alpha_10() {
    check_orders(2, 10.0, &[64, 128, 256]);
}

#[test]
fn bad_input() {
    let m = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        4,
        4,
        GridPattern::Right,
    )
    .unwrap();
    let f = vec![1.0; m.n_points()];
    assert!(matches!(
        redistance_ppr(&m, &f, &PprOptions::default()),
        Err(Error::EmptyLevelSet(_))
    ));
    let mut g: Vec<f64> = m.points.iter().map(|p| p.x).collect();
    g[7] = f64::NAN;
    assert!(matches!(
        redistance_ppr(&m, &g, &PprOptions::default()),
        Err(Error::InvalidField { .. })
    ));
    let bad = PprOptions {
        degree: 3,
        ..PprOptions::default()
    };
    assert!(matches!(
        redistance_ppr(&m, &g, &bad),
        Err(Error::InvalidInput(_))
    ));
}
