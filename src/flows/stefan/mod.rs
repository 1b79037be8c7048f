//! The Stefan problem of solidification (001 §6, eq. (6.1)–(6.6)) on an interface-fitted mesh:
//! the heat equation with the Gibbs–Thomson value on the interface, the Stefan condition for the
//! normal velocity, and Frank's expanding circle as the exact solution to test against.
//!
//! The mesh pieces here work on any conforming [`crate::mesh::Mesh2`] whose triangles are
//! labelled by side (the fitted mesh of 001 §2: one label inside the solid `Ω−`, another in the
//! liquid `Ω+`) and whose interface vertices are flagged:
//! - `heat.rs`: one implicit Euler step of `∂T/∂t = ΔT` (6.1) with `T` prescribed on the
//!   interface (6.2) and `∂T/∂n = 0` on `∂Ω` (6.3);
//! - `velocity.rs`: the Stefan condition `v_n = −[∂T/∂n]` (6.4) at the interface vertices;
//! - `frank.rs`: Frank's circle `R(t) = S0 √t` and its temperature.

mod frank;
mod heat;
mod velocity;

pub use frank::{exp_integral_e1, FrankCircle};
pub use heat::heat_step;
pub(crate) use velocity::check_velocity_inputs;
pub use velocity::stefan_velocity;
