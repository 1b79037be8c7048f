//! The DT-Grid narrow band in the plane (000 §2–§3 in two dimensions): a level-set function on
//! the nodes of a square grid within `j` cells of its zero level, stored in a
//! [`DtGrid<[i32; 2]>`](super::DtGrid), Q1 finite elements on the band's cells, mean curvature
//! motion with Dirichlet conditions and the nested inner iteration (000 §2.3–§2.4), and the
//! band behind the back-end contract for [`D2`](crate::backends::D2).
//!
//! The pieces that do not depend on the dimension are shared with the 3D band: the storage and
//! the [`Band`](super::Band) seam, the Q1 element ([`crate::fem::q1`]), the linear systems of a
//! step ([`super::scheme`]: `M + τ L`, CG with Dirichlet rows), the options and reports of a
//! step ([`super::mcf::McfOptions`], [`super::mcf::StepReport`]) and the band with its interior
//! flags ([`super::lattice::NarrowBand`]).
//!
//! Files: `lattice.rs` (the square grid, the band of half-width `j` around the crossed cells,
//! 000 (2.8)), `cubic.rs` (bilinear and bicubic Catmull–Rom reconstruction of a band field:
//! values, gradients, Hessians, nodal curvature), `level.rs` (the zero level as polylines by
//! marching squares, with crossings and mid-points on the bicubic zero level; area, length),
//! `distance.rs` (the signed distance extension of 000 §2.4), `fem.rs` (the Q1 band matrices
//! of 000 (2.6)–(2.7) and the transparent boundary vector of 000 (2.9)), `heat.rs` (the heat
//! equation on a circle with natural or transparent conditions, 000 Table 2.1 in the plane),
//! `mcf.rs` (one mean curvature step, 000 (2.5), (2.11), (2.12)), `backend.rs`
//! ([`DtGrid2Backend`]).

pub mod backend;
pub mod cubic;
pub mod distance;
pub mod fem;
pub mod heat;
pub mod lattice;
pub mod level;
pub mod mcf;

pub use backend::{DtGrid2Backend, DtGrid2Options};
pub use lattice::{Plane, C2};

/// The band storage in the plane.
pub type Grid2 = super::DtGrid<C2>;
