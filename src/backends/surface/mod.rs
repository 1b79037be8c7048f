//! Parametric interfaces moved by Dziuk's surface finite elements (002): closed surfaces in 3D
//! as meshes of P1 (flat) or isoparametric P2 (curved) triangles, closed curves in 2D as
//! polygons or chains of quadratic arcs, and the θ-scheme for their mean curvature flow
//!
//! `∫_{Γⁿ} (Uⁿ⁺¹ − id)·φ + τ ∫_{Γⁿ} (θ ∇_Γ Uⁿ⁺¹ + (1 − θ) I) : ∇_Γ φ = 0`
//!
//! (002), assembled with tangential gradients of the Lagrange basis on each (curved) element and
//! solved with the shared [`crate::fem`] solvers. A sphere of radius `R0` shrinks as
//! `R(t) = √(R0² − 4t)`, a circle as `R(t) = √(R0² − 2t)`; the averaged radius `∫|x| / ∫1` of
//! 002 measures the error. The time discretisation is first order in `τ` for every `θ`
//! (on a sphere the step multiplies the radius by `(1 − (1 − θ)ε)/(1 + θε)`, `ε = 2τ/R²`,
//! against the exact `√(1 − 2ε)`), so with `τ` halved per refinement the error of the
//! averaged radius is dominated by the time step.
//!
//! Files: `element.rs` (curved triangles in 3D), `mesh.rs` ([`ParametricSurface`], the
//! icosahedral sphere), `mcf.rs` (the θ-scheme on surfaces), `curve.rs` ([`ParametricCurve`]).

mod curve;
mod element;
mod mcf;
mod mesh;

pub use curve::ParametricCurve;
pub use mcf::{assemble_surface, theta_solve, theta_step, ThetaStepStats};
pub use mesh::ParametricSurface;
