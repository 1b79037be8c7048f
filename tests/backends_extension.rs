//! The velocity extension of 001 §3 on an interface-fitted mesh: the least-squares extension
//! with the gradient-jump rows (3.9) against the harmonic one.

use anisomesh::backends::fitted::{
    extend_velocity, fit, normal_derivative_jumps, ExtensionKind, ExtensionOptions, FitOptions,
};
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::DVec2;

const CENTRE: DVec2 = DVec2::new(0.031, -0.017);

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

fn opts(kind: ExtensionKind) -> ExtensionOptions {
    ExtensionOptions { kind, band: None }
}

/// Extends the trace of `g` on the circle of radius 0.5 around `CENTRE` over an n × n grid of
/// (−1, 1)² (with `g` also given on the outer boundary when `dirichlet`). Returns the largest
/// error against `g` at the fitted vertices within `0.25` of the circle, the mean error of
/// the unrefined trace (the extension at the two ends of each cut base edge, interpolated to
/// the cut point, against `g` there) and the largest gradient jump (3.9).
fn run(n: usize, kind: ExtensionKind, dirichlet: bool, g: &dyn Fn(DVec2) -> f64) -> [f64; 3] {
    let base = grid(n);
    let phi: Vec<f64> = base
        .points
        .iter()
        .map(|p| (*p - CENTRE).length() - 0.5)
        .collect();
    // Cuts within h/100 of a vertex are snapped to it (as the Stefan loop does): the jump
    // rows (3.9) of slivers thinner than that dominate the normal equations.
    let maxu = phi.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let snap = 0.01 * (2.0 / n as f64) / maxu;
    let fm = fit(&base, &phi, &FitOptions { iso: 0.0, snap }).unwrap();
    let m = &fm.mesh;
    let boundary = m.boundary_vertex_flags();
    let known: Vec<bool> = (0..m.n_points())
        .map(|v| fm.u[v] == 0.0 || (dirichlet && boundary[v]))
        .collect();
    let vals: Vec<f64> = m.points.iter().map(|&p| g(p)).collect();
    let ext = extend_velocity(&fm, &vals, &known, &opts(kind)).unwrap();
    let near = (0..m.n_points())
        .filter(|&v| fm.u[v].abs() < 0.25)
        .fold(0.0f64, |a, v| a.max((ext.values[v] - vals[v]).abs()));
    let trace = fm
        .cuts
        .iter()
        .enumerate()
        .map(|(k, &([p, q], s))| {
            let v = fm.n_base_vertices + k;
            let interp = (1.0 - s) * ext.values[p as usize] + s * ext.values[q as usize];
            (interp - vals[v]).abs()
        })
        .sum::<f64>()
        / fm.cuts.len() as f64;
    let jump = normal_derivative_jumps(m, &ext.values)
        .unwrap()
        .into_iter()
        .fold(0.0f64, |a, j| a.max(j.abs()));
    [near, trace, jump]
}

fn order(e: &[[f64; 3]], i: usize) -> Vec<f64> {
    e.windows(2).map(|w| (w[0][i] / w[1][i]).log2()).collect()
}

#[test]
fn harmonic_function_is_reproduced_to_second_order() {
    // e^x cos y is harmonic: with its values on Γ and on ∂Ω the system (3.1)–(3.5) is
    // consistent (Dirichlet in place of (3.5)) and both extensions converge to it.
    // The harmonic extension is the P1 Galerkin solution: second order. The least-squares one
    // also fits the jump rows (3.9), whose one-sided P1 gradients are consistent only to
    // O(h) (the two sides' errors add to about h ∂²u/∂n²): first order off Γ (measured
    // 0.042, 0.017, 0.0074, 0.0044 for n = 16 … 128).
    let g = |p: DVec2| p.x.exp() * p.y.cos();
    let ns = [16, 32, 64, 128];
    let hm: Vec<[f64; 3]> = ns
        .iter()
        .map(|&n| run(n, ExtensionKind::Harmonic, true, &g))
        .collect();
    let ls: Vec<[f64; 3]> = ns
        .iter()
        .map(|&n| run(n, ExtensionKind::LeastSquares, true, &g))
        .collect();
    let (oh, ol) = (order(&hm, 0), order(&ls, 0));
    eprintln!("harmonic {hm:?} orders {oh:?}\nLS {ls:?} orders {ol:?}");
    assert!(oh.iter().all(|&x| x > 1.7), "harmonic orders {oh:?}");
    assert!(hm[3][0] < 1e-4, "harmonic {hm:?}");
    let o = (ls[0][0] / ls[3][0]).log2() / 3.0;
    assert!(o > 0.9 && ls[3][0] < 0.01, "LS order {o} of {ls:?}");
}

#[test]
fn least_squares_extension_is_smooth_across_the_interface() {
    // A velocity that is the trace of a smooth, non-harmonic function, extended with the
    // natural condition (3.5): the harmonic extension is kinked across Γ (a gradient jump of
    // order 1, the unrefined trace off by O(h)), the least-squares one is not.
    let g = |p: DVec2| 1.0 + 0.5 * p.x + 0.8 * p.y * p.y + 0.3 * (3.0 * p.x).sin();
    let ls: Vec<[f64; 3]> = [16, 32, 64, 128]
        .iter()
        .map(|&n| run(n, ExtensionKind::LeastSquares, false, &g))
        .collect();
    let hm: Vec<[f64; 3]> = [16, 32, 64, 128]
        .iter()
        .map(|&n| run(n, ExtensionKind::Harmonic, false, &g))
        .collect();
    let (ols, ohm) = (order(&ls, 1), order(&hm, 1));
    eprintln!("LS {ls:?} trace orders {ols:?}\nharmonic {hm:?} trace orders {ohm:?}");
    // Mean unrefined-trace error for n = 16 … 128, measured: LS 1.3e-3, 3.6e-4, 9.0e-5, 1.7e-5
    // (orders 1.9, 2.0, 2.4); harmonic 2.6e-2, 1.3e-2, 6.0e-3, 3.0e-3 (order 1).
    assert!(ols[1..].iter().all(|&x| x > 1.7), "LS trace orders {ols:?}");
    assert!(
        ohm.iter().all(|&x| x < 1.4),
        "harmonic trace orders {ohm:?}"
    );
    for k in 0..4 {
        assert!(
            ls[k][2] < 0.1 * hm[k][2],
            "jumps LS {:?} harmonic {:?}",
            ls[k],
            hm[k]
        );
        assert!(
            ls[k][1] < hm[k][1],
            "traces LS {:?} harmonic {:?}",
            ls[k],
            hm[k]
        );
    }
}

#[test]
fn band_and_bad_input() {
    let base = grid(16);
    let phi: Vec<f64> = base.points.iter().map(|p| p.length() - 0.5).collect();
    let fm = fit(&base, &phi, &FitOptions::default()).unwrap();
    let n = fm.mesh.n_points();
    let known: Vec<bool> = fm.u.iter().map(|&u| u == 0.0).collect();
    let vals = vec![1.0; n];
    // A constant is extended exactly, on the whole mesh and in a band.
    for band in [None, Some(0.3)] {
        let o = ExtensionOptions {
            kind: ExtensionKind::LeastSquares,
            band,
        };
        let e = extend_velocity(&fm, &vals, &known, &o).unwrap();
        for v in 0..n {
            if e.in_region[v] {
                assert!(
                    (e.values[v] - 1.0).abs() < 1e-9,
                    "{band:?} {v} {}",
                    e.values[v]
                );
            }
        }
        assert!(e.jump_rows > 0 && e.unknowns > 0);
        assert_eq!(band.is_some(), e.in_region.iter().any(|&r| !r));
    }
    let o = opts(ExtensionKind::LeastSquares);
    assert!(extend_velocity(&fm, &vals[1..], &known, &o).is_err());
    assert!(extend_velocity(&fm, &vals, &vec![false; n], &o).is_err());
    let mut nan = vals.clone();
    let first = known.iter().position(|&k| k).unwrap();
    nan[first] = f64::NAN;
    assert!(extend_velocity(&fm, &nan, &known, &o).is_err());
    let bad_band = ExtensionOptions {
        band: Some(-1.0),
        ..o
    };
    assert!(extend_velocity(&fm, &vals, &known, &bad_band).is_err());
}
