//! Gmsh `.msh` version 4.1 ASCII for 2D triangle meshes.
//!
//! Reading: `$MeshFormat` (4.1, ASCII), `$PhysicalNames`, `$Entities`, `$Nodes` (entity blocks,
//! parametric or not), `$Elements` of type 2 (triangles), 1 (lines) and 15 (points); other
//! sections are skipped. The first physical tag of a surface becomes `tri_ref`, of a curve the
//! `edge_ref` of its lines, of a point the `vert_ref` of its node (which is also flagged corner
//! and required); an entity without a physical group gives label 0. Nodes are numbered in
//! increasing tag order and triangles in increasing element-tag order; `z` must be 0.
//!
//! Writing: one point entity per corner, one curve entity per edge label (every boundary edge and
//! every labelled interior edge), one surface entity per `tri_ref`; non-zero labels become
//! physical tags, physical names are optional.

mod read;
mod write;

pub use read::{parse_msh, read_msh, read_msh_full};
pub use write::{write_msh, write_msh_named};

use crate::mesh::Mesh2;

/// A physical group name: dimension, physical tag, name.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct PhysicalName {
    /// Dimension of the group: 0 points, 1 curves, 2 surfaces.
    pub dim: u8,
    /// The physical tag (the label it names).
    pub tag: i32,
    /// The name, without quotes.
    pub name: String,
}

/// A mesh read from a `.msh` file with its physical names.
#[derive(Debug, Clone)]
pub struct GmshMesh {
    /// The mesh, labels taken from the physical tags.
    pub mesh: Mesh2,
    /// The `$PhysicalNames` entries, in file order.
    pub physical_names: Vec<PhysicalName>,
}
