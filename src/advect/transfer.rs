//! Solution transfer between two meshes of the same domain (004 §3.5: after each adaptation the
//! level set is carried over to the new mesh).
//!
//! - [`interpolate`]: the new nodal values are the old field evaluated at the new vertices,
//!   located by walking — P1 or the limited quadratic reconstruction of [`super::evaluate`].
//!   Exact for linear fields with either option, and for quadratics with the quadratic option
//!   when the recovered derivatives are exact.
//! - [`project`]: conservative transfer, the L2 projection `∫ u_new φ_i = ∫ u_old φ_i` on the new
//!   mesh. *Supermesh-free approximation*: the right-hand side is integrated on the new elements
//!   only (each split `subdivisions` times into four, degree-4 rule on each piece), not on the
//!   intersection of old and new elements. Where an old element edge crosses a sub-triangle, the
//!   piecewise-linear old field has a kink the rule does not see; the resulting error in
//!   `∫ u` is `O(h_sub² |∇u_old jump|)` per crossed piece, so the integral of `u` is kept to
//!   quadrature accuracy, not to round-off. Points outside the old mesh take the inflow value.

use super::evaluate::{FieldEvaluator, Inflow, Interpolation};
use super::galerkin::{pull_back, Form};
use crate::error::Result;
use crate::geom::DVec2;
use crate::mesh::Mesh2;

/// Interpolation by location: `u_new_i = u_old(x_i)` (P1 or quadratic evaluation).
pub fn interpolate(
    old: &Mesh2,
    u_old: &[f64],
    new: &Mesh2,
    interp: Interpolation,
    inflow: Inflow,
) -> Result<Vec<f64>> {
    let eval = FieldEvaluator::new(old, u_old, interp, inflow)?;
    pull_back(&eval, new, &|x: DVec2| x, Form::Nodal, 1e-12)
}

/// Conservative transfer: L2 projection of the old field onto the new P1 space, with the
/// supermesh-free quadrature described in the module documentation.
pub fn project(
    old: &Mesh2,
    u_old: &[f64],
    new: &Mesh2,
    interp: Interpolation,
    subdivisions: u8,
    inflow: Inflow,
) -> Result<Vec<f64>> {
    let eval = FieldEvaluator::new(old, u_old, interp, inflow)?;
    pull_back(
        &eval,
        new,
        &|x: DVec2| x,
        Form::L2Projection { subdivisions },
        1e-12,
    )
}

/// `∫ u` of a P1 field (mass lumping is exact for the integral of a P1 function).
pub fn integral(mesh: &Mesh2, u: &[f64]) -> f64 {
    mesh.live_tris()
        .map(|t| {
            let [a, b, c] = mesh.tris[t];
            mesh.tri_area(t) * (u[a as usize] + u[b as usize] + u[c as usize]) / 3.0
        })
        .sum()
}
