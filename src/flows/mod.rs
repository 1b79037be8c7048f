//! Benchmark flow solvers (two-phase Stokes, ...).

pub mod couette;
pub mod frank;
pub mod stokes;
pub mod streamlines;

pub use couette::{CouetteCase, CouetteResult, InterfaceViscosity};
pub use frank::{exp_integral_e1, FrankCircle};
pub use stokes::{
    negative_fraction, rigid_motion_fit, stokes_errors, RigidFit, StokesProblem, StokesReport,
    StokesSolution, StokesSolver, Viscosity,
};
pub use streamlines::{streamline, StreamlineOptions};
