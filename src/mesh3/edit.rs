//! [`EditMesh3`]: a tetrahedral mesh prepared for local edits (004 §3.5 operators in 3D).
//!
//! Tetrahedra live in a flat array with tombstones (a removed tetrahedron has all four
//! vertices [`NONE`]) until [`EditMesh3::compact`]; each vertex keeps its ball (the tetrahedra
//! that contain it), from which edge shells and face neighbours are found; boundary triangles
//! are kept by their sorted vertices with their labels. Ridges and corners are derived from the
//! boundary: a boundary vertex whose boundary triangles all lie in one plane with one label is a
//! *face* vertex, else it is a *feature* vertex (on a ridge or a corner); so are the vertices on
//! the ridges and the corners of [`Mesh3::features`], which the edits keep. The edits
//! (`ops.rs`) keep every invariant that [`EditMesh3::check`] verifies.

use std::collections::{HashMap, HashSet};

use super::Mesh3;
use crate::error::{Error, MeshDefect, Result};
use crate::geom::DVec3;
use crate::mesh::NONE;

/// The position of a vertex relative to the boundary.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum VertexKind {
    /// Not on the boundary.
    Interior,
    /// On the boundary, all its boundary triangles in the plane of this unit normal with one
    /// label: it may move in that plane.
    Face(DVec3),
    /// On a ridge or a corner (several planes or labels meet, or a ridge or corner of
    /// [`Mesh3::features`]): it does not move.
    Feature,
}

thread_local! {
    /// The mark of the current [`EditMesh3::vertex_neighbours`] call and, per vertex, the
    /// mark of the last call that listed it.
    static SEEN: std::cell::RefCell<(u32, Vec<u32>)> = const { std::cell::RefCell::new((0, Vec::new())) };
}

/// A tetrahedral mesh with vertex balls and boundary triangles, for local edits.
#[derive(Debug, Clone, Default)]
pub struct EditMesh3 {
    /// Vertex coordinates (removed vertices keep their slot, with an empty ball).
    pub points: Vec<DVec3>,
    /// Vertex indices of each tetrahedron, positively oriented; `[NONE; 4]` once removed.
    pub tets: Vec<[u32; 4]>,
    /// Sub-domain label of each tetrahedron.
    pub tet_ref: Vec<i32>,
    /// The tetrahedra containing each vertex (unordered).
    pub ball: Vec<Vec<u32>>,
    /// Boundary triangles by sorted vertices, with their labels.
    pub bfaces: HashMap<[u32; 3], i32>,
    /// Whether each vertex lies on the boundary (on a boundary triangle).
    pub on_boundary: Vec<bool>,
    /// Ridge edges (smaller vertex first), from [`Mesh3::features`].
    pub ridges: HashSet<[u32; 2]>,
    /// Per vertex: the number of ridges on it.
    pub ridge_count: Vec<u8>,
    /// Per vertex: whether it is a corner (fixed).
    pub fixed: Vec<bool>,
    /// Removed tetrahedron slots, reused by later edits.
    pub(super) free: Vec<u32>,
    /// A value cached per tetrahedron slot by the caller (the adaptation keeps its quality
    /// there), `NaN` when unknown: every edit that adds or removes a tetrahedron, or moves one
    /// of its vertices, resets it, so a value that is not `NaN` belongs to the current
    /// tetrahedron with its current vertex positions.
    pub cache: Vec<f64>,
    /// Per tetrahedron slot: the value of [`EditMesh3::now`] when the tetrahedron was created
    /// or one of its vertices last moved, so that a caller can tell which tetrahedra changed
    /// since a given time.
    pub tet_stamp: Vec<u32>,
    /// The current time of the edits, set by the caller (the adaptation sets its pass number).
    pub now: u32,
}

/// `p` projected onto the plane through `p0` with unit normal `n`. Where the plane is
/// perpendicular to a coordinate axis (the other two normal components below 1e-14), that
/// coordinate is copied from `p0`, so a vertex of an axis-aligned face stays exactly in the
/// plane however often it moves (a plain projection leaves rounding residues such as 1e-20
/// that make the vertex's tetrahedra with a ridge slightly off the plane).
#[inline]
pub fn onto_plane(p0: DVec3, n: DVec3, p: DVec3) -> DVec3 {
    let mut q = p - n * (p - p0).dot(n);
    match plane_axis(n) {
        Some(0) => q.x = p0.x,
        Some(1) => q.y = p0.y,
        Some(_) => q.z = p0.z,
        None => {}
    }
    q
}

/// The coordinate axis a unit normal `n` points along (its other two components below
/// 1e-14), if any.
#[inline]
fn plane_axis(n: DVec3) -> Option<usize> {
    let a = n.abs();
    if a.y < 1e-14 && a.z < 1e-14 {
        Some(0)
    } else if a.x < 1e-14 && a.z < 1e-14 {
        Some(1)
    } else if a.x < 1e-14 && a.y < 1e-14 {
        Some(2)
    } else {
        None
    }
}

/// Whether `p` lies in the plane through `p0` with unit normal `n`: exactly for a plane
/// perpendicular to a coordinate axis (see [`onto_plane`]), to 1e-12 relative otherwise.
#[inline]
pub fn in_plane(p0: DVec3, n: DVec3, p: DVec3) -> bool {
    match plane_axis(n) {
        Some(k) => p[k] == p0[k],
        None => {
            let d = p - p0;
            d.dot(n).abs() <= 1e-12 * (1.0 + d.length())
        }
    }
}

/// The sorted vertices of a triangle.
#[inline]
pub fn sorted3(mut f: [u32; 3]) -> [u32; 3] {
    f.sort_unstable();
    f
}

/// The face of tetrahedron `t` opposite its local vertex `i`.
#[inline]
pub fn tet_face(t: &[u32; 4], i: usize) -> [u32; 3] {
    match i {
        0 => [t[1], t[2], t[3]],
        1 => [t[0], t[2], t[3]],
        2 => [t[0], t[1], t[3]],
        _ => [t[0], t[1], t[2]],
    }
}

impl EditMesh3 {
    /// Builds the editable form of `m`: its tetrahedra and labels, the balls, and the boundary
    /// triangles with their labels (faces between two tetrahedra are interior and not kept).
    pub fn from_mesh(m: &Mesh3) -> Result<EditMesh3> {
        m.check()?;
        let mut e = EditMesh3 {
            points: m.points.clone(),
            tets: m.tets.clone(),
            tet_ref: m.tet_ref.clone(),
            ball: vec![Vec::new(); m.n_points()],
            bfaces: HashMap::new(),
            on_boundary: vec![false; m.n_points()],
            ridges: m.features.ridges.iter().copied().collect(),
            ridge_count: vec![0; m.n_points()],
            fixed: vec![false; m.n_points()],
            free: Vec::new(),
            cache: vec![f64::NAN; m.n_tets()],
            tet_stamp: vec![0; m.n_tets()],
            now: 0,
        };
        for r in &e.ridges {
            for &v in r {
                e.ridge_count[v as usize] = e.ridge_count[v as usize].saturating_add(1);
            }
        }
        for &v in &m.features.corners {
            e.fixed[v as usize] = true;
        }
        for (t, tet) in m.tets.iter().enumerate() {
            for &v in tet {
                e.ball[v as usize].push(t as u32);
            }
            for i in 0..4 {
                if m.neighbours[t][i] == NONE {
                    let f = tet_face(tet, i);
                    for v in f {
                        e.on_boundary[v as usize] = true;
                    }
                    e.bfaces.insert(sorted3(f), m.face_ref[t][i]);
                }
            }
        }
        if e.bfaces.is_empty() && !e.tets.is_empty() {
            return Err(Error::InvalidInput(
                "a tetrahedral mesh without boundary triangles".into(),
            ));
        }
        Ok(e)
    }

    /// The compacted [`Mesh3`] (live vertices and tetrahedra, renumbered in their order), with
    /// face neighbours, sub-domain labels and boundary face labels; also returns the old index
    /// of each new vertex.
    pub fn to_mesh(&self) -> (Mesh3, Vec<u32>) {
        let (map, old) = self.live_vertex_map();
        let mut tets = Vec::new();
        let mut tet_ref = Vec::new();
        for (t, tet) in self.tets.iter().enumerate() {
            if tet[0] != NONE {
                tets.push(tet.map(|v| map[v as usize]));
                tet_ref.push(self.tet_ref[t]);
            }
        }
        let points = old.iter().map(|&v| self.points[v as usize]).collect();
        let mut m = Mesh3::from_parts(points, tets, tet_ref);
        for t in 0..m.n_tets() {
            for i in 0..4 {
                if m.neighbours[t][i] == NONE {
                    let f = sorted3(tet_face(&m.tets[t], i).map(|v| old[v as usize]));
                    m.face_ref[t][i] = self.bfaces.get(&f).copied().unwrap_or(1);
                }
            }
        }
        let mut ridges: Vec<[u32; 2]> = self
            .ridges
            .iter()
            .map(|&[a, b]| super::edge_key(map[a as usize], map[b as usize]))
            .collect();
        ridges.sort_unstable();
        m.features.ridges = ridges;
        m.features.corners = (0..old.len() as u32)
            .filter(|&v| self.fixed[old[v as usize] as usize])
            .collect();
        (m, old)
    }

    /// For every vertex slot its new index among the live vertices (`NONE` if removed), and
    /// the old index of every live vertex.
    pub fn live_vertex_map(&self) -> (Vec<u32>, Vec<u32>) {
        let mut map = vec![NONE; self.points.len()];
        let mut old = Vec::new();
        for (v, b) in self.ball.iter().enumerate() {
            if !b.is_empty() {
                map[v] = old.len() as u32;
                old.push(v as u32);
            }
        }
        (map, old)
    }

    /// Whether vertex `v` is live (in at least one tetrahedron).
    #[inline]
    pub fn alive(&self, v: u32) -> bool {
        !self.ball[v as usize].is_empty()
    }

    /// Number of live tetrahedra.
    pub fn n_live_tets(&self) -> usize {
        self.tets.len() - self.free.len()
    }

    /// Number of live vertices.
    pub fn n_live_vertices(&self) -> usize {
        self.ball.iter().filter(|b| !b.is_empty()).count()
    }

    /// The neighbours of `v` (vertices sharing a tetrahedron with it), sorted.
    pub fn vertex_neighbours(&self, v: u32, out: &mut Vec<u32>) {
        out.clear();
        // An interior vertex has about half as many neighbours as ball tetrahedra: one
        // allocation for a fresh buffer instead of a few reallocations.
        out.reserve(self.ball[v as usize].len() + 4);
        // Each neighbour appears in about five tetrahedra of the ball: the first occurrence is
        // kept by a per-thread mark per vertex, so only the distinct ones are sorted.
        SEEN.with_borrow_mut(|(mark, seen)| {
            *mark = mark.wrapping_add(1);
            if *mark == 0 {
                seen.fill(0);
                *mark = 1;
            }
            if seen.len() < self.points.len() {
                seen.resize(self.points.len(), 0);
            }
            seen[v as usize] = *mark;
            for &t in &self.ball[v as usize] {
                for w in self.tets[t as usize] {
                    if seen[w as usize] != *mark {
                        seen[w as usize] = *mark;
                        out.push(w);
                    }
                }
            }
        });
        out.sort_unstable();
    }

    /// The tetrahedra containing the edge `(a, b)` (its shell), in ball order.
    pub fn shell(&self, a: u32, b: u32, out: &mut Vec<u32>) {
        out.clear();
        out.extend(
            self.ball[a as usize]
                .iter()
                .copied()
                .filter(|&t| self.tets[t as usize].contains(&b)),
        );
    }

    /// The tetrahedra containing the triangle `f` (one or two in a valid mesh).
    pub fn face_tets(&self, f: [u32; 3]) -> Vec<u32> {
        self.ball[f[0] as usize]
            .iter()
            .copied()
            .filter(|&t| {
                let tet = &self.tets[t as usize];
                tet.contains(&f[1]) && tet.contains(&f[2])
            })
            .collect()
    }

    /// The two tetrahedra on the triangle `f`, or `None` when it is not an interior face.
    pub fn face_pair(&self, f: [u32; 3]) -> Option<[u32; 2]> {
        let mut out = [0u32; 2];
        let mut n = 0;
        // Scan the smallest of the three balls.
        let mut k = 0;
        for i in 1..3 {
            if self.ball[f[i] as usize].len() < self.ball[f[k] as usize].len() {
                k = i;
            }
        }
        let (x, y) = (f[(k + 1) % 3], f[(k + 2) % 3]);
        for &t in &self.ball[f[k] as usize] {
            let tet = &self.tets[t as usize];
            if tet.contains(&x) && tet.contains(&y) {
                if n == 2 {
                    return None;
                }
                out[n] = t;
                n += 1;
            }
        }
        (n == 2).then_some(out)
    }

    /// Whether `(a, b)` is an edge of a boundary triangle.
    pub fn is_boundary_edge(&self, a: u32, b: u32) -> bool {
        self.ball[a as usize].iter().any(|&t| {
            let tet = &self.tets[t as usize];
            tet.contains(&b)
                && tet
                    .iter()
                    .any(|&c| c != a && c != b && self.bfaces.contains_key(&sorted3([a, b, c])))
        })
    }

    /// The boundary triangles containing `v`, with their labels.
    pub fn vertex_bfaces(&self, v: u32, out: &mut Vec<([u32; 3], i32)>) {
        out.clear();
        for &t in &self.ball[v as usize] {
            let tet = self.tets[t as usize];
            for i in 0..4 {
                if tet[i] == v {
                    continue;
                }
                let f = sorted3(tet_face(&tet, i));
                if let Some(&l) = self.bfaces.get(&f) {
                    out.push((f, l));
                }
            }
        }
        out.sort_unstable();
        out.dedup();
    }

    /// The unit normal of the triangle `f` (by its sorted vertex order: only the direction
    /// up to sign matters to the callers).
    pub fn face_normal(&self, f: [u32; 3]) -> DVec3 {
        let [a, b, c] = f.map(|v| self.points[v as usize]);
        (b - a).cross(c - a).normalize_or_zero()
    }

    /// Where `v` lies relative to the boundary ([`VertexKind`]).
    pub fn vertex_kind(&self, v: u32) -> VertexKind {
        if self.fixed[v as usize] || self.ridge_count[v as usize] > 0 {
            return VertexKind::Feature;
        }
        if !self.on_boundary[v as usize] {
            return VertexKind::Interior;
        }
        let mut fs = Vec::new();
        self.vertex_bfaces(v, &mut fs);
        let Some(&(f0, l0)) = fs.first() else {
            return VertexKind::Interior;
        };
        let n0 = self.face_normal(f0);
        let planar = fs
            .iter()
            .all(|&(f, l)| l == l0 && self.face_normal(f).cross(n0).length() < 1e-9);
        if planar {
            VertexKind::Face(n0)
        } else {
            VertexKind::Feature
        }
    }

    /// Stores a new tetrahedron (reusing a free slot) and adds it to its vertices' balls.
    pub(super) fn add_tet(&mut self, tet: [u32; 4], r: i32) -> u32 {
        let t = match self.free.pop() {
            Some(t) => {
                self.tets[t as usize] = tet;
                self.tet_ref[t as usize] = r;
                self.cache[t as usize] = f64::NAN;
                self.tet_stamp[t as usize] = self.now;
                t
            }
            None => {
                self.tets.push(tet);
                self.tet_ref.push(r);
                self.cache.push(f64::NAN);
                self.tet_stamp.push(self.now);
                (self.tets.len() - 1) as u32
            }
        };
        for v in tet {
            self.ball[v as usize].push(t);
        }
        t
    }

    /// Removes tetrahedron `t` from its vertices' balls and frees its slot.
    pub(super) fn remove_tet(&mut self, t: u32) {
        let tet = self.tets[t as usize];
        for v in tet {
            let b = &mut self.ball[v as usize];
            if let Some(k) = b.iter().position(|&x| x == t) {
                b.swap_remove(k);
            }
        }
        self.tets[t as usize] = [NONE; 4];
        self.cache[t as usize] = f64::NAN;
        self.free.push(t);
    }

    /// Adds a vertex at `p` (empty ball until a tetrahedron uses it).
    pub(super) fn add_vertex(&mut self, p: DVec3) -> u32 {
        self.points.push(p);
        self.ball.push(Vec::new());
        self.on_boundary.push(false);
        self.ridge_count.push(0);
        self.fixed.push(false);
        (self.points.len() - 1) as u32
    }

    /// Drops removed tetrahedra and vertices and renumbers the vertices in the order `order`
    /// (a permutation of the live vertices, e.g. along a space-filling curve; `None` keeps
    /// their order). Returns the old index of every new vertex.
    pub fn compact(&mut self, order: Option<&[u32]>) -> Vec<u32> {
        let old: Vec<u32> = match order {
            Some(o) => o.to_vec(),
            None => self.live_vertex_map().1,
        };
        let mut map = vec![NONE; self.points.len()];
        for (i, &v) in old.iter().enumerate() {
            map[v as usize] = i as u32;
        }
        let mut live: Vec<(u32, [u32; 4], i32, u32)> = Vec::with_capacity(self.n_live_tets());
        for (t, tet) in self.tets.iter().enumerate() {
            if tet[0] != NONE {
                let nt = tet.map(|v| map[v as usize]);
                let key = *nt.iter().min().unwrap_or(&0);
                live.push((key, nt, self.tet_ref[t], self.tet_stamp[t]));
            }
        }
        live.sort_by_key(|x| x.0);
        self.points = old.iter().map(|&v| self.points[v as usize]).collect();
        self.on_boundary = old.iter().map(|&v| self.on_boundary[v as usize]).collect();
        self.ridge_count = old.iter().map(|&v| self.ridge_count[v as usize]).collect();
        self.fixed = old.iter().map(|&v| self.fixed[v as usize]).collect();
        self.ridges = self
            .ridges
            .iter()
            .map(|&[a, b]| super::edge_key(map[a as usize], map[b as usize]))
            .collect();
        self.tets = live.iter().map(|x| x.1).collect();
        self.tet_ref = live.iter().map(|x| x.2).collect();
        self.tet_stamp = live.iter().map(|x| x.3).collect();
        self.cache = vec![f64::NAN; self.tets.len()];
        self.free.clear();
        self.ball = vec![Vec::new(); self.points.len()];
        for (t, tet) in self.tets.iter().enumerate() {
            for &v in tet {
                self.ball[v as usize].push(t as u32);
            }
        }
        self.bfaces = self
            .bfaces
            .iter()
            .map(|(f, &l)| (sorted3(f.map(|v| map[v as usize])), l))
            .collect();
        old
    }

    /// Verifies every invariant: indices in range, positive volumes, each vertex's ball exactly
    /// the live tetrahedra containing it, every face shared by at most two tetrahedra, the
    /// boundary triangles exactly the faces of one tetrahedron (boundary closure), and the
    /// free list exactly the removed slots.
    pub fn check(&self) -> Result<()> {
        let n = self.points.len();
        let mut faces: HashMap<[u32; 3], u32> = HashMap::with_capacity(2 * self.tets.len());
        let mut count = vec![0usize; n];
        let mut removed = 0;
        for (t, tet) in self.tets.iter().enumerate() {
            if tet[0] == NONE {
                removed += 1;
                continue;
            }
            if tet.iter().any(|&v| v as usize >= n) {
                return Err(MeshDefect::IndexOutOfRange {
                    tri: t,
                    vertex: *tet.iter().max().unwrap_or(&0) as u64,
                    n_points: n,
                }
                .into());
            }
            let s = sorted3([tet[0], tet[1], tet[2]]);
            if s.windows(2).any(|w| w[0] == w[1]) || s.contains(&tet[3]) {
                return Err(MeshDefect::RepeatedVertex { tri: t }.into());
            }
            let vol = super::signed_volume(
                self.points[tet[0] as usize],
                self.points[tet[1] as usize],
                self.points[tet[2] as usize],
                self.points[tet[3] as usize],
            );
            if !positive(vol) {
                return Err(MeshDefect::InvertedTriangle {
                    tri: t,
                    signed_area: vol,
                }
                .into());
            }
            for &v in tet {
                count[v as usize] += 1;
                if !self.ball[v as usize].contains(&(t as u32)) {
                    return Err(bad(t, "a tetrahedron is missing from its vertex's ball"));
                }
            }
            for i in 0..4 {
                let c = faces.entry(sorted3(tet_face(tet, i))).or_insert(0);
                *c += 1;
                if *c > 2 {
                    return Err(bad(t, "a face shared by more than two tetrahedra"));
                }
            }
        }
        if removed != self.free.len() || self.free.iter().collect::<HashSet<_>>().len() != removed {
            return Err(bad(0, "the free list differs from the removed tetrahedra"));
        }
        for (v, &c) in count.iter().enumerate() {
            if self.ball[v].len() != c {
                return Err(bad(
                    v,
                    "a vertex ball lists tetrahedra that do not contain it",
                ));
            }
        }
        let mut bnd = vec![false; n];
        for f in self.bfaces.keys() {
            for &v in f {
                bnd[v as usize] = true;
            }
        }
        if (0..n).any(|v| !self.ball[v].is_empty() && bnd[v] != self.on_boundary[v]) {
            return Err(bad(
                0,
                "a vertex's boundary flag differs from its boundary triangles",
            ));
        }
        let mut rc = vec![0u8; n];
        for &[a, b] in &self.ridges {
            if a as usize >= n || b as usize >= n || !self.is_boundary_edge(a, b) {
                return Err(bad(0, "a ridge is not an edge of a boundary triangle"));
            }
            rc[a as usize] = rc[a as usize].saturating_add(1);
            rc[b as usize] = rc[b as usize].saturating_add(1);
        }
        if rc != self.ridge_count || self.fixed.len() != n {
            return Err(bad(
                0,
                "the ridge counts or corner flags differ from the ridges",
            ));
        }
        let unshared = faces.iter().filter(|(_, &c)| c == 1).count();
        if unshared != self.bfaces.len()
            || faces
                .iter()
                .any(|(f, &c)| c == 1 && !self.bfaces.contains_key(f))
        {
            return Err(bad(
                0,
                "the boundary triangles differ from the unshared faces",
            ));
        }
        Ok(())
    }
}

fn bad(t: usize, detail: &'static str) -> Error {
    MeshDefect::BadAdjacency {
        tri: t,
        edge: 0,
        detail,
    }
    .into()
}

/// Whether `x > 0` (false for NaN).
#[inline]
pub(super) fn positive(x: f64) -> bool {
    x > 0.0
}
