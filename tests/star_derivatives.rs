//! The 004 star's exact gradient and Hessian (`StarSurface`, Cartesian form differentiated
//! exactly) against Richardson-extrapolated differences of its value in spherical coordinates.

use anisomesh::geom::DVec3;
use anisomesh::levelset::{Shape, StarSurface};

/// Central differences of `f` at `p` with steps `h` and `h/2`, Richardson-extrapolated
/// (error `O(h⁴)`): the gradient and the Hessian.
fn differences(f: impl Fn(DVec3) -> f64, p: DVec3, h: f64) -> (DVec3, [[f64; 3]; 3]) {
    let e = |i: usize, h: f64| {
        let mut v = DVec3::ZERO;
        v[i] = h;
        v
    };
    let grad = |h: f64| {
        DVec3::from_array([0, 1, 2].map(|i| (f(p + e(i, h)) - f(p - e(i, h))) / (2.0 * h)))
    };
    let hess = |h: f64| {
        let mut m = [[0.0; 3]; 3];
        for (i, row) in m.iter_mut().enumerate() {
            for (j, x) in row.iter_mut().enumerate() {
                let (a, b) = (e(i, h), e(j, h));
                *x = (f(p + a + b) - f(p + a - b) - f(p - a + b) + f(p - a - b)) / (4.0 * h * h);
            }
        }
        m
    };
    let g = (4.0 * grad(h / 2.0) - grad(h)) / 3.0;
    let (h1, h2) = (hess(h), hess(h / 2.0));
    let mut m = [[0.0; 3]; 3];
    for i in 0..3 {
        for j in 0..3 {
            m[i][j] = (4.0 * h2[i][j] - h1[i][j]) / 3.0;
        }
    }
    (g, m)
}

/// The exact gradient and Hessian against extrapolated differences of the spherical-
/// coordinate value at 500 random points (not within 0.1 of the axis or 0.2 of the centre),
/// to 1e-6 of their size.
#[test]
fn exact_derivatives_match_differences() {
    let s = StarSurface {
        centre: DVec3::new(0.01, -0.02, 0.03),
        ..StarSurface::PAPER
    };
    let mut seed = 0x9e37_79b9_7f4a_7c15u64;
    let mut rnd = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        (seed >> 11) as f64 / (1u64 << 53) as f64 * 2.0 - 1.0
    };
    let mut n = 0;
    while n < 500 {
        let p = DVec3::new(rnd(), rnd(), rnd());
        let d = p - s.centre;
        if d.truncate().length() < 0.1 || d.length() < 0.2 {
            continue;
        }
        n += 1;
        let (g, h) = differences(|q| s.distance(q), p, 2e-4);
        let (gj, hj) = (s.gradient(p), s.hessian(p).to_matrix());
        assert!(
            (g - gj).length() <= 1e-6 * gj.length().max(1.0),
            "{p}: {g} {gj}"
        );
        let scale = (0..9)
            .map(|k| hj[(k / 3, k % 3)].abs())
            .fold(1.0f64, f64::max);
        for i in 0..3 {
            for j in 0..3 {
                assert!(
                    (h[i][j] - hj[(i, j)]).abs() <= 1e-6 * scale,
                    "{p} {i}{j}: {} {}",
                    h[i][j],
                    hj[(i, j)]
                );
            }
        }
    }
}

/// On the axis and at the centre the derivatives are finite; near the axis the gradient
/// tends to that of `r − r0` (the angular term is `O(s²)`).
#[test]
fn derivatives_on_the_axis_are_finite() {
    let s = StarSurface::PAPER;
    for p in [
        DVec3::ZERO,
        DVec3::new(0.0, 0.0, 0.45),
        DVec3::new(0.0, 0.0, -0.7),
    ] {
        assert!(s.gradient(p).is_finite() && s.hessian(p).is_finite(), "{p}");
    }
    let p = DVec3::new(1e-7, 2e-7, 0.45);
    assert!((s.gradient(p) - p / p.length()).length() < 1e-5);
    assert!((s.distance(p) - (p.length() - 0.45)).abs() < 1e-12);
}
