//! The local edits of [`EditMesh3`]: edge split, edge collapse, face 2-3 swap, edge removal
//! (3-2 and n-to-(2n-4)), vertex move. Each validates what makes the result a valid mesh
//! (positive volumes, conformity, the boundary kept) and either applies the change or leaves
//! the mesh untouched; metric criteria (lengths, quality) are the callers'.

use super::edit::{positive, sorted3, EditMesh3, VertexKind};
use super::signed_volume;
use crate::geom::DVec3;

/// The longest ring of an edge that [`EditMesh3::best_edge_removal`] retriangulates.
pub const MAX_RING: usize = 7;

impl EditMesh3 {
    fn vol(&self, t: [u32; 4]) -> f64 {
        let p = t.map(|v| self.points[v as usize]);
        signed_volume(p[0], p[1], p[2], p[3])
    }

    /// Whether `(a, b)` is an edge (some tetrahedron contains both).
    #[inline]
    pub fn is_edge(&self, a: u32, b: u32) -> bool {
        // Scan the smaller ball.
        let (a, b) = if self.ball[a as usize].len() <= self.ball[b as usize].len() {
            (a, b)
        } else {
            (b, a)
        };
        self.ball[a as usize]
            .iter()
            .any(|&t| self.tets[t as usize].contains(&b))
    }

    /// Splits the edge `(a, b)` at `p` (a point of the open segment): every tetrahedron of its
    /// shell becomes two, boundary triangles on the edge become two with the same label.
    /// Returns the new vertex, or `None` (mesh unchanged) when `(a, b)` is not an edge or a
    /// child would not have a positive volume.
    pub fn split_edge(&mut self, a: u32, b: u32, p: DVec3) -> Option<u32> {
        if !self.split_valid(a, b, p) {
            return None;
        }
        let mut shell = Vec::new();
        self.shell(a, b, &mut shell);
        let m = self.add_vertex(p);
        let sub = |tet: [u32; 4], x: u32| tet.map(|v| if v == x { m } else { v });
        for &t in &shell {
            let tet = self.tets[t as usize];
            let r = self.tet_ref[t as usize];
            for c in tet {
                if c != a && c != b {
                    if let Some(l) = self.bfaces.remove(&sorted3([a, b, c])) {
                        self.bfaces.insert(sorted3([a, m, c]), l);
                        self.bfaces.insert(sorted3([m, b, c]), l);
                        self.on_boundary[m as usize] = true;
                    }
                }
            }
            self.remove_tet(t);
            self.add_tet(sub(tet, b), r);
            self.add_tet(sub(tet, a), r);
        }
        if self.ridges.remove(&super::edge_key(a, b)) {
            self.ridges.insert(super::edge_key(a, m));
            self.ridges.insert(super::edge_key(m, b));
            self.ridge_count[m as usize] = 2;
        }
        Some(m)
    }

    /// Whether [`EditMesh3::split_edge`] would split `(a, b)` at `p`: an edge whose children
    /// all have positive volume.
    pub fn split_valid(&self, a: u32, b: u32, p: DVec3) -> bool {
        let mut shell = Vec::new();
        self.shell(a, b, &mut shell);
        let at = |tet: [u32; 4], x: u32| {
            let q = tet.map(|v| if v == x { p } else { self.points[v as usize] });
            signed_volume(q[0], q[1], q[2], q[3])
        };
        !shell.is_empty()
            && shell.iter().all(|&t| {
                let tet = self.tets[t as usize];
                positive(at(tet, a)) && positive(at(tet, b))
            })
    }

    /// The tetrahedra that collapsing `a` onto `b` would leave (each tetrahedron of `a`'s
    /// ball not containing `b`, with `a` replaced by `b`), or `None` when the collapse is not
    /// valid: `(a, b)` not an edge; a common neighbour of `a` and `b` outside the shell (the
    /// link condition); a new tetrahedron without positive volume; for a boundary `a`, the edge
    /// not on the boundary, a label of `a` missing at `b`, or a boundary triangle that would
    /// change its plane or degenerate (so faces stay planar, ridges straight, corners kept); a
    /// corner `a`; a ridge vertex `a` unless `(a, b)` is one of its two ridges and the ridge is
    /// straight at `a`.
    pub fn collapse_check(&self, a: u32, b: u32) -> Option<Vec<[u32; 4]>> {
        if self.fixed[a as usize] || !self.ridge_collapse_ok(a, b) {
            return None;
        }
        let mut shell = Vec::new();
        self.shell(a, b, &mut shell);
        if shell.is_empty() {
            return None;
        }
        let mut na = Vec::new();
        let mut nb = Vec::new();
        self.vertex_neighbours(a, &mut na);
        self.vertex_neighbours(b, &mut nb);
        let mut in_shell: Vec<u32> = shell.iter().flat_map(|&t| self.tets[t as usize]).collect();
        in_shell.sort_unstable();
        in_shell.dedup();
        if na
            .iter()
            .any(|v| nb.binary_search(v).is_ok() && in_shell.binary_search(v).is_err())
        {
            return None;
        }
        let mut fa = Vec::new();
        if self.on_boundary[a as usize] {
            self.vertex_bfaces(a, &mut fa);
            if !self.is_boundary_edge(a, b) {
                return None;
            }
            let mut fb = Vec::new();
            self.vertex_bfaces(b, &mut fb);
            if fa.iter().any(|&(_, l)| fb.iter().all(|&(_, lb)| lb != l)) {
                return None;
            }
            for &(f, _) in &fa {
                if f.contains(&b) {
                    continue;
                }
                let n0 = self.face_normal(f);
                let [p, q, r] = f.map(|v| self.points[if v == a { b } else { v } as usize]);
                let n1 = (q - p).cross(r - p);
                let len = n1.length();
                if !positive(len) || (n1 / len).cross(n0).length() > 1e-9 || n1.dot(n0) <= 0.0 {
                    return None;
                }
            }
        }
        let mut out = Vec::new();
        for &t in &self.ball[a as usize] {
            let tet = self.tets[t as usize];
            if tet.contains(&b) {
                continue;
            }
            let nt = tet.map(|v| if v == a { b } else { v });
            if !positive(self.vol(nt)) {
                return None;
            }
            out.push(nt);
        }
        Some(out)
    }

    /// Collapses `a` onto `b` when [`EditMesh3::collapse_check`] allows it; returns whether
    /// it did. `a` is left with an empty ball (removed).
    pub fn collapse_edge(&mut self, a: u32, b: u32) -> bool {
        if self.collapse_check(a, b).is_none() {
            return false;
        }
        self.collapse_unchecked(a, b);
        true
    }

    /// Whether the ridges allow removing `a` by a collapse onto `b`: `a` on no ridge, or on
    /// exactly two, one of them `(a, b)`, the other `(a, c)` with `c`, `a`, `b` in line.
    fn ridge_collapse_ok(&self, a: u32, b: u32) -> bool {
        if self.ridge_count[a as usize] == 0 {
            return true;
        }
        if self.ridge_count[a as usize] != 2 || !self.ridges.contains(&super::edge_key(a, b)) {
            return false;
        }
        let mut nb = Vec::new();
        self.vertex_neighbours(a, &mut nb);
        let Some(c) = nb
            .into_iter()
            .find(|&c| c != b && self.ridges.contains(&super::edge_key(a, c)))
        else {
            return false;
        };
        let p = |v: u32| self.points[v as usize];
        let (u, w) = (p(b) - p(a), p(a) - p(c));
        u.cross(w).length() <= 1e-12 * u.length() * w.length() && u.dot(w) > 0.0
    }

    /// Collapses `a` onto `b`; the caller has just validated it with
    /// [`EditMesh3::collapse_check`].
    pub fn collapse_unchecked(&mut self, a: u32, b: u32) {
        if self.ridge_count[a as usize] > 0 {
            let mut nb = Vec::new();
            self.vertex_neighbours(a, &mut nb);
            for c in nb {
                if self.ridges.remove(&super::edge_key(a, c)) {
                    self.ridge_count[c as usize] -= 1;
                    if c != b {
                        self.ridges.insert(super::edge_key(b, c));
                        self.ridge_count[b as usize] += 1;
                        self.ridge_count[c as usize] += 1;
                    }
                }
            }
            self.ridge_count[a as usize] = 0;
        }
        let mut fa = Vec::new();
        if self.on_boundary[a as usize] {
            self.vertex_bfaces(a, &mut fa);
        }
        for (f, l) in fa {
            self.bfaces.remove(&f);
            if !f.contains(&b) {
                self.bfaces
                    .insert(sorted3(f.map(|v| if v == a { b } else { v })), l);
            }
        }
        let ball = self.ball[a as usize].clone();
        for t in ball {
            let tet = self.tets[t as usize];
            let r = self.tet_ref[t as usize];
            self.remove_tet(t);
            if !tet.contains(&b) {
                self.add_tet(tet.map(|v| if v == a { b } else { v }), r);
            }
        }
    }

    /// The ring of the interior edge `(a, b)`: the vertices around it in the order that makes
    /// every `(a, b, c_i, c_{i+1})` positively oriented, or `None` for a boundary edge, an edge
    /// whose shell has several sub-domains, or a ring longer than [`MAX_RING`].
    pub fn edge_ring(&self, a: u32, b: u32) -> Option<Vec<u32>> {
        // (c, d) per shell tetrahedron, in the positive order (a, b, c, d): tetrahedra are
        // positively oriented, so that order is the tetrahedron's own up to an even
        // permutation (no volume to evaluate, no allocation).
        let mut next = [(0u32, 0u32); MAX_RING];
        let mut n = 0;
        let mut r0 = None;
        for &t in &self.ball[a as usize] {
            let tet = self.tets[t as usize];
            let Some(ib) = tet.iter().position(|&v| v == b) else {
                continue;
            };
            if n == MAX_RING {
                return None;
            }
            let r = self.tet_ref[t as usize];
            if *r0.get_or_insert(r) != r {
                return None;
            }
            let ia = tet.iter().position(|&v| v == a)?;
            let mut rest = [0usize; 2];
            let mut k = 0;
            for i in 0..4 {
                if i != ia && i != ib {
                    rest[k] = i;
                    k += 1;
                }
            }
            let perm = [ia, ib, rest[0], rest[1]];
            let mut inversions = 0;
            for i in 0..4 {
                for j in i + 1..4 {
                    inversions += usize::from(perm[i] > perm[j]);
                }
            }
            let (c, d) = (tet[rest[0]], tet[rest[1]]);
            next[n] = if inversions % 2 == 0 { (c, d) } else { (d, c) };
            n += 1;
        }
        if n < 3 {
            return None;
        }
        let next = &next[..n];
        let mut ring = Vec::with_capacity(n);
        ring.push(next[0].0);
        let mut cur = next[0].1;
        while ring.len() < n {
            ring.push(cur);
            cur = next.iter().find(|x| x.0 == cur)?.1;
        }
        if cur != ring[0] {
            return None;
        }
        Some(ring)
    }

    /// The best retriangulation of the shell of the interior edge `(a, b)` without that edge
    /// (3 tetrahedra become 2, n become 2n − 4): over all triangulations of its ring (dynamic
    /// programming), the one that maximises the smallest `quality` of its tetrahedra; only
    /// positively oriented tetrahedra and new ring diagonals that are not already edges and
    /// that `new_edge` accepts count. Returns that smallest quality and the tetrahedra, or
    /// `None` when no triangulation has its smallest quality above `floor` (pass
    /// `f64::NEG_INFINITY` for any valid one). Partial triangulations that cannot beat the best
    /// found so far are not evaluated further (the result is the same, the work smaller).
    pub fn best_edge_removal(
        &self,
        a: u32,
        b: u32,
        floor: f64,
        quality: impl Fn([u32; 4]) -> f64,
        new_edge: impl Fn(u32, u32) -> bool,
    ) -> Option<(f64, Vec<[u32; 4]>)> {
        let ring = self.edge_ring(a, b)?;
        let n = ring.len();
        let mut best = [[floor; MAX_RING]; MAX_RING];
        let mut arg = [[0usize; MAX_RING]; MAX_RING];
        // Whether the ring diagonal (i, j) may be created (the closing pair (0, n − 1) is a
        // ring edge); asked only of pairs some triangle could use, the caller's test (a length,
        // in the metric) before the ball scan of `is_edge`.
        let diag_ok = |i: usize, j: usize| {
            (i == 0 && j == n - 1) || new_edge(ring[i], ring[j]) && !self.is_edge(ring[i], ring[j])
        };
        // The worse of the two tetrahedra on the triangle (i, k, j), or anything at most
        // `beat` when it cannot exceed `beat`.
        let tri_q = |i: usize, k: usize, j: usize, beat: f64| -> f64 {
            let (ci, ck, cj) = (ring[i], ring[k], ring[j]);
            let up = [a, ci, ck, cj];
            let down = [ci, ck, cj, b];
            if !(positive(self.vol(up)) && positive(self.vol(down))) {
                return f64::NEG_INFINITY;
            }
            let qu = quality(up);
            if qu <= beat {
                return qu;
            }
            qu.min(quality(down))
        };
        for len in 2..n {
            for i in 0..n - len {
                let j = i + len;
                let mut allowed = None;
                for k in i + 1..j {
                    let sub_l = if k == i + 1 {
                        f64::INFINITY
                    } else {
                        best[i][k]
                    };
                    let sub_r = if j == k + 1 {
                        f64::INFINITY
                    } else {
                        best[k][j]
                    };
                    if sub_l.min(sub_r) <= best[i][j] {
                        continue;
                    }
                    if !*allowed.get_or_insert_with(|| diag_ok(i, j)) {
                        break;
                    }
                    let q = tri_q(i, k, j, best[i][j]).min(sub_l).min(sub_r);
                    if q > best[i][j] {
                        best[i][j] = q;
                        arg[i][j] = k;
                    }
                }
            }
        }
        let q = best[0][n - 1];
        if q <= floor {
            return None;
        }
        let mut out = Vec::with_capacity(2 * n - 4);
        let mut stack = vec![(0, n - 1)];
        while let Some((i, j)) = stack.pop() {
            if j < i + 2 {
                continue;
            }
            let k = arg[i][j];
            out.push([a, ring[i], ring[k], ring[j]]);
            out.push([ring[i], ring[k], ring[j], b]);
            stack.push((i, k));
            stack.push((k, j));
        }
        Some((q, out))
    }

    /// Replaces the shell of the edge `(a, b)` by `tets` (from
    /// [`EditMesh3::best_edge_removal`]), keeping the sub-domain label.
    pub fn replace_shell(&mut self, a: u32, b: u32, tets: &[[u32; 4]]) {
        let mut shell = Vec::new();
        self.shell(a, b, &mut shell);
        let r = self.tet_ref[shell[0] as usize];
        for t in shell {
            self.remove_tet(t);
        }
        for &t in tets {
            self.add_tet(t, r);
        }
    }

    /// The 2-3 swap of the interior triangle `f`: its two tetrahedra `(f, d)`, `(f, e)` become
    /// the three around the new edge `(d, e)`. Returns them, or `None` when `f` is on the
    /// boundary, between sub-domains, `(d, e)` is already an edge or does not cross `f`.
    pub fn face_swap_check(&self, f: [u32; 3]) -> Option<[[u32; 4]; 3]> {
        self.face_swap_plan(f).map(|x| x.1)
    }

    /// [`EditMesh3::face_swap_check`] that also returns the two tetrahedra on `f`.
    pub fn face_swap_plan(&self, f: [u32; 3]) -> Option<([u32; 2], [[u32; 4]; 3])> {
        let ts = self.face_pair(f)?;
        if self.tet_ref[ts[0] as usize] != self.tet_ref[ts[1] as usize] {
            return None;
        }
        let apex = |t: u32| {
            self.tets[t as usize]
                .iter()
                .copied()
                .find(|v| !f.contains(v))
        };
        let (d, e) = (apex(ts[0])?, apex(ts[1])?);
        if self.is_edge(d, e) {
            return None;
        }
        let [x, y, z] = f;
        for ring in [[x, y, z], [x, z, y]] {
            let new = [
                [d, e, ring[0], ring[1]],
                [d, e, ring[1], ring[2]],
                [d, e, ring[2], ring[0]],
            ];
            if new.iter().all(|&t| self.vol(t) > 0.0) {
                return Some((ts, new));
            }
        }
        None
    }

    /// Applies a 2-3 swap of `f` planned by [`EditMesh3::face_swap_check`].
    pub fn face_swap_apply(&mut self, f: [u32; 3], new: [[u32; 4]; 3]) {
        let Some(ts) = self.face_pair(f) else {
            return;
        };
        let r = self.tet_ref[ts[0] as usize];
        for t in ts {
            self.remove_tet(t);
        }
        for t in new {
            self.add_tet(t, r);
        }
    }

    /// Whether moving `v` to `p` keeps every tetrahedron of its ball positive and, on the
    /// boundary, `v` in the plane of its boundary triangles (a face vertex may slide in its
    /// plane, a ridge or corner vertex may not move).
    pub fn move_valid(&self, v: u32, p: DVec3) -> bool {
        match self.vertex_kind(v) {
            VertexKind::Interior => {}
            VertexKind::Face(n) => {
                if !super::edit::in_plane(self.points[v as usize], n, p) {
                    return false;
                }
            }
            VertexKind::Feature => return false,
        }
        self.ball[v as usize].iter().all(|&t| {
            let q = self.tets[t as usize].map(|w| if w == v { p } else { self.points[w as usize] });
            signed_volume(q[0], q[1], q[2], q[3]) > 0.0
        })
    }

    /// Moves `v` to `p` when [`EditMesh3::move_valid`] allows it; returns whether it did.
    pub fn move_vertex(&mut self, v: u32, p: DVec3) -> bool {
        if !self.move_valid(v, p) {
            return false;
        }
        self.set_point(v, p);
        true
    }

    /// Moves `v` to `p` (the caller has validated the move) and resets the cached values of
    /// the tetrahedra of its ball.
    pub fn set_point(&mut self, v: u32, p: DVec3) {
        self.points[v as usize] = p;
        for &t in &self.ball[v as usize] {
            self.cache[t as usize] = f64::NAN;
            self.tet_stamp[t as usize] = self.now;
        }
    }
}
