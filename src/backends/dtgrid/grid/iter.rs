//! Streaming iterators over a DT-Grid (000 §3): the nodes in storage order, the cells (`2^d`
//! corner lines walked in lockstep) and the `3^d` neighbourhoods (`3^d` lines in lockstep).
//! None of them uses random access or hashing: every cursor only moves forward.

use super::{DtCoord, DtGrid, Level};
use std::cmp::Ordering;

/// A forward cursor over the points of levels `0..depth` (the prefixes of length `depth`).
#[derive(Clone, Debug)]
pub(crate) struct Cursor {
    depth: usize,
    /// Current point, run and coordinate per level.
    pub(crate) p: [usize; 3],
    r: [usize; 3],
    pub(crate) x: [i32; 3],
    pub(crate) done: bool,
}

impl Cursor {
    pub(crate) fn new(levels: &[Level], depth: usize) -> Self {
        let done = *levels[depth - 1].acc.last().unwrap_or(&0) == 0;
        let mut x = [0; 3];
        if !done {
            for k in 0..depth {
                x[k] = levels[k].starts[0];
            }
        }
        Cursor {
            depth,
            p: [0; 3],
            r: [0; 3],
            x,
            done,
        }
    }

    /// Moves to the next point of level `depth − 1`.
    pub(crate) fn advance(&mut self, levels: &[Level]) {
        self.step(levels, self.depth - 1);
    }

    fn step(&mut self, levels: &[Level], k: usize) {
        let lev = &levels[k];
        self.p[k] += 1;
        if self.p[k] as u32 == *lev.acc.last().unwrap_or(&0) {
            self.done = true;
            return;
        }
        if self.p[k] as u32 == lev.acc[self.r[k] + 1] {
            self.r[k] += 1;
            self.x[k] = lev.starts[self.r[k]];
            if k > 0 && self.r[k] as u32 == lev.lines[self.p[k - 1] + 1] {
                self.step(levels, k - 1);
            }
        } else {
            self.x[k] += 1;
        }
    }

    /// The prefix compared with `t` (both of length `depth`).
    fn cmp_prefix(&self, t: &[i32]) -> Ordering {
        self.x[..self.depth].cmp(t)
    }

    /// Advances to the first prefix `≥ t`; returns its line (point index) when it equals `t`.
    pub(crate) fn seek(&mut self, levels: &[Level], t: &[i32]) -> Option<usize> {
        while !self.done && self.cmp_prefix(t) == Ordering::Less {
            self.advance(levels);
        }
        (!self.done && self.cmp_prefix(t) == Ordering::Equal).then(|| self.p[self.depth - 1])
    }
}

/// The nodes of a [`DtGrid`] in storage (lexicographic) order.
pub struct CoordIter<'a, C: DtCoord> {
    g: &'a DtGrid<C>,
    cur: Cursor,
}

impl<'a, C: DtCoord> CoordIter<'a, C> {
    /// Starts at the first node.
    pub fn new(g: &'a DtGrid<C>) -> Self {
        CoordIter {
            g,
            cur: Cursor::new(&g.levels, C::DIM),
        }
    }
}

impl<C: DtCoord> Iterator for CoordIter<'_, C> {
    type Item = C;
    fn next(&mut self) -> Option<C> {
        if self.cur.done {
            return None;
        }
        let c = C::from_slice(&self.cur.x[..C::DIM]);
        self.cur.advance(&self.g.levels);
        Some(c)
    }
}

/// A line's run pointer while walking it forward.
#[derive(Clone, Copy, Debug, Default)]
struct LineWalk {
    r: usize,
    end: usize,
}

/// The cells of a [`DtGrid`] whose `2^d` corners are all band nodes, in lexicographic order of
/// their lowest corner, found by intersecting the runs of the `2^(d−1)` corner lines.
#[derive(Clone)]
pub struct CellIter<'a, C: DtCoord> {
    g: &'a DtGrid<C>,
    prim: Cursor,
    /// Cursors finding the lines at prefix offsets `e ∈ {0,1}^(d−1)`, `e ≠ 0`.
    sec: Vec<Cursor>,
    lines: [LineWalk; 4],
    /// Per corner line, node index minus coordinate on the current interval's runs.
    bases: [u32; 4],
    started: bool,
    active: bool,
    x: i32,
    hi: i32,
}

impl<'a, C: DtCoord> CellIter<'a, C> {
    /// Starts before the first cell.
    pub fn new(g: &'a DtGrid<C>) -> Self {
        let depth = C::DIM - 1;
        let prim = Cursor::new(&g.levels, depth);
        CellIter {
            g,
            sec: vec![prim.clone(); (1 << depth) - 1],
            prim,
            lines: [LineWalk::default(); 4],
            bases: [0; 4],
            started: false,
            active: false,
            x: 0,
            hi: 0,
        }
    }

    /// One iterator per entry of the increasing `xs`, each starting before the first cell whose
    /// lowest corner has first coordinate `≥ xs[k]` (it runs on to the end; the caller stops
    /// it). One forward pass over the lines, so slabs of cells can be streamed in parallel.
    pub fn slabs(g: &'a DtGrid<C>, xs: &[i32]) -> Vec<Self> {
        let depth = C::DIM - 1;
        let mut cur = Cursor::new(&g.levels, depth);
        let mut out = Vec::with_capacity(xs.len());
        for &x0 in xs {
            let mut t = [i32::MIN; 3];
            t[0] = x0;
            cur.seek(&g.levels, &t[..depth]);
            let mut it = Self::new(g);
            it.prim = cur.clone();
            it.sec = vec![cur.clone(); (1 << depth) - 1];
            out.push(it);
        }
        out
    }

    fn nl(&self) -> usize {
        1 << (C::DIM - 1)
    }

    /// The cell interval `[start, end − 1]` of run `r` on the last level.
    fn cell_span(last: &Level, r: usize) -> (i32, i32) {
        (last.starts[r], last.end(r) - 1)
    }

    /// Finds the next interval of cells common to all corner lines, from the current runs on.
    fn find_interval(&mut self) -> bool {
        let last = self.g.last();
        let nl = self.nl();
        loop {
            let mut lo = i32::MIN;
            for w in &self.lines[..nl] {
                if w.r == w.end {
                    return false;
                }
                lo = lo.max(last.starts[w.r]);
            }
            let mut hi = i32::MAX;
            let mut ok = true;
            for w in &mut self.lines[..nl] {
                let (_, h) = Self::cell_span(last, w.r);
                if h < lo {
                    w.r += 1;
                    ok = false;
                } else {
                    hi = hi.min(h);
                }
            }
            if ok {
                for (b, w) in self.bases.iter_mut().zip(&self.lines[..nl]) {
                    *b = last.acc[w.r].wrapping_sub(last.starts[w.r] as u32);
                }
                self.x = lo;
                self.hi = hi;
                return true;
            }
        }
    }

    /// Sets up the corner lines of the primary cursor's prefix; false when one is missing.
    fn setup_lines(&mut self) -> bool {
        let levels = &self.g.levels;
        let depth = C::DIM - 1;
        let last = self.g.last();
        let l0 = self.prim.p[depth - 1];
        let runs = last.line_runs(l0);
        self.lines[0] = LineWalk {
            r: runs.start,
            end: runs.end,
        };
        for e in 1..self.nl() {
            let mut t = [0i32; 3];
            for (a, v) in t.iter_mut().enumerate().take(depth) {
                *v = self.prim.x[a] + ((e >> a) & 1) as i32;
            }
            match self.sec[e - 1].seek(levels, &t[..depth]) {
                Some(l) => {
                    let runs = last.line_runs(l);
                    self.lines[e] = LineWalk {
                        r: runs.start,
                        end: runs.end,
                    };
                }
                None => return false,
            }
        }
        true
    }
}

impl<C: DtCoord> Iterator for CellIter<'_, C> {
    type Item = (C, C::Cell);
    fn next(&mut self) -> Option<(C, C::Cell)> {
        let d = C::DIM;
        loop {
            if self.active {
                if self.x <= self.hi {
                    let x = self.x;
                    let mut cell = C::empty_cell();
                    let mask = (1 << (d - 1)) - 1;
                    for (c, v) in cell.as_mut().iter_mut().enumerate() {
                        let dx = ((c >> (d - 1)) & 1) as u32;
                        *v = self.bases[c & mask].wrapping_add(x as u32) + dx;
                    }
                    let mut lo = self.prim.x;
                    lo[d - 1] = x;
                    self.x += 1;
                    return Some((C::from_slice(&lo[..d]), cell));
                }
                let last = self.g.last();
                let hi = self.hi;
                for w in &mut self.lines[..1 << (d - 1)] {
                    if Self::cell_span(last, w.r).1 == hi {
                        w.r += 1;
                    }
                }
                if self.find_interval() {
                    continue;
                }
                self.active = false;
            }
            if self.started {
                self.prim.advance(&self.g.levels);
            }
            self.started = true;
            if self.prim.done {
                return None;
            }
            if self.setup_lines() && self.find_interval() {
                self.active = true;
            }
        }
    }
}

impl<C: DtCoord> DtGrid<C> {
    /// Calls `f(c, node, nbrs)` for every node in storage order with its `3^d` neighbourhood:
    /// `nbrs[m]` is the index of the node at `c + δ`, or `None` outside the band, where
    /// `m = Σ_a (δ_a + 1)·3^a` (axis 0 least significant; `nbrs[(3^d − 1)/2]` is the node).
    ///
    /// The `3^(d−1)` neighbouring lines are walked in lockstep with the node's line, so the
    /// pass streams through the arrays without random access.
    pub fn for_each_neighbourhood(&self, mut f: impl FnMut(C, usize, &[Option<usize>])) {
        let d = C::DIM;
        let depth = d - 1;
        let levels = &self.levels;
        let last = self.last();
        let mut prim = Cursor::new(levels, depth);
        let nlines = 3usize.pow(depth as u32);
        let mut sec = vec![prim.clone(); nlines];
        let mut walks: Vec<Option<LineWalk>> = vec![None; nlines];
        let mut nbrs = vec![None; nlines * 3];
        let mut node = 0usize;
        while !prim.done {
            for (ei, (s, w)) in sec.iter_mut().zip(walks.iter_mut()).enumerate() {
                let mut t = [0i32; 3];
                let mut q = ei;
                for (a, v) in t.iter_mut().enumerate().take(depth) {
                    *v = prim.x[a] + (q % 3) as i32 - 1;
                    q /= 3;
                }
                *w = s.seek(levels, &t[..depth]).map(|l| {
                    let runs = last.line_runs(l);
                    LineWalk {
                        r: runs.start,
                        end: runs.end,
                    }
                });
            }
            let own = last.line_runs(prim.p[depth - 1]);
            for r in own {
                for x in last.starts[r]..=last.end(r) {
                    for (ei, w) in walks.iter_mut().enumerate() {
                        let Some(w) = w else {
                            for dx in 0..3 {
                                nbrs[ei + nlines * dx] = None;
                            }
                            continue;
                        };
                        while w.r < w.end && last.end(w.r) < x - 1 {
                            w.r += 1;
                        }
                        for dx in 0..3 {
                            let v = x + dx as i32 - 1;
                            let mut found = None;
                            let mut q = w.r;
                            while q < w.end && last.starts[q] <= v {
                                if v <= last.end(q) {
                                    found =
                                        Some((last.acc[q] + (v - last.starts[q]) as u32) as usize);
                                    break;
                                }
                                q += 1;
                            }
                            nbrs[ei + nlines * dx] = found;
                        }
                    }
                    let mut c = prim.x;
                    c[d - 1] = x;
                    f(C::from_slice(&c[..d]), node, &nbrs);
                    node += 1;
                }
            }
            prim.advance(levels);
        }
    }
}
