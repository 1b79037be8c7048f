//! The invariant checker of [`Mesh3`].

use std::collections::{HashMap, HashSet};

use super::{signed_volume, Mesh3};
use crate::error::{Error, MeshDefect, Result};
use crate::mesh::NONE;

impl Mesh3 {
    /// Verify: indices in range, no repeated vertex, finite coordinates, positive volumes, every
    /// face shared by at most two tetrahedra, no hanging node (no vertex at the midpoint of an
    /// edge of a face that only one tetrahedron has), the bisection data in step with `tets`, and
    /// the face adjacency and labels: `neighbours` symmetric and sharing the face, `NONE` exactly
    /// on unshared faces, label arrays of the right length, an interior face labelled the same
    /// from both sides; every ridge an edge of a boundary face, every corner a vertex.
    pub fn check(&self) -> Result<()> {
        let n = self.points.len();
        if let Some(v) = self.points.iter().position(|p| !p.is_finite()) {
            return Err(MeshDefect::NonFiniteCoordinate { vertex: v }.into());
        }
        if self.maubach.len() != self.tets.len() || self.generation.len() != self.tets.len() {
            return Err(Error::InvalidMesh(MeshDefect::BadLabel {
                tri: self.tets.len(),
                detail: "bisection data and tetrahedra have different lengths",
            }));
        }
        let mut faces: HashMap<[u32; 3], u32> = HashMap::with_capacity(2 * self.tets.len());
        for (t, tet) in self.tets.iter().enumerate() {
            for &v in tet {
                if v as usize >= n {
                    return Err(MeshDefect::IndexOutOfRange {
                        tri: t,
                        vertex: v as u64,
                        n_points: n,
                    }
                    .into());
                }
            }
            let mut s = *tet;
            s.sort_unstable();
            if s.windows(2).any(|w| w[0] == w[1]) {
                return Err(MeshDefect::RepeatedVertex { tri: t }.into());
            }
            let mut m = self.maubach[t].0;
            m.sort_unstable();
            if m != s {
                return Err(Error::InvalidMesh(MeshDefect::BadLabel {
                    tri: t,
                    detail: "bisection order does not hold the tetrahedron's vertices",
                }));
            }
            let p = self.tet_points(t);
            let vol = signed_volume(p[0], p[1], p[2], p[3]);
            if vol <= 0.0 {
                return Err(MeshDefect::InvertedTriangle {
                    tri: t,
                    signed_area: vol,
                }
                .into());
            }
            for i in 0..4 {
                let mut f = [0u32; 3];
                let mut k = 0;
                for (j, &v) in tet.iter().enumerate() {
                    if j != i {
                        f[k] = v;
                        k += 1;
                    }
                }
                f.sort_unstable();
                let c = faces.entry(f).or_insert(0);
                *c += 1;
                if *c > 2 {
                    return Err(MeshDefect::NonManifoldEdge {
                        a: f[0] as usize,
                        b: f[1] as usize,
                    }
                    .into());
                }
            }
        }
        let key = |p: crate::geom::DVec3| [p.x.to_bits(), p.y.to_bits(), p.z.to_bits()];
        let at: HashSet<[u64; 3]> = self.points.iter().map(|&p| key(p)).collect();
        for (f, &c) in &faces {
            if c != 1 {
                continue;
            }
            for (a, b) in [(f[0], f[1]), (f[1], f[2]), (f[0], f[2])] {
                let m = 0.5 * (self.points[a as usize] + self.points[b as usize]);
                if at.contains(&key(m)) {
                    let v = self
                        .points
                        .iter()
                        .position(|&p| key(p) == key(m))
                        .unwrap_or(0);
                    return Err(MeshDefect::HangingVertex {
                        vertex: v,
                        a: a as usize,
                        b: b as usize,
                    }
                    .into());
                }
            }
        }
        self.check_topology(&faces)?;
        self.check_features(&faces)
    }

    /// The adjacency and label part of [`Mesh3::check`]; `faces` counts the tetrahedra of each
    /// face (sorted vertices).
    fn check_topology(&self, faces: &HashMap<[u32; 3], u32>) -> Result<()> {
        let nt = self.tets.len();
        let lengths = [
            (
                self.neighbours.len(),
                "neighbour array length differs from tetrahedron count",
            ),
            (
                self.tet_ref.len(),
                "sub-domain label array length differs from tetrahedron count",
            ),
            (
                self.face_ref.len(),
                "face label array length differs from tetrahedron count",
            ),
        ];
        for (len, detail) in lengths {
            if len != nt {
                return Err(MeshDefect::BadLabel {
                    tri: len.min(nt),
                    detail,
                }
                .into());
            }
        }
        for t in 0..nt {
            for i in 0..4 {
                let bad = |detail| -> Result<()> {
                    Err(MeshDefect::BadAdjacency {
                        tri: t,
                        edge: i,
                        detail,
                    }
                    .into())
                };
                let nb = self.neighbours[t][i];
                let shared = faces.get(&self.face_key(t, i)) == Some(&2);
                if nb == NONE {
                    if shared {
                        return bad("a face shared by two tetrahedra has no neighbour");
                    }
                    continue;
                }
                if nb as usize >= nt || nb as usize == t {
                    return bad("neighbour index out of range or the tetrahedron itself");
                }
                let Some(j) = self.mirror_face(t, i, nb as usize) else {
                    return bad("neighbour does not share this face");
                };
                if self.neighbours[nb as usize][j] != t as u32 {
                    return bad("neighbour does not point back (asymmetric adjacency)");
                }
                if self.face_ref[t][i] != self.face_ref[nb as usize][j] {
                    return Err(MeshDefect::BadLabel {
                        tri: t,
                        detail: "an interior face has different labels on its two sides",
                    }
                    .into());
                }
            }
        }
        Ok(())
    }
}
