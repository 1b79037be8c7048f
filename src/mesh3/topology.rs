//! Face adjacency and labels of [`Mesh3`]: the tetrahedron across each face, sub-domain labels
//! and boundary face labels, with the same conventions as `Mesh2` (local face `i` is the face
//! opposite local vertex `i`; [`NONE`] across the boundary; label 0 = unlabelled).
//!
//! Topology only: nothing here looks at coordinates.

use std::collections::HashMap;

use super::Mesh3;
use crate::mesh::NONE;

impl Mesh3 {
    /// The three vertices of local face `i` of tetrahedron `t` (the face opposite local vertex
    /// `i`), in local order.
    #[inline]
    pub fn face_vertices(&self, t: usize, i: usize) -> [u32; 3] {
        let v = self.tets[t];
        let mut f = [0u32; 3];
        let mut k = 0;
        for (j, &x) in v.iter().enumerate() {
            if j != i {
                f[k] = x;
                k += 1;
            }
        }
        f
    }

    /// The vertices of local face `i` of `t`, sorted (the face's identity).
    #[inline]
    pub fn face_key(&self, t: usize, i: usize) -> [u32; 3] {
        let mut f = self.face_vertices(t, i);
        f.sort_unstable();
        f
    }

    /// The local face of tetrahedron `n` that is face `i` of `t`, if they share it.
    pub fn mirror_face(&self, t: usize, i: usize, n: usize) -> Option<usize> {
        let key = self.face_key(t, i);
        (0..4).find(|&j| self.face_key(n, j) == key)
    }

    /// The boundary faces `(t, i)` (no tetrahedron across), in tetrahedron order.
    pub fn boundary_faces(&self) -> impl Iterator<Item = (usize, usize)> + '_ {
        (0..self.n_tets()).flat_map(move |t| {
            (0..4)
                .filter(move |&i| self.neighbours[t][i] == NONE)
                .map(move |i| (t, i))
        })
    }

    /// Recomputes [`Mesh3::neighbours`] from `tets` (faces matched by their sorted vertices). A
    /// face shared by more than two tetrahedra keeps the first pairing; [`Mesh3::check`] reports it.
    pub(crate) fn build_neighbours(&mut self) {
        let mut nbr = vec![[NONE; 4]; self.tets.len()];
        let mut open: HashMap<[u32; 3], (u32, u8)> = HashMap::with_capacity(2 * self.tets.len());
        for t in 0..self.tets.len() {
            for i in 0..4 {
                let key = self.face_key(t, i);
                match open.remove(&key) {
                    Some((s, j)) => {
                        nbr[t][i] = s;
                        nbr[s as usize][j as usize] = t as u32;
                    }
                    None => {
                        open.insert(key, (t as u32, i as u8));
                    }
                }
            }
        }
        self.neighbours = nbr;
    }

    /// Sets the label of every boundary face to `label(mesh, face vertices)`.
    pub fn label_boundary(&mut self, label: impl Fn(&Mesh3, [u32; 3]) -> i32) {
        let faces: Vec<(usize, usize)> = self.boundary_faces().collect();
        for (t, i) in faces {
            let l = label(self, self.face_vertices(t, i));
            self.face_ref[t][i] = l;
        }
    }
}
