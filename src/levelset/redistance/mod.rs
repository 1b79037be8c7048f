//! Level-set redistancing (geometric, PPR with oblique projection, fast marching).
//!
//! - [`geometric`]: exact distance to the piecewise-linear zero level (004 §2.2), 2D and 3D.
//! - [`ppr_method`]: 003 §6 — PPR recovered gradient ([`ppr`]), quasi-normal field, oblique
//!   projection (6.10)–(6.11) ([`oblique`]) on the cut cells, fast marching extension ([`fmm`]),
//!   P1 and P2, triangles and tetrahedra.

mod bvh;
mod fmm;
pub mod geometric;
mod oblique;
mod ppr;
pub mod ppr_method;
mod simplices;

pub use geometric::{redistance_geometric, redistance_geometric_3d};
pub use ppr_method::{redistance_ppr, redistance_ppr_3d, PprOptions, PprOutput, PprReport};
