//! One semi-implicit mean curvature step of a P1 level set on a fixed tetrahedral mesh: 000
//! eq. (2.4)–(2.5) in 3D, `(M[uⁿ] + dt L[uⁿ]) uⁿ⁺¹ = M[uⁿ] uⁿ`, with the lumped mass weighted by
//! the cell value of `|∇uⁿ|_ε⁻¹` (eq. (2.6)) and the stiffness `∫ |∇uⁿ|_ε⁻¹ ∇φ_i·∇φ_j`
//! (eq. (2.7)), natural conditions on the box (the shared [`crate::fem::p1_simplex`] layer).

use super::mcf::StepCost;
use crate::error::Result;
use crate::fem::p1_simplex::{add_stiffness, cell_gradients, lumped_mass, pattern};
use crate::fem::solve::cg;
use crate::fem::CgOptions;
use crate::geom::DVec3;
use std::time::Instant;

/// `uⁿ⁺¹` after one step of length `dt` of 000 eq. (2.5) on the tetrahedra `tets` over
/// `points`, with the regularisation `|x|_ε = √(ε² + |x|²)` of `grad_eps`; the solve's cost is
/// added to `cost`. Errors: bad cells or field, a failed solve.
pub(crate) fn semi_implicit_step(
    points: &[DVec3],
    tets: &[[u32; 4]],
    u: &[f64],
    dt: f64,
    grad_eps: f64,
    opts: &CgOptions,
    cost: &mut StepCost,
) -> Result<Vec<f64>> {
    let t = Instant::now();
    let w: Vec<f64> = cell_gradients(points, tets, u)?
        .iter()
        .map(|g| 1.0 / (grad_eps * grad_eps + g.length_squared()).sqrt())
        .collect();
    let lumped = lumped_mass(points, tets, Some(&w))?;
    let mut a = pattern(points.len(), tets)?;
    let wdt: Vec<f64> = w.iter().map(|w| w * dt).collect();
    add_stiffness(&mut a, points, tets, &wdt)?;
    for (i, &m) in lumped.iter().enumerate() {
        a.add(i, i, m)?;
    }
    let rhs: Vec<f64> = lumped.iter().zip(u).map(|(m, u)| m * u).collect();
    cost.assembly += t.elapsed().as_secs_f64();
    let t = Instant::now();
    let mut x = u.to_vec();
    let r = cg(&a, &rhs, &mut x, opts)?;
    cost.solve += t.elapsed().as_secs_f64();
    cost.iterations += r.iterations;
    cost.converged &= r.converged;
    Ok(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3::Mesh3;

    /// An affine level set does not move inside the box (its curvature is zero); a sphere's
    /// distance shrinks its zero level at about the speed 2/R.
    #[test]
    fn planes_stay_and_spheres_shrink() {
        let m = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::ONE, [16, 16, 16]).unwrap();
        let opts = CgOptions::default();
        let mut cost = StepCost {
            converged: true,
            ..StepCost::default()
        };
        let plane: Vec<f64> = m.points.iter().map(|p| p.x + 0.5 * p.y - 0.1).collect();
        let next =
            semi_implicit_step(&m.points, &m.tets, &plane, 0.01, 1e-3, &opts, &mut cost).unwrap();
        // Natural conditions: the box's boundary pulls on an affine field (a boundary flux),
        // inside it does not (the flux decays over √dt = 0.1).
        let drift = plane
            .iter()
            .zip(&next)
            .zip(&m.points)
            .filter(|(_, p)| p.abs().max_element() <= 0.5)
            .map(|((a, b), _)| (a - b).abs())
            .fold(0.0, f64::max);
        assert!(drift < 5e-3, "{drift}");
        let r0 = 0.6;
        let u: Vec<f64> = m.points.iter().map(|p| p.length() - r0).collect();
        let dt = 0.005;
        let next = semi_implicit_step(&m.points, &m.tets, &u, dt, 1e-3, &opts, &mut cost).unwrap();
        let vol = |u: &[f64]| crate::levelset::enclosed_measure(&m.points, &m.tets, u).unwrap();
        let r = |v: f64| (3.0 * v / (4.0 * std::f64::consts::PI)).cbrt();
        let speed = (r(vol(&u)) - r(vol(&next))) / dt;
        assert!((speed * r0 / 2.0 - 1.0).abs() < 0.15, "speed {speed}");
        assert!(cost.converged && cost.iterations > 0);
    }
}
