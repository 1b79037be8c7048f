//! Molecular solvation by the variational implicit-solvent model on the interface-fitted mesh
//! (001 §7): the model and its 2D first variation (`model.rs`), the free energy of a fitted
//! solute region (`energy.rs`), the systems and initial wraps of 001 §7 (`systems.rs`), and the
//! relaxation loop (`relax.rs`).

mod energy;
mod model;
mod relax;
mod systems;

pub use energy::{free_energy, Energy};
pub use model::{Parameters, Particle, System};
pub use relax::{relax, setup, RelaxOptions, Relaxation, StepRecord};
pub use systems::{
    initial_level_set, SystemKind, Wrap, LOOSE_MARGIN, RING_RADIUS, ROD_PARTICLES, ROD_SPACING,
    TIGHT_RADIUS,
};
