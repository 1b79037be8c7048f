//! Building a DT-Grid: the streaming builder over sorted nodes or runs, and the band of an
//! implicit function by hierarchical block pruning (000 §3), which never visits the whole grid.

use super::{grid_extent, DtCoord, DtGrid, Level, MAX_COORD};
use crate::error::{Error, Result};
use rayon::prelude::*;

/// A run along the last axis: its first node `c` (unused trailing components are zero) and its
/// node count.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord)]
pub(crate) struct Run {
    pub(crate) c: [i32; 3],
    pub(crate) len: u32,
}

/// Appends nodes or runs in strictly increasing lexicographic order, level by level.
pub(crate) struct Builder<C: DtCoord> {
    levels: Vec<Level>,
    /// Points per level so far.
    points: [u64; 3],
    /// The last node pushed.
    prev: Option<[i32; 3]>,
    _c: std::marker::PhantomData<C>,
}

impl<C: DtCoord> Builder<C> {
    pub(crate) fn new() -> Self {
        let mut levels = vec![Level::default(); C::DIM];
        levels[0].lines.push(0);
        Builder {
            levels,
            points: [0; 3],
            prev: None,
            _c: std::marker::PhantomData,
        }
    }

    /// Appends one node.
    pub(crate) fn push(&mut self, c: C) -> Result<()> {
        let mut a = [0; 3];
        for (k, v) in a.iter_mut().enumerate().take(C::DIM) {
            *v = c.get(k);
        }
        self.push_run(Run { c: a, len: 1 })
    }

    /// Appends the `run.len ≥ 1` nodes from `run.c` along the last axis.
    pub(crate) fn push_run(&mut self, run: Run) -> Result<()> {
        let d = C::DIM;
        let c = run.c;
        if c[..d].iter().any(|v| v.abs() > MAX_COORD)
            || c[d - 1] as i64 + run.len as i64 > MAX_COORD as i64
        {
            return Err(Error::InvalidInput(format!(
                "band node {:?} outside the coordinate range ±2^30",
                &c[..d]
            )));
        }
        let first = match self.prev {
            None => 0,
            Some(p) => match (0..d).find(|&k| c[k] != p[k]) {
                Some(k) if c[k] > p[k] => k,
                _ => {
                    return Err(Error::InvalidInput(format!(
                    "band nodes not in strictly increasing lexicographic order: {:?} after {:?}",
                    &c[..d],
                    &p[..d]
                )))
                }
            },
        };
        for k in first..d {
            let n = if k == d - 1 { run.len as u64 } else { 1 };
            let lev = &mut self.levels[k];
            let extend = k == first && self.prev.is_some_and(|p| c[k] == p[k] + 1);
            if !extend {
                if k > first {
                    lev.lines.push(lev.starts.len() as u32);
                }
                lev.starts.push(c[k]);
                lev.acc.push(self.points[k] as u32);
            }
            self.points[k] += n;
            if self.points[k] >= u32::MAX as u64 || lev.starts.len() >= u32::MAX as usize {
                return Err(Error::TooLarge(format!(
                    "a DT-Grid holds fewer than 2^32 - 1 nodes and runs; level {k} has {}",
                    self.points[k]
                )));
            }
        }
        let mut last = c;
        last[d - 1] += run.len as i32 - 1;
        self.prev = Some(last);
        Ok(())
    }

    pub(crate) fn finish(mut self) -> DtGrid<C> {
        for (k, lev) in self.levels.iter_mut().enumerate() {
            lev.lines.push(lev.starts.len() as u32);
            lev.acc.push(self.points[k] as u32);
            lev.lines.shrink_to_fit();
            lev.starts.shrink_to_fit();
            lev.acc.shrink_to_fit();
        }
        DtGrid::from_levels(self.levels)
    }
}

/// Sorts runs lexicographically and merges those that overlap or touch on the same line.
pub(crate) fn normalize(runs: &mut Vec<Run>, d: usize) {
    runs.par_sort_unstable();
    let mut out: Vec<Run> = Vec::with_capacity(runs.len());
    for &r in runs.iter() {
        if let Some(last) = out.last_mut() {
            let end = last.c[d - 1] as i64 + last.len as i64;
            if last.c[..d - 1] == r.c[..d - 1] && r.c[d - 1] as i64 <= end {
                let new_end = end.max(r.c[d - 1] as i64 + r.len as i64);
                last.len = (new_end - last.c[d - 1] as i64) as u32;
                continue;
            }
        }
        out.push(r);
    }
    *runs = out;
}

/// Builds a grid from runs already normalized (sorted, disjoint, not touching).
pub(crate) fn from_runs<C: DtCoord>(runs: &[Run]) -> Result<DtGrid<C>> {
    let mut b = Builder::<C>::new();
    for &r in runs {
        b.push_run(r)?;
    }
    Ok(b.finish())
}

/// The uniform grid and band half-width of [`DtGrid::from_implicit`]: nodes `0..=n` along every
/// axis, node `i` at the point `origin + h·i`.
#[derive(Clone, Copy, Debug)]
pub struct Implicit {
    /// Cells per side.
    pub n: usize,
    /// The point of node 0 (the first `d` components are used).
    pub origin: [f64; 3],
    /// The grid spacing.
    pub h: f64,
    /// The band half-width `j` in cells: the band holds the nodes where `|f| ≤ j·h`.
    pub half_width: u32,
}

/// Side of the leaf blocks of the pruning, in nodes.
const LEAF: i64 = 8;

impl<C: DtCoord> DtGrid<C> {
    /// The band `{ i : |f(origin + h·i)| ≤ j·h }` of a 1-Lipschitz function `f` (a signed
    /// distance, say) given on points (slices of length `d`).
    ///
    /// Hierarchical block pruning: a block of nodes is skipped when `|f|` at its centre exceeds
    /// `j·h` plus its half-diagonal, which no 1-Lipschitz `f` can have and still reach the band
    /// inside the block; surviving blocks split in `2^d` down to `8^d` leaves, whose nodes are
    /// evaluated. The work is proportional to the band plus a shell of the leaf size around it,
    /// never to the whole grid; the leaves are processed in parallel and the result does not
    /// depend on the thread count. For an `f` steeper than 1 nodes may be missed.
    ///
    /// Errors: [`Error::InvalidInput`] for `n` outside `1..2^30`, a non-positive or non-finite
    /// `h`, or a band wider than the grid (`2j > n`); [`Error::TooLarge`] beyond `2^32 − 1`
    /// nodes.
    pub fn from_implicit(g: &Implicit, f: impl Fn(&[f64]) -> f64 + Sync) -> Result<Self> {
        let d = C::DIM;
        let n = grid_extent(g.n)? as i64;
        if !(g.h > 0.0 && g.h.is_finite()) || g.origin[..d].iter().any(|o| !o.is_finite()) {
            return Err(Error::InvalidInput(format!(
                "grid spacing {} and origin {:?} must be finite, h > 0",
                g.h,
                &g.origin[..d]
            )));
        }
        if 2 * g.half_width as i64 > n {
            return Err(Error::InvalidInput(format!(
                "band half-width {} cells is wider than the grid of {n} cells",
                g.half_width
            )));
        }
        let w = g.half_width as f64 * g.h;
        let point = |x: [f64; 3]| -> [f64; 3] {
            let mut p = [0.0; 3];
            for a in 0..d {
                p[a] = g.origin[a] + g.h * x[a];
            }
            p
        };
        // Whether the block of nodes lo..lo+s (clipped to 0..=n) may hold band nodes.
        let keep = |lo: [i64; 3], s: i64| -> bool {
            let mut centre = [0.0; 3];
            let mut diag2 = 0.0;
            for a in 0..d {
                let hi = (lo[a] + s - 1).min(n);
                centre[a] = 0.5 * (lo[a] + hi) as f64;
                let e = 0.5 * (hi - lo[a]) as f64;
                diag2 += e * e;
            }
            let slack = w + g.h * diag2.sqrt();
            f(&point(centre)[..d]).abs() <= slack * (1.0 + 1e-12) + 1e-300
        };
        let mut size = LEAF;
        while size < n + 1 {
            size *= 2;
        }
        // Coarse levels sequentially until there are enough blocks to share, then in parallel.
        let mut blocks = vec![[0i64; 3]];
        while size > LEAF {
            let half = size / 2;
            let children: Vec<[i64; 3]> = blocks
                .par_iter()
                .flat_map_iter(|lo| {
                    let lo = *lo;
                    (0..1usize << d).filter_map(move |ch| {
                        let mut c = lo;
                        for (a, v) in c.iter_mut().enumerate().take(d) {
                            *v += half * ((ch >> a) & 1) as i64;
                        }
                        (c[..d].iter().all(|&v| v <= n)).then_some(c)
                    })
                })
                .filter(|c| keep(*c, half))
                .collect();
            blocks = children;
            size = half;
        }
        blocks.par_sort_unstable();
        // Slabs of leaves sharing their first coordinate, evaluated in parallel.
        let mut slabs: Vec<&[[i64; 3]]> = Vec::new();
        let mut rest = &blocks[..];
        while let Some(first) = rest.first() {
            let k = rest.partition_point(|b| b[0] == first[0]);
            slabs.push(&rest[..k]);
            rest = &rest[k..];
        }
        let per_slab: Vec<Vec<Run>> = slabs
            .par_iter()
            .map(|slab| {
                let mut runs = Vec::new();
                for lo in slab.iter() {
                    leaf_runs(d, n, *lo, &|x| f(&point(x)[..d]).abs() <= w, &mut runs);
                }
                normalize(&mut runs, d);
                runs
            })
            .collect();
        let mut b = Builder::<C>::new();
        for runs in &per_slab {
            for &r in runs {
                b.push_run(r)?;
            }
        }
        Ok(b.finish())
    }
}

/// Appends the runs of band nodes in the leaf block at `lo` (clipped to `0..=n`).
fn leaf_runs(
    d: usize,
    n: i64,
    lo: [i64; 3],
    inside: &dyn Fn([f64; 3]) -> bool,
    out: &mut Vec<Run>,
) {
    let hi: Vec<i64> = (0..d).map(|a| (lo[a] + LEAF - 1).min(n)).collect();
    // Iterate the prefixes (axes 0..d-1) of the block, then scan the last axis.
    let mut pre = lo;
    loop {
        let mut x = [0.0; 3];
        for a in 0..d - 1 {
            x[a] = pre[a] as f64;
        }
        let mut open: Option<Run> = None;
        for i in lo[d - 1]..=hi[d - 1] {
            x[d - 1] = i as f64;
            if inside(x) {
                match &mut open {
                    Some(r) => r.len += 1,
                    None => {
                        let mut c = [0i32; 3];
                        for a in 0..d - 1 {
                            c[a] = pre[a] as i32;
                        }
                        c[d - 1] = i as i32;
                        open = Some(Run { c, len: 1 });
                    }
                }
            } else if let Some(r) = open.take() {
                out.push(r);
            }
        }
        out.extend(open);
        // Next prefix, last prefix axis fastest.
        let mut a = d - 1;
        loop {
            if a == 0 {
                return;
            }
            a -= 1;
            if pre[a] < hi[a] {
                pre[a] += 1;
                break;
            }
            pre[a] = lo[a];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn more_than_u32_nodes_is_too_large() {
        // Two lines of 2^31 nodes each: 2^32 nodes, one beyond the limit.
        let mut b = Builder::<[i32; 2]>::new();
        let len = 1u32 << 31;
        b.push_run(Run {
            c: [0, -(1 << 30), 0],
            len,
        })
        .unwrap();
        let r = b.push_run(Run {
            c: [1, -(1 << 30), 0],
            len,
        });
        assert!(matches!(r, Err(Error::TooLarge(_))), "{r:?}");
    }

    #[test]
    fn runs_push_like_nodes() {
        // Touching runs merge into one; the grid equals the node-by-node build.
        let mut a = Builder::<[i32; 3]>::new();
        let mut b = Builder::<[i32; 3]>::new();
        for (c, len) in [
            ([0, 0, 3], 2u32),
            ([0, 0, 5], 1),
            ([0, 2, -1], 4),
            ([3, 0, 0], 1),
        ] {
            a.push_run(Run { c, len }).unwrap();
            for k in 0..len as i32 {
                b.push([c[0], c[1], c[2] + k]).unwrap();
            }
        }
        let (a, b) = (a.finish(), b.finish());
        assert_eq!(a, b);
        assert_eq!(a.runs(), 3);
    }
}
