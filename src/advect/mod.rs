//! Characteristics-Galerkin advection and solution transfer.
