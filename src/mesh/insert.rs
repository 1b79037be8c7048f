//! Inserting a vertex at a given point of a planar mesh: located with exact orientation tests,
//! then the containing triangle is split into three ([`TriMesh::split_triangle`]) or, for a
//! point on an edge, the one or two triangles sharing that edge into two each
//! ([`TriMesh::split_edge`]).

use super::{Location, Mesh2, TriMesh, NONE};
use crate::error::{Error, Result};
use crate::geom::{orient2d, DVec2};

/// How [`Mesh2::insert_point`] placed the point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Insertion {
    /// The point is an existing vertex: nothing changed.
    Existing(u32),
    /// A new vertex strictly inside a triangle (split into three).
    InTriangle(u32),
    /// A new vertex on an interior edge (two triangles split into two each).
    OnEdge(u32),
    /// A new vertex on a boundary edge (one triangle split into two).
    OnBoundary(u32),
}

impl Insertion {
    /// The index of the vertex at the point.
    pub fn vertex(self) -> u32 {
        match self {
            Insertion::Existing(v)
            | Insertion::InTriangle(v)
            | Insertion::OnEdge(v)
            | Insertion::OnBoundary(v) => v,
        }
    }
}

impl Mesh2 {
    /// Inserts a vertex at `p` (exact coordinates) and returns where it went. The point is
    /// located with exact orientation tests; a point equal to a vertex returns that vertex, a
    /// point on an edge splits the edge. The new vertex has label 0 and is neither a corner nor
    /// required (the caller sets these). The mesh stays valid ([`Mesh2::check`]) and its area is
    /// unchanged. The vertices of the new triangles are seeded into them.
    ///
    /// Errors: `p` not finite, or outside the mesh ([`Error::InvalidInput`], naming the point).
    pub fn insert_point(&mut self, p: DVec2) -> Result<Insertion> {
        if !p.is_finite() {
            return Err(Error::InvalidInput(format!(
                "insert_point: the point ({}, {}) is not finite",
                p.x, p.y
            )));
        }
        let seed = self.live_tris().next().map_or(NONE, |t| t as u32);
        let t = match self.locate(p, seed) {
            Location::Inside { tri, .. } => tri,
            Location::Outside { .. } => {
                return Err(Error::InvalidInput(format!(
                    "insert_point: the point ({}, {}) lies outside the mesh",
                    p.x, p.y
                )))
            }
        };
        let pts = self.tri_points(t as usize);
        // Exact orientation of p against each local edge i (opposite vertex i); all >= 0 here.
        let on: Vec<usize> = (0..3)
            .filter(|&i| orient2d(pts[super::next(i)], pts[super::prev(i)], p) == 0.0)
            .collect();
        match on.as_slice() {
            [] => {
                let v = self.add_vertex(p, 0, &mut ());
                let [a, ..] = self.tris[t as usize];
                let [t1, t2] = self.split_triangle(t, v, &mut ());
                self.seed_into(t1);
                self.seed_into(t2);
                self.vert_tri[a as usize] = t;
                self.vert_tri[v as usize] = t;
                Ok(Insertion::InTriangle(v))
            }
            [i] => {
                let v = self.add_vertex(p, 0, &mut ());
                let tri = self.tris[t as usize];
                let (c, a) = (tri[*i], tri[super::next(*i)]);
                let s = self.split_edge(t, *i, v, &mut ());
                self.seed_into(s.t1);
                self.vert_tri[c as usize] = t;
                self.vert_tri[a as usize] = t;
                if s.t2 == NONE {
                    return Ok(Insertion::OnBoundary(v));
                }
                let d = self.tris[s.t2 as usize][0];
                self.seed_into(s.t3);
                self.vert_tri[d as usize] = s.t2;
                self.vert_tri[self.tris[s.t2 as usize][1] as usize] = s.t2;
                Ok(Insertion::OnEdge(v))
            }
            // On two edges: the vertex they share (opposite the third).
            [i, j] => Ok(Insertion::Existing(self.tris[t as usize][3 - i - j])),
            _ => Err(Error::InvalidInput(format!(
                "insert_point: triangle {t} is degenerate at ({}, {})",
                p.x, p.y
            ))),
        }
    }
}

impl<P> TriMesh<P> {
    /// Sets the seed of every corner of triangle `t` to `t`.
    fn seed_into(&mut self, t: u32) {
        for v in self.tris[t as usize] {
            self.vert_tri[v as usize] = t;
        }
    }
}
