//! # anisomesh
//!
//! Unstructured anisotropic mesh adaptation around level-set interfaces: a simplicial mesh core,
//! Riemannian metric fields, derivative recovery, local remeshing operators, a finite element
//! layer and the benchmark flows built on them. See `README.md` and `ARCHITECTURE.md`.

pub mod adapt;
pub mod advect;
pub mod backends;
pub mod bench;
pub mod error;
pub mod fem;
pub mod flows;
pub mod geom;
pub mod io;
pub mod levelset;
pub mod mesh;
pub mod mesh3;
pub mod metric;
pub mod plot;
pub mod recovery;

pub use error::{Error, MeshDefect, Result};
pub use geom::{DVec2, DVec3};
pub use mesh::{GridPattern, Location, Mesh2, NONE};
pub use metric::Sym2;
