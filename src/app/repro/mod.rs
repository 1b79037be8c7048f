//! Benchmark flows: one file per benchmark, each returning a typed report.

pub mod adapt_run;
pub mod advect;
pub mod band_memory;
pub mod convergence;
pub mod couette;
pub mod couette_sweep;
pub mod crosscheck;
pub mod dtgrid;
pub mod dtgrid_obj;
pub mod peers;
pub mod peers_fit;
pub mod reinit;
pub mod solvation;
pub mod speed;
pub mod stefan;
pub mod surface_distance;
pub mod surface_mcf;
pub mod zalesak;
