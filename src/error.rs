//! The one error type of the library.
//!
//! Every fallible library function returns [`Result<T>`]. Each variant names *what* was wrong and
//! *where* (file and line, or the index of the offending entity), so that the CLI can print it in
//! one line. "A valid result that did not converge" is not an error: it is reported in the
//! statistics a pass returns (see `adapt::AdaptReport`).

use std::fmt;
use std::path::{Path, PathBuf};

/// Library result type.
pub type Result<T, E = Error> = std::result::Result<T, E>;

/// A defect found in a mesh by [`crate::mesh::Mesh2::check`] or while building a mesh.
#[derive(Debug, Clone, PartialEq)]
pub enum MeshDefect {
    /// A triangle refers to a vertex index that does not exist.
    IndexOutOfRange {
        /// The triangle.
        tri: usize,
        /// The vertex index it holds.
        vertex: u64,
        /// The number of vertices.
        n_points: usize,
    },
    /// A triangle repeats a vertex.
    RepeatedVertex {
        /// The triangle.
        tri: usize,
    },
    /// A vertex coordinate is NaN or infinite.
    NonFiniteCoordinate {
        /// The vertex.
        vertex: usize,
    },
    /// A triangle has zero signed area.
    DegenerateTriangle {
        /// The triangle.
        tri: usize,
    },
    /// A triangle is oriented clockwise (negative signed area).
    InvertedTriangle {
        /// The triangle.
        tri: usize,
        /// Its signed area (negative).
        signed_area: f64,
    },
    /// Two triangles have the same three vertices.
    DuplicateTriangle {
        /// The first of the two triangles.
        first: usize,
        /// The second.
        second: usize,
    },
    /// Two vertices have identical coordinates.
    DuplicateVertex {
        /// The first of the two vertices.
        first: usize,
        /// The second.
        second: usize,
    },
    /// More than two triangles share the edge `(a, b)`.
    NonManifoldEdge {
        /// One end of the edge.
        a: usize,
        /// The other end.
        b: usize,
    },
    /// The neighbour relation is not symmetric or does not match the shared edge.
    BadAdjacency {
        /// The triangle.
        tri: usize,
        /// Its local edge.
        edge: usize,
        /// What is inconsistent.
        detail: &'static str,
    },
    /// A vertex of the mesh lies strictly inside a boundary edge (a hanging node).
    HangingVertex {
        /// The hanging vertex.
        vertex: usize,
        /// One end of the boundary edge.
        a: usize,
        /// The other end.
        b: usize,
    },
    /// Triangles around a vertex overlap (their angles add up to more than a full turn).
    OverlappingTriangles {
        /// The vertex.
        vertex: usize,
    },
    /// Label arrays do not match the element count, or an interior edge has two labels.
    BadLabel {
        /// The triangle (the array length when a whole array is wrong).
        tri: usize,
        /// What is wrong.
        detail: &'static str,
    },
    /// A per-vertex array has the wrong length or a bad seed triangle.
    BadVertexData {
        /// The vertex (the array length when a whole array is wrong).
        vertex: usize,
        /// What is wrong.
        detail: &'static str,
    },
}

impl fmt::Display for MeshDefect {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use MeshDefect::*;
        match self {
            IndexOutOfRange {
                tri,
                vertex,
                n_points,
            } => write!(
                f,
                "triangle {tri} refers to vertex {vertex}, but there are only {n_points} vertices"
            ),
            RepeatedVertex { tri } => write!(f, "triangle {tri} repeats a vertex"),
            NonFiniteCoordinate { vertex } => {
                write!(f, "vertex {vertex} has a NaN or infinite coordinate")
            }
            DegenerateTriangle { tri } => write!(f, "triangle {tri} has zero area"),
            InvertedTriangle { tri, signed_area } => write!(
                f,
                "triangle {tri} is inverted (clockwise, signed area {signed_area:e})"
            ),
            DuplicateTriangle { first, second } => {
                write!(f, "triangles {first} and {second} have the same vertices")
            }
            DuplicateVertex { first, second } => {
                write!(
                    f,
                    "vertices {first} and {second} have identical coordinates"
                )
            }
            NonManifoldEdge { a, b } => {
                write!(f, "edge ({a}, {b}) is shared by more than two triangles")
            }
            BadAdjacency { tri, edge, detail } => {
                write!(f, "triangle {tri}, edge {edge}: {detail}")
            }
            HangingVertex { vertex, a, b } => write!(
                f,
                "vertex {vertex} lies inside boundary edge ({a}, {b}): the mesh is not conforming"
            ),
            OverlappingTriangles { vertex } => {
                write!(f, "triangles around vertex {vertex} overlap")
            }
            BadLabel { tri, detail } => write!(f, "triangle {tri}: {detail}"),
            BadVertexData { vertex, detail } => write!(f, "vertex {vertex}: {detail}"),
        }
    }
}

/// The library error.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A file could not be opened, read, written or renamed.
    #[error("{}: {source}", path.display())]
    Io {
        /// The file.
        path: PathBuf,
        /// The operating-system error.
        #[source]
        source: std::io::Error,
    },
    /// A file was read but its content is malformed.
    #[error("{}:{line}: {msg}", path.display())]
    Parse {
        /// The file.
        path: PathBuf,
        /// The 1-based line.
        line: usize,
        /// What is wrong there.
        msg: String,
    },
    /// The mesh is not a valid conforming, counter-clockwise triangulation.
    #[error("invalid mesh: {0}")]
    InvalidMesh(MeshDefect),
    /// A metric tensor is not symmetric positive definite (NaN, negative or zero eigenvalue).
    #[error("invalid metric at vertex {vertex}: {msg}")]
    InvalidMetric {
        /// The vertex.
        vertex: usize,
        /// What is wrong with its tensor.
        msg: String,
    },
    /// A field has the wrong length or holds NaN values.
    #[error("invalid field '{name}': {msg}")]
    InvalidField {
        /// The name of the field.
        name: String,
        /// What is wrong, naming the first bad entity.
        msg: String,
    },
    /// A level set has no zero crossing where one is needed.
    #[error("empty level set: {0}")]
    EmptyLevelSet(String),
    /// An iterative method stopped without reaching its tolerance where that is fatal.
    #[error("did not converge: {0}")]
    NotConverged(String),
    /// Any other invalid argument (an option out of range, an unknown shape name, ...).
    #[error("{0}")]
    InvalidInput(String),
    /// A feature of an input file or request that is not supported.
    #[error("unsupported: {0}")]
    Unsupported(String),
    /// A request, or an adaptation under way, exceeds a vertex limit.
    #[error("too large: {0}")]
    TooLarge(String),
}

impl From<MeshDefect> for Error {
    fn from(d: MeshDefect) -> Self {
        Error::InvalidMesh(d)
    }
}

impl Error {
    /// An I/O error on `path`.
    pub fn io(path: &Path, source: std::io::Error) -> Self {
        Error::Io {
            path: path.to_path_buf(),
            source,
        }
    }

    /// A parse error at `line` (1-based) of `path`.
    pub fn parse(path: &Path, line: usize, msg: impl Into<String>) -> Self {
        Error::Parse {
            path: path.to_path_buf(),
            line,
            msg: msg.into(),
        }
    }
}
