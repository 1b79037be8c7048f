//! Level-set redistancing (geometric, PPR with oblique projection, fast marching).
//!
//! - [`geometric`]: exact distance to the piecewise-linear zero level (004 §2.2), 2D and 3D.

mod bvh;
pub mod geometric;

pub use geometric::{redistance_geometric, redistance_geometric_3d};
