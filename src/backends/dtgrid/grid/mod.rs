//! The DT-Grid (000 §3): a narrow band of uniform-grid nodes stored as a dimension-recursive
//! run-length encoding, with memory proportional to the band and independent of the grid size.
//!
//! Level `k` (`0 ≤ k < d`) encodes coordinate `k`. Its *points* are the distinct prefixes
//! `(x_0, …, x_k)` of band nodes in lexicographic order; the points of the last level are the
//! nodes. The points of level `k − 1` own one *line* each at level `k` (level 0 has a single
//! line), and a line is a sorted list of maximal *runs* of consecutive `x_k`. Per level the grid
//! keeps, as in 000 §3:
//! - `lines[l]`: the first run of line `l` (one entry per line plus an end sentinel);
//! - `starts[r]`: the first coordinate of run `r`;
//! - `acc[r]`: the index of the first point of run `r` (plus an end sentinel), so a run's length
//!   is `acc[r + 1] − acc[r]` and its end coordinate is not stored.
//!
//! Every count (runs, points, nodes) is below `2^32`, the node limit of the [`Band`] seam, and is
//! stored as `u32`; builders return [`Error::TooLarge`] beyond. The index then takes 8 bytes per
//! run plus 4 bytes per line: about 1.1 bytes per node for a sphere band of half-width 2 cells in
//! a `1024³` grid (`anisomesh bench band`). Values are not stored: the caller keeps a `Vec`
//! indexed by node.
//!
//! Files: `build.rs` (the streaming builder, [`DtGrid::from_implicit`]), `iter.rs` (sequential,
//! cell and neighbourhood iterators walking lines in lockstep), `dilate.rs` (band dilation on
//! runs and value transfer between bands).

mod build;
mod dilate;
mod iter;

pub use build::Implicit;
pub use dilate::transfer_values;
pub use iter::{CellIter, CoordIter};

use super::band::{Band, GridCoord};
use crate::error::{Error, Result};

/// The largest absolute coordinate a DT-Grid accepts (so that `x ± 1` never overflows `i32`).
pub const MAX_COORD: i32 = 1 << 30;

/// A [`GridCoord`] that can be built from its coordinates (`[i32; 2]`, `[i32; 3]`).
pub trait DtCoord: GridCoord {
    /// The coordinate with components `s[0..DIM]`.
    fn from_slice(s: &[i32]) -> Self;
}

impl DtCoord for [i32; 2] {
    fn from_slice(s: &[i32]) -> Self {
        [s[0], s[1]]
    }
}

impl DtCoord for [i32; 3] {
    fn from_slice(s: &[i32]) -> Self {
        [s[0], s[1], s[2]]
    }
}

/// One level of the run-length encoding (see the module documentation).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub(crate) struct Level {
    /// First run of each line, plus the end sentinel.
    pub(crate) lines: Vec<u32>,
    /// First coordinate of each run.
    pub(crate) starts: Vec<i32>,
    /// Index of each run's first point, plus the end sentinel (the point count).
    pub(crate) acc: Vec<u32>,
}

impl Level {
    /// The run range of line `l`.
    #[inline]
    pub(crate) fn line_runs(&self, l: usize) -> std::ops::Range<usize> {
        self.lines[l] as usize..self.lines[l + 1] as usize
    }

    /// The last coordinate of run `r`.
    #[inline]
    pub(crate) fn end(&self, r: usize) -> i32 {
        self.starts[r] + (self.acc[r + 1] - self.acc[r]) as i32 - 1
    }

    /// The point at coordinate `x` on line `l`, if any (binary search over the line's runs).
    #[inline]
    pub(crate) fn find(&self, l: usize, x: i32) -> Option<usize> {
        let runs = self.line_runs(l);
        let s = &self.starts[runs.clone()];
        let k = s.partition_point(|&st| st <= x);
        if k == 0 {
            return None;
        }
        let r = runs.start + k - 1;
        let off = (x - self.starts[r]) as u32;
        (off < self.acc[r + 1] - self.acc[r]).then(|| (self.acc[r] + off) as usize)
    }

    fn bytes(&self) -> usize {
        4 * (self.lines.len() + self.starts.len() + self.acc.len())
    }
}

/// A narrow band of grid nodes in DT-Grid storage (000 §3), in 2D (`C = [i32; 2]`) or 3D
/// (`C = [i32; 3]`).
///
/// Random access ([`Band::index`]) is a binary search within one line per level, `O(d log r)`
/// for `r` runs per line; sequential iteration ([`Band::coords`]), the cell iterator
/// ([`Band::cells`]) and the neighbourhoods ([`DtGrid::for_each_neighbourhood`]) stream through
/// the arrays without random access.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct DtGrid<C: DtCoord> {
    pub(crate) levels: Vec<Level>,
    _coord: std::marker::PhantomData<C>,
}

impl<C: DtCoord> DtGrid<C> {
    pub(crate) fn from_levels(levels: Vec<Level>) -> Self {
        debug_assert_eq!(levels.len(), C::DIM);
        DtGrid {
            levels,
            _coord: std::marker::PhantomData,
        }
    }

    /// The number of maximal runs along the last axis (the innermost level).
    pub fn runs(&self) -> usize {
        self.levels[C::DIM - 1].starts.len()
    }

    /// Builds the band from nodes in strictly increasing lexicographic order, all within the
    /// grid of `n` cells per side (nodes `0..=n` along every axis).
    /// Errors: [`Error::InvalidInput`] for a node outside the grid or out of order,
    /// [`Error::TooLarge`] beyond `2^32 − 1` nodes.
    pub fn from_sorted_in(coords: impl IntoIterator<Item = C>, n: usize) -> Result<Self> {
        let n = grid_extent(n)?;
        let mut b = build::Builder::<C>::new();
        for c in coords {
            for a in 0..C::DIM {
                if !(0..=n).contains(&c.get(a)) {
                    return Err(Error::InvalidInput(format!(
                        "band node {c:?} lies outside the grid 0..={n}"
                    )));
                }
            }
            b.push(c)?;
        }
        Ok(b.finish())
    }

    /// The innermost level (its points are the nodes).
    #[inline]
    pub(crate) fn last(&self) -> &Level {
        &self.levels[C::DIM - 1]
    }
}

/// The grid extent `n` as `i32`, checked against [`MAX_COORD`].
pub(crate) fn grid_extent(n: usize) -> Result<i32> {
    if n == 0 || n >= MAX_COORD as usize {
        return Err(Error::InvalidInput(format!(
            "grid of {n} cells per side: need 1 ≤ n < 2^30"
        )));
    }
    Ok(n as i32)
}

impl<C: DtCoord> Band for DtGrid<C> {
    type Coord = C;

    fn from_sorted(coords: impl IntoIterator<Item = C>) -> Result<Self> {
        let mut b = build::Builder::<C>::new();
        for c in coords {
            b.push(c)?;
        }
        Ok(b.finish())
    }

    fn len(&self) -> usize {
        *self.last().acc.last().unwrap_or(&0) as usize
    }

    fn index(&self, c: C) -> Option<usize> {
        let mut line = 0;
        for (k, lev) in self.levels.iter().enumerate() {
            line = lev.find(line, c.get(k))?;
        }
        Some(line)
    }

    fn coords(&self) -> impl Iterator<Item = C> + '_ {
        CoordIter::new(self)
    }

    fn cells(&self) -> impl Iterator<Item = (C, C::Cell)> + '_ {
        CellIter::new(self)
    }

    fn index_bytes(&self) -> usize {
        self.levels.iter().map(Level::bytes).sum::<usize>() + std::mem::size_of::<Self>()
    }
}
