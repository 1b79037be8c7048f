//! Local edits of the triangle topology: add or move a vertex, split an edge, split a triangle,
//! flip an edge (collapse and cavity filling are in `cavity.rs`). The edits read and write the
//! connectivity, the labels and the vertex seeds only; they never look at coordinates, so the
//! caller decides *whether* an edit is valid (orientation, quality, metric) and the edit keeps
//! the mesh consistent.
//!
//! Every edit reports what it changed to an [`EditListener`]: the adaptation workspace extends
//! its per-vertex and per-triangle data and marks what it must examine again; `&mut ()` listens
//! to nothing.
//!
//! Common rules: new triangles are appended, changed triangles keep their slot, deleted ones
//! become tombstones. Labels follow the pieces (the halves of an edge keep its label, new
//! interior edges get 0, sub-domain labels are inherited). A vertex seed (`vert_tri`) is changed
//! only where it would no longer hold its vertex, unless an edit documents otherwise.

use super::{next, prev, TriMesh, NONE};

/// Hears what a mesh edit changed. Every method has an empty default.
///
/// The events of one edit come in the order the edit makes the changes; a triangle may be
/// reported more than once.
pub trait EditListener {
    /// Vertex `v` was appended ([`TriMesh::add_vertex`]).
    fn vertex_added(&mut self, _v: u32) {}
    /// The coordinates of vertex `v` changed ([`TriMesh::move_vertex`]); its triangles are
    /// reported changed next.
    fn vertex_moved(&mut self, _v: u32) {}
    /// Triangle `t` was appended with corners `tri`.
    fn triangle_added(&mut self, _t: u32, _tri: [u32; 3]) {}
    /// Triangle `t` changed (corners, neighbours or labels); its corners are now `tri`.
    fn triangle_changed(&mut self, _t: u32, _tri: [u32; 3]) {}
    /// Triangle `t` was deleted (it is now a tombstone).
    fn triangle_removed(&mut self, _t: u32) {}
}

/// The listener that ignores every event.
impl EditListener for () {}

/// The triangles a [`TriMesh::split_edge`] produced: the split triangle `t` and its new sibling
/// `t1`, and across the edge `t2` and `t3` ([`NONE`] for a boundary edge).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EdgeSplit {
    /// The triangle whose local edge was split (kept in its slot).
    pub t: u32,
    /// The triangle appended beside `t`.
    pub t1: u32,
    /// The triangle across the split edge (kept in its slot), or [`NONE`].
    pub t2: u32,
    /// The triangle appended beside `t2`, or [`NONE`].
    pub t3: u32,
}

impl<P> TriMesh<P> {
    /// Appends an isolated vertex at `p` with label `vert_ref` (not a corner, not required, no
    /// seed) and returns its index. Insert it with [`TriMesh::split_edge`],
    /// [`TriMesh::split_triangle`] or [`TriMesh::fill_cavity`].
    pub fn add_vertex(&mut self, p: P, vert_ref: i32, l: &mut impl EditListener) -> u32 {
        let v = self.points.len() as u32;
        self.points.push(p);
        self.vert_ref.push(vert_ref);
        self.corner.push(false);
        self.required.push(false);
        self.vert_tri.push(NONE);
        l.vertex_added(v);
        v
    }

    /// Moves vertex `v` to `p`; `fan` must be its triangles ([`TriMesh::vertex_fan`]), which are
    /// reported changed in that order. The topology is unchanged.
    pub fn move_vertex(&mut self, v: u32, p: P, fan: &[u32], l: &mut impl EditListener) {
        self.points[v as usize] = p;
        l.vertex_moved(v);
        for &t in fan {
            l.triangle_changed(t, self.tris[t as usize]);
        }
    }

    /// Appends a triangle with sub-domain label `tref` (neighbours unset, edges unlabelled).
    pub(super) fn push_tri(&mut self, tri: [u32; 3], tref: i32, l: &mut impl EditListener) -> u32 {
        let t = self.tris.len() as u32;
        self.tris.push(tri);
        self.neighbours.push([NONE; 3]);
        self.edge_ref.push([0; 3]);
        self.tri_ref.push(tref);
        l.triangle_added(t, tri);
        t
    }

    /// Makes `t` (local edge `i`) and `u` (local edge `j`) neighbours; `u == NONE` makes the edge
    /// a boundary edge of `t`.
    #[inline]
    pub(super) fn link(&mut self, t: u32, i: usize, u: u32, j: usize) {
        self.neighbours[t as usize][i] = u;
        if u != NONE {
            self.neighbours[u as usize][j] = t;
        }
    }

    /// Local index in `nb` of the edge it shares with `t`, 0 when `nb` is [`NONE`].
    #[inline]
    fn mirror_or_zero(&self, t: usize, nb: u32) -> usize {
        if nb == NONE {
            0
        } else {
            self.mirror_edge(t, nb as usize).unwrap_or(0)
        }
    }

    /// Splits local edge `i` of triangle `t` at the isolated vertex `m` (from
    /// [`TriMesh::add_vertex`]; the caller places it on the edge). With `t = (c, a, b)` (`c`
    /// opposite the edge) and `(d, b, a)` the triangle `t2` across it: `t` becomes `(c, a, m)`,
    /// `t1 = (c, m, b)` is appended, `t2` becomes `(d, b, m)` and `t3 = (d, m, a)` is appended.
    /// The halves of the edge keep its label. Seeds: `m` gets `t`.
    pub fn split_edge(&mut self, t: u32, i: usize, m: u32, l: &mut impl EditListener) -> EdgeSplit {
        let tu = t as usize;
        let tri = self.tris[tu];
        let (c, a, b) = (tri[i], tri[next(i)], tri[prev(i)]);
        let nbs = self.neighbours[tu];
        let refs = self.edge_ref[tu];
        let (n_bc, n_ca, t2) = (nbs[next(i)], nbs[prev(i)], nbs[i]);
        let (r_bc, r_ca, r_ab) = (refs[next(i)], refs[prev(i)], refs[i]);
        let tref = self.tri_ref[tu];
        let j_bc = self.mirror_or_zero(tu, n_bc);
        // t := (c, a, m); t1 := (c, m, b)
        self.tris[tu] = [c, a, m];
        self.edge_ref[tu] = [r_ab, 0, r_ca];
        self.neighbours[tu] = [NONE, NONE, n_ca];
        l.triangle_changed(t, self.tris[tu]);
        let t1 = self.push_tri([c, m, b], tref, l);
        self.edge_ref[t1 as usize] = [r_ab, r_bc, 0];
        self.link(t, 1, t1, 2);
        self.link(t1, 1, n_bc, j_bc);
        self.vert_tri[m as usize] = t;
        if self.vert_tri[b as usize] == t {
            self.vert_tri[b as usize] = t1;
        }
        let mut t3 = NONE;
        if t2 != NONE {
            let t2u = t2 as usize;
            let tri2 = self.tris[t2u];
            let j = self.mirror_edge(tu, t2u).unwrap_or(0);
            let d = tri2[j];
            let nb2 = self.neighbours[t2u];
            let rf2 = self.edge_ref[t2u];
            // tri2 = (d, b, a) up to rotation: edge (a, d) is opposite b = local next(j),
            // edge (d, b) is opposite a = local prev(j).
            let (n_ad, n_db) = (nb2[next(j)], nb2[prev(j)]);
            let (r_ad, r_db) = (rf2[next(j)], rf2[prev(j)]);
            let j_ad = self.mirror_or_zero(t2u, n_ad);
            let tref2 = self.tri_ref[t2u];
            // t2 := (d, b, m); t3 := (d, m, a)
            self.tris[t2u] = [d, b, m];
            self.edge_ref[t2u] = [r_ab, 0, r_db];
            self.neighbours[t2u] = [NONE, NONE, n_db];
            l.triangle_changed(t2, self.tris[t2u]);
            t3 = self.push_tri([d, m, a], tref2, l);
            self.edge_ref[t3 as usize] = [r_ab, r_ad, 0];
            self.link(t2, 1, t3, 2);
            self.link(t3, 1, n_ad, j_ad);
            // Across the split edge: (a, m) is t.0 / t3.0, (m, b) is t1.0 / t2.0.
            self.link(t, 0, t3, 0);
            self.link(t1, 0, t2, 0);
            if self.vert_tri[a as usize] == t2 {
                self.vert_tri[a as usize] = t3;
            }
        }
        EdgeSplit { t, t1, t2, t3 }
    }

    /// Splits triangle `t = (a, b, c)` at the isolated vertex `v` (placed inside it by the
    /// caller) into `(a, b, v)` (kept in slot `t`), `(b, c, v)` and `(c, a, v)` (appended, in
    /// that order; returned). The new interior edges are unlabelled. Seeds: `v` gets `t`.
    pub fn split_triangle(&mut self, t: u32, v: u32, l: &mut impl EditListener) -> [u32; 2] {
        let tu = t as usize;
        let [a, b, c] = self.tris[tu];
        let (nb, er, tref) = (self.neighbours[tu], self.edge_ref[tu], self.tri_ref[tu]);
        let t1 = self.push_tri([b, c, v], tref, l);
        let t2 = self.push_tri([c, a, v], tref, l);
        self.tris[tu] = [a, b, v];
        // Local edge 2 (opposite the new vertex) of each piece is an edge of the old triangle.
        self.neighbours[tu] = [t1, t2, nb[2]];
        self.edge_ref[tu] = [0, 0, er[2]];
        self.neighbours[t1 as usize] = [t2, t, NONE];
        self.edge_ref[t1 as usize] = [0, 0, er[0]];
        self.neighbours[t2 as usize] = [t, t1, NONE];
        self.edge_ref[t2 as usize] = [0, 0, er[1]];
        let (j0, j1) = (
            self.mirror_or_zero(tu, nb[0]),
            self.mirror_or_zero(tu, nb[1]),
        );
        self.link(t1, 2, nb[0], j0);
        self.link(t2, 2, nb[1], j1);
        l.triangle_changed(t, self.tris[tu]);
        self.vert_tri[v as usize] = t;
        if self.vert_tri[c as usize] == t {
            self.vert_tri[c as usize] = t1;
        }
        [t1, t2]
    }

    /// Flips local edge `i` of triangle `t`: with `t = (c, a, b)` and `(d, b, a)` the triangle
    /// `t2` across the edge, `t` becomes `(c, a, d)` and `t2` becomes `(d, b, c)` (both keep
    /// their slots). Returns `t2`. The caller checks that the edge is interior and unlabelled
    /// and that the quadrilateral is convex.
    pub fn flip_edge(&mut self, t: u32, i: usize, l: &mut impl EditListener) -> u32 {
        let tu = t as usize;
        let t2 = self.neighbours[tu][i];
        let t2u = t2 as usize;
        let tri = self.tris[tu];
        let (c, a, b) = (tri[i], tri[next(i)], tri[prev(i)]);
        let j = self.mirror_edge(tu, t2u).unwrap_or(0);
        let d = self.tris[t2u][j];
        let (nb1, rf1) = (self.neighbours[tu], self.edge_ref[tu]);
        let (nb2, rf2) = (self.neighbours[t2u], self.edge_ref[t2u]);
        let (n_bc, r_bc, n_ca, r_ca) = (nb1[next(i)], rf1[next(i)], nb1[prev(i)], rf1[prev(i)]);
        let (n_ad, r_ad, n_db, r_db) = (nb2[next(j)], rf2[next(j)], nb2[prev(j)], rf2[prev(j)]);
        let j_ad = self.mirror_or_zero(t2u, n_ad);
        let j_bc = self.mirror_or_zero(tu, n_bc);
        self.tris[tu] = [c, a, d];
        self.tris[t2u] = [d, b, c];
        self.edge_ref[tu] = [r_ad, 0, r_ca];
        self.edge_ref[t2u] = [r_bc, 0, r_db];
        self.neighbours[tu] = [NONE, t2, n_ca];
        self.neighbours[t2u] = [NONE, t, n_db];
        self.link(t, 0, n_ad, j_ad);
        self.link(t2, 0, n_bc, j_bc);
        if self.vert_tri[a as usize] == t2 {
            self.vert_tri[a as usize] = t;
        }
        if self.vert_tri[b as usize] == t {
            self.vert_tri[b as usize] = t2;
        }
        l.triangle_changed(t, self.tris[tu]);
        l.triangle_changed(t2, self.tris[t2u]);
        t2
    }
}
