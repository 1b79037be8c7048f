//! Transport of any shape in any velocity field (`anisomesh advect`): the built-in cases (single
//! vortex, four-vortex deformation, Zalesak rotation), one run through
//! [`anisomesh::advect::run`] with its report, the output files and figures, and the comparison
//! of mesh families at equal error.
//!
//! Modules: [`cases`], [`run`](mod@run), [`output`], [`compare`] and [`freefem`].

pub mod cases;
pub mod compare;
pub mod freefem;
pub mod output;
pub mod run;

pub use cases::{builtin, custom};
pub use run::{run, Family, RunSettings};
