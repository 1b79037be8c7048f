//! Benchmark flow solvers (two-phase Stokes, ...).

pub mod couette;
pub mod stefan;
pub mod stokes;
pub mod streamlines;

pub use couette::{CouetteCase, CouetteResult, InterfaceViscosity};
pub use stokes::{
    negative_fraction, rigid_motion_fit, stokes_errors, RigidFit, StokesProblem, StokesReport,
    StokesSolution, StokesSolver, Viscosity,
};
pub use streamlines::{streamline, StreamlineOptions};
