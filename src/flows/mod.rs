//! Benchmark flow solvers (two-phase Stokes, ...).

pub mod couette;
pub mod stokes;
mod stokes_uzawa;
pub mod streamlines;

pub use couette::{CouetteCase, CouetteResult};
pub use stokes::{
    rigid_motion_fit, stokes_errors, RigidFit, StokesProblem, StokesReport, StokesSolution,
    StokesSolver, Viscosity,
};
pub use streamlines::{streamline, StreamlineOptions};
