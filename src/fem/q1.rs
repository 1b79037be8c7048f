//! The Q1 element on the reference square `[0, 1]²` or cube `[0, 1]³`: (bi/tri)linear shape
//! functions, tensor Gauss quadrature, the lumped mass and the stiffness with a coefficient per
//! quadrature point (scalar or tensor) on a cell of side `h` — the elements of the narrow-band
//! finite elements of 000 §2 (eq. (2.5)–(2.7)).
//!
//! Corner `c` (`0 ≤ c < 2^d`) sits at the offset whose coordinate along axis `a` is bit `a` of
//! `c` — the numbering of [`crate::backends::dtgrid::GridCoord::corner`]. Its shape function is
//! `ψ_c(ξ) = Π_a (ξ_a if bit a of c is set, else 1 − ξ_a)`.

use crate::error::{Error, Result};

/// The Q1 element of dimension 2 or 3 with a tensor Gauss rule, its shape functions and
/// reference gradients tabulated at the quadrature points.
#[derive(Debug, Clone, PartialEq)]
pub struct Q1 {
    /// The space dimension (2 or 3).
    pub dim: usize,
    /// The number of corners, `2^dim`.
    pub corners: usize,
    /// Quadrature points on the reference cell (unused trailing coordinates are 0).
    pub points: Vec<[f64; 3]>,
    /// Quadrature weights on the reference cell (they sum to 1, the reference measure).
    pub weights: Vec<f64>,
    /// `values[q * corners + c]`: `ψ_c` at point `q`.
    pub values: Vec<f64>,
    /// `grads[q * corners + c]`: the reference gradient of `ψ_c` at point `q`.
    pub grads: Vec<[f64; 3]>,
}

/// Gauss–Legendre points and weights on `[0, 1]` with `k` points (1 to 3): exact for
/// polynomials of degree `2k − 1`.
fn gauss_01(k: usize) -> Option<(Vec<f64>, Vec<f64>)> {
    let (x, w): (Vec<f64>, Vec<f64>) = match k {
        1 => (vec![0.0], vec![2.0]),
        2 => {
            let a = 1.0 / 3f64.sqrt();
            (vec![-a, a], vec![1.0, 1.0])
        }
        3 => {
            let a = 0.6f64.sqrt();
            (vec![-a, 0.0, a], vec![5.0 / 9.0, 8.0 / 9.0, 5.0 / 9.0])
        }
        _ => return None,
    };
    Some((
        x.iter().map(|x| 0.5 * (x + 1.0)).collect(),
        w.iter().map(|w| 0.5 * w).collect(),
    ))
}

/// `ψ_c(ξ)` on the reference cell of dimension `dim`.
pub fn shape(dim: usize, c: usize, xi: &[f64]) -> f64 {
    (0..dim)
        .map(|a| {
            if (c >> a) & 1 == 1 {
                xi[a]
            } else {
                1.0 - xi[a]
            }
        })
        .product()
}

/// The reference gradient of `ψ_c` at `ξ` (unused trailing components are 0).
pub fn shape_grad(dim: usize, c: usize, xi: &[f64]) -> [f64; 3] {
    let mut g = [0.0; 3];
    for (a, ga) in g.iter_mut().enumerate().take(dim) {
        *ga = (0..dim)
            .map(|b| {
                let set = (c >> b) & 1 == 1;
                match (b == a, set) {
                    (true, true) => 1.0,
                    (true, false) => -1.0,
                    (false, true) => xi[b],
                    (false, false) => 1.0 - xi[b],
                }
            })
            .product();
    }
    g
}

impl Q1 {
    /// The element of dimension `dim` (2 or 3) with `k` Gauss points per axis (1 to 3; `k = 2`
    /// integrates the Q1 mass and stiffness exactly).
    /// Error: [`Error::InvalidInput`] for another dimension or point count.
    pub fn new(dim: usize, k: usize) -> Result<Q1> {
        if !(2..=3).contains(&dim) {
            return Err(Error::InvalidInput(format!(
                "Q1: dimension {dim} (2 or 3 supported)"
            )));
        }
        let (x, w) = gauss_01(k).ok_or_else(|| {
            Error::InvalidInput(format!("Q1: {k} Gauss points per axis (1 to 3 supported)"))
        })?;
        let corners = 1 << dim;
        let nq = k.pow(dim as u32);
        let mut points = Vec::with_capacity(nq);
        let mut weights = Vec::with_capacity(nq);
        for q in 0..nq {
            let mut p = [0.0; 3];
            let mut wq = 1.0;
            let mut r = q;
            for pa in p.iter_mut().take(dim) {
                *pa = x[r % k];
                wq *= w[r % k];
                r /= k;
            }
            points.push(p);
            weights.push(wq);
        }
        let mut values = Vec::with_capacity(nq * corners);
        let mut grads = Vec::with_capacity(nq * corners);
        for p in &points {
            for c in 0..corners {
                values.push(shape(dim, c, p));
                grads.push(shape_grad(dim, c, p));
            }
        }
        Ok(Q1 {
            dim,
            corners,
            points,
            weights,
            values,
            grads,
        })
    }

    /// The lumped mass of one corner on a cell of side `h` with coefficient 1: `h^d / 2^d`.
    pub fn lumped_mass(&self, h: f64) -> f64 {
        h.powi(self.dim as i32) / self.corners as f64
    }

    /// `∫_K f` on the cell of side `h` whose reference point is `ξ`: `h^d Σ_q w_q f(ξ_q)`.
    pub fn integrate(&self, h: f64, mut f: impl FnMut(&[f64; 3]) -> f64) -> f64 {
        let s: f64 = self
            .points
            .iter()
            .zip(&self.weights)
            .map(|(p, w)| w * f(p))
            .sum();
        s * h.powi(self.dim as i32)
    }

    /// The physical gradient at point `q` of the Q1 function with corner values `u` on a cell
    /// of side `h`.
    pub fn gradient(&self, q: usize, h: f64, u: &[f64]) -> [f64; 3] {
        let mut g = [0.0; 3];
        for (c, uc) in u.iter().enumerate().take(self.corners) {
            let gc = self.grads[q * self.corners + c];
            for a in 0..3 {
                g[a] += uc * gc[a] / h;
            }
        }
        g
    }

    /// The stiffness `K_ij = ∫_K a ∇ψ_i · ∇ψ_j` on a cell of side `h` with the scalar coefficient
    /// `coef(q)` at quadrature point `q`, written row-major into `out` (`corners²` entries).
    pub fn stiffness(&self, h: f64, mut coef: impl FnMut(usize) -> f64, out: &mut [f64]) {
        let n = self.corners;
        out[..n * n].fill(0.0);
        let scale = h.powi(self.dim as i32 - 2);
        for (q, w) in self.weights.iter().enumerate() {
            let a = w * scale * coef(q);
            let g = &self.grads[q * n..(q + 1) * n];
            for i in 0..n {
                for j in 0..n {
                    out[i * n + j] +=
                        a * (g[i][0] * g[j][0] + g[i][1] * g[j][1] + g[i][2] * g[j][2]);
                }
            }
        }
    }

    /// The stiffness `K_ij = ∫_K A ∇ψ_j · ∇ψ_i` with the tensor coefficient `coef(q)` (a
    /// symmetric `3 × 3` matrix; only the leading `d × d` block is used), row-major into `out`.
    pub fn stiffness_tensor(
        &self,
        h: f64,
        mut coef: impl FnMut(usize) -> [[f64; 3]; 3],
        out: &mut [f64],
    ) {
        let n = self.corners;
        out[..n * n].fill(0.0);
        let scale = h.powi(self.dim as i32 - 2);
        for (q, w) in self.weights.iter().enumerate() {
            let a = coef(q);
            let g = &self.grads[q * n..(q + 1) * n];
            for j in 0..n {
                let mut agj = [0.0; 3];
                for (r, ar) in a.iter().enumerate() {
                    agj[r] = ar[0] * g[j][0] + ar[1] * g[j][1] + ar[2] * g[j][2];
                }
                for i in 0..n {
                    out[i * n + j] +=
                        w * scale * (g[i][0] * agj[0] + g[i][1] * agj[1] + g[i][2] * agj[2]);
                }
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_and_nodal_property() {
        for dim in [2, 3] {
            let e = Q1::new(dim, 3).unwrap();
            for q in 0..e.weights.len() {
                let s: f64 = (0..e.corners).map(|c| e.values[q * e.corners + c]).sum();
                assert!((s - 1.0).abs() < 1e-14);
                for a in 0..dim {
                    let g: f64 = (0..e.corners).map(|c| e.grads[q * e.corners + c][a]).sum();
                    assert!(g.abs() < 1e-14);
                }
            }
            for c in 0..e.corners {
                for d in 0..e.corners {
                    let xi: Vec<f64> = (0..dim).map(|a| ((d >> a) & 1) as f64).collect();
                    let v = shape(dim, c, &xi);
                    assert_eq!(v, if c == d { 1.0 } else { 0.0 });
                }
            }
        }
    }

    #[test]
    fn gauss_rules_integrate_polynomials_exactly() {
        // ∫_[0,h]^3 x^a y^b z^c = h^(a+b+c+3) / ((a+1)(b+1)(c+1)), exact up to degree 2k−1 per axis.
        let h: f64 = 0.3;
        for k in 1..=3 {
            let e = Q1::new(3, k).unwrap();
            let top = 2 * k - 1;
            for a in 0..=top {
                for b in 0..=top {
                    let exact = h.powi((a + b + 1 + 3) as i32) / ((a + 1) * (b + 1) * 2) as f64;
                    let got = e.integrate(h, |p| {
                        (h * p[0]).powi(a as i32) * (h * p[1]).powi(b as i32) * (h * p[2])
                    });
                    assert!((got - exact).abs() < 1e-14 * exact.max(1e-3), "{k} {a} {b}");
                }
            }
        }
    }

    #[test]
    fn stiffness_rows_sum_to_zero_and_match_the_laplacian() {
        for dim in [2, 3] {
            let e = Q1::new(dim, 2).unwrap();
            let n = e.corners;
            let mut k = vec![0.0; n * n];
            let h: f64 = 0.25;
            e.stiffness(h, |_| 2.0, &mut k);
            for i in 0..n {
                let s: f64 = (0..n).map(|j| k[i * n + j]).sum();
                assert!(s.abs() < 1e-14);
                assert!(k[i * n + i] > 0.0);
            }
            // uᵀ K u = 2 ∫ |∇u|² = 2 h^d / h² for u = x / h... with u = ξ_0 (corner values bit 0).
            let u: Vec<f64> = (0..n).map(|c| (c & 1) as f64).collect();
            let e2: f64 = (0..n)
                .map(|i| (0..n).map(|j| u[i] * k[i * n + j] * u[j]).sum::<f64>())
                .sum();
            assert!((e2 - 2.0 * h.powi(dim as i32 - 2)).abs() < 1e-13);
            let mut kt = vec![0.0; n * n];
            e.stiffness_tensor(
                h,
                |_| [[2.0, 0.0, 0.0], [0.0, 2.0, 0.0], [0.0, 0.0, 2.0]],
                &mut kt,
            );
            for (a, b) in k.iter().zip(&kt) {
                assert!((a - b).abs() < 1e-14);
            }
            assert!((e.lumped_mass(h) * n as f64 - h.powi(dim as i32)).abs() < 1e-15);
        }
    }
}
