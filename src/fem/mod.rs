//! The finite element layer: quadrature, elements, assembly into CSR, solvers.
//!
//! - [`quadrature`]: triangle and tetrahedron rules (degrees 1, 2, 5, 7 and more).
//! - [`csr`]: the square sparse matrix [`Csr`] built from element-to-dof maps.
//! - [`rect_csr`]: the rectangular sparse matrix [`RectCsr`] (off-diagonal blocks such as a
//!   discrete divergence and its transpose).
//! - [`assembly`]: deterministic parallel element assembly.
//! - [`p1`]: P1 mass, lumped mass, stiffness (scalar or tensor coefficient), load, errors.
//! - [`p1_simplex`]: P1 on triangles or tetrahedra from points and cells (weighted lumped mass,
//!   per-cell stiffness, cell gradients).
//! - [`p1_bubble`]: the MINI element (P1-bubble / P1) with the bubble condensed.
//! - [`q1`]: the Q1 element on the reference square/cube (shape functions, tensor Gauss rules,
//!   lumped mass, weighted stiffness).
//! - [`dirichlet`]: symmetric Dirichlet elimination.
//! - [`solve`]: PCG (Jacobi, IC(0)) and sparse direct solves (faer Cholesky and LU).

pub mod assembly;
pub mod bicgstab;
pub mod csr;
pub mod dirichlet;
pub mod lagrange;
pub mod p1;
pub mod p1_bubble;
pub mod p1_simplex;
pub mod q1;
pub mod quadrature;
pub mod rect_csr;
pub mod solve;

pub use csr::Csr;
pub use rect_csr::RectCsr;
pub use solve::{CgOptions, CgReport, PrecondKind};
