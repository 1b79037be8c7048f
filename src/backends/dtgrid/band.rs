//! The narrow band as the finite elements see it (000 §2–§3): the nodes of a uniform grid that
//! lie within a few cells of the zero level, in lexicographic storage order, and the grid cells
//! whose `2^d` corners are all band nodes (the Q1 elements).
//!
//! [`Band`] is the seam between the storage (the dimension-recursive run-length encoding of a
//! DT-Grid, 000 §3) and the band finite elements (000 §2): assembly, the matrix–vector product
//! and the boundary conditions only use this trait, so any storage that answers it can carry them.

use crate::error::Result;

/// Integer grid coordinates of a node, `[i32; 2]` or `[i32; 3]`, ordered lexicographically
/// (the first coordinate most significant, the last one fastest — the storage order of 000 §3).
pub trait GridCoord:
    Copy + Ord + Eq + std::hash::Hash + std::fmt::Debug + Send + Sync + 'static
{
    /// The number of space dimensions.
    const DIM: usize;
    /// The node indices of one cell's `2^DIM` corners: `[u32; 4]` or `[u32; 8]`.
    type Cell: Copy + std::fmt::Debug + Send + Sync + AsRef<[u32]> + AsMut<[u32]> + 'static;
    /// The offset of corner `c` (`0 ≤ c < 2^DIM`) from a cell's lowest corner: along axis `a`
    /// it is bit `a` of `c` (corner 0 is the lowest corner, corner `2^DIM − 1` the highest).
    fn corner(self, c: usize) -> Self;
    /// The coordinate moved by `delta` along `axis`.
    fn offset(self, axis: usize, delta: i32) -> Self;
    /// Coordinate `axis`.
    fn get(self, axis: usize) -> i32;
    /// A cell whose corner indices are all zero.
    fn empty_cell() -> Self::Cell;
}

impl GridCoord for [i32; 2] {
    const DIM: usize = 2;
    type Cell = [u32; 4];
    fn corner(self, c: usize) -> Self {
        [self[0] + (c & 1) as i32, self[1] + ((c >> 1) & 1) as i32]
    }
    fn offset(mut self, axis: usize, delta: i32) -> Self {
        self[axis] += delta;
        self
    }
    fn get(self, axis: usize) -> i32 {
        self[axis]
    }
    fn empty_cell() -> [u32; 4] {
        [0; 4]
    }
}

impl GridCoord for [i32; 3] {
    const DIM: usize = 3;
    type Cell = [u32; 8];
    fn corner(self, c: usize) -> Self {
        [
            self[0] + (c & 1) as i32,
            self[1] + ((c >> 1) & 1) as i32,
            self[2] + ((c >> 2) & 1) as i32,
        ]
    }
    fn offset(mut self, axis: usize, delta: i32) -> Self {
        self[axis] += delta;
        self
    }
    fn get(self, axis: usize) -> i32 {
        self[axis]
    }
    fn empty_cell() -> [u32; 8] {
        [0; 8]
    }
}

/// A set of grid nodes (a narrow band) with node indices `0..len()` in lexicographic order.
///
/// Node indices are `u32` inside cells (a band has fewer than `2^32` nodes; constructors return
/// [`crate::Error::TooLarge`] beyond); storage internals may use wider integers.
pub trait Band: Sized + Send + Sync {
    /// The grid coordinate type, `[i32; 2]` or `[i32; 3]`.
    type Coord: GridCoord;

    /// Builds the band from its nodes given in strictly increasing lexicographic order.
    /// Error: [`crate::Error::InvalidInput`] when the order is not strictly increasing.
    fn from_sorted(coords: impl IntoIterator<Item = Self::Coord>) -> Result<Self>;

    /// The number of band nodes.
    fn len(&self) -> usize;

    /// Whether the band has no node.
    fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// The index of the node at `c`, or `None` when `c` is not in the band (random access).
    fn index(&self, c: Self::Coord) -> Option<usize>;

    /// Every node's coordinates, in index order (sequential iteration in storage order).
    fn coords(&self) -> impl Iterator<Item = Self::Coord> + '_;

    /// The cells whose `2^d` corners are all band nodes, in lexicographic order of their lowest
    /// corner: `(lowest corner, corner node indices)` with corners numbered as in
    /// [`GridCoord::corner`].
    fn cells(&self) -> impl Iterator<Item = (Self::Coord, <Self::Coord as GridCoord>::Cell)> + '_;

    /// The bytes the band's index uses (everything but the values stored per node).
    fn index_bytes(&self) -> usize;
}
