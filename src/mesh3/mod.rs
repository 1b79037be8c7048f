//! Tetrahedral meshes (3D), used by the redistancing work (003 §8) and the tetrahedral
//! adaptation (004 §5).
//!
//! - [`Mesh3`]: points and positively oriented tetrahedra, face neighbours, sub-domain and
//!   boundary face labels (`topology.rs`), [`Mesh3::check`], vertex-to-vertex adjacency.
//! - [`Mesh3::kuhn_box`]: the structured Kuhn (Freudenthal) subdivision of a box, 6 tetrahedra per
//!   cube (`kuhn.rs`).
//! - [`Mesh3::refine`]: conforming local refinement by newest-vertex bisection (Maubach's tagged
//!   bisection, compatible with the Kuhn mesh) with closure (`bisect.rs`).
//! - [`EditMesh3`]: the editable form (vertex balls, boundary triangles with labels, tombstones;
//!   `edit.rs`) and its local edits (`ops.rs`): edge split, edge collapse with the link
//!   condition and the boundary rules, face 2-3 swap, edge removal n → 2n − 4, vertex move.
//! - [`hilbert_order`]: vertex order along a Hilbert curve (`hilbert.rs`).
//! - [`Features3`]: ridges and corners of the boundary, found from labels and angles or read
//!   from a file, kept by the edits (`features.rs`).

mod bisect;
mod check;
pub mod edit;
mod features;
mod hilbert;
mod kuhn;
mod ops;
mod topology;

pub use edit::{EditMesh3, VertexKind};
pub use features::{edge_key, DeclaredFeatures3, Features3, DEFAULT_RIDGE_ANGLE};
pub use hilbert::hilbert_order;
pub use ops::MAX_RING;

use crate::geom::DVec3;

/// A conforming tetrahedral mesh. `tets[t]` is positively oriented (positive signed volume).
///
/// Conventions (those of `Mesh2`): local face `i` of tetrahedron `t` is the face opposite local
/// vertex `i`; `neighbours[t][i]` is the tetrahedron across it, or [`crate::mesh::NONE`] on the
/// boundary; `face_ref[t][i]` is its label (0 = unlabelled; boundary faces default to 1, an
/// interior face has the same label seen from both sides); `tet_ref[t]` is the sub-domain label.
///
/// `maubach[t]` is the vertex order and tag of tetrahedron `t` used by newest-vertex bisection
/// (the refinement edge is `order[0]–order[tag]`); it is the same vertex set as `tets[t]`, possibly
/// in another order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh3 {
    /// Vertex coordinates.
    pub points: Vec<DVec3>,
    /// Vertex indices of each tetrahedron, positively oriented.
    pub tets: Vec<[u32; 4]>,
    /// The tetrahedron across local face `i`, or `NONE` on the boundary.
    pub neighbours: Vec<[u32; 4]>,
    /// Sub-domain label of each tetrahedron.
    pub tet_ref: Vec<i32>,
    /// Label of local face `i` of each tetrahedron (0 = unlabelled).
    pub face_ref: Vec<[i32; 4]>,
    /// Number of bisections from the initial (Kuhn) tetrahedron.
    pub generation: Vec<u8>,
    /// Ridges and corners of the boundary kept by the adaptation (none unless set, e.g. by
    /// [`Mesh3::detect_features`]).
    pub features: Features3,
    maubach: Vec<([u32; 4], u8)>,
}

/// Signed volume of the tetrahedron `(a, b, c, d)` (positive when `d` is on the side of
/// `(b - a) × (c - a)`).
#[inline]
pub fn signed_volume(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    crate::geom::simplex::volume(&[a, b, c, d])
}

impl Mesh3 {
    /// Number of vertices.
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    /// Number of tetrahedra.
    pub fn n_tets(&self) -> usize {
        self.tets.len()
    }

    /// The four corner points of tetrahedron `t`.
    pub fn tet_points(&self, t: usize) -> [DVec3; 4] {
        self.tets[t].map(|v| self.points[v as usize])
    }

    /// Signed volume of tetrahedron `t`.
    pub fn tet_volume(&self, t: usize) -> f64 {
        let [a, b, c, d] = self.tet_points(t);
        signed_volume(a, b, c, d)
    }

    /// Total volume.
    pub fn volume(&self) -> f64 {
        (0..self.n_tets()).map(|t| self.tet_volume(t)).sum()
    }

    /// Longest edge of tetrahedron `t`.
    pub fn tet_diameter(&self, t: usize) -> f64 {
        crate::geom::simplex::diameter(&self.tet_points(t))
    }

    /// Vertex-to-vertex adjacency in offset-plus-data form (`v2v`): the neighbours of `v` are
    /// `data[off[v]..off[v + 1]]`, sorted.
    pub fn v2v(&self) -> (Vec<usize>, Vec<u32>) {
        let mut nb: Vec<Vec<u32>> = vec![Vec::new(); self.n_points()];
        for t in &self.tets {
            for i in 0..4 {
                for j in 0..4 {
                    if i != j {
                        nb[t[i] as usize].push(t[j]);
                    }
                }
            }
        }
        let mut off = Vec::with_capacity(self.n_points() + 1);
        let mut data = Vec::new();
        off.push(0);
        for mut l in nb {
            l.sort_unstable();
            l.dedup();
            data.extend_from_slice(&l);
            off.push(data.len());
        }
        (off, data)
    }

    /// Builds a mesh from points and tetrahedra (each oriented positively by swapping two
    /// vertices where needed), with face neighbours, the given sub-domain labels and boundary
    /// faces labelled 1. The bisection order of each tetrahedron is its vertex order with tag 3.
    pub fn from_parts(points: Vec<DVec3>, tets: Vec<[u32; 4]>, tet_ref: Vec<i32>) -> Mesh3 {
        let n = tets.len();
        let mut m = Mesh3::from_maubach(
            points,
            tets.into_iter().map(|t| (t, 3)).collect(),
            vec![0; n],
        );
        m.tet_ref = tet_ref;
        m
    }

    /// Build from Maubach-ordered tetrahedra, orienting `tets` positively: face neighbours,
    /// sub-domain 0, boundary faces labelled 1.
    fn from_maubach(
        points: Vec<DVec3>,
        maubach: Vec<([u32; 4], u8)>,
        generation: Vec<u8>,
    ) -> Mesh3 {
        let n = maubach.len();
        let mut m = Mesh3 {
            points,
            tets: Vec::new(),
            neighbours: Vec::new(),
            tet_ref: vec![0; n],
            face_ref: vec![[0; 4]; n],
            generation,
            features: Features3::default(),
            maubach,
        };
        m.tets = m.maubach.iter().map(|(o, _)| m.oriented(*o)).collect();
        m.build_neighbours();
        m.label_boundary(|_, _| 1);
        m
    }

    fn oriented(&self, t: [u32; 4]) -> [u32; 4] {
        let p = t.map(|v| self.points[v as usize]);
        if signed_volume(p[0], p[1], p[2], p[3]) < 0.0 {
            [t[1], t[0], t[2], t[3]]
        } else {
            t
        }
    }
}

#[cfg(test)]
mod tests;
