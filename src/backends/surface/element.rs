//! Isoparametric Lagrange triangles embedded in 3D: the map `F(ξ) = Σ_j X_j φ_j(ξ)` of a P1
//! (flat) or P2 (curved) triangle with nodes `X_j`, its area element and the tangential
//! gradients `∇_Γ φ_j = J G⁻¹ ∇_ξ φ_j` (`J = DF`, `G = JᵀJ`) of its shape functions, and the
//! element mass and stiffness matrices `∫ φ_i φ_j`, `∫ ∇_Γ φ_i · ∇_Γ φ_j` over the curved
//! triangle (002; Dziuk's surface finite elements).
//!
//! The reference triangle has vertices `(0,0)`, `(1,0)`, `(0,1)`, barycentric coordinates
//! `λ = (1 − ξ − η, ξ, η)` and the local numbering of [`crate::fem::lagrange`] (vertices, then
//! the edge midpoints of (0,1), (1,2), (2,0)).

use crate::fem::lagrange::p2_grads;
use crate::fem::quadrature::tri_rule;
use crate::geom::DVec3;

/// Gradients of the barycentric coordinates with respect to `(ξ, η)` (third entry unused).
const REF_GRADS: [[f64; 3]; 3] = [[-1.0, -1.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];

/// The shape functions (3 or 6) and their `(ξ, η)` gradients at barycentric `lam`.
pub(crate) fn reference_basis(nodes: usize, lam: &[f64; 3]) -> (Vec<f64>, Vec<[f64; 2]>) {
    if nodes == 3 {
        let g = REF_GRADS.iter().map(|g| [g[0], g[1]]).collect();
        (lam.to_vec(), g)
    } else {
        let mut v = vec![0.0; 6];
        crate::fem::lagrange::p2_values(lam, &mut v);
        let mut g = vec![[0.0; 3]; 6];
        p2_grads(lam, &REF_GRADS, &mut g);
        (v, g.iter().map(|g| [g[0], g[1]]).collect())
    }
}

/// The geometry of a curved triangle at one reference point.
pub(crate) struct PointGeometry {
    /// Shape function values.
    pub values: Vec<f64>,
    /// Tangential gradients of the shape functions.
    pub grads: Vec<DVec3>,
    /// The position `F(ξ)`.
    pub x: DVec3,
    /// `∂_ξ F × ∂_η F` (its length is the area element; it points to the side the nodes are
    /// oriented towards).
    pub normal: DVec3,
}

/// Evaluates the element with nodes `x` (3 or 6) at barycentric `lam`. Returns `None` for a
/// degenerate element (zero area element).
pub(crate) fn evaluate(x: &[DVec3], lam: &[f64; 3]) -> Option<PointGeometry> {
    let (values, rg) = reference_basis(x.len(), lam);
    let mut pos = DVec3::ZERO;
    let (mut a1, mut a2) = (DVec3::ZERO, DVec3::ZERO);
    for j in 0..x.len() {
        pos += values[j] * x[j];
        a1 += rg[j][0] * x[j];
        a2 += rg[j][1] * x[j];
    }
    let (g11, g12, g22) = (a1.dot(a1), a1.dot(a2), a2.dot(a2));
    let det = g11 * g22 - g12 * g12;
    if !(det > 0.0 && det.is_finite()) {
        return None;
    }
    let grads = rg
        .iter()
        .map(|g| {
            let c1 = (g22 * g[0] - g12 * g[1]) / det;
            let c2 = (-g12 * g[0] + g11 * g[1]) / det;
            c1 * a1 + c2 * a2
        })
        .collect();
    Some(PointGeometry {
        values,
        grads,
        x: pos,
        normal: a1.cross(a2),
    })
}

/// Element mass and stiffness matrices (row-major, `n × n` with `n = x.len()`), integrated with
/// a rule of degree `degree` on the reference triangle. `None` for a degenerate element.
pub(crate) fn mass_stiffness(x: &[DVec3], degree: usize) -> Option<(Vec<f64>, Vec<f64>)> {
    let n = x.len();
    let (mut m, mut a) = (vec![0.0; n * n], vec![0.0; n * n]);
    let rule = tri_rule(degree);
    for (lam, w) in rule.points.iter().zip(&rule.weights) {
        let g = evaluate(x, lam)?;
        // Reference area 1/2.
        let dw = 0.5 * w * g.normal.length();
        for i in 0..n {
            for j in 0..n {
                m[i * n + j] += dw * g.values[i] * g.values[j];
                a[i * n + j] += dw * g.grads[i].dot(g.grads[j]);
            }
        }
    }
    Some((m, a))
}

/// `∫ f(x, n) dA` over the element, with `n` the unit normal, by a rule of degree `degree`.
pub(crate) fn integrate(
    x: &[DVec3],
    degree: usize,
    mut f: impl FnMut(DVec3, DVec3) -> f64,
) -> Option<f64> {
    let rule = tri_rule(degree);
    let mut s = 0.0;
    for (lam, w) in rule.points.iter().zip(&rule.weights) {
        let g = evaluate(x, lam)?;
        let da = g.normal.length();
        s += 0.5 * w * da * f(g.x, g.normal / da);
    }
    Some(s)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_triangle_matches_p1_formulas() {
        let x = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let (m, a) = mass_stiffness(&x, 2).unwrap();
        // Mass of the unit right triangle: area/12 (2 on the diagonal).
        assert!((m[0] - 1.0 / 12.0).abs() < 1e-14 && (m[1] - 1.0 / 24.0).abs() < 1e-14);
        // Stiffness: [[1, -.5, -.5], [-.5, .5, 0], [-.5, 0, .5]].
        let want = [1.0, -0.5, -0.5, -0.5, 0.5, 0.0, -0.5, 0.0, 0.5];
        assert!(a.iter().zip(want).all(|(a, b)| (a - b).abs() < 1e-14));
    }

    #[test]
    fn p2_rows_of_stiffness_sum_to_zero_and_mass_to_area() {
        // A curved triangle: midpoints lifted off the plane.
        let v = [DVec3::ZERO, DVec3::X, DVec3::Y];
        let mut x = v.to_vec();
        for [i, j] in crate::fem::lagrange::TRI_EDGES {
            x.push(0.5 * (v[i] + v[j]) + 0.1 * DVec3::Z);
        }
        let (m, a) = mass_stiffness(&x, 6).unwrap();
        for i in 0..6 {
            assert!(a[i * 6..i * 6 + 6].iter().sum::<f64>().abs() < 1e-12);
        }
        let area = integrate(&x, 6, |_, _| 1.0).unwrap();
        assert!((m.iter().sum::<f64>() - area).abs() < 1e-12 && area > 0.5);
    }
}
