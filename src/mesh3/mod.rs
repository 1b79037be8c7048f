//! Tetrahedral meshes (3D), used by the redistancing work.
