//! The nearest zero-level triangle of every band node by a direct search of the crossed cells
//! around it (the signed distance extension of 000 §2.4): the first, exact stage of
//! [`super::distance`], before closest-triangle propagation takes over where it cannot certify.
//!
//! A node `p` looks at the crossed cells that have a corner in its `3³` neighbourhood (lowest
//! corner at `p + {−2, …, 1}³`, a `4³` window). They come from the sorted crossed cells by one
//! forward cursor per window column, as the window of a node after `p` in storage order starts
//! after `p`'s. Each cell carries a flat cylinder around its triangles (the slab across their
//! mean normal and a disc along it), a lower bound of the distance to them: the cell of the
//! lowest bound is measured first, then every other cell whose bound does not exceed the best
//! triangle so far (by more than the tie tolerance), so a node mostly measures one or two cells
//! (the disc bound of each triangle skips most of their triangles too). Every
//! triangle outside the window is at least `2h` from `p`, so the result is exact when the best
//! distance is below `2h`; the node is then *certified*, and propagation does not revisit it
//! for its own sake.

use super::distance::{nearest, Tris, NONE};
use super::lattice::{Lattice, C3};
use super::zero_level::Level;
use crate::geom::DVec3;
use rayon::prelude::*;

/// The window's columns and depth: offsets `LO..LO + W` along every axis.
const LO: i32 = -2;
const W: usize = 4;

/// Per node: its nearest triangle (`NONE` if none in the window), the distance, whether it is a
/// corner of a crossed cell (`I¹`), and whether the search certified the triangle.
pub(super) struct Gathered {
    pub best: Vec<u32>,
    pub dist: Vec<f64>,
    pub crossing: Vec<bool>,
    pub certified: Vec<bool>,
}

/// The crossed cells of `l` with a bound around each cell's triangles and the cell's range of
/// triangles.
struct Cells {
    keys: Vec<C3>,
    bounds: Vec<Slab>,
    /// Cell `k`'s triangles are `first[k]..first[k + 1]`.
    first: Vec<u32>,
}

impl Cells {
    fn new(l: &Level) -> Cells {
        let keys: Vec<C3> = l.cells.iter().map(|(c, _)| *c).collect();
        let mut first = vec![0u32; keys.len() + 1];
        for &c in &l.tri_cell {
            first[c as usize + 1] += 1;
        }
        for k in 1..first.len() {
            first[k] += first[k - 1];
        }
        let bounds = (0..keys.len())
            .into_par_iter()
            .map(|k| Slab::new(&l.tris[first[k] as usize..first[k + 1] as usize]))
            .collect();
        Cells {
            keys,
            bounds,
            first,
        }
    }
}

/// A flat cylinder holding a cell's triangles: the slab `|n · (x − c)| ≤ half` and, in the plane,
/// the disc of radius `radius` about `c` (`n` the mean normal of the triangles, `c` the centre of
/// their box; one cache line).
#[derive(Clone, Copy)]
#[repr(C, align(64))]
struct Slab {
    centre: DVec3,
    radius: f64,
    normal: DVec3,
    half: f64,
}

impl Slab {
    fn new(tris: &[[DVec3; 3]]) -> Slab {
        let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
        let mut n = DVec3::ZERO;
        for &[a, b, c] in tris {
            lo = lo.min(a).min(b).min(c);
            hi = hi.max(a).max(b).max(c);
            n += (b - a).cross(c - a);
        }
        let normal = n.try_normalize().unwrap_or(DVec3::ZERO);
        let centre = 0.5 * (lo + hi);
        let (mut half, mut radius) = (0.0f64, 0.0f64);
        for &v in tris.iter().flatten() {
            let s = normal.dot(v - centre);
            half = half.max(s.abs());
            radius = radius.max((v - centre - s * normal).length());
        }
        // Rounding slack, so the bound never exceeds a distance computed from the vertices.
        Slab {
            centre,
            radius: radius * (1.0 + 1e-9),
            normal,
            half: half * (1.0 + 1e-9),
        }
    }

    /// A lower bound of the distance of `p` to the triangles inside: every point `x` of them has
    /// `|p − x|² = (n · (p − x))² + |in-plane part of p − x|²`, each part bounded from below by
    /// the slab and the disc.
    #[inline]
    fn lower_bound(&self, p: DVec3) -> f64 {
        let d = p - self.centre;
        let s = self.normal.dot(d);
        let across = (s.abs() - self.half).max(0.0);
        let along = ((d - s * self.normal).length() - self.radius).max(0.0);
        (across * across + along * along).sqrt() * (1.0 - 1e-9)
    }
}

/// The nearest triangle of `l` (`tris`) to every node of the sorted coordinates `coords`
/// within its window; ties within `tie` as in [`nearest`].
pub(super) fn gather(lat: &Lattice, l: &Level, tris: &Tris, coords: &[C3], tie: f64) -> Gathered {
    const CHUNK: usize = 1 << 13;
    let cells = Cells::new(l);
    let keys = &cells.keys;
    let nk = keys.len();
    // Certified below this distance (with a margin for rounding).
    let reach = 2.0 * lat.h * (1.0 - 1e-9) - tie;
    let mut out = vec![(f64::INFINITY, NONE, 0u8); coords.len()];
    out.par_chunks_mut(CHUNK)
        .enumerate()
        .for_each(|(chunk, out)| {
            let start = chunk * CHUNK;
            let column = |c: C3, k: usize| (c[0] + LO + (k % W) as i32, c[1] + LO + (k / W) as i32);
            // One cursor per window column, started by a search at the chunk's first node.
            let mut cur = [0usize; W * W];
            for (k, cur) in cur.iter_mut().enumerate() {
                let (x, y) = column(coords[start], k);
                let t = [x, y, coords[start][2] + LO];
                *cur = keys.partition_point(|c| *c < t);
            }
            // The window's cells as (lower bound, cell).
            let mut cand = [(0.0f64, 0u32); W * W * W];
            for (o, &c) in out.iter_mut().zip(&coords[start..]) {
                let p = lat.pos(c);
                let (mut n, mut crossing) = (0, false);
                for (k, cur) in cur.iter_mut().enumerate() {
                    let (x, y) = column(c, k);
                    let (lo, hi) = ([x, y, c[2] + LO], [x, y, c[2] + LO + W as i32 - 1]);
                    while *cur < nk && keys[*cur] < lo {
                        *cur += 1;
                    }
                    let mut q = *cur;
                    while q < nk && keys[q] <= hi {
                        let d = keys[q];
                        crossing |= (0..3).all(|a| (-1..=0).contains(&(d[a] - c[a])));
                        cand[n] = (cells.bounds[q].lower_bound(p), q as u32);
                        n += 1;
                        q += 1;
                    }
                }
                let cand = &mut cand[..n];
                // The cell of the lowest bound first (the first of them in cell order), then the
                // others in cell order, each unless its bound exceeds the best so far (the
                // order does not depend on the chunking).
                if let Some(k) = (0..n).min_by(|&a, &b| cand[a].0.total_cmp(&cand[b].0)) {
                    cand[..=k].rotate_right(1);
                }
                let (mut bd, mut bt) = (f64::INFINITY, NONE);
                for &(lb, q) in cand.iter() {
                    if lb > bd + tie {
                        continue;
                    }
                    let q = q as usize;
                    let range = cells.first[q]..cells.first[q + 1];
                    (bd, bt, _) = nearest(tris, p, (bd, bt, 0), tie, range.map(|t| (0, t)));
                }
                let certified = bt != NONE && bd < reach;
                *o = (bd, bt, crossing as u8 | (certified as u8) << 1);
            }
        });
    Gathered {
        best: out.iter().map(|o| o.1).collect(),
        dist: out.iter().map(|o| o.0).collect(),
        crossing: out.iter().map(|o| o.2 & 1 != 0).collect(),
        certified: out.iter().map(|o| o.2 & 2 != 0).collect(),
    }
}
