//! The one invariant checker, called after every operator in tests: [`Mesh2::check`] for planar
//! meshes, its topological part [`TriMesh::check_topology`] for any point type.

use super::build::{validate_elements, validate_indices};
use super::{next, prev, Mesh2, TriMesh, NONE};
use crate::error::{MeshDefect, Result};
use crate::geom::{orient2d, DVec2};

impl Mesh2 {
    /// Verifies every invariant of the mesh and reports the first defect found:
    /// array lengths, index ranges, finite coordinates, strictly positive orientation (exact
    /// predicate), symmetric adjacency that matches the shared edge, labels (an interior labelled
    /// edge carries the same label on both sides), valid vertex seeds, no duplicate vertices, no
    /// overlapping fans (angle sum at a vertex at most a full turn, decided by exact orientation
    /// predicates) and no hanging vertex inside a boundary edge (conformity). Tombstoned
    /// triangles are skipped.
    pub fn check(&self) -> Result<()> {
        self.check_lengths()?;
        // Independent parts run side by side; the first defect in the order listed wins.
        let (elements, adjacency) = rayon::join(
            || validate_elements(&self.points, &self.tris),
            || self.check_adjacency(),
        );
        elements?;
        adjacency?;
        let referenced = self.check_seeds()?;
        let (duplicates, fans) = rayon::join(
            || self.check_duplicate_points(&referenced),
            || {
                self.check_fans(Some(&|v, walked| self.overlapping_fan(v, walked)))?;
                self.check_hanging_vertices()
            },
        );
        duplicates?;
        fans
    }

    /// Whether the angles of the triangles around the referenced vertex `v` (a single fan of
    /// counter-clockwise triangles) add up to more than a full turn, decided without
    /// trigonometry: each triangle at `v` sweeps the directions from its edge `(v, tri[next(i)])`
    /// counter-clockwise to `(v, tri[prev(i)])`, and the number of sweeps that contain the
    /// direction `d` of the first edge of the fan (half-open: the end included, the start not)
    /// counts the full turns (exact orientation predicates). The fan is walked from its start,
    /// the boundary edge of an open fan. A closed fan turns exactly once; an open fan may end
    /// exactly on `d` (a slit).
    fn overlapping_fan(&self, v: usize, walked: &mut u32) -> bool {
        let pv = self.points[v];
        let mut first: Option<(DVec2, bool)> = None;
        let (mut turns, mut ends_on_d) = (0u32, false);
        self.for_each_fan_triangle(v as u32, |t| {
            *walked += 1;
            let t = t as usize;
            let Some(k) = self.local_index(t, v as u32) else {
                return;
            };
            let tri = self.tris[t];
            let a = self.points[tri[next(k)] as usize];
            let b = self.points[tri[prev(k)] as usize];
            let (d, open) = *first.get_or_insert((a, self.neighbours[t][prev(k)] == NONE));
            if orient2d(pv, a, d) > 0.0 && orient2d(pv, d, b) >= 0.0 {
                turns += 1;
                if open && self.neighbours[t][next(k)] == NONE && orient2d(pv, d, b) == 0.0 {
                    ends_on_d = true;
                }
            }
        });
        match first {
            Some((_, true)) => turns > u32::from(ends_on_d),
            _ => turns > 1,
        }
    }

    /// No two referenced vertices at the same coordinates.
    fn check_duplicate_points(&self, referenced: &[bool]) -> Result<()> {
        if !self.may_have_duplicate_points(referenced) {
            return Ok(());
        }
        // Sort by (x, y) in the order of f64::total_cmp, as integer keys.
        let key = |x: f64| {
            let b = x.to_bits() as i64;
            b ^ (((b >> 63) as u64) >> 1) as i64
        };
        let mut order: Vec<(i64, i64, u32)> = (0..self.points.len())
            .filter(|&v| referenced[v])
            .map(|v| (key(self.points[v].x), key(self.points[v].y), v as u32))
            .collect();
        order.sort_unstable();
        for w in order.windows(2) {
            let (a, b) = (w[0].2 as usize, w[1].2 as usize);
            if self.points[a] == self.points[b] {
                return Err(MeshDefect::DuplicateVertex {
                    first: a.min(b),
                    second: a.max(b),
                }
                .into());
            }
        }
        Ok(())
    }

    /// Whether two referenced vertices may have equal coordinates: `false` only when no two do
    /// (a hash table of the points, open addressing), so that the sort of
    /// [`Mesh2::check_duplicate_points`], which names the first pair in its order, runs only
    /// when there is a pair to name.
    fn may_have_duplicate_points(&self, referenced: &[bool]) -> bool {
        let n = self.points.len();
        if n >= NONE as usize {
            return true;
        }
        let size = (2 * n).next_power_of_two().max(16);
        let mut table = vec![NONE; size];
        // `+ 0.0` turns -0 into +0, which are equal coordinates with other bits.
        let bits = |v: usize| {
            let p = self.points[v];
            ((p.x + 0.0).to_bits(), (p.y + 0.0).to_bits())
        };
        for v in (0..n).filter(|&v| referenced[v]) {
            let (x, y) = bits(v);
            // The top bits of a product depend on all the bits of its factors.
            let h = (x.wrapping_mul(0x9E37_79B9_7F4A_7C15) ^ y).wrapping_mul(0xC2B2_AE3D_27D4_EB4F);
            let mut slot = (h >> (64 - size.trailing_zeros())) as usize;
            loop {
                let w = table[slot];
                if w == NONE {
                    table[slot] = v as u32;
                    break;
                }
                if bits(w as usize) == (x, y) {
                    return true;
                }
                slot = (slot + 1) & (size - 1);
            }
        }
        false
    }

    /// Conformity: no boundary vertex lies strictly inside a boundary edge. Uses a uniform bucket
    /// grid over the boundary edges, so the cost is about linear in the boundary size.
    fn check_hanging_vertices(&self) -> Result<()> {
        let edges = self.boundary_edges();
        if edges.is_empty() {
            return Ok(());
        }
        let mut bverts: Vec<u32> = edges.iter().flat_map(|e| [e.0, e.1]).collect();
        bverts.sort_unstable();
        bverts.dedup();
        let (lo, hi) = bverts.iter().fold(
            (DVec2::splat(f64::INFINITY), DVec2::splat(f64::NEG_INFINITY)),
            |(lo, hi), &v| {
                (
                    lo.min(self.points[v as usize]),
                    hi.max(self.points[v as usize]),
                )
            },
        );
        let n = (edges.len() as f64).sqrt().ceil().max(1.0) as usize;
        let size = (hi - lo).max(DVec2::splat(1e-300));
        let cell = |p: DVec2| -> (usize, usize) {
            let q = (p - lo) / size * n as f64;
            (
                (q.x.max(0.0) as usize).min(n - 1),
                (q.y.max(0.0) as usize).min(n - 1),
            )
        };
        let mut buckets: Vec<Vec<u32>> = vec![Vec::new(); n * n];
        for &v in &bverts {
            let (i, j) = cell(self.points[v as usize]);
            buckets[j * n + i].push(v);
        }
        for &(a, b, _) in &edges {
            let (pa, pb) = (self.points[a as usize], self.points[b as usize]);
            let (i0, j0) = cell(pa.min(pb));
            let (i1, j1) = cell(pa.max(pb));
            // Long edges that span many cells are rare in valid meshes; cap the work per edge by
            // scanning only the cells of its bounding box.
            for j in j0..=j1 {
                for i in i0..=i1 {
                    for &v in &buckets[j * n + i] {
                        if v == a || v == b {
                            continue;
                        }
                        let p = self.points[v as usize];
                        if orient2d(pa, pb, p) == 0.0 && (p - pa).dot(p - pb) < 0.0 {
                            return Err(MeshDefect::HangingVertex {
                                vertex: v as usize,
                                a: a as usize,
                                b: b as usize,
                            }
                            .into());
                        }
                    }
                }
            }
        }
        Ok(())
    }
}

/// The overlap test of [`Mesh2::check`] for a vertex; it walks the vertex's fan and counts the
/// triangles it meets in its second argument.
type OverlapTest<'a> = &'a dyn Fn(usize, &mut u32) -> bool;

impl<P> TriMesh<P> {
    /// Verifies the invariants that do not involve coordinates and reports the first defect
    /// found: array lengths, index ranges, distinct corners, symmetric adjacency that matches
    /// the shared edge, equal labels on both sides of an interior edge, valid vertex seeds, and
    /// a single fan around every vertex (manifold). [`Mesh2::check`] adds the geometric checks.
    pub fn check_topology(&self) -> Result<()> {
        self.check_lengths()?;
        for (t, tri) in self.tris.iter().enumerate() {
            validate_indices(t, tri, self.points.len())?;
        }
        self.check_adjacency()?;
        self.check_seeds()?;
        self.check_fans(None)
    }

    /// Every per-triangle and per-vertex array has the right length.
    fn check_lengths(&self) -> Result<()> {
        let nt = self.tris.len();
        let np = self.points.len();
        for (len, detail) in [
            (
                self.neighbours.len(),
                "neighbour array length differs from triangle count",
            ),
            (
                self.tri_ref.len(),
                "sub-domain label array length differs from triangle count",
            ),
            (
                self.edge_ref.len(),
                "edge label array length differs from triangle count",
            ),
        ] {
            if len != nt {
                return Err(MeshDefect::BadLabel {
                    tri: len.min(nt),
                    detail,
                }
                .into());
            }
        }
        for (len, detail) in [
            (
                self.vert_ref.len(),
                "vertex label array length differs from vertex count",
            ),
            (
                self.corner.len(),
                "corner flag array length differs from vertex count",
            ),
            (
                self.required.len(),
                "required flag array length differs from vertex count",
            ),
            (
                self.vert_tri.len(),
                "vertex seed array length differs from vertex count",
            ),
        ] {
            if len != np {
                return Err(MeshDefect::BadVertexData {
                    vertex: len.min(np),
                    detail,
                }
                .into());
            }
        }
        Ok(())
    }

    fn check_adjacency(&self) -> Result<()> {
        for t in self.live_tris() {
            for i in 0..3 {
                let nb = self.neighbours[t][i];
                if nb == NONE {
                    continue;
                }
                let bad = |detail| -> Result<()> {
                    Err(MeshDefect::BadAdjacency {
                        tri: t,
                        edge: i,
                        detail,
                    }
                    .into())
                };
                if nb as usize >= self.tris.len() {
                    return bad("neighbour index out of range");
                }
                if self.is_deleted(nb as usize) {
                    return bad("neighbour is a deleted triangle");
                }
                let Some(j) = self.mirror_edge(t, nb as usize) else {
                    return bad("neighbour does not point back (asymmetric adjacency)");
                };
                let [a, b] = self.edge_vertices(t, i);
                let [c, d] = self.edge_vertices(nb as usize, j);
                if !(a == d && b == c) {
                    return bad("neighbour does not share this edge in opposite direction");
                }
                if self.edge_ref[t][i] != self.edge_ref[nb as usize][j] {
                    return Err(MeshDefect::BadLabel {
                        tri: t,
                        detail: "an interior edge has different labels on its two sides",
                    }
                    .into());
                }
            }
        }
        Ok(())
    }

    /// Every vertex seed holds its vertex; every referenced vertex has one. Returns which
    /// vertices a live triangle references.
    fn check_seeds(&self) -> Result<Vec<bool>> {
        let mut referenced = vec![false; self.points.len()];
        for t in self.live_tris() {
            for &v in &self.tris[t] {
                referenced[v as usize] = true;
            }
        }
        for (v, &seed) in self.vert_tri.iter().enumerate() {
            if seed == NONE {
                if referenced[v] {
                    return Err(MeshDefect::BadVertexData {
                        vertex: v,
                        detail: "vertex is used by a triangle but has no seed triangle",
                    }
                    .into());
                }
                continue;
            }
            let s = seed as usize;
            if s >= self.tris.len() || self.is_deleted(s) || self.local_index(s, v as u32).is_none()
            {
                return Err(MeshDefect::BadVertexData {
                    vertex: v,
                    detail: "seed triangle does not contain the vertex",
                }
                .into());
            }
        }
        Ok(referenced)
    }

    /// Every referenced vertex: its fan, walked from its seed, must reach every triangle that uses
    /// it (a single manifold fan), and with `overlapping` (the test of [`Mesh2::check`], which
    /// walks the fan itself and counts its triangles in `walked`) the angles around it must not
    /// exceed a full turn.
    fn check_fans(&self, overlapping: Option<OverlapTest<'_>>) -> Result<()> {
        let mut uses = vec![0u32; self.points.len()];
        for t in self.live_tris() {
            for &v in &self.tris[t] {
                uses[v as usize] += 1;
            }
        }
        for (v, &used) in uses.iter().enumerate() {
            if used == 0 {
                continue;
            }
            // The fan is walked once: by the overlap test (which counts it) or here.
            let mut walked = 0u32;
            let overlaps = match overlapping {
                Some(f) => f(v, &mut walked),
                None => {
                    self.for_each_fan_triangle(v as u32, |_| walked += 1);
                    false
                }
            };
            if walked != used {
                return Err(MeshDefect::BadVertexData {
                    vertex: v,
                    detail: "the triangles around the vertex do not form a single fan (non-manifold vertex)",
                }
                .into());
            }
            if overlaps {
                return Err(MeshDefect::OverlappingTriangles { vertex: v }.into());
            }
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Referenced vertices at equal coordinates are reported as the first pair in (x, y) order,
    /// the two smallest indices there; -0 and +0 are the same coordinate to the pre-test.
    #[test]
    fn duplicate_points_are_found() {
        let tri = |o: DVec2, s: f64| [o, o + DVec2::new(s, 0.0), o + DVec2::new(0.0, s)];
        let mesh = |groups: &[[DVec2; 3]]| {
            let points: Vec<DVec2> = groups.iter().flatten().copied().collect();
            let tris = (0..groups.len() as u32)
                .map(|k| [3 * k, 3 * k + 1, 3 * k + 2])
                .collect();
            Mesh2::from_triangles(points, tris).unwrap()
        };
        let (a, b) = (DVec2::new(2.0, 2.0), DVec2::new(5.0, 0.0));
        // Triangles meeting at one point from three separate triangles: vertices 0, 4, 8 at a.
        let m = mesh(&[tri(a, 1.0), tri(a - DVec2::X, 1.0), tri(a - DVec2::Y, 1.0)]);
        assert_eq!(m.points[4], a);
        assert_eq!(m.points[8], a);
        let referenced = vec![true; m.points.len()];
        assert!(m.may_have_duplicate_points(&referenced));
        match m.check() {
            Err(crate::error::Error::InvalidMesh(MeshDefect::DuplicateVertex {
                first,
                second,
            })) => assert_eq!((first, second), (0, 4)),
            other => panic!("expected duplicate vertices, got {other:?}"),
        }
        let m = mesh(&[tri(a, 1.0), tri(b, 1.0)]);
        assert!(!m.may_have_duplicate_points(&referenced[..6]));
        m.check().unwrap();
        let zeros = mesh(&[
            tri(DVec2::new(-0.0, 3.0), 1.0),
            tri(DVec2::new(0.0, 3.0), -1.0),
        ]);
        assert!(zeros.may_have_duplicate_points(&referenced[..6]));
    }

    /// A fan that winds twice around its vertex (seven triangles of 4π/7 each) is caught by
    /// the orientation-predicate test; one winding of the same triangles is valid.
    #[test]
    fn a_fan_winding_twice_is_overlapping() {
        let fan = |turns: f64, n: usize| {
            let mut points = vec![DVec2::ZERO];
            let step = turns * 2.0 * std::f64::consts::PI / n as f64;
            points.extend((0..n).map(|k| DVec2::from_angle(step * k as f64)));
            let tris = (0..n)
                .map(|k| [0, 1 + k as u32, 1 + ((k + 1) % n) as u32])
                .collect();
            Mesh2::from_triangles(points, tris).unwrap()
        };
        fan(1.0, 7).check().unwrap();
        match fan(2.0, 7).check() {
            Err(crate::error::Error::InvalidMesh(MeshDefect::OverlappingTriangles { vertex })) => {
                assert_eq!(vertex, 0)
            }
            other => panic!("expected an overlapping fan, got {other:?}"),
        }
    }
}
