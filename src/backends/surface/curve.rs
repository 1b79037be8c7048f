//! [`ParametricCurve`]: a closed plane curve as a polygon (P1) or a chain of isoparametric
//! quadratic arcs (P2), and Dziuk's θ-scheme for its curve-shortening flow (002 in one
//! dimension less): each coordinate solves `(M + τθA) U_k = M x_k − τ(1 − θ) A x_k` with the
//! mass and stiffness matrices of the curve `Γⁿ`, so a circle of radius `R0` follows
//! `R(t) = √(R0² − 2t)`.
//!
//! Nodes: `nodes[..n]` are the vertices in counter-clockwise order; for order 2,
//! `nodes[n + i]` is the node inside the arc from vertex `i` to vertex `i + 1`.

use super::mcf::{check_theta_tau, theta_solve, ThetaStepStats};
use crate::error::{Error, Result};
use crate::fem::quadrature::gauss_jacobi01;
use crate::fem::{CgOptions, Csr};
use crate::geom::DVec2;

/// Gauss points per arc for matrices and measures (exact to degree 9 on straight arcs).
const GAUSS_POINTS: usize = 5;

/// A closed curve of order 1 or 2 (see the module documentation).
#[derive(Debug, Clone, PartialEq)]
pub struct ParametricCurve {
    /// The polynomial order (1 or 2).
    pub order: usize,
    /// The node positions: vertices, then (order 2) one inner node per arc.
    pub nodes: Vec<DVec2>,
    /// The number of vertices (= arcs).
    pub n_vertices: usize,
}

/// Shape functions and their derivatives on `[0, 1]`.
fn basis(order: usize, s: f64) -> (Vec<f64>, Vec<f64>) {
    if order == 1 {
        (vec![1.0 - s, s], vec![-1.0, 1.0])
    } else {
        (
            vec![
                (1.0 - s) * (1.0 - 2.0 * s),
                s * (2.0 * s - 1.0),
                4.0 * s * (1.0 - s),
            ],
            vec![4.0 * s - 3.0, 4.0 * s - 1.0, 4.0 - 8.0 * s],
        )
    }
}

impl ParametricCurve {
    /// A curve through `vertices` (counter-clockwise, at least 3); for order 2 the inner node of
    /// each arc is `project` of the chord midpoint. Errors: fewer than 3 vertices, an order
    /// other than 1 or 2, non-finite points.
    pub fn new(
        vertices: Vec<DVec2>,
        order: usize,
        project: impl Fn(DVec2) -> DVec2,
    ) -> Result<ParametricCurve> {
        if vertices.len() < 3 || (order != 1 && order != 2) {
            return Err(Error::InvalidInput(format!(
                "parametric curve: need 3 vertices and order 1 or 2 (got {}, {order})",
                vertices.len()
            )));
        }
        let n = vertices.len();
        let mut nodes = vertices;
        if order == 2 {
            for i in 0..n {
                nodes.push(project(0.5 * (nodes[i] + nodes[(i + 1) % n])));
            }
        }
        if nodes.iter().any(|p| !p.is_finite()) {
            return Err(Error::InvalidInput(
                "parametric curve: non-finite point".into(),
            ));
        }
        Ok(ParametricCurve {
            order,
            nodes,
            n_vertices: n,
        })
    }

    /// The circle of radius `radius` about `centre` with `n` equally spaced vertices (inner
    /// nodes on the circle too).
    pub fn circle(centre: DVec2, radius: f64, n: usize, order: usize) -> Result<ParametricCurve> {
        let at = |a: f64| centre + radius * DVec2::new(a.cos(), a.sin());
        let step = std::f64::consts::TAU / n.max(1) as f64;
        let vertices = (0..n).map(|i| at(i as f64 * step)).collect();
        Self::new(vertices, order, |p| {
            centre + radius * (p - centre).normalize()
        })
    }

    /// The node indices of arc `e` (2 or 3).
    pub fn arc(&self, e: usize) -> Vec<usize> {
        let n = self.n_vertices;
        if self.order == 1 {
            vec![e, (e + 1) % n]
        } else {
            vec![e, (e + 1) % n, n + e]
        }
    }

    /// `∫_Γ f(x, t) ds` with `t` the unit tangent (counter-clockwise).
    pub fn integrate(&self, f: impl Fn(DVec2, DVec2) -> f64) -> f64 {
        let rule = gauss_jacobi01(GAUSS_POINTS, 0.0);
        let mut sum = 0.0;
        for e in 0..self.n_vertices {
            let idx = self.arc(e);
            for &(s, w) in &rule {
                let (v, d) = basis(self.order, s);
                let (mut x, mut dx) = (DVec2::ZERO, DVec2::ZERO);
                for (k, &i) in idx.iter().enumerate() {
                    x += v[k] * self.nodes[i];
                    dx += d[k] * self.nodes[i];
                }
                let j = dx.length();
                if j > 0.0 {
                    sum += w * j * f(x, dx / j);
                }
            }
        }
        sum
    }

    /// The length.
    pub fn length(&self) -> f64 {
        self.integrate(|_, _| 1.0)
    }

    /// The enclosed area `½ ∫ x × t ds` (positive for a counter-clockwise curve).
    pub fn enclosed_area(&self) -> f64 {
        self.integrate(|x, t| 0.5 * x.perp_dot(t))
    }

    /// The averaged radius `∫_Γ |x − c| / ∫_Γ 1` about `c` (the curve version of 002's).
    pub fn mean_radius(&self, c: DVec2) -> f64 {
        self.integrate(|x, _| (x - c).length()) / self.length()
    }

    /// The mass and stiffness matrices of the curve. Error: an arc of zero length.
    pub fn assemble(&self) -> Result<(Csr, Csr)> {
        let arcs: Vec<Vec<u32>> = (0..self.n_vertices)
            .map(|e| self.arc(e).iter().map(|&i| i as u32).collect())
            .collect();
        let mut m = Csr::from_element_iter(self.nodes.len(), arcs.iter().map(|a| &a[..]))?;
        let mut a = m.clone();
        let rule = gauss_jacobi01(GAUSS_POINTS, 0.0);
        for idx in &arcs {
            for &(s, w) in &rule {
                let (v, d) = basis(self.order, s);
                let dx: DVec2 = idx
                    .iter()
                    .zip(&d)
                    .map(|(&i, &dk)| dk * self.nodes[i as usize])
                    .sum();
                let j = dx.length();
                if j.is_nan() || j <= 0.0 {
                    return Err(Error::InvalidInput(
                        "parametric curve: an arc collapsed to a point".into(),
                    ));
                }
                for (p, &r) in idx.iter().enumerate() {
                    for (q, &c) in idx.iter().enumerate() {
                        m.add(r as usize, c as usize, w * j * v[p] * v[q])?;
                        a.add(r as usize, c as usize, w * d[p] * d[q] / j)?;
                    }
                }
            }
        }
        Ok((m, a))
    }

    /// One θ-step of curve shortening with time step `tau` (see the module documentation).
    pub fn theta_step(&mut self, tau: f64, theta: f64) -> Result<ThetaStepStats> {
        check_theta_tau(theta, tau)?;
        let (m, a) = self.assemble()?;
        let mut x: Vec<Vec<f64>> = (0..2)
            .map(|d| self.nodes.iter().map(|p| p[d]).collect())
            .collect();
        let stats = theta_solve(&m, &a, tau, theta, &mut x)?;
        for (i, p) in self.nodes.iter_mut().enumerate() {
            *p = DVec2::new(x[0][i], x[1][i]);
        }
        if self.nodes.iter().any(|p| !p.is_finite()) {
            return Err(Error::NotConverged(
                "curve θ-step produced non-finite nodes".into(),
            ));
        }
        Ok(stats)
    }

    /// The discrete curvature at the vertices: `κ_i = (M⁻¹ A x)_i · ν_i`, the discrete
    /// Laplace–Beltrami of the position (`Δ_Γ x = −κ ν`) along the outer vertex normal `ν_i`
    /// (bisector of the adjacent chords); `1/R` on a circle of radius `R`.
    pub fn vertex_curvature(&self) -> Result<Vec<f64>> {
        let (m, a) = self.assemble()?;
        let opts = CgOptions {
            rtol: 1e-12,
            ..CgOptions::default()
        };
        let mut hn = Vec::new();
        for d in 0..2 {
            let x: Vec<f64> = self.nodes.iter().map(|p| p[d]).collect();
            let b = a.mul(&x);
            let mut y = vec![0.0; x.len()];
            crate::fem::solve::cg(&m, &b, &mut y, &opts)?;
            hn.push(y);
        }
        let n = self.n_vertices;
        Ok((0..n)
            .map(|i| {
                let (p, q) = (self.nodes[(i + n - 1) % n], self.nodes[(i + 1) % n]);
                let t = (q - p).normalize_or_zero();
                let normal = DVec2::new(t.y, -t.x);
                DVec2::new(hn[0][i], hn[1][i]).dot(normal)
            })
            .collect())
    }

    /// The vertices as a closed polyline.
    pub fn polyline(&self) -> crate::levelset::Polyline {
        let points = if self.order == 1 {
            self.nodes.clone()
        } else {
            let n = self.n_vertices;
            (0..n)
                .flat_map(|i| [self.nodes[i], self.nodes[n + i]])
                .collect()
        };
        crate::levelset::Polyline {
            points,
            closed: true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::PI;

    #[test]
    fn circle_measures_and_curvature() {
        for order in [1, 2] {
            let c = ParametricCurve::circle(DVec2::new(0.3, -0.1), 0.5, 64, order).unwrap();
            let tol = if order == 1 { 2e-3 } else { 1e-5 };
            assert!((c.length() / PI - 1.0).abs() < tol);
            assert!((c.enclosed_area() / (0.25 * PI) - 1.0).abs() < tol);
            let k = c.vertex_curvature().unwrap();
            assert!(k.iter().all(|k| (k / 2.0 - 1.0).abs() < 1e-2), "{k:?}");
        }
    }
}
