//! The cells crossed by the zero level of an implicit function found without visiting the whole
//! grid (000 §3): the nodes where `|f| ≤ 2h` come from the block-pruned construction of
//! [`DtGrid::from_implicit`] (a block is discarded when `|f|` at its centre exceeds its
//! half-diagonal plus the band width, valid for a function with a known Lipschitz bound `L`;
//! `f/L` is pruned), and the crossed cells are the cells of that thin band whose corner values
//! change sign. The work and memory are proportional to the band plus a shell of leaf blocks
//! around it, so a sphere in a `4096³` grid costs seconds where the dense pass over all `n³`
//! nodes ([`super::lattice::crossing_cells_of_fn`]) would evaluate `6.9·10¹⁰` points.
//!
//! Why the thin band holds every crossed cell: if a cell's corner values `a < 0 ≤ b` change sign,
//! `|a|, |b| ≤ |a − b| ≤ L·√3·h`, so every corner of every crossed cell has `|f/L| ≤ √3 h < 2h`.
//! The result is the same list, in the same order, as the dense pass.

use super::band::Band;
use super::grid::{DtGrid, Implicit};
use super::lattice::{band_around, crosses, crossing_cells_of_fn, Lattice, NarrowBand, C3};
use super::mcf::McfState;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use rayon::prelude::*;
use std::sync::Mutex;

/// Below this many nodes per side the dense pass over the grid is cheaper than the pruning.
pub const DENSE_BELOW: usize = 48;

/// The cells (lowest corners, sorted) crossed by the zero level of `f`, an `lipschitz`-Lipschitz
/// function, found by block pruning (see the module documentation).
/// Errors: [`Error::InvalidField`] for a NaN met at a node or block centre,
/// [`Error::InvalidInput`] for a non-positive Lipschitz bound or a grid too small for the thin
/// band (`n < 5`), [`Error::TooLarge`] beyond `2^32 − 1` band nodes.
pub fn crossing_cells_pruned(
    lat: &Lattice,
    f: &(impl Fn(DVec3) -> f64 + Sync),
    lipschitz: f64,
) -> Result<Vec<C3>> {
    if !(lipschitz.is_finite() && lipschitz > 0.0) {
        return Err(Error::InvalidInput(format!(
            "Lipschitz bound {lipschitz} of the level-set function (finite, positive)"
        )));
    }
    let g = Implicit {
        n: lat.n - 1,
        origin: [lat.lo; 3],
        h: lat.h,
        half_width: 2,
    };
    let nan: Mutex<Option<[f64; 3]>> = Mutex::new(None);
    // A NaN keeps its block and node (value 0) and is reported below.
    let scaled = |s: &[f64]| -> f64 {
        let v = f(DVec3::new(s[0], s[1], s[2]));
        if v.is_nan() {
            let mut g = nan.lock().unwrap_or_else(|e| e.into_inner());
            if g.is_none() {
                *g = Some([s[0], s[1], s[2]]);
            }
            return 0.0;
        }
        v / lipschitz
    };
    let thin: DtGrid<C3> = DtGrid::from_implicit(&g, scaled)?;
    if let Some(p) = *nan.lock().unwrap_or_else(|e| e.into_inner()) {
        return Err(Error::InvalidField {
            name: "level-set function".into(),
            msg: format!("NaN at the point {p:?}"),
        });
    }
    let coords: Vec<C3> = thin.coords().collect();
    let v: Vec<f64> = coords.par_iter().map(|&c| f(lat.pos(c))).collect();
    drop(coords);
    Ok(thin
        .cells()
        .filter(|(_, idx)| crosses(&idx.map(|i| v[i as usize])))
        .map(|(c, _)| c)
        .collect())
}

/// The crossed cells of `f` by the cheaper of the dense pass and the pruning: the pruning when
/// a Lipschitz bound is known and the grid has at least [`DENSE_BELOW`] nodes per side.
/// Errors: as [`crossing_cells_pruned`] and [`crossing_cells_of_fn`].
pub fn crossing_cells(
    lat: &Lattice,
    f: &(impl Fn(DVec3) -> f64 + Sync),
    lipschitz: Option<f64>,
) -> Result<Vec<C3>> {
    match lipschitz {
        Some(l) if lat.n >= DENSE_BELOW => crossing_cells_pruned(lat, f, l),
        _ => crossing_cells_of_fn(lat, f),
    }
}

/// The band of half-width `j` around the zero level of the `lipschitz`-Lipschitz function `f`
/// and `f` at its nodes.
/// Errors: as [`crossing_cells`] and [`band_around`].
pub fn band_of_fn<B: Band<Coord = C3>>(
    lat: &Lattice,
    j: usize,
    f: &(impl Fn(DVec3) -> f64 + Sync),
    lipschitz: Option<f64>,
) -> Result<(NarrowBand<B>, Vec<f64>)> {
    let cross = crossing_cells(lat, f, lipschitz)?;
    let nb: NarrowBand<B> = band_around(lat, &cross, j)?;
    drop(cross);
    let coords: Vec<C3> = nb.band.coords().collect();
    let v: Vec<f64> = coords.par_iter().map(|&c| f(lat.pos(c))).collect();
    Ok((nb, v))
}

impl<B: Band<Coord = C3> + Clone> McfState<B> {
    /// [`McfState::new`] for a `lipschitz`-Lipschitz `f` (1 for a signed distance): the same
    /// state, with the crossed cells found by block pruning instead of a pass over every grid
    /// node (on grids of at least [`DENSE_BELOW`] nodes per side).
    /// Errors: as [`McfState::new`], and [`Error::InvalidInput`] for a non-positive bound.
    pub fn with_lipschitz(
        lat: Lattice,
        j: usize,
        f: &(impl Fn(DVec3) -> f64 + Sync),
        lipschitz: f64,
    ) -> Result<McfState<B>> {
        let (nb, v) = band_of_fn::<B>(&lat, j, f, Some(lipschitz))?;
        let (nb, phi) = super::mcf::rebuild(&lat, &nb, &v)?;
        Ok(McfState { lat, nb, phi })
    }
}
