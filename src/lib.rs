//! # anisomesh
//!
//! Unstructured anisotropic mesh adaptation around level-set interfaces: a simplicial mesh core,
//! Riemannian metric fields, derivative recovery, local remeshing operators, a finite element
//! layer and the flows built on them (characteristics advection, two-phase Stokes,
//! redistancing). Papers are cited by key ("004 eq. (6)"); `docs/references.md` lists them.
//!
//! The entry point is [`adapt::run`]:
//!
//! ```no_run
//! use anisomesh::prelude::*;
//!
//! let circle = Expr::parse("sqrt(x^2 + y^2) - 0.5")?;
//! let domain = (DVec2::splat(-1.0), DVec2::splat(1.0));
//! let out = adapt::run(AdaptTarget::shape(circle, domain), &RunOptions::default())?;
//! println!("{} vertices", out.mesh.n_points());
//! # Ok::<(), anisomesh::Error>(())
//! ```

#![warn(missing_docs)]

pub mod adapt;
pub mod advect;
pub mod backends;
pub mod error;
pub mod fem;
pub mod flows;
pub mod geom;
pub mod io;
pub mod levelset;
pub mod mesh;
pub mod mesh3;
pub mod metric;
pub mod recovery;

pub use error::{Error, MeshDefect, Result};
pub use geom::{DVec2, DVec3};
pub use mesh::{GridPattern, Location, Mesh2, NONE};
pub use metric::Sym2;

/// The names most programs need: `use anisomesh::prelude::*;`.
pub mod prelude {
    pub use crate::adapt::{self, AdaptTarget, LevelSetMetric, RunOptions};
    pub use crate::io;
    pub use crate::levelset::{Expr, Shape};
    pub use crate::{DVec2, Error, GridPattern, Mesh2, Result, Sym2};
}
