//! The application's tests: the benchmark flows, paper reproductions, peer glue and figures,
//! asserting the measured numbers they report.

mod adapt_gradation;
mod advect_cases;
mod advect_zalesak;
mod convergence_fronts;
mod convergence_sweep;
mod couette_bench;
mod crosscheck;
mod fit_peers;
mod peers_glue;
mod plot_figures;
mod plot_surface;
mod reinit_drift;
mod reinit_torus;
mod stokes_couette;
