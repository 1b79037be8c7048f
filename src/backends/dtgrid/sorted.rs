//! [`SortedBand`]: the simplest [`Band`] — the node coordinates in a sorted vector, random access
//! by binary search, cells found by looking up their corners. A reference for other storages
//! and a storage for moderate bands (16 or 24 bytes of index per node).

use super::band::{Band, GridCoord};
use crate::error::{Error, Result};

/// A band stored as its sorted node coordinates.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct SortedBand<C> {
    coords: Vec<C>,
}

impl<C: GridCoord> SortedBand<C> {
    /// The sorted node coordinates.
    pub fn as_slice(&self) -> &[C] {
        &self.coords
    }
}

impl<C: GridCoord> Band for SortedBand<C> {
    type Coord = C;

    fn from_sorted(coords: impl IntoIterator<Item = C>) -> Result<Self> {
        let coords: Vec<C> = coords.into_iter().collect();
        if let Some(i) = coords.windows(2).position(|w| w[0] >= w[1]) {
            return Err(Error::InvalidInput(format!(
                "band nodes not strictly increasing at position {}: {:?} then {:?}",
                i + 1,
                coords[i],
                coords[i + 1]
            )));
        }
        if coords.len() >= u32::MAX as usize {
            return Err(Error::TooLarge(format!(
                "a band of {} nodes (at most 2^32 − 1)",
                coords.len()
            )));
        }
        Ok(SortedBand { coords })
    }

    fn len(&self) -> usize {
        self.coords.len()
    }

    fn index(&self, c: C) -> Option<usize> {
        self.coords.binary_search(&c).ok()
    }

    fn coords(&self) -> impl Iterator<Item = C> + '_ {
        self.coords.iter().copied()
    }

    fn cells(&self) -> impl Iterator<Item = (C, C::Cell)> + '_ {
        let n = 1usize << C::DIM;
        self.coords.iter().enumerate().filter_map(move |(i0, &c)| {
            let mut cell = C::empty_cell();
            let idx = cell.as_mut();
            idx[0] = i0 as u32;
            for (k, slot) in idx.iter_mut().enumerate().take(n).skip(1) {
                *slot = self.index(c.corner(k))? as u32;
            }
            Some((c, cell))
        })
    }

    fn index_bytes(&self) -> usize {
        self.coords.len() * std::mem::size_of::<C>()
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn cells_are_the_full_cubes() {
        // A 3 × 3 × 2 block of nodes minus one corner node: 4 cells, one of them loses it.
        let mut nodes = Vec::new();
        for i in 0..3 {
            for j in 0..3 {
                for k in 0..2 {
                    if [i, j, k] != [2, 2, 1] {
                        nodes.push([i, j, k]);
                    }
                }
            }
        }
        let b = SortedBand::<[i32; 3]>::from_sorted(nodes.clone()).unwrap();
        assert_eq!(b.len(), 17);
        let cells: Vec<_> = b.cells().collect();
        assert_eq!(cells.len(), 3);
        for (c, idx) in cells {
            for (k, &i) in idx.iter().enumerate() {
                assert_eq!(b.coords().nth(i as usize).unwrap(), c.corner(k));
            }
        }
        assert!(SortedBand::<[i32; 3]>::from_sorted([[0, 0, 1], [0, 0, 0]]).is_err());
        assert_eq!(b.index([2, 2, 1]), None);
        assert_eq!(b.index([0, 0, 1]), Some(1));
    }
}
