//! [`TriMesh`], the simplicial core: a conforming triangulation stored as flat arrays (struct of
//! arrays), generic over the point type; [`Mesh2`] is the planar, counter-clockwise case.
//!
//! Conventions (used by every module):
//! - `tris[t] = [a, b, c]` counter-clockwise.
//! - Local edge `i` of triangle `t` is the edge *opposite* local vertex `i`, i.e. the edge
//!   `(tris[t][(i+1)%3], tris[t][(i+2)%3])`.
//! - `neighbours[t][i]` is the triangle across local edge `i`, or [`NONE`] on the boundary.
//! - `edge_ref[t][i]` is the label of local edge `i` (0 = unlabelled). Boundary edges and edges
//!   between sub-domains (interfaces) carry labels; an interior labelled edge has the same label
//!   seen from both sides.
//! - `tri_ref[t]` is the sub-domain label; `vert_ref[v]` the vertex label; `corner[v]` and
//!   `required[v]` mark vertices the remesher must keep in place.
//! - `vert_tri[v]` is one triangle containing `v` (a seed for ring walks), or [`NONE`] for an
//!   isolated vertex.
//! - A triangle whose first vertex is [`NONE`] is *deleted* (a tombstone); [`TriMesh::compact`]
//!   removes tombstones and unreferenced vertices.
//!
//! Topology is kept apart from geometry. `impl<P> TriMesh<P>` holds what never looks at
//! coordinates: adjacency, fans, rings, edges, boundary loops, compaction (`topology.rs`), the
//! topological part of the invariant check (`check.rs`), building adjacency from triangles
//! (`build.rs`) and the local edits with their [`EditListener`] hook (`edit.rs`, `cavity.rs`).
//! `impl Mesh2` adds the planar geometry: areas, orientation checks, point location
//! (`locate.rs`), point insertion (`insert.rs`), grids (`grid.rs`), spatial ordering
//! (`order.rs`) and the constrained Delaunay mesher (`polygon.rs`, `cdt.rs`). A triangulated
//! surface in space is a `TriMesh<DVec3>` and reuses the topology and the edits.

pub(crate) mod build;
mod cavity;
mod cdt;
mod check;
mod edit;
mod field;
mod grid;
mod insert;
mod locate;
mod order;
mod polygon;
mod topology;

pub use cavity::CavityEdge;
pub use cdt::from_polygon;
pub use edit::{EdgeSplit, EditListener};
pub use field::check_p1_field;
pub use grid::GridPattern;
pub use insert::Insertion;
pub use locate::Location;
pub use polygon::{circle_points, DomainLoop, LoopKind, PolygonDomain};

use crate::geom::DVec2;

/// Sentinel for "no triangle / no vertex".
pub const NONE: u32 = u32::MAX;

/// The next local index, `(i + 1) % 3`.
#[inline]
pub const fn next(i: usize) -> usize {
    if i == 2 {
        0
    } else {
        i + 1
    }
}

/// The previous local index, `(i + 2) % 3`.
#[inline]
pub const fn prev(i: usize) -> usize {
    if i == 0 {
        2
    } else {
        i - 1
    }
}

/// Local index of `v` in `tri`; the caller knows it is a corner (2 otherwise).
#[inline]
pub(crate) fn local_index_of(tri: [u32; 3], v: u32) -> usize {
    if tri[0] == v {
        0
    } else if tri[1] == v {
        1
    } else {
        2
    }
}

/// A conforming triangulation with points of type `P` (see the module documentation for the
/// conventions). The topology (every field but `points`) does not depend on `P`.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriMesh<P> {
    /// Vertex coordinates.
    pub points: Vec<P>,
    /// Triangle corners; `tris[t][0] == NONE` marks a deleted triangle (a tombstone).
    pub tris: Vec<[u32; 3]>,
    /// `neighbours[t][i]`: the triangle across local edge `i` (opposite corner `i`), or [`NONE`].
    pub neighbours: Vec<[u32; 3]>,
    /// Sub-domain label per triangle.
    pub tri_ref: Vec<i32>,
    /// Label of each local edge (0 = unlabelled; boundary and interface edges carry one).
    pub edge_ref: Vec<[i32; 3]>,
    /// Label per vertex.
    pub vert_ref: Vec<i32>,
    /// Corner vertices (kept in place by the remesher).
    pub corner: Vec<bool>,
    /// Required vertices (kept in place by the remesher).
    pub required: Vec<bool>,
    /// One live triangle holding each vertex (a seed for fan walks), or [`NONE`].
    pub vert_tri: Vec<u32>,
}

/// A planar triangulation with counter-clockwise triangles.
pub type Mesh2 = TriMesh<DVec2>;

impl<P> TriMesh<P> {
    /// Number of vertices (including unreferenced ones before [`TriMesh::compact`]).
    #[inline]
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// Number of triangle slots (including tombstones before [`TriMesh::compact`]).
    #[inline]
    pub fn n_tris(&self) -> usize {
        self.tris.len()
    }

    /// Whether triangle `t` is a tombstone.
    #[inline]
    pub fn is_deleted(&self, t: usize) -> bool {
        self.tris[t][0] == NONE
    }

    /// Iterator over the indices of live (not deleted) triangles.
    pub fn live_tris(&self) -> impl Iterator<Item = usize> + '_ {
        (0..self.tris.len()).filter(move |&t| !self.is_deleted(t))
    }

    /// Number of live triangles.
    pub fn n_live_tris(&self) -> usize {
        self.live_tris().count()
    }

    /// The two vertices of local edge `i` of triangle `t`, in the triangle's orientation.
    #[inline]
    pub fn edge_vertices(&self, t: usize, i: usize) -> [u32; 2] {
        let tri = self.tris[t];
        [tri[next(i)], tri[prev(i)]]
    }

    /// The three corner points of triangle `t`.
    #[inline]
    pub fn tri_points(&self, t: usize) -> [P; 3]
    where
        P: Copy,
    {
        let [a, b, c] = self.tris[t];
        [
            self.points[a as usize],
            self.points[b as usize],
            self.points[c as usize],
        ]
    }
}

impl Mesh2 {
    /// Signed area of triangle `t` (positive for a valid, counter-clockwise triangle).
    #[inline]
    pub fn tri_area(&self, t: usize) -> f64 {
        let [a, b, c] = self.tri_points(t);
        crate::geom::signed_area(a, b, c)
    }

    /// Total area of the live triangles.
    pub fn area(&self) -> f64 {
        self.live_tris().map(|t| self.tri_area(t)).sum()
    }

    /// Axis-aligned bounding box `(min, max)` of the vertices; `None` for an empty mesh.
    pub fn bounding_box(&self) -> Option<(DVec2, DVec2)> {
        let first = *self.points.first()?;
        Some(
            self.points
                .iter()
                .fold((first, first), |(lo, hi), &p| (lo.min(p), hi.max(p))),
        )
    }
}

#[cfg(test)]
mod tests;
