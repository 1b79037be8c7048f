//! Rebuilding the band when the zero level moves (000 §2.3): dilation of a seed set on runs,
//! the seed of the cells where a field changes sign, and the transfer of node values from an
//! old band to a new one.

use super::build::{from_runs, normalize, Run};
use super::{grid_extent, CoordIter, DtCoord, DtGrid};
use crate::backends::dtgrid::band::Band;
use crate::error::{Error, Result};
use std::cmp::Ordering;

impl<C: DtCoord> DtGrid<C> {
    /// The runs along the last axis, in storage order.
    pub(crate) fn to_runs(&self) -> Vec<Run> {
        let d = C::DIM;
        let last = self.last();
        let mut out = Vec::with_capacity(self.runs());
        let mut cur = super::iter::Cursor::new(&self.levels, d - 1);
        while !cur.done {
            for r in last.line_runs(cur.p[d - 2]) {
                let mut c = cur.x;
                c[d - 1] = last.starts[r];
                out.push(Run {
                    c,
                    len: last.acc[r + 1] - last.acc[r],
                });
            }
            cur.advance(&self.levels);
        }
        out
    }

    /// The nodes within Chebyshev distance `j` (in cells: `max_a |x_a − y_a| ≤ j`) of a node of
    /// `self`, clipped to the grid `0..=n`: the band of half-width `j` around the seed `self`.
    ///
    /// Computed on runs, one axis after the other (the Chebyshev ball is a product of
    /// intervals): along the last axis every run grows by `j` at both ends; along another axis
    /// every run is copied to the `2j + 1` neighbouring lines; runs are then sorted and merged.
    /// The cost is `O(d (2j+1) R log R)` for `R` runs, independent of the grid size.
    ///
    /// Errors: [`Error::InvalidInput`] for a seed node outside `0..=n` or `j > n` (a band
    /// wider than the grid), [`Error::TooLarge`] beyond `2^32 − 1` nodes.
    pub fn dilate(&self, j: u32, n: usize) -> Result<Self> {
        let d = C::DIM;
        let n = grid_extent(n)?;
        if j as i64 > n as i64 {
            return Err(Error::InvalidInput(format!(
                "dilation by {j} cells is wider than the grid of {n} cells"
            )));
        }
        let j = j as i32;
        let mut runs = self.to_runs();
        for r in &mut runs {
            let end = r.c[d - 1] + r.len as i32 - 1;
            if r.c[..d].iter().any(|&v| v < 0 || v > n) || end > n {
                return Err(Error::InvalidInput(format!(
                    "seed node {:?} lies outside the grid 0..={n}",
                    &r.c[..d]
                )));
            }
            let s = (r.c[d - 1] - j).max(0);
            let e = (end + j).min(n);
            r.c[d - 1] = s;
            r.len = (e - s + 1) as u32;
        }
        normalize(&mut runs, d);
        for a in 0..d - 1 {
            let mut grown = Vec::with_capacity(runs.len() * (2 * j as usize + 1));
            for r in &runs {
                for t in (r.c[a] - j).max(0)..=(r.c[a] + j).min(n) {
                    let mut q = *r;
                    q.c[a] = t;
                    grown.push(q);
                }
            }
            normalize(&mut grown, d);
            runs = grown;
        }
        from_runs(&runs)
    }

    /// The nodes `x + δ` with `x` in `self` and `−minus ≤ δ_a ≤ plus` along every axis (not
    /// clipped to any grid): `grow(0, 1)` turns cells (lowest corners) into their corner nodes,
    /// `grow(1, 1)` is the `3^d` neighbourhood. Computed on runs as [`DtGrid::dilate`]; the
    /// lowest and highest coordinate along each axis come with it (for the caller's bounds
    /// check).
    /// Error: [`Error::InvalidInput`] for a negative `minus` or `plus`, or coordinates beyond
    /// `±2^30`.
    pub fn grow(&self, minus: i32, plus: i32) -> Result<(Self, [i32; 3], [i32; 3])> {
        let d = C::DIM;
        if minus < 0 || plus < 0 {
            return Err(Error::InvalidInput(format!(
                "growing a band by -{minus}..{plus} cells"
            )));
        }
        let mut runs = self.to_runs();
        for r in &mut runs {
            r.c[d - 1] -= minus;
            r.len += (minus + plus) as u32;
        }
        normalize(&mut runs, d);
        for a in 0..d - 1 {
            let mut grown = Vec::with_capacity(runs.len() * (minus + plus + 1) as usize);
            for r in &runs {
                for t in r.c[a] - minus..=r.c[a] + plus {
                    let mut q = *r;
                    q.c[a] = t;
                    grown.push(q);
                }
            }
            normalize(&mut grown, d);
            runs = grown;
        }
        let (mut lo, mut hi) = ([i32::MAX; 3], [i32::MIN; 3]);
        for r in &runs {
            for a in 0..d {
                lo[a] = lo[a].min(r.c[a]);
                let end = if a == d - 1 {
                    r.c[a] + r.len as i32 - 1
                } else {
                    r.c[a]
                };
                hi[a] = hi[a].max(end);
            }
        }
        Ok((from_runs(&runs)?, lo, hi))
    }

    /// The corner nodes of the cells whose corner values `u` are neither all `> 0` nor all
    /// `< 0` (the cells the zero level of `u` meets): the seed of the band around that level.
    /// Error: [`Error::InvalidField`] when `u` does not have one value per node.
    pub fn sign_change_seed(&self, u: &[f64]) -> Result<Self> {
        if u.len() != self.len() {
            return Err(Error::InvalidField {
                name: "u".into(),
                msg: format!("{} values for {} band nodes", u.len(), self.len()),
            });
        }
        let mut mark = vec![false; self.len()];
        for (_, cell) in self.cells() {
            let cs = cell.as_ref();
            let pos = cs.iter().all(|&i| u[i as usize] > 0.0);
            let neg = cs.iter().all(|&i| u[i as usize] < 0.0);
            if !pos && !neg {
                for &i in cs {
                    mark[i as usize] = true;
                }
            }
        }
        Self::from_sorted(self.coords().zip(mark).filter_map(|(c, m)| m.then_some(c)))
    }
}

/// The values of `new`'s nodes: `old_values` where the node is also in `old`, `fill` elsewhere
/// (one merge pass over both bands in storage order).
/// Error: [`Error::InvalidField`] when `old_values` does not have one value per node of `old`.
pub fn transfer_values<C: DtCoord>(
    old: &DtGrid<C>,
    old_values: &[f64],
    new: &DtGrid<C>,
    fill: f64,
) -> Result<Vec<f64>> {
    if old_values.len() != old.len() {
        return Err(Error::InvalidField {
            name: "old_values".into(),
            msg: format!("{} values for {} band nodes", old_values.len(), old.len()),
        });
    }
    let mut out = Vec::with_capacity(new.len());
    let mut it = CoordIter::new(old)
        .zip(old_values.iter().copied())
        .peekable();
    for c in CoordIter::new(new) {
        let mut v = fill;
        while let Some(&(o, ov)) = it.peek() {
            match o.cmp(&c) {
                Ordering::Less => {
                    it.next();
                }
                Ordering::Equal => {
                    v = ov;
                    it.next();
                    break;
                }
                Ordering::Greater => break,
            }
        }
        out.push(v);
    }
    Ok(out)
}
