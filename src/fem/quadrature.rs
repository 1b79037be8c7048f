//! Quadrature rules on the triangle and the tetrahedron, in barycentric coordinates.
//!
//! A rule is a list of barycentric points and weights that sum to 1, so that
//! `∫_K f ≈ |K| Σ_q w_q f(x_q)` on any simplex `K`. Rules are exact for all polynomials up to
//! [`QuadRule::degree`].
//!
//! Triangle: degree 1 (centroid), degree 2 (3 interior points), degree 5 (Radon's 7-point rule,
//! closed form, as tabulated by Strang–Fix and Dunavant), and for degree 6 and above a conical
//! (collapsed, Stroud) product of Gauss–Jacobi rules, which is exact by construction and computed
//! to round-off: degree 7 uses 4x4 = 16 points. Tetrahedron: degree 1 (centroid), degree 2
//! (4 points), degree 3 (Stroud's 5-point rule, one negative weight) and conical products above
//! (degree 5 = 27 points).
//!
//! Rules are built once and cached; [`tri_rule`] and [`tet_rule`] return `&'static` references.

use std::sync::OnceLock;

/// Highest degree available on the triangle.
pub const TRI_MAX_DEGREE: usize = 21;
/// Highest degree available on the tetrahedron.
pub const TET_MAX_DEGREE: usize = 15;

/// A quadrature rule on a simplex with `N` barycentric coordinates (3: triangle, 4: tetrahedron).
#[derive(Debug, Clone, PartialEq)]
pub struct QuadRule<const N: usize> {
    /// Polynomial degree up to which the rule is exact.
    pub degree: usize,
    /// Barycentric coordinates of the points (each row sums to 1).
    pub points: Vec<[f64; N]>,
    /// Weights relative to the simplex measure (they sum to 1).
    pub weights: Vec<f64>,
}

impl<const N: usize> QuadRule<N> {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.weights.len()
    }

    /// Whether the rule has no points (never true for the rules of this module).
    pub fn is_empty(&self) -> bool {
        self.weights.is_empty()
    }

    /// `Σ_q w_q f(λ_q)`: the mean value of `f` over the simplex (multiply by the measure to get
    /// the integral). `f` receives barycentric coordinates.
    pub fn mean(&self, mut f: impl FnMut(&[f64; N]) -> f64) -> f64 {
        self.points
            .iter()
            .zip(&self.weights)
            .map(|(l, w)| w * f(l))
            .sum()
    }
}

/// The cheapest triangle rule exact to degree `degree` (clamped to [`TRI_MAX_DEGREE`]; check
/// [`QuadRule::degree`] if you might ask for more).
pub fn tri_rule(degree: usize) -> &'static QuadRule<3> {
    static RULES: OnceLock<Vec<QuadRule<3>>> = OnceLock::new();
    let rules = RULES.get_or_init(|| (0..=TRI_MAX_DEGREE).map(build_tri).collect());
    &rules[degree.min(TRI_MAX_DEGREE)]
}

/// The cheapest tetrahedron rule exact to degree `degree` (clamped to [`TET_MAX_DEGREE`]).
pub fn tet_rule(degree: usize) -> &'static QuadRule<4> {
    static RULES: OnceLock<Vec<QuadRule<4>>> = OnceLock::new();
    let rules = RULES.get_or_init(|| (0..=TET_MAX_DEGREE).map(build_tet).collect());
    &rules[degree.min(TET_MAX_DEGREE)]
}

/// Points of the orbit `(a, a, 1-2a)` under permutations (3 points).
fn orbit3(a: f64) -> [[f64; 3]; 3] {
    let b = 1.0 - 2.0 * a;
    [[b, a, a], [a, b, a], [a, a, b]]
}

fn build_tri(degree: usize) -> QuadRule<3> {
    match degree {
        0 | 1 => QuadRule {
            degree: 1,
            points: vec![[1.0 / 3.0; 3]],
            weights: vec![1.0],
        },
        2 => QuadRule {
            degree: 2,
            points: orbit3(1.0 / 6.0).to_vec(),
            weights: vec![1.0 / 3.0; 3],
        },
        3..=5 => {
            // Radon's degree-5 rule (Strang–Fix table 4.1, Dunavant n = 7).
            let s = 15f64.sqrt();
            let (a1, a2) = ((6.0 - s) / 21.0, (6.0 + s) / 21.0);
            let (w1, w2) = ((155.0 - s) / 1200.0, (155.0 + s) / 1200.0);
            let mut points = vec![[1.0 / 3.0; 3]];
            points.extend(orbit3(a1));
            points.extend(orbit3(a2));
            QuadRule {
                degree: 5,
                points,
                weights: vec![0.225, w1, w1, w1, w2, w2, w2],
            }
        }
        d => conical_tri(d),
    }
}

fn build_tet(degree: usize) -> QuadRule<4> {
    match degree {
        0 | 1 => QuadRule {
            degree: 1,
            points: vec![[0.25; 4]],
            weights: vec![1.0],
        },
        2 => {
            let a = (5.0 - 5f64.sqrt()) / 20.0;
            let b = 1.0 - 3.0 * a;
            QuadRule {
                degree: 2,
                points: vec![[b, a, a, a], [a, b, a, a], [a, a, b, a], [a, a, a, b]],
                weights: vec![0.25; 4],
            }
        }
        3 => {
            // Stroud T3:3-1 (5 points, centroid weight -4/5).
            let (a, b) = (1.0 / 6.0, 0.5);
            QuadRule {
                degree: 3,
                points: vec![
                    [0.25; 4],
                    [b, a, a, a],
                    [a, b, a, a],
                    [a, a, b, a],
                    [a, a, a, b],
                ],
                weights: vec![-0.8, 0.45, 0.45, 0.45, 0.45],
            }
        }
        d => conical_tet(d),
    }
}

/// Conical product rule on the triangle: `x = u`, `y = v (1 - u)` with Gauss–Jacobi in `u`
/// (weight `1 - u`) and Gauss–Legendre in `v`; `n` points per direction with `2n - 1 >= degree`.
fn conical_tri(degree: usize) -> QuadRule<3> {
    let n = degree.div_ceil(2).max(1);
    let gu = gauss_jacobi01(n, 1.0);
    let gv = gauss_jacobi01(n, 0.0);
    let mut points = Vec::with_capacity(n * n);
    let mut weights = Vec::with_capacity(n * n);
    // Σ weights of gu is 1/2 (∫(1-u)du), of gv is 1; the triangle has area 1/2: scale by 2.
    for &(u, wu) in &gu {
        for &(v, wv) in &gv {
            let (x, y) = (u, v * (1.0 - u));
            points.push([1.0 - x - y, x, y]);
            weights.push(2.0 * wu * wv);
        }
    }
    QuadRule {
        degree: 2 * n - 1,
        points,
        weights,
    }
}

/// Conical product rule on the tetrahedron: `x = u`, `y = v (1-u)`, `z = w (1-u)(1-v)` with
/// Gauss–Jacobi weights `(1-u)^2`, `(1-v)` and Gauss–Legendre in `w`.
fn conical_tet(degree: usize) -> QuadRule<4> {
    let n = degree.div_ceil(2).max(1);
    let gu = gauss_jacobi01(n, 2.0);
    let gv = gauss_jacobi01(n, 1.0);
    let gw = gauss_jacobi01(n, 0.0);
    let mut points = Vec::with_capacity(n * n * n);
    let mut weights = Vec::with_capacity(n * n * n);
    // Weight sums: 1/3 * 1/2 * 1 = 1/6 = volume of the reference tetrahedron: scale by 6.
    for &(u, wu) in &gu {
        for &(v, wv) in &gv {
            for &(w, ww) in &gw {
                let x = u;
                let y = v * (1.0 - u);
                let z = w * (1.0 - u) * (1.0 - v);
                points.push([1.0 - x - y - z, x, y, z]);
                weights.push(6.0 * wu * wv * ww);
            }
        }
    }
    QuadRule {
        degree: 2 * n - 1,
        points,
        weights,
    }
}

/// Gauss–Jacobi rule with `n` points on `[0, 1]` for the weight `(1 - x)^alpha`: pairs
/// `(node, weight)`, exact for polynomials of degree `2n - 1` times the weight.
///
/// Golub–Welsch: the nodes are the eigenvalues of the Jacobi matrix of the monic recurrence,
/// polished by Newton on the orthonormal polynomial; the weights are the Christoffel numbers
/// `1 / Σ_k p_k(x)^2`, accurate to round-off.
pub fn gauss_jacobi01(n: usize, alpha: f64) -> Vec<(f64, f64)> {
    // Monic recurrence coefficients of Jacobi(alpha, beta = 0) on [-1, 1], mapped to [0, 1].
    let (a, b) = (alpha, 0.0f64);
    let mu0 = 1.0 / (alpha + 1.0);
    let diag: Vec<f64> = (0..n)
        .map(|k| {
            let k = k as f64;
            let s = 2.0 * k + a + b;
            let ak = if k == 0.0 {
                (b - a) / (a + b + 2.0)
            } else {
                (b * b - a * a) / (s * (s + 2.0))
            };
            0.5 * (ak + 1.0)
        })
        .collect();
    // off[k] = beta_k for k >= 1 (off[0] unused).
    let off: Vec<f64> = (0..=n)
        .map(|k| {
            if k == 0 {
                return 0.0;
            }
            let k = k as f64;
            let s = 2.0 * k + a + b;
            let bk = if k == 1.0 {
                4.0 * (1.0 + a) * (1.0 + b) / ((2.0 + a + b).powi(2) * (3.0 + a + b))
            } else {
                4.0 * k * (k + a) * (k + b) * (k + a + b) / (s * s * (s + 1.0) * (s - 1.0))
            };
            0.25 * bk
        })
        .collect();
    let mut jac = nalgebra::DMatrix::<f64>::zeros(n, n);
    for k in 0..n {
        jac[(k, k)] = diag[k];
        if k + 1 < n {
            let s = off[k + 1].sqrt();
            jac[(k, k + 1)] = s;
            jac[(k + 1, k)] = s;
        }
    }
    let mut nodes: Vec<f64> = nalgebra::SymmetricEigen::new(jac)
        .eigenvalues
        .iter()
        .copied()
        .collect();
    nodes.sort_by(f64::total_cmp);
    // Orthonormal polynomials p_0..p_n at x and the derivative of p_n.
    let eval = |x: f64| -> (f64, f64, f64) {
        let mut p_prev = 0.0;
        let mut p = 1.0 / mu0.sqrt();
        let mut dp_prev = 0.0;
        let mut dp = 0.0;
        let mut sum_sq = p * p;
        for k in 0..n {
            let sb_next = off[k + 1].sqrt();
            let sb = off[k].sqrt();
            let p_next = ((x - diag[k]) * p - sb * p_prev) / sb_next;
            let dp_next = ((x - diag[k]) * dp + p - sb * dp_prev) / sb_next;
            p_prev = p;
            p = p_next;
            dp_prev = dp;
            dp = dp_next;
            if k + 1 < n {
                sum_sq += p * p;
            }
        }
        (p, dp, sum_sq)
    };
    nodes
        .into_iter()
        .map(|mut x| {
            for _ in 0..3 {
                let (p, dp, _) = eval(x);
                if dp != 0.0 {
                    x -= p / dp;
                }
            }
            let (_, _, sum_sq) = eval(x);
            (x, 1.0 / sum_sq)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gauss_legendre_two_points() {
        let g = gauss_jacobi01(2, 0.0);
        let x0 = 0.5 - 0.5 / 3f64.sqrt();
        assert!((g[0].0 - x0).abs() < 1e-15, "{g:?}");
        assert!((g[0].1 - 0.5).abs() < 1e-15 && (g[1].1 - 0.5).abs() < 1e-15);
    }

    #[test]
    fn jacobi_weights_integrate_weight_function() {
        for alpha in [0.0, 1.0, 2.0] {
            for n in 1..8 {
                let g = gauss_jacobi01(n, alpha);
                for k in 0..2 * n {
                    // ∫_0^1 x^k (1-x)^alpha dx = B(k+1, alpha+1)
                    let exact = match alpha as u32 {
                        0 => 1.0 / (k as f64 + 1.0),
                        1 => 1.0 / ((k as f64 + 1.0) * (k as f64 + 2.0)),
                        _ => 2.0 / ((k as f64 + 1.0) * (k as f64 + 2.0) * (k as f64 + 3.0)),
                    };
                    let q: f64 = g.iter().map(|(x, w)| w * x.powi(k as i32)).sum();
                    assert!((q - exact).abs() < 1e-15, "alpha {alpha} n {n} k {k}");
                }
            }
        }
    }
}
