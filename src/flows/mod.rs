//! Benchmark flow solvers (two-phase Stokes, ...).
