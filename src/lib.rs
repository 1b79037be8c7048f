//! # anisomesh
//!
//! Unstructured anisotropic mesh adaptation around level-set interfaces: a simplicial mesh core,
//! Riemannian metric fields, derivative recovery, local remeshing operators, a finite element
//! layer and the benchmark flows built on them. See `README.md` and `ARCHITECTURE.md`.

pub mod error;
pub mod geom;
pub mod mesh;

pub use error::{Error, MeshDefect, Result};
pub use geom::{DVec2, DVec3};
pub use mesh::{GridPattern, Location, Mesh2, NONE};
