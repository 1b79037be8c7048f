//! The DT-Grid narrow-band back end (000): a level-set function stored on the nodes of a uniform
//! grid within a band around its zero level, Q1 finite elements on the band's cells.
//!
//! Files: `band.rs` (the [`Band`] seam between storage and finite elements), [`grid`] (the
//! DT-Grid storage of 000 §3: [`DtGrid`]), `sorted.rs`
//! ([`SortedBand`], a sorted-vector storage), [`lattice`] (the grid and the band of half-width
//! `j` around a zero level), [`fem`] (Q1 band matrices, the transparent boundary vector),
//! [`scheme`] (the linear systems of a step under each boundary condition), [`heat`] (the heat
//! equation on a sphere, 000 Table 2.1), [`mcf`] (mean curvature motion with Dirichlet conditions
//! and the nested inner iteration, 000 §2.4, Table 2.2), [`surface`] (the zero level, surface
//! integrals, signed distance), [`backend`] (the band behind the back-end contract),
//! [`probe`] (point values and curvature of a band field), [`shape_heat`] (the heat equation on
//! the zero level of any implicit function), [`stencil`] (band assembly by neighbour-offset
//! masks), [`elemop`] (the mean curvature system applied element by element).

pub mod backend;
mod band;
pub mod distance;
pub mod elemop;
pub mod fem;
pub mod ghost;
pub mod grid;
pub mod heat;
pub mod lattice;
pub mod mcf;
mod nbhd;
pub mod probe;
pub mod scheme;
pub mod shape_heat;
mod sorted;
pub mod stencil;
pub mod surface;
mod zero_level;

pub use backend::{DtGridBackend, DtGridOptions};
pub use band::{Band, GridCoord};
pub use grid::{DtCoord, DtGrid, Implicit};
pub use sorted::SortedBand;
pub mod lean;
pub mod matfree;
pub mod obj;
pub mod plane;
pub mod reaction;
pub mod sparse_init;
