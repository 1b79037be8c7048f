//! The interface-fitted back end of 001: a base triangulation cut along the zero level of a P1
//! level set so that the interface is a chain of mesh edges (001 §2), with the two sides labelled
//! as `mmg2d -ls` labels them. P1 problems posed on the two sides (Stefan, solvation) are solved
//! on [`FittedMesh::mesh`] and mapped back to the base mesh with
//! [`FittedMesh::restrict_to_base`]; base fields reach the fitted mesh with
//! [`FittedMesh::extend_from_base`].
//!
//! Files: `fit.rs` (cutting and labelling), `curvature.rs` (curvature by local averaging,
//! 001 (5.2)), `stefan.rs` (the Stefan loop of 001 §6 on the fitted mesh), `reinit.rs` (the
//! Poisson reinitialisation of 001 §4), `backend.rs` (the back-end contract on a uniform base
//! grid), `extension.rs` (the velocity extension of 001 §3), `stefan_flux.rs` (the Stefan velocity from
//! quadratic one-sided gradients or from the heat step's residuals), `stefan_energy.rs` (the
//! energy balance and the conservative transfer), `stefan_seed.rs` (the pentagon seed).

mod backend;
mod curvature;
mod extension;
mod fit;
mod reinit;
pub mod solvation;
mod stefan;
mod stefan_energy;
mod stefan_flux;
mod stefan_seed;

pub use backend::{FittedBackend, FittedOptions, FittedRedistancing};
pub use curvature::{
    interface_curvature, interface_fit_curvature, vertex_curvature, VertexCurvature,
};
pub use extension::{
    extend_velocity, normal_derivative_jumps, Extension, ExtensionKind, ExtensionOptions,
};
pub use fit::{
    fit, snapped_values, FitOptions, FittedMesh, REF_INSIDE, REF_INTERFACE, REF_OUTSIDE,
};
pub use reinit::{poisson_reinit, PoissonOutput, PoissonReinit};
pub use stefan::{
    circle_deviation, stefan_step, Anisotropy, Coefficient, StefanAdvection, StefanCurvature,
    StefanFlux, StefanOptions, StefanState, StefanStepReport, VelocityExtension,
};
pub use stefan_energy::StefanBudget;
pub use stefan_flux::{stefan_velocity_quadratic, stefan_velocity_residual};
pub use stefan_seed::pentagon_seed;
