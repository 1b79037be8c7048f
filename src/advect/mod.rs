//! Characteristics-Galerkin advection and solution transfer (004 §2.2, §3.5, §5.1).
//!
//! - [`characteristics`]: feet of the characteristics `X^n(x)` (Euler, midpoint, RK4, sub-steps)
//!   and point location by walking;
//! - [`evaluate`]: evaluation of a P1 field at a located point (P1 or limited quadratic);
//! - [`galerkin`]: one step `u^{n+1} = u^n ∘ X^n`, nodal or L2-projected (004 eq. (2));
//! - [`transfer`]: interpolation and conservative projection between meshes;
//! - [`mass_correction`]: constant shift restoring the enclosed area or volume (004 §5.1);
//! - [`fixed_point`]: the transient fixed-point adaptation over a period (004 §3.5);
//! - [`expr_velocity`]: a velocity field from two expressions in `x`, `y`, `t`;
//! - [`run`](mod@run): a whole transport run of any level set in any velocity field, with the
//!   measures after each period;
//! - [`shape_error`]: symmetric-difference area and Hausdorff distance to a reference shape.

pub mod adapter;
pub mod characteristics;
pub mod evaluate;
pub mod expr_velocity;
pub mod fixed_point;
pub mod galerkin;
pub(crate) mod interim;
pub mod mass_correction;
pub mod run;
pub mod shape_error;
pub mod transfer;

pub use adapter::LevelSetAdapter;
pub use characteristics::{foot, FootOptions, FootScheme, Rotation, Velocity};
pub use evaluate::{Derivatives, FieldEvaluator, Inflow, Interpolation};
pub use expr_velocity::ExprVelocity;
pub use fixed_point::{advance_period, Adapter, FixedPointOptions, IdentityAdapter, PeriodResult};
pub use galerkin::{advect, AdvectOptions, Form};
pub use mass_correction::{correct_mass, correct_volume, MassCorrection};
pub use run::{run, MeshFamily, RunOptions, RunResult, Snapshot, StepStats};
pub use shape_error::{hausdorff, symmetric_difference};

/// Exact area of `{u < 0}` of a P1 field ([`crate::levelset::interface::enclosed_area`]).
pub fn enclosed_area(mesh: &crate::Mesh2, u: &[f64]) -> crate::Result<f64> {
    crate::levelset::interface::enclosed_area(mesh, u)
}

/// Length of the zero level of a P1 field ([`crate::levelset::interface::interface_length`]).
pub fn interface_length(mesh: &crate::Mesh2, u: &[f64]) -> crate::Result<f64> {
    crate::levelset::interface::interface_length(mesh, u)
}
