//! Quadrature rules integrate every monomial up to their degree exactly (to 1e-14), on the
//! reference simplex and on a skewed one.

use anisomesh::fem::quadrature::{tet_rule, tri_rule, QuadRule};
use std::collections::HashMap;

fn factorial(n: u32) -> f64 {
    (1..=n).map(f64::from).product()
}

/// Polynomial in barycentric coordinates: exponents -> coefficient.
type BaryPoly<const N: usize> = HashMap<[u32; N], f64>;

fn poly_mul<const N: usize>(a: &BaryPoly<N>, b: &BaryPoly<N>) -> BaryPoly<N> {
    let mut c = BaryPoly::new();
    for (ea, ca) in a {
        for (eb, cb) in b {
            let mut e = [0; N];
            for k in 0..N {
                e[k] = ea[k] + eb[k];
            }
            *c.entry(e).or_insert(0.0) += ca * cb;
        }
    }
    c
}

/// Mean over the simplex of `Π λ_k^{e_k}`: `(N-1)! Π e_k! / (Σ e_k + N - 1)!`.
fn bary_mean<const N: usize>(e: &[u32; N]) -> f64 {
    let d = (N - 1) as u32;
    factorial(d) * e.iter().map(|&k| factorial(k)).product::<f64>()
        / factorial(e.iter().sum::<u32>() + d)
}

/// Checks all monomials `x^a y^b (z^c)` of total degree <= rule.degree on the simplex with the
/// given vertices: exact mean from the barycentric expansion vs the rule.
fn check_rule<const N: usize>(rule: &QuadRule<N>, verts: &[[f64; 3]; N], dim: usize) {
    let wsum: f64 = rule.weights.iter().sum();
    assert!((wsum - 1.0).abs() < 1e-14, "weights sum to {wsum}");
    for p in &rule.points {
        assert!((p.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }
    // coordinate k as a linear polynomial in λ
    let coord = |k: usize| -> BaryPoly<N> {
        let mut m = BaryPoly::new();
        for (v, vert) in verts.iter().enumerate() {
            let mut e = [0; N];
            e[v] = 1;
            m.insert(e, vert[k]);
        }
        m
    };
    let d = rule.degree as u32;
    let mut exps = vec![];
    for a in 0..=d {
        for b in 0..=d - a {
            if dim == 2 {
                exps.push([a, b, 0]);
            } else {
                for c in 0..=d - a - b {
                    exps.push([a, b, c]);
                }
            }
        }
    }
    for e in exps {
        let mut poly = BaryPoly::new();
        poly.insert([0; N], 1.0);
        for (k, &ek) in e.iter().enumerate().take(dim) {
            let ck = coord(k);
            for _ in 0..ek {
                poly = poly_mul(&poly, &ck);
            }
        }
        let exact: f64 = poly.iter().map(|(ex, c)| c * bary_mean(ex)).sum();
        let quad = rule.mean(|l| {
            let mut x = [0.0; 3];
            for (v, vert) in verts.iter().enumerate() {
                for k in 0..3 {
                    x[k] += l[v] * vert[k];
                }
            }
            (0..dim).map(|k| x[k].powi(e[k] as i32)).product()
        });
        let scale = poly.values().map(|c| c.abs()).sum::<f64>().max(1.0);
        assert!(
            (quad - exact).abs() < 1e-14 * scale,
            "degree {} rule, monomial {:?}: quad {quad:e} exact {exact:e}",
            rule.degree,
            &e[..dim]
        );
    }
}

#[test]
fn triangle_rules_are_exact_to_their_degree() {
    let reference = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let skewed = [[0.3, -0.2, 0.0], [1.4, 0.1, 0.0], [0.9, 0.8, 0.0]];
    for (asked, expect_deg, max_pts) in [(1, 1, 1), (2, 2, 3), (5, 5, 7), (7, 7, 16), (9, 9, 25)] {
        let r = tri_rule(asked);
        assert!(
            r.degree >= expect_deg && r.len() <= max_pts,
            "degree {asked}"
        );
        check_rule(r, &reference, 2);
        check_rule(r, &skewed, 2);
    }
}

#[test]
fn tetrahedron_rules_are_exact_to_their_degree() {
    let reference = [
        [0.0, 0.0, 0.0],
        [1.0, 0.0, 0.0],
        [0.0, 1.0, 0.0],
        [0.0, 0.0, 1.0],
    ];
    let skewed = [
        [0.1, 0.2, -0.1],
        [1.2, 0.0, 0.1],
        [0.3, 0.9, 0.0],
        [0.2, 0.3, 0.8],
    ];
    for (asked, max_pts) in [(1, 1), (2, 4), (3, 5), (5, 27), (7, 64)] {
        let r = tet_rule(asked);
        assert!(r.degree >= asked && r.len() <= max_pts, "degree {asked}");
        check_rule(r, &reference, 3);
        check_rule(r, &skewed, 3);
    }
}

#[test]
fn rules_fail_one_degree_above() {
    // The check is sharp: each rule misses some monomial of degree + 1 on the reference triangle.
    for asked in [1, 2, 5, 7] {
        let r = tri_rule(asked);
        let d = r.degree as i32 + 1;
        let worst = (0..=d)
            .map(|a| {
                let b = d - a;
                let exact = factorial(a as u32) * factorial(b as u32) / factorial(d as u32 + 2);
                let quad = 0.5 * r.mean(|l| l[1].powi(a) * l[2].powi(b));
                (quad - exact).abs()
            })
            .fold(0.0, f64::max);
        assert!(
            worst > 1e-8,
            "degree {asked} rule is exact one degree higher"
        );
    }
}
