//! Mesh and field file formats.
