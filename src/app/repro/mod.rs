//! Benchmark flows: one file per benchmark, each returning a typed report.

pub mod adapt_run;
pub mod band_memory;
pub mod convergence;
pub mod couette;
pub mod couette_sweep;
pub mod peers;
pub mod reinit;
pub mod speed;
pub mod stefan;
pub mod zalesak;
