//! Building a mesh from a list of points and triangles: validation and adjacency. The
//! adjacency and the labels are topology ([`TriMesh::from_topology`]); [`Mesh2`] adds the
//! coordinate and orientation checks.

use super::{next, prev, Mesh2, TriMesh, NONE};
use crate::error::{MeshDefect, Result};
use crate::geom::{orient2d, DVec2};

impl Mesh2 {
    /// Builds a mesh from points and counter-clockwise triangles, computing the neighbour
    /// relation. Sub-domain labels are 0, boundary edges get label 1, no corners.
    ///
    /// Rejected with a [`MeshDefect`] naming the first offending entity: out-of-range indices,
    /// repeated vertices, non-finite coordinates, degenerate or clockwise triangles, duplicate
    /// triangles, edges shared by more than two triangles.
    pub fn from_triangles(points: Vec<DVec2>, tris: Vec<[u32; 3]>) -> Result<Mesh2> {
        let n = tris.len();
        Self::from_parts(points, tris, vec![0; n])
    }

    /// As [`Mesh2::from_triangles`], with a sub-domain label per triangle. Edges between
    /// triangles of different labels are labelled 2 (interface); boundary edges are labelled 1.
    pub fn from_parts(points: Vec<DVec2>, tris: Vec<[u32; 3]>, tri_ref: Vec<i32>) -> Result<Mesh2> {
        validate_elements(&points, &tris)?;
        if tri_ref.len() != tris.len() {
            return Err(MeshDefect::BadLabel {
                tri: tri_ref.len().min(tris.len()),
                detail: "the number of sub-domain labels differs from the number of triangles",
            }
            .into());
        }
        let neighbours = build_adjacency(&tris)?;
        Ok(TriMesh::assemble(points, tris, neighbours, tri_ref))
    }
}

impl<P> TriMesh<P> {
    /// Builds a mesh from points and triangles using only the connectivity (no coordinate is
    /// read): the neighbour relation, boundary edges labelled 1, sub-domain labels 0, no corners.
    /// The triangles must be consistently oriented (each interior edge traversed once in each
    /// direction); for a closed surface there is no boundary.
    ///
    /// Rejected with a [`MeshDefect`] naming the first offending entity: out-of-range indices,
    /// repeated vertices, duplicate triangles, inconsistent orientation, edges shared by more
    /// than two triangles.
    pub fn from_topology(points: Vec<P>, tris: Vec<[u32; 3]>) -> Result<TriMesh<P>> {
        for (t, tri) in tris.iter().enumerate() {
            validate_indices(t, tri, points.len())?;
        }
        let neighbours = build_adjacency(&tris)?;
        let n = tris.len();
        Ok(TriMesh::assemble(points, tris, neighbours, vec![0; n]))
    }

    /// A mesh from validated parts: edges labelled 1 on the boundary, 2 between sub-domains.
    pub(crate) fn assemble(
        points: Vec<P>,
        tris: Vec<[u32; 3]>,
        neighbours: Vec<[u32; 3]>,
        tri_ref: Vec<i32>,
    ) -> TriMesh<P> {
        let np = points.len();
        let mut mesh = TriMesh {
            points,
            edge_ref: vec![[0; 3]; tris.len()],
            tris,
            neighbours,
            tri_ref,
            vert_ref: vec![0; np],
            corner: vec![false; np],
            required: vec![false; np],
            vert_tri: Vec::new(),
        };
        for t in 0..mesh.tris.len() {
            for i in 0..3 {
                let nb = mesh.neighbours[t][i];
                mesh.edge_ref[t][i] = if nb == NONE {
                    1
                } else if mesh.tri_ref[nb as usize] != mesh.tri_ref[t] {
                    2
                } else {
                    0
                };
            }
        }
        mesh.rebuild_vertex_seeds();
        mesh
    }

    /// Recomputes `vert_tri` (one live triangle per vertex, `NONE` for unreferenced vertices).
    /// Each vertex gets the triangle in which it is followed by a boundary edge if it has one, so
    /// ring walks starting there see the whole fan in one direction.
    pub fn rebuild_vertex_seeds(&mut self) {
        self.vert_tri = vec![NONE; self.points.len()];
        for t in 0..self.tris.len() {
            if self.tris[t][0] == NONE {
                continue;
            }
            for i in 0..3 {
                let v = self.tris[t][i] as usize;
                // Edge opposite prev(i) starts at v: (v, tri[next(i)]) is local edge prev(i).
                let on_boundary = self.neighbours[t][prev(i)] == NONE;
                if self.vert_tri[v] == NONE || on_boundary {
                    self.vert_tri[v] = t as u32;
                }
            }
        }
    }

    /// Recomputes `neighbours` from `tris` (tombstones skipped). Used after bulk edits.
    pub fn rebuild_adjacency(&mut self) -> Result<()> {
        self.neighbours = build_adjacency(&self.tris)?;
        self.rebuild_vertex_seeds();
        Ok(())
    }
}

/// Index, coordinate and orientation checks on raw element data.
pub(crate) fn validate_elements(points: &[DVec2], tris: &[[u32; 3]]) -> Result<()> {
    for (v, p) in points.iter().enumerate() {
        if !p.is_finite() {
            return Err(MeshDefect::NonFiniteCoordinate { vertex: v }.into());
        }
    }
    for (t, tri) in tris.iter().enumerate() {
        if tri[0] == NONE {
            continue;
        }
        validate_indices(t, tri, points.len())?;
        let [a, b, c] = tri.map(|v| points[v as usize]);
        let o = orient2d(a, b, c);
        if o == 0.0 {
            return Err(MeshDefect::DegenerateTriangle { tri: t }.into());
        }
        if o < 0.0 {
            return Err(MeshDefect::InvertedTriangle {
                tri: t,
                signed_area: 0.5 * o,
            }
            .into());
        }
    }
    Ok(())
}

/// Index checks on the live triangle `t`: corners in range and distinct.
pub(crate) fn validate_indices(t: usize, tri: &[u32; 3], n_points: usize) -> Result<()> {
    if tri[0] == NONE {
        return Ok(());
    }
    for &v in tri {
        if v as usize >= n_points {
            return Err(MeshDefect::IndexOutOfRange {
                tri: t,
                vertex: v as u64,
                n_points,
            }
            .into());
        }
    }
    if tri[0] == tri[1] || tri[1] == tri[2] || tri[0] == tri[2] {
        return Err(MeshDefect::RepeatedVertex { tri: t }.into());
    }
    Ok(())
}

/// Computes the neighbour relation by grouping half-edges by their smaller vertex (a counting
/// sort) and sorting each small group by `(larger vertex, triangle, local edge)`: the groups are
/// visited in the order of a full sort of `(min, max, t, i)`, so the first defect reported is
/// the same. Errors on duplicate triangles, edges used twice in the same direction
/// (inconsistent orientation / overlap) and non-manifold edges.
pub(crate) fn build_adjacency(tris: &[[u32; 3]]) -> Result<Vec<[u32; 3]>> {
    let nv = tris
        .iter()
        .filter(|t| t[0] != NONE)
        .flat_map(|t| t.iter())
        .map(|&v| v as usize + 1)
        .max()
        .unwrap_or(0);
    if tris.len() >= 1 << 30 {
        return build_adjacency_sorted(tris);
    }
    // start[v]..start[v + 1]: the half-edges `max << 32 | t << 2 | i` whose smaller vertex is v.
    let mut start = vec![0u32; nv + 1];
    for tri in tris.iter().filter(|t| t[0] != NONE) {
        for i in 0..3 {
            start[tri[next(i)].min(tri[prev(i)]) as usize + 1] += 1;
        }
    }
    for v in 0..nv {
        start[v + 1] += start[v];
    }
    let mut half = vec![0u64; start[nv] as usize];
    for (t, tri) in tris.iter().enumerate() {
        if tri[0] == NONE {
            continue;
        }
        for i in 0..3 {
            let (a, b) = (tri[next(i)], tri[prev(i)]);
            let v = a.min(b) as usize;
            half[start[v] as usize] = (u64::from(a.max(b)) << 32) | ((t as u64) << 2) | i as u64;
            start[v] += 1;
        }
    }
    // start[v] is now the end of v's group, the start of v + 1's.
    let max_of = |h: u64| (h >> 32) as u32;
    let mut nb = vec![[NONE; 3]; tris.len()];
    let mut lo = 0usize;
    for (v, &end) in start.iter().enumerate().take(nv) {
        let hi = end as usize;
        let group = &mut half[lo..hi];
        lo = hi;
        // Insertion sort by (max, t, i): the groups are small (a vertex's edges).
        for k in 1..group.len() {
            let h = group[k];
            let mut j = k;
            while j > 0 && group[j - 1] > h {
                group[j] = group[j - 1];
                j -= 1;
            }
            group[j] = h;
        }
        let mut k = 0;
        while k < group.len() {
            let max = max_of(group[k]);
            let mut e = k + 1;
            while e < group.len() && max_of(group[e]) == max {
                e += 1;
            }
            let unpack = |h: u64| (((h & 0xffff_ffff) >> 2) as usize, (h & 3) as usize);
            match e - k {
                1 => {}
                2 => {
                    let ((t0, i0), (t1, i1)) = (unpack(group[k]), unpack(group[k + 1]));
                    let fwd = |t: usize, i: usize| tris[t][next(i)] < tris[t][prev(i)];
                    if fwd(t0, i0) == fwd(t1, i1) {
                        return Err(same_direction(tris, t0, t1, i1));
                    }
                    nb[t0][i0] = t1 as u32;
                    nb[t1][i1] = t0 as u32;
                }
                _ => {
                    return Err(MeshDefect::NonManifoldEdge {
                        a: v,
                        b: max as usize,
                    }
                    .into())
                }
            }
            k = e;
        }
    }
    Ok(nb)
}

/// The defect of an edge traversed twice in the same direction, by triangles `t0 < t1` (`t1`'s
/// local edge `i1`): a duplicate triangle or a fold.
fn same_direction(tris: &[[u32; 3]], t0: usize, t1: usize, i1: usize) -> crate::error::Error {
    let mut s0 = tris[t0];
    let mut s1 = tris[t1];
    s0.sort_unstable();
    s1.sort_unstable();
    if s0 == s1 {
        return MeshDefect::DuplicateTriangle {
            first: t0.min(t1),
            second: t0.max(t1),
        }
        .into();
    }
    MeshDefect::BadAdjacency {
        tri: t1,
        edge: i1,
        detail: "edge is traversed twice in the same direction (overlapping triangles)",
    }
    .into()
}

/// [`build_adjacency`] by sorting all half-edges at once (meshes of 2^30 triangles or more).
fn build_adjacency_sorted(tris: &[[u32; 3]]) -> Result<Vec<[u32; 3]>> {
    // Half-edge key: (min, max, t, i, forward)
    let mut half: Vec<(u32, u32, u32, u8, bool)> = Vec::with_capacity(3 * tris.len());
    for (t, tri) in tris.iter().enumerate() {
        if tri[0] == NONE {
            continue;
        }
        for i in 0..3 {
            let a = tri[next(i)];
            let b = tri[prev(i)];
            half.push((a.min(b), a.max(b), t as u32, i as u8, a < b));
        }
    }
    half.sort_unstable();
    let mut nb = vec![[NONE; 3]; tris.len()];
    let mut k = 0;
    while k < half.len() {
        let mut e = k + 1;
        while e < half.len() && half[e].0 == half[k].0 && half[e].1 == half[k].1 {
            e += 1;
        }
        match e - k {
            1 => {}
            2 => {
                let (h0, h1) = (half[k], half[k + 1]);
                if h0.4 == h1.4 {
                    // Same direction twice: either a duplicate triangle or a fold.
                    let (t0, t1) = (h0.2 as usize, h1.2 as usize);
                    let mut s0 = tris[t0];
                    let mut s1 = tris[t1];
                    s0.sort_unstable();
                    s1.sort_unstable();
                    if s0 == s1 {
                        return Err(MeshDefect::DuplicateTriangle {
                            first: t0.min(t1),
                            second: t0.max(t1),
                        }
                        .into());
                    }
                    return Err(MeshDefect::BadAdjacency {
                        tri: t1,
                        edge: h1.3 as usize,
                        detail:
                            "edge is traversed twice in the same direction (overlapping triangles)",
                    }
                    .into());
                }
                nb[h0.2 as usize][h0.3 as usize] = h1.2;
                nb[h1.2 as usize][h1.3 as usize] = h0.2;
            }
            _ => {
                return Err(MeshDefect::NonManifoldEdge {
                    a: half[k].0 as usize,
                    b: half[k].1 as usize,
                }
                .into())
            }
        }
        k = e;
    }
    Ok(nb)
}
