//! The `3³` neighbourhoods of the nodes of a sorted band (the distance extension of 000 §2.4
//! visits them several times per rebuild), in 40 bytes per node instead of 27 indices.
//!
//! The neighbours of a node in one grid column `(x + dx, y + dy)` are consecutive in storage
//! order, so a column is its first index at or above `z − 1` (the base) and three bits saying
//! which of `z − 1, z, z + 1` are band nodes: a neighbour's index is the base plus the number of
//! present neighbours below it in its column.

use super::lattice::C3;
use rayon::prelude::*;

/// The neighbours of one node (itself included) in the band.
#[derive(Clone, Copy, Debug, Default)]
pub(super) struct Nbhd {
    /// Per column `k`: the first index at or above `(x + dx, y + dy, z − 1)`.
    base: [u32; 9],
    /// Bit `dz · 9 + k`: the neighbour at offset `(k mod 3 − 1, k div 3 − 1, dz − 1)` is a band
    /// node.
    mask: u32,
}

impl Nbhd {
    /// The indices of the neighbours present, in slot order (`z` slowest, then `y`, then `x`).
    /// A column's slots come in increasing `dz`, so each column keeps the index of its next
    /// present neighbour (no population count per neighbour).
    #[inline]
    pub(super) fn iter(&self) -> impl Iterator<Item = u32> + '_ {
        self.slots().map(|(_, i)| i)
    }

    /// The present neighbours as `(slot, index)`, in slot order; slot `dz · 9 + dy · 3 + dx`
    /// holds the neighbour at offset `(dx − 1, dy − 1, dz − 1)` ([`SLOT_SELF`] the node itself).
    #[inline]
    pub(super) fn slots(&self) -> impl Iterator<Item = (u32, u32)> + '_ {
        let mut m = self.mask;
        let mut next = self.base;
        std::iter::from_fn(move || {
            if m == 0 {
                return None;
            }
            let slot = m.trailing_zeros();
            m &= m - 1;
            let k = (slot % 9) as usize;
            let i = next[k];
            next[k] += 1;
            Some((slot, i))
        })
    }
}

/// The slot of the node itself in its neighbourhood.
pub(super) const SLOT_SELF: u32 = 13;

/// Per slot `s`: bit `r` is set when the neighbour at slot `r` of the node at slot `s` is itself
/// in the neighbourhood (the two offsets add up to one within `3³`).
pub(super) const WITHIN: [u32; 27] = within();

const fn within() -> [u32; 27] {
    let mut out = [0u32; 27];
    let mut s = 0;
    while s < 27 {
        let mut r = 0;
        while r < 27 {
            let (a, b) = (offset(s), offset(r));
            let mut inside = true;
            let mut k = 0;
            while k < 3 {
                let v = a[k] + b[k];
                if v < -1 || v > 1 {
                    inside = false;
                }
                k += 1;
            }
            if inside {
                out[s] |= 1 << r;
            }
            r += 1;
        }
        s += 1;
    }
    out
}

/// Per slot `s`: bit `c` is set when the cell that has the neighbour at slot `s` as its corner
/// `c` (corner bits: 1 = x, 2 = y, 4 = z) also has the node itself as a corner.
pub(super) const SHARED_CELL: [u8; 27] = shared_cell();

const fn shared_cell() -> [u8; 27] {
    let mut out = [0u8; 27];
    let mut s = 0;
    while s < 27 {
        let o = offset(s);
        let mut c = 0;
        while c < 8 {
            // The cell's lowest corner is `o − bits(c)` from the node; the node is a corner when
            // `bits(c) − o` is 0 or 1 along every axis.
            let mut inside = true;
            let mut k = 0;
            while k < 3 {
                let v = ((c >> k) & 1) - o[k];
                if v < 0 || v > 1 {
                    inside = false;
                }
                k += 1;
            }
            if inside {
                out[s] |= 1 << c;
            }
            c += 1;
        }
        s += 1;
    }
    out
}

/// The offset `(dx, dy, dz)` of slot `s`.
const fn offset(s: usize) -> [i32; 3] {
    [
        (s % 3) as i32 - 1,
        ((s / 3) % 3) as i32 - 1,
        (s / 9) as i32 - 1,
    ]
}

/// The neighbourhood of every node of the sorted coordinates `coords`, found by one forward
/// cursor per neighbouring column (in parallel chunks; no search but at a chunk's start).
pub(super) fn neighbourhoods(coords: &[C3]) -> Vec<Nbhd> {
    const CHUNK: usize = 1 << 14;
    let n = coords.len();
    let mut out = vec![Nbhd::default(); n];
    out.par_chunks_mut(CHUNK)
        .enumerate()
        .for_each(|(chunk, out)| {
            let start = chunk * CHUNK;
            let first = coords[start];
            let mut cur = [0usize; 9];
            for (k, cur) in cur.iter_mut().enumerate() {
                let t = [
                    first[0] + (k % 3) as i32 - 1,
                    first[1] + (k / 3) as i32 - 1,
                    first[2] - 1,
                ];
                *cur = coords.partition_point(|c| *c < t);
            }
            for (o, &c) in out.iter_mut().zip(&coords[start..]) {
                let mut mask = 0u32;
                for (k, cur) in cur.iter_mut().enumerate() {
                    let (x, y) = (c[0] + (k % 3) as i32 - 1, c[1] + (k / 3) as i32 - 1);
                    let t0 = [x, y, c[2] - 1];
                    while *cur < n && coords[*cur] < t0 {
                        *cur += 1;
                    }
                    o.base[k] = *cur as u32;
                    let mut q = *cur;
                    for dz in 0..3 {
                        let t = [x, y, c[2] + dz as i32 - 1];
                        while q < n && coords[q] < t {
                            q += 1;
                        }
                        if q < n && coords[q] == t {
                            mask |= 1 << (dz * 9 + k);
                        }
                    }
                }
                o.mask = mask;
            }
        });
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::band::Band;
    use crate::backends::dtgrid::lattice::{band_around, crossing_cells_of_fn, Lattice};
    use crate::backends::dtgrid::{DtGrid, SortedBand};
    use crate::geom::DVec3;

    #[test]
    fn neighbourhoods_equal_random_access() {
        // A band with holes, several runs per column and chunk boundaries inside runs.
        let lat = Lattice::unit(81).unwrap();
        let f = |p: DVec3| {
            let r = p.length();
            (r - 0.3).abs().min((r - 0.15).abs()) - 0.02 + 0.01 * (9.0 * p.x).sin()
        };
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb = band_around::<DtGrid<C3>>(&lat, &cross, 1).unwrap();
        let coords: Vec<C3> = nb.band.coords().collect();
        assert!(coords.len() > 1 << 15, "{} nodes", coords.len());
        let band = SortedBand::from_sorted(coords.iter().copied()).unwrap();
        let nbr = neighbourhoods(&coords);
        for (c, nb) in coords.iter().zip(&nbr) {
            let mut want = Vec::new();
            for dz in -1..=1 {
                for dy in -1..=1 {
                    for dx in -1..=1 {
                        let q = [c[0] + dx, c[1] + dy, c[2] + dz];
                        want.extend(band.index(q).map(|i| i as u32));
                    }
                }
            }
            assert_eq!(nb.iter().collect::<Vec<_>>(), want, "{c:?}");
        }
    }
}
