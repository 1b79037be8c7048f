//! Sharp features of a tetrahedral mesh's boundary: ridges and corners, found from the boundary
//! triangles (their labels and the angle between their normals, as `mmg3d -ar`) and from the
//! features a Medit file declares (`Edges`, `Ridges`, `RequiredEdges`, `Corners`,
//! `RequiredVertices`).
//!
//! - A **ridge** is a boundary edge between two boundary triangles with different labels, or
//!   whose outward normals make an angle above the ridge angle (45° by default, mmg3d's `-ar`
//!   default), or an edge on three or more boundary triangles, or an edge the file declares.
//! - A **corner** is a vertex on one ridge or on three or more (a ridge end or a meeting point),
//!   a vertex where its two ridges turn by more than the ridge angle, or a vertex the file
//!   declares a corner or required.
//!
//! [`Features3`] is kept on [`Mesh3::features`]; the editable mesh ([`super::EditMesh3`])
//! carries it through its edits: a split ridge edge gives two ridge edges, a ridge vertex is
//! removed only by a collapse along its ridge where the ridge is straight, ridge vertices and
//! corners do not move. Together with the rules for faces (boundary triangles keep their
//! plane), the boundary of a polyhedral domain, its ridges and its corners are kept exactly.

use std::collections::{HashMap, HashSet};

use super::Mesh3;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::DVec3;

/// mmg3d's default ridge angle (`-ar`), in degrees.
pub const DEFAULT_RIDGE_ANGLE: f64 = 45.0;

/// The ridges and corners of a mesh's boundary (module documentation). Indices are 0-based.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Features3 {
    /// Ridge edges, each with its smaller vertex first, sorted.
    pub ridges: Vec<[u32; 2]>,
    /// Corner vertices (never moved nor removed), sorted.
    pub corners: Vec<u32>,
}

/// The features a file declares (0-based vertex indices): edges (Medit `Edges`, whether or not
/// listed in `Ridges` or `RequiredEdges`), corners (`Corners`) and required vertices
/// (`RequiredVertices`).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct DeclaredFeatures3 {
    /// Declared edges.
    pub edges: Vec<[u32; 2]>,
    /// Declared corners.
    pub corners: Vec<u32>,
    /// Declared required vertices.
    pub required: Vec<u32>,
}

/// An edge with its smaller vertex first.
#[inline]
pub fn edge_key(a: u32, b: u32) -> [u32; 2] {
    [a.min(b), a.max(b)]
}

impl Features3 {
    /// Whether there is no ridge and no corner.
    pub fn is_empty(&self) -> bool {
        self.ridges.is_empty() && self.corners.is_empty()
    }

    /// The ridges as segments between points of `points`.
    pub fn segments(&self, points: &[DVec3]) -> Vec<[DVec3; 2]> {
        self.ridges
            .iter()
            .map(|e| e.map(|v| points[v as usize]))
            .collect()
    }
}

impl Mesh3 {
    /// The ridges and corners of the boundary with the ridge angle `angle_deg` (degrees, in
    /// `[0, 180]`) and the features of `declared` (module documentation). Errors: an angle
    /// out of range, a declared vertex out of range, a declared edge that is not an edge of a
    /// boundary triangle (named with 1-based vertices).
    pub fn detect_features(
        &self,
        angle_deg: f64,
        declared: &DeclaredFeatures3,
    ) -> Result<Features3> {
        if !(0.0..=180.0).contains(&angle_deg) {
            return Err(Error::InvalidInput(format!(
                "ridge angle {angle_deg}: expected 0 to 180 degrees"
            )));
        }
        let n = self.n_points();
        let cos_max = angle_deg.to_radians().cos();
        // Boundary edges with the (label, outward unit normal) of their triangles.
        let mut edges: HashMap<[u32; 2], Vec<(i32, DVec3)>> = HashMap::new();
        for (t, i) in self.boundary_faces() {
            let f = self.face_vertices(t, i);
            let [a, b, c] = f.map(|v| self.points[v as usize]);
            let inward = self.points[self.tets[t][i] as usize] - a;
            let mut nrm = (b - a).cross(c - a).normalize_or_zero();
            if nrm.dot(inward) > 0.0 {
                nrm = -nrm;
            }
            for (x, y) in [(f[0], f[1]), (f[1], f[2]), (f[0], f[2])] {
                edges
                    .entry(edge_key(x, y))
                    .or_default()
                    .push((self.face_ref[t][i], nrm));
            }
        }
        let mut ridges: HashSet<[u32; 2]> = edges
            .iter()
            .filter(|(_, fs)| match fs.as_slice() {
                [(l0, n0), (l1, n1)] => l0 != l1 || n0.dot(*n1) < cos_max,
                _ => true,
            })
            .map(|(&e, _)| e)
            .collect();
        let in_range = |v: u32, what: &str| {
            if (v as usize) < n {
                Ok(v)
            } else {
                Err(Error::InvalidInput(format!(
                    "{what} refers to vertex {} beyond the {n} vertices",
                    v as u64 + 1
                )))
            }
        };
        for &[a, b] in &declared.edges {
            in_range(a, "a declared edge")?;
            in_range(b, "a declared edge")?;
            let e = edge_key(a, b);
            if !edges.contains_key(&e) {
                return Err(Error::InvalidInput(format!(
                    "declared edge ({}, {}) is not an edge of a boundary triangle",
                    a as u64 + 1,
                    b as u64 + 1
                )));
            }
            ridges.insert(e);
        }
        let mut ridges: Vec<[u32; 2]> = ridges.into_iter().collect();
        ridges.sort_unstable();
        let mut nb: Vec<Vec<u32>> = vec![Vec::new(); n];
        for &[a, b] in &ridges {
            nb[a as usize].push(b);
            nb[b as usize].push(a);
        }
        let mut corner = vec![false; n];
        for (v, w) in nb.iter().enumerate() {
            corner[v] = match w.as_slice() {
                [] => false,
                [x, y] => {
                    let p = self.points[v];
                    let (d0, d1) = (p - self.points[*x as usize], self.points[*y as usize] - p);
                    // The turn between the incoming and the outgoing direction.
                    d0.normalize_or_zero().dot(d1.normalize_or_zero()) < cos_max
                }
                _ => true,
            };
        }
        for &v in declared.corners.iter().chain(&declared.required) {
            corner[in_range(v, "a declared corner or required vertex")? as usize] = true;
        }
        let corners = (0..n as u32).filter(|&v| corner[v as usize]).collect();
        Ok(Features3 { ridges, corners })
    }

    /// The feature part of [`Mesh3::check`]: every ridge an edge of a boundary face (`faces`
    /// counts the tetrahedra of each face), every corner a vertex.
    pub(super) fn check_features(&self, faces: &HashMap<[u32; 3], u32>) -> Result<()> {
        let n = self.n_points();
        if let Some(&v) = self.features.corners.iter().find(|&&v| v as usize >= n) {
            return Err(MeshDefect::IndexOutOfRange {
                tri: 0,
                vertex: v as u64,
                n_points: n,
            }
            .into());
        }
        if self.features.ridges.is_empty() {
            return Ok(());
        }
        let mut bedges: HashSet<[u32; 2]> = HashSet::new();
        for (f, &c) in faces {
            if c == 1 {
                for (x, y) in [(f[0], f[1]), (f[1], f[2]), (f[0], f[2])] {
                    bedges.insert(edge_key(x, y));
                }
            }
        }
        for &[a, b] in &self.features.ridges {
            if !bedges.contains(&edge_key(a, b)) {
                return Err(MeshDefect::BadAdjacency {
                    tri: 0,
                    edge: 0,
                    detail: "a ridge is not an edge of a boundary triangle",
                }
                .into());
            }
        }
        Ok(())
    }

    /// Splits the ridges that [`Mesh3::refine`] bisected: `mid` maps an edge (smaller vertex
    /// first) to its midpoint vertex.
    pub(super) fn split_ridges(&mut self, mid: &HashMap<(u32, u32), u32>) {
        let mut todo = std::mem::take(&mut self.features.ridges);
        let mut out = Vec::with_capacity(todo.len());
        while let Some([a, b]) = todo.pop() {
            match mid.get(&(a, b)) {
                Some(&z) => {
                    todo.push(edge_key(a, z));
                    todo.push(edge_key(z, b));
                }
                None => out.push([a, b]),
            }
        }
        out.sort_unstable();
        self.features.ridges = out;
    }
}
