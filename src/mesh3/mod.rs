//! Tetrahedral meshes (3D), used by the redistancing work (003 §8).
//!
//! - [`Mesh3`]: points and positively oriented tetrahedra, [`Mesh3::check`], vertex-to-vertex
//!   adjacency.
//! - [`Mesh3::kuhn_box`]: the structured Kuhn (Freudenthal) subdivision of a box, 6 tetrahedra per
//!   cube (`kuhn.rs`).
//! - [`Mesh3::refine`]: conforming local refinement by newest-vertex bisection (Maubach's tagged
//!   bisection, compatible with the Kuhn mesh) with closure (`bisect.rs`).

mod bisect;
mod check;
mod kuhn;

use crate::geom::DVec3;

/// A conforming tetrahedral mesh. `tets[t]` is positively oriented (positive signed volume).
///
/// `maubach[t]` is the vertex order and tag of tetrahedron `t` used by newest-vertex bisection
/// (the refinement edge is `order[0]–order[tag]`); it is the same vertex set as `tets[t]`, possibly
/// in another order.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Mesh3 {
    pub points: Vec<DVec3>,
    pub tets: Vec<[u32; 4]>,
    /// Number of bisections from the initial (Kuhn) tetrahedron.
    pub generation: Vec<u8>,
    maubach: Vec<([u32; 4], u8)>,
}

/// Signed volume of the tetrahedron `(a, b, c, d)` (positive when `d` is on the side of
/// `(b - a) × (c - a)`).
#[inline]
pub fn signed_volume(a: DVec3, b: DVec3, c: DVec3, d: DVec3) -> f64 {
    (b - a).dot((c - a).cross(d - a)) / 6.0
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
        let p = self.tet_points(t);
        let mut h: f64 = 0.0;
        for i in 0..4 {
            for j in i + 1..4 {
                h = h.max((p[i] - p[j]).length());
            }
        }
        h
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

    /// Build from Maubach-ordered tetrahedra, orienting `tets` positively.
    fn from_maubach(
        points: Vec<DVec3>,
        maubach: Vec<([u32; 4], u8)>,
        generation: Vec<u8>,
    ) -> Mesh3 {
        let mut m = Mesh3 {
            points,
            tets: Vec::new(),
            generation,
            maubach,
        };
        m.tets = m.maubach.iter().map(|(o, _)| m.oriented(*o)).collect();
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
