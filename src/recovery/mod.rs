//! Derivative recovery from P1 fields: gradients and Hessians on vertex patches.
//!
//! - [`recover_ls`] / [`hessian_ls()`] / [`gradient_ls`]: least-squares Taylor fit of 004 §4.3
//!   (value kept, gradient and Hessian fitted on a widened vertex patch). Exact for quadratics.
//! - [`gradient_ppr`]: polynomial preserving recovery, 003 §6.2 (full quadratic fit, value
//!   included). Exact for quadratics, second-order gradient for smooth fields.
//! - [`hessian_double_l2`]: double lumped L2 projection (004 §4.3's "dual L2 projection").
//! - [`recover_ls3`]: the least-squares Taylor fit on tetrahedral meshes (value kept, nine
//!   coefficients, SVD), exact for quadratics.
//!
//! All take a valid [`crate::Mesh2`] (as [`crate::Mesh2::check`] accepts) and one finite value
//! per vertex, run in parallel over vertices and are deterministic.

pub mod hessian_ls;
mod input;
pub mod l2_projection;
mod lsq;
pub mod lsq3;
mod patch;
pub mod ppr;

pub use hessian_ls::{gradient_ls, hessian_ls, recover_ls, Recovered};
pub use input::MIN_COMPONENT_VERTICES;
pub use l2_projection::hessian_double_l2;
pub use lsq3::{recover_ls3, Recovered3};
pub use ppr::gradient_ppr;
