//! Polynomial preserving recovery (PPR) of the gradient of a P1 field (003 §6.2, k = 1).
//!
//! At each vertex `v` a full quadratic `p_v` (6 coefficients, the value included) is fitted in
//! the least-squares sense to the nodal values at all vertices of the patch `omega(v)`, `v`
//! itself included:
//! `sum_z |u_h(z) - p_v(z)|^2 = min over P2`, and `(G_h u_h)(v) = grad p_v(v)` (003 §6.2).
//! The patch is the first ring, widened by further rings while it has fewer than 7 vertices or
//! the fit is ill-conditioned (the "enlarge the neighbourhood" option of 003 §6.2); if no
//! well-posed quadratic fit exists the cross term is dropped, then the fit is linear (the
//! "fewer degrees of freedom" fallback of 003 §6.2). Quadratics are reproduced exactly, and for
//! smooth fields the recovered gradient is second-order accurate (superconvergent).

use super::input;
use super::patch::{fit_vertex, Value, Workspace};
use crate::error::Result;
use crate::geom::DVec2;
use crate::mesh::Mesh2;
use rayon::prelude::*;

/// PPR gradient at every vertex (003 §6.2, module docs). Parallel over vertices, deterministic.
/// Unreferenced vertices get zero.
///
/// Errors: [`crate::Error::InvalidField`] if `u` does not hold one finite value per vertex (naming
/// the first bad vertex); [`crate::Error::InvalidInput`] if a connected component of the mesh has
/// fewer than 6 vertices.
pub fn gradient_ppr(mesh: &Mesh2, u: &[f64]) -> Result<Vec<DVec2>> {
    crate::mesh::check_p1_field(mesh.n_points(), u, "u")?;
    input::check_mesh(mesh)?;
    Ok((0..mesh.n_points() as u32)
        .into_par_iter()
        .with_min_len(256)
        .map_init(Workspace::default, |ws, v| {
            fit_vertex(mesh, u, v, Value::Fitted, ws).gradient
        })
        .collect())
}
