//! Benchmark flow solvers (two-phase Stokes, ...).

pub mod couette;
pub mod stokes;

pub use couette::{CouetteCase, CouetteResult};
pub use stokes::{
    rigid_motion_fit, stokes_errors, RigidFit, StokesProblem, StokesReport, StokesSolution,
    StokesSolver, Viscosity,
};
