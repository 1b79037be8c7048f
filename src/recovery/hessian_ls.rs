//! Least-squares recovery of the gradient and Hessian of a P1 field (004 §4.3).
//!
//! At each vertex `x` the quadratic Taylor polynomial
//! `u(x_i) = u(x) + (x_i - x) . grad u(x) + 1/2 (x_i - x)^T H(x) (x_i - x)` (004 §4.3, following
//! its reference \[3\]) is fitted in the least-squares sense to the nodal values of the patch around
//! `x`. The value `u(x)` is **kept fixed** (it is the nodal value), leaving 5 unknowns: the
//! gradient and the `d(d+1)/2 = 3` Hessian coefficients. The patch is the first ring, widened to
//! further rings when it has fewer than 6 neighbours or the system is ill-conditioned; local
//! coordinates are whitened by the patch's second-moment tensor and the system is solved by QR
//! (see `patch.rs` and `lsq.rs`). Quadratic fields are recovered exactly (up to round-off) at
//! every vertex, boundary vertices and corners included, on any mesh and at any aspect ratio.

use super::input;
use super::patch::{fit_vertex, Value, Workspace};
use crate::error::Result;
use crate::geom::DVec2;
use crate::mesh::Mesh2;
use crate::metric::Sym2;
use rayon::prelude::*;

/// Recovered derivatives of a P1 field, one entry per vertex.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Recovered {
    /// Gradient at each vertex.
    pub gradient: Vec<DVec2>,
    /// Hessian at each vertex.
    pub hessian: Vec<Sym2>,
}

/// Gradient and Hessian at every vertex by the least-squares Taylor fit of 004 §4.3 (module
/// docs). Computed in parallel over vertices; the result does not depend on the thread count.
/// Unreferenced vertices get zeros.
///
/// Errors: [`crate::Error::InvalidField`] if `u` does not hold one finite value per vertex (naming
/// the first bad vertex); [`crate::Error::InvalidInput`] if a connected component of the mesh has
/// fewer than 6 vertices.
pub fn recover_ls(mesh: &Mesh2, u: &[f64]) -> Result<Recovered> {
    crate::mesh::check_p1_field(mesh.n_points(), u, "u")?;
    input::check_mesh(mesh)?;
    let (gradient, hessian) = (0..mesh.n_points() as u32)
        .into_par_iter()
        .with_min_len(256)
        .map_init(Workspace::default, |ws, v| {
            let f = fit_vertex(mesh, u, v, Value::Fixed, ws);
            (f.gradient, f.hessian)
        })
        .unzip();
    Ok(Recovered { gradient, hessian })
}

/// The Hessian of [`recover_ls`] (004 §4.3).
pub fn hessian_ls(mesh: &Mesh2, u: &[f64]) -> Result<Vec<Sym2>> {
    recover_ls(mesh, u).map(|r| r.hessian)
}

/// The gradient of the quadratic least-squares fit of [`recover_ls`]: exact for quadratics,
/// second-order accurate for smooth fields. (For PPR, which also fits the vertex value, see
/// [`super::gradient_ppr`].)
pub fn gradient_ls(mesh: &Mesh2, u: &[f64]) -> Result<Vec<DVec2>> {
    recover_ls(mesh, u).map(|r| r.gradient)
}
