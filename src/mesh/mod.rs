//! `Mesh2`, the simplicial core: a conforming, counter-clockwise triangulation stored as flat
//! arrays (struct of arrays).
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
//! - A triangle whose first vertex is [`NONE`] is *deleted* (a tombstone); [`Mesh2::compact`]
//!   removes tombstones and unreferenced vertices.
//!
//! Topology (this file and `topology.rs`) is kept apart from geometry (`locate.rs`,
//! `quality.rs`): the adjacency code never looks at coordinates.

mod build;
mod cdt;
mod check;
mod field;
mod grid;
mod locate;
mod order;
mod topology;

pub use cdt::{circle_points, from_polygon, DomainLoop, LoopKind, PolygonDomain};
pub use field::check_p1_field;
pub use grid::GridPattern;
pub use locate::Location;

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

/// A two-dimensional conforming triangulation. See the module documentation for conventions.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh2 {
    pub points: Vec<DVec2>,
    pub tris: Vec<[u32; 3]>,
    pub neighbours: Vec<[u32; 3]>,
    pub tri_ref: Vec<i32>,
    pub edge_ref: Vec<[i32; 3]>,
    pub vert_ref: Vec<i32>,
    pub corner: Vec<bool>,
    pub required: Vec<bool>,
    pub vert_tri: Vec<u32>,
}

impl Mesh2 {
    /// Number of vertices (including unreferenced ones before [`Mesh2::compact`]).
    #[inline]
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// Number of triangle slots (including tombstones before [`Mesh2::compact`]).
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

    /// The three corner points of triangle `t`.
    #[inline]
    pub fn tri_points(&self, t: usize) -> [DVec2; 3] {
        let [a, b, c] = self.tris[t];
        [
            self.points[a as usize],
            self.points[b as usize],
            self.points[c as usize],
        ]
    }

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

    /// The two vertices of local edge `i` of triangle `t`, in the triangle's orientation.
    #[inline]
    pub fn edge_vertices(&self, t: usize, i: usize) -> [u32; 2] {
        let tri = self.tris[t];
        [tri[next(i)], tri[prev(i)]]
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
