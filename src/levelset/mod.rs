//! Level-set functions: implicit shapes, zero-level extraction and measures, redistancing.
//!
//! Sign convention (004 §2.1): a level-set function is negative inside and positive outside.

mod arcpoly;
pub mod compare;
pub mod compare3;
pub mod compare_radial;
pub mod expr;
pub mod implicit_volume;
pub mod interface;
pub mod measure;
pub mod radial;
pub mod redistance;
pub mod shapes;
mod surface;
pub mod triangulated;

pub use expr::{Expr, Variables};
pub use implicit_volume::implicit_volume;
pub use interface::{
    enclosed_area, extract_zero_level, interface_distance, interface_length, InterfaceError,
    Polyline,
};
pub use measure::{enclosed_measure, interface_measure};
pub use radial::{icosphere, radial_surface, torus_surface};
pub use shapes::{
    nodal_distance, normalized_distance, shape_by_name, Ball, Circle, Difference, Flower,
    Intersection, Normalized, Rotated, Shape, ShapePoint, Sphere, StarSurface, Torus, Union,
    Zalesak, SHAPE_NAMES,
};
pub use surface::TriangleSurface;
pub use triangulated::TriangulatedShape;
