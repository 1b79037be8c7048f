//! Level-set redistancing (geometric, PPR with oblique projection, fast marching).
//!
//! - [`geometric`]: exact distance to the piecewise-linear zero level (004 §2.2), written once
//!   for triangles and tetrahedra; the cut of one cell is per dimension ([`ZeroLevelPieces`]).
//! - [`ppr_method`]: 003 §6 — PPR recovered gradient (`ppr.rs`), quasi-normal field, oblique
//!   projection (6.10)–(6.11) (`oblique.rs`) on the cut cells, fast marching extension (`fmm.rs`),
//!   P1 and P2, triangles and tetrahedra.
//! - [`fmm_method`]: first-order fast marching from the cut cells alone.

mod bvh;
mod fmm;
pub mod fmm_method;
pub mod geometric;
mod oblique;
mod pieces;
mod ppr;
pub mod ppr_method;
mod simplices;

pub use fmm_method::redistance_fmm_cells;
pub use geometric::{redistance_geometric, redistance_geometric_cells};
pub use pieces::ZeroLevelPieces;
pub use ppr_method::{redistance_ppr, redistance_ppr_cells, PprOptions, PprOutput, PprReport};
