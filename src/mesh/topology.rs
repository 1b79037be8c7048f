//! Pure topology on [`TriMesh`]: local indices, vertex fans and rings, patches, boundary edges,
//! edge labels, compaction. Nothing here reads coordinates.

use super::{next, prev, TriMesh, NONE};
use rayon::prelude::*;

impl<P> TriMesh<P> {
    /// Local index (0..3) of vertex `v` in triangle `t`, if it is a corner of it.
    #[inline]
    pub fn local_index(&self, t: usize, v: u32) -> Option<usize> {
        self.tris[t].iter().position(|&w| w == v)
    }

    /// Local index in triangle `nb` of the edge it shares with triangle `t`.
    #[inline]
    pub fn mirror_edge(&self, t: usize, nb: usize) -> Option<usize> {
        self.neighbours[nb].iter().position(|&w| w as usize == t)
    }

    /// The live triangles around vertex `v`, in counter-clockwise order. For a boundary vertex the
    /// fan starts at the triangle whose edge leaving `v` counter-clockwise is on the boundary.
    /// Returns an empty list for an unreferenced vertex.
    pub fn vertex_fan(&self, v: u32) -> Vec<u32> {
        let mut fan = Vec::with_capacity(8);
        self.for_each_fan_triangle(v, |t| fan.push(t));
        fan
    }

    /// Calls `f` on each live triangle around `v` (counter-clockwise), without allocating.
    pub fn for_each_fan_triangle(&self, v: u32, mut f: impl FnMut(u32)) {
        let seed = match self.vert_tri.get(v as usize) {
            Some(&t) if t != NONE => t,
            _ => return,
        };
        // Walk counter-clockwise from the seed; a closed fan comes back to it (one traversal,
        // the common case). An open fan hits the boundary: then the part clockwise of the seed
        // is collected and emitted first, reversed.
        let mut ccw = [NONE; 24];
        let mut n = 0;
        let mut t = seed;
        loop {
            if n == ccw.len() {
                return self.for_each_fan_triangle_long(v, seed, f);
            }
            ccw[n] = t;
            n += 1;
            let i = match self.local_index(t as usize, v) {
                Some(i) => i,
                None => return,
            };
            // Counter-clockwise: cross the edge (v, tri[prev(i)]), which is local edge next(i).
            let after = self.neighbours[t as usize][next(i)];
            if after == seed {
                ccw[..n].iter().for_each(|&t| f(t));
                return;
            }
            if after == NONE {
                break;
            }
            t = after;
        }
        let mut cw = [NONE; 24];
        let mut m = 0;
        let mut t = seed;
        loop {
            let i = match self.local_index(t as usize, v) {
                Some(i) => i,
                None => return,
            };
            // The edge (v, tri[next(i)]) is local edge prev(i); the triangle across it precedes
            // us in counter-clockwise order.
            let before = self.neighbours[t as usize][prev(i)];
            if before == NONE {
                break;
            }
            if m == cw.len() {
                return self.for_each_fan_triangle_long(v, seed, f);
            }
            cw[m] = before;
            m += 1;
            t = before;
        }
        cw[..m].iter().rev().for_each(|&t| f(t));
        ccw[..n].iter().for_each(|&t| f(t));
    }

    /// [`TriMesh::for_each_fan_triangle`] for fans of more than 24 triangles (two traversals).
    fn for_each_fan_triangle_long(&self, v: u32, seed: u32, mut f: impl FnMut(u32)) {
        // Rotate clockwise to the start of an open fan (or back to the seed for a closed one).
        let mut start = seed;
        loop {
            let i = match self.local_index(start as usize, v) {
                Some(i) => i,
                None => return,
            };
            let before = self.neighbours[start as usize][prev(i)];
            if before == NONE {
                break;
            }
            start = before;
            if start == seed {
                break;
            }
        }
        let mut t = start;
        loop {
            f(t);
            let i = match self.local_index(t as usize, v) {
                Some(i) => i,
                None => return,
            };
            let after = self.neighbours[t as usize][next(i)];
            if after == NONE || after == start {
                return;
            }
            t = after;
        }
    }

    /// The vertices adjacent to `v` (its first ring), counter-clockwise, each once.
    pub fn vertex_ring(&self, v: u32) -> Vec<u32> {
        let mut ring = Vec::with_capacity(8);
        let mut first = true;
        self.for_each_fan_triangle(v, |t| {
            let i = self.local_index(t as usize, v).unwrap_or(0);
            let tri = self.tris[t as usize];
            if first {
                ring.push(tri[next(i)]);
                first = false;
            }
            ring.push(tri[prev(i)]);
        });
        if ring.len() > 1 && ring.first() == ring.last() {
            ring.pop();
        }
        ring
    }

    /// Whether vertex `v` is on the boundary (its fan is open).
    pub fn is_boundary_vertex(&self, v: u32) -> bool {
        let seed = self.vert_tri[v as usize];
        if seed == NONE {
            return false;
        }
        let mut boundary = false;
        self.for_each_fan_triangle(v, |t| {
            if let Some(i) = self.local_index(t as usize, v) {
                let tt = t as usize;
                if self.neighbours[tt][next(i)] == NONE || self.neighbours[tt][prev(i)] == NONE {
                    boundary = true;
                }
            }
        });
        boundary
    }

    /// Flags of all boundary vertices, in one pass over the triangles.
    pub fn boundary_vertex_flags(&self) -> Vec<bool> {
        let mut flag = vec![false; self.points.len()];
        for t in self.live_tris() {
            for i in 0..3 {
                if self.neighbours[t][i] == NONE {
                    let [a, b] = self.edge_vertices(t, i);
                    flag[a as usize] = true;
                    flag[b as usize] = true;
                }
            }
        }
        flag
    }

    /// The vertices within `rings` edge-hops of `v`, excluding `v` itself, nearest rings first.
    pub fn vertex_patch(&self, v: u32, rings: usize) -> Vec<u32> {
        let mut seen = vec![v];
        let mut frontier = vec![v];
        for _ in 0..rings {
            let mut next_frontier = Vec::new();
            for &w in &frontier {
                for u in self.vertex_ring(w) {
                    if !seen.contains(&u) {
                        seen.push(u);
                        next_frontier.push(u);
                    }
                }
            }
            frontier = next_frontier;
        }
        seen.remove(0);
        seen
    }

    /// Vertex-to-vertex adjacency of the whole mesh in compressed form: `(offsets, neighbours)`,
    /// the ring of `v` being `neighbours[offsets[v]..offsets[v+1]]` (sorted ascending).
    pub fn v2v(&self) -> (Vec<usize>, Vec<u32>) {
        // Bucket the directed edges of the live triangles by their first vertex (each interior
        // edge arrives twice), then sort and deduplicate each ring in place and close the gaps.
        let n = self.points.len();
        let mut start = vec![0usize; n + 1];
        for t in self.live_tris() {
            for &v in &self.tris[t] {
                start[v as usize + 1] += 2;
            }
        }
        for v in 0..n {
            start[v + 1] += start[v];
        }
        let mut fill = start.clone();
        let mut ring = vec![0u32; start[n]];
        for t in self.live_tris() {
            let tri = self.tris[t];
            for i in 0..3 {
                let (a, b) = (tri[i], tri[next(i)]);
                ring[fill[a as usize]] = b;
                fill[a as usize] += 1;
                ring[fill[b as usize]] = a;
                fill[b as usize] += 1;
            }
        }
        let mut offsets = vec![0usize; n + 1];
        let mut len = 0;
        for v in 0..n {
            let (lo, hi) = (start[v], start[v + 1]);
            ring[lo..hi].sort_unstable();
            let mut prev_w = NONE;
            for k in lo..hi {
                let w = ring[k];
                if w != prev_w {
                    ring[len] = w;
                    len += 1;
                    prev_w = w;
                }
            }
            offsets[v + 1] = len;
        }
        ring.truncate(len);
        (offsets, ring)
    }

    /// The unique edges `(a, b)` with `a < b`, each with one triangle and local index holding it.
    pub fn edges(&self) -> Vec<([u32; 2], u32, u8)> {
        let mut out = Vec::with_capacity(3 * self.tris.len() / 2 + 8);
        for t in self.live_tris() {
            for i in 0..3 {
                let nb = self.neighbours[t][i];
                // Take each interior edge from the triangle with the smaller index.
                if nb == NONE || (nb as usize) > t {
                    let [a, b] = self.edge_vertices(t, i);
                    out.push(([a.min(b), a.max(b)], t as u32, i as u8));
                }
            }
        }
        out
    }

    /// The boundary edges as `(a, b, label)`, oriented with the domain on their left.
    pub fn boundary_edges(&self) -> Vec<(u32, u32, i32)> {
        let mut out = Vec::new();
        for t in self.live_tris() {
            for i in 0..3 {
                if self.neighbours[t][i] == NONE {
                    let [a, b] = self.edge_vertices(t, i);
                    out.push((a, b, self.edge_ref[t][i]));
                }
            }
        }
        out
    }

    /// The boundary as closed loops of vertex indices (each loop counter-clockwise for the outer
    /// boundary, clockwise for holes). Loops are returned without repeating the first vertex.
    pub fn boundary_loops(&self) -> Vec<Vec<u32>> {
        let edges = self.boundary_edges();
        let mut succ = std::collections::HashMap::with_capacity(edges.len());
        for &(a, b, _) in &edges {
            succ.insert(a, b);
        }
        let mut used = std::collections::HashSet::with_capacity(edges.len());
        let mut loops = Vec::new();
        for &(a, _, _) in &edges {
            if used.contains(&a) {
                continue;
            }
            let mut lp = Vec::new();
            let mut v = a;
            while used.insert(v) {
                lp.push(v);
                match succ.get(&v) {
                    Some(&w) => v = w,
                    None => break,
                }
            }
            loops.push(lp);
        }
        loops
    }

    /// Labels the edge `(a, b)` with `label` on both of its sides; `false` when there is no such
    /// edge.
    pub fn label_edge(&mut self, a: u32, b: u32, label: i32) -> bool {
        let mut found = false;
        for t in self.vertex_fan(a) {
            let t = t as usize;
            for i in 0..3 {
                let [x, y] = self.edge_vertices(t, i);
                if (x == a && y == b) || (x == b && y == a) {
                    self.edge_ref[t][i] = label;
                    found = true;
                }
            }
        }
        found
    }

    /// Which vertices some live triangle references.
    pub(crate) fn used_vertices(&self) -> Vec<bool> {
        let mut used = vec![false; self.points.len()];
        for t in self.live_tris() {
            for &v in &self.tris[t] {
                used[v as usize] = true;
            }
        }
        used
    }
}

impl<P: Copy + Send + Sync> TriMesh<P> {
    /// Removes deleted triangles and unreferenced vertices, renumbering everything. Returns the map
    /// old vertex index -> new index (`NONE` for removed vertices).
    pub fn compact(&mut self) -> Vec<u32> {
        let used = self.used_vertices();
        let vorder: Vec<u32> = (0..self.points.len() as u32)
            .filter(|&v| used[v as usize])
            .collect();
        let torder: Vec<u32> = self.live_tris().map(|t| t as u32).collect();
        self.renumber(&vorder, &torder).0
    }

    /// Renumbers the mesh: `vorder` lists the old indices of the kept vertices in their new order,
    /// `torder` the old indices of the kept (live) triangles in theirs. Every live triangle must be
    /// listed and every vertex they reference. Returns the maps old -> new (`NONE` for dropped)
    /// for vertices and triangles.
    pub(crate) fn renumber(&mut self, vorder: &[u32], torder: &[u32]) -> (Vec<u32>, Vec<u32>) {
        let mut vmap = vec![NONE; self.points.len()];
        for (new, &old) in vorder.iter().enumerate() {
            vmap[old as usize] = new as u32;
        }
        let mut tmap = vec![NONE; self.tris.len()];
        for (new, &old) in torder.iter().enumerate() {
            tmap[old as usize] = new as u32;
        }
        // Gathers in parallel (rayon): the result does not depend on the thread count.
        fn gather<T: Copy + Send + Sync>(v: &[T], order: &[u32]) -> Vec<T> {
            order.par_iter().map(|&o| v[o as usize]).collect()
        }
        self.points = gather(&self.points, vorder);
        self.vert_ref = gather(&self.vert_ref, vorder);
        self.corner = gather(&self.corner, vorder);
        self.required = gather(&self.required, vorder);
        let remap_t = |t: u32| if t == NONE { NONE } else { tmap[t as usize] };
        self.tris = torder
            .par_iter()
            .map(|&t| self.tris[t as usize].map(|v| vmap[v as usize]))
            .collect();
        self.neighbours = torder
            .par_iter()
            .map(|&t| self.neighbours[t as usize].map(remap_t))
            .collect();
        self.tri_ref = gather(&self.tri_ref, torder);
        self.edge_ref = gather(&self.edge_ref, torder);
        self.rebuild_vertex_seeds();
        (vmap, tmap)
    }
}
