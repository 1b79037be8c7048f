//! The finite element layer: quadrature, elements, assembly into CSR, solvers.

pub mod lagrange;
