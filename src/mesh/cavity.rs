//! Edits that remove a set of triangles and reconnect what is left: collapsing an edge (the
//! triangles on it disappear, their outer edges are glued) and filling a cavity with the star
//! of a vertex. Topology only, as the edits of `edit.rs`; the same [`EditListener`] hears them.

use super::edit::EditListener;
use super::{local_index_of, TriMesh, NONE};

/// An edge on the boundary of a cavity: from `u` to `w` with the cavity on its left, the
/// triangle `outside` across it with the edge's local index there (`outside == NONE` on the
/// mesh boundary), and its label.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CavityEdge {
    /// First vertex (counter-clockwise around the cavity).
    pub u: u32,
    /// Second vertex.
    pub w: u32,
    /// The triangle across the edge, or [`NONE`].
    pub outside: u32,
    /// The local index of the edge in `outside` (0 when `outside == NONE`).
    pub outside_edge: u8,
    /// The edge label.
    pub label: i32,
}

impl<P> TriMesh<P> {
    /// The boundary edges of the cavity made of the live triangles `cavity`, in the order of the
    /// cavity's triangles and their local edges. `None` if an adjacency is inconsistent.
    pub fn cavity_boundary(&self, cavity: &[u32]) -> Option<Vec<CavityEdge>> {
        let mut boundary = Vec::with_capacity(cavity.len() + 2);
        for &c in cavity {
            let c = c as usize;
            for e in 0..3 {
                let nb = self.neighbours[c][e];
                if nb != NONE && cavity.contains(&nb) {
                    continue;
                }
                let [u, w] = self.edge_vertices(c, e);
                let j = if nb != NONE {
                    self.mirror_edge(c, nb as usize)? as u8
                } else {
                    0
                };
                boundary.push(CavityEdge {
                    u,
                    w,
                    outside: nb,
                    outside_edge: j,
                    label: self.edge_ref[c][e],
                });
            }
        }
        Some(boundary)
    }

    /// Fills the cavity `cavity` (triangles to remove, with sub-domain label that of
    /// `cavity[0]`) with the star of the isolated vertex `v`: one triangle `(v, u, w)` on each of
    /// its `boundary` edges ([`TriMesh::cavity_boundary`]). The cavity must be a topological disc
    /// without interior vertices: `cavity.len() + 2` boundary edges forming one loop with
    /// distinct vertices. The cavity's slots are reused in order and the rest appended; returns
    /// the star's triangles in the order of `boundary`. Seeds: every boundary vertex `u` gets the
    /// star triangle starting at it, `v` the first one.
    pub fn fill_cavity(
        &mut self,
        v: u32,
        cavity: &[u32],
        boundary: &[CavityEdge],
        l: &mut impl EditListener,
    ) -> Vec<u32> {
        let tref = self.tri_ref[cavity[0] as usize];
        let mut slots: Vec<u32> = cavity.to_vec();
        while slots.len() < boundary.len() {
            let t = self.push_tri([v, v, v], tref, l);
            slots.push(t);
        }
        for (k, e) in boundary.iter().enumerate() {
            let t = slots[k];
            let tu = t as usize;
            self.tris[tu] = [v, e.u, e.w];
            self.tri_ref[tu] = tref;
            self.edge_ref[tu] = [e.label, 0, 0];
            self.neighbours[tu] = [NONE; 3];
            l.triangle_changed(t, self.tris[tu]);
            self.link(t, 0, e.outside, e.outside_edge as usize);
            self.vert_tri[e.u as usize] = t;
        }
        // Star adjacency: (v, u, w) meets the triangle starting at w across edge (w, v), local 1,
        // whose local 2 is edge (v, w).
        for k in 0..boundary.len() {
            let w = boundary[k].w;
            if let Some(k2) = boundary.iter().position(|e| e.u == w) {
                self.link(slots[k], 1, slots[k2], 2);
            }
        }
        slots.truncate(boundary.len());
        self.vert_tri[v as usize] = slots[0];
        slots
    }

    /// Collapses vertex `a` onto its neighbour `b`, with `fan` the triangles around `a` in the
    /// order of [`TriMesh::vertex_fan`]: the (one or two) triangles holding the edge `(a, b)`
    /// are deleted and their two outer edges glued (keeping a boundary label, else a curve
    /// label of either), and `a` is replaced by `b` in the rest of its fan. `a` is left isolated.
    /// The caller checks validity (link condition, orientation, labels).
    pub fn collapse_edge(&mut self, a: u32, b: u32, fan: &[u32], l: &mut impl EditListener) {
        let mut survivor = NONE;
        let mut fixups: [(u32, u32); 2] = [(NONE, NONE); 2];
        let mut nfix = 0;
        for &t in fan {
            let tu = t as usize;
            let tri = self.tris[tu];
            if !tri.contains(&b) {
                continue;
            }
            let ia = local_index_of(tri, a);
            let ib = local_index_of(tri, b);
            let ic = 3 - ia - ib;
            let c = tri[ic];
            let (n_ac, r_ac) = (self.neighbours[tu][ib], self.edge_ref[tu][ib]);
            let (n_bc, r_bc) = (self.neighbours[tu][ia], self.edge_ref[tu][ia]);
            let r = if n_ac == NONE {
                r_ac
            } else if n_bc == NONE {
                r_bc
            } else if r_ac != 0 {
                r_ac
            } else {
                r_bc
            };
            let j_ac = if n_ac != NONE {
                self.mirror_edge(tu, n_ac as usize)
            } else {
                None
            };
            let j_bc = if n_bc != NONE {
                self.mirror_edge(tu, n_bc as usize)
            } else {
                None
            };
            if let Some(j) = j_ac {
                self.neighbours[n_ac as usize][j] = n_bc;
                self.edge_ref[n_ac as usize][j] = r;
                l.triangle_changed(n_ac, self.tris[n_ac as usize]);
            }
            if let Some(j) = j_bc {
                self.neighbours[n_bc as usize][j] = n_ac;
                self.edge_ref[n_bc as usize][j] = r;
                l.triangle_changed(n_bc, self.tris[n_bc as usize]);
            }
            // Seeds for c and b: a surviving neighbour that holds them.
            let keep = if n_bc != NONE { n_bc } else { n_ac };
            if nfix < 2 {
                fixups[nfix] = (c, keep);
                nfix += 1;
            }
            if n_bc != NONE {
                survivor = n_bc;
            }
            self.tris[tu] = [NONE; 3];
            self.neighbours[tu] = [NONE; 3];
            l.triangle_removed(t);
        }
        for &t in fan {
            let tu = t as usize;
            if self.tris[tu][0] == NONE {
                continue;
            }
            let ia = local_index_of(self.tris[tu], a);
            self.tris[tu][ia] = b;
            l.triangle_changed(t, self.tris[tu]);
            survivor = t;
        }
        self.vert_tri[a as usize] = NONE;
        self.vert_tri[b as usize] = survivor;
        for &(c, keep) in &fixups[..nfix] {
            let s = self.vert_tri[c as usize];
            if s == NONE || self.tris[s as usize][0] == NONE {
                self.vert_tri[c as usize] = keep;
            }
        }
    }
}
