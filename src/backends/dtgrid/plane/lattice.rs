//! The square grid of a planar band and the band of half-width `j` around a zero level
//! (000 (2.8) in two dimensions): `I¹` holds the corners of the cells the zero level crosses,
//! `I^{k+1}` adds the `3 × 3` neighbourhood of every node of `I^k`; the band nodes are
//! `I^{j+1}`, the nodes of `I^j` are interior and the others form the boundary layer (the
//! Dirichlet nodes of 000 §2.4).

use super::Grid2;
use crate::backends::dtgrid::band::{Band, GridCoord};
use crate::backends::dtgrid::lattice::{crosses, NarrowBand};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use rayon::prelude::*;

/// A grid coordinate in the plane: `[x, y]`, `x` most significant in storage order.
pub type C2 = [i32; 2];

/// The absent neighbour in a [`neighbours`] table.
pub const NONE: u32 = u32::MAX;

/// The square grid with nodes `0..n` along both axes at spacing `h`, node `c` at `h c` (local
/// coordinates; a back end shifts them to its domain).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Plane {
    /// Nodes per side.
    pub n: usize,
    /// The grid spacing.
    pub h: f64,
}

impl Plane {
    /// The grid of `n` nodes per side and spacing `h`.
    /// Error: [`Error::InvalidInput`] for `n < 3`, more than `2^30` nodes per side or a spacing
    /// that is not finite and positive.
    pub fn new(n: usize, h: f64) -> Result<Plane> {
        if !((3..=1 << 30).contains(&n) && h.is_finite() && h > 0.0) {
            return Err(Error::InvalidInput(format!(
                "planar grid of {n} nodes per side (3 to 2^30) at spacing {h} (positive)"
            )));
        }
        Ok(Plane { n, h })
    }

    /// The position of node `c`.
    #[inline]
    pub fn pos(&self, c: C2) -> DVec2 {
        DVec2::new(self.h * c[0] as f64, self.h * c[1] as f64)
    }

    /// Whether `c` is a node of the grid.
    #[inline]
    pub fn contains(&self, c: C2) -> bool {
        c.iter().all(|&x| x >= 0 && (x as usize) < self.n)
    }
}

/// Sorted, deduplicated `3 × 3` neighbourhood of the sorted nodes `nodes`.
/// Error: [`Error::InvalidInput`] when it leaves the grid (the band does not fit).
fn dilate(plane: &Plane, nodes: &[C2]) -> Result<Vec<C2>> {
    let mut out: Vec<C2> = nodes
        .par_iter()
        .flat_map_iter(|&c| (0..9i32).map(move |k| [c[0] + k % 3 - 1, c[1] + k / 3 - 1]))
        .collect();
    out.par_sort_unstable();
    out.dedup();
    if let Some(c) = out.iter().find(|c| !plane.contains(**c)) {
        return Err(Error::InvalidInput(format!(
            "the narrow band leaves the grid at node {c:?} (the shape does not fit in the grid \
             with this band width)"
        )));
    }
    Ok(out)
}

/// The band of half-width `j ≥ 1` around the cells `crossing` (lowest corners of the cells the
/// zero level crosses, any order).
/// Errors: [`Error::EmptyLevelSet`] when `crossing` is empty, [`Error::InvalidInput`] when
/// `j = 0` or the band leaves the grid.
pub fn band_around(plane: &Plane, crossing: &[C2], j: usize) -> Result<NarrowBand<Grid2>> {
    if j == 0 {
        return Err(Error::InvalidInput(
            "band half-width j = 0 (at least 1)".into(),
        ));
    }
    if crossing.is_empty() {
        return Err(Error::EmptyLevelSet(
            "no grid cell is crossed by the zero level".into(),
        ));
    }
    let mut inner: Vec<C2> = crossing
        .iter()
        .flat_map(|&c| (0..4).map(move |k| c.corner(k)))
        .collect();
    inner.par_sort_unstable();
    inner.dedup();
    if let Some(c) = inner.iter().find(|c| !plane.contains(**c)) {
        return Err(Error::InvalidInput(format!(
            "the zero level reaches the grid boundary at node {c:?} (the shape does not fit in \
             the grid)"
        )));
    }
    for _ in 1..j {
        inner = dilate(plane, &inner)?;
    }
    let all = dilate(plane, &inner)?;
    let mut interior = vec![false; all.len()];
    let mut k = 0;
    for (i, c) in all.iter().enumerate() {
        while k < inner.len() && inner[k] < *c {
            k += 1;
        }
        interior[i] = k < inner.len() && inner[k] == *c;
    }
    Ok(NarrowBand {
        band: Grid2::from_sorted(all)?,
        interior,
        j,
    })
}

/// The cells of the whole grid crossed by the zero level of `f` (one value negative, one
/// non-negative among the four corners), sorted.
/// Errors: [`Error::InvalidField`] when `f` is NaN at a node, [`Error::TooLarge`] beyond
/// `2^28` nodes.
pub fn crossing_cells_of_fn(plane: &Plane, f: &(impl Fn(DVec2) -> f64 + Sync)) -> Result<Vec<C2>> {
    let n = plane.n;
    if n.saturating_mul(n) > 1 << 28 {
        return Err(Error::TooLarge(format!(
            "a planar grid of {n} × {n} nodes (at most 2^28)"
        )));
    }
    let v: Vec<f64> = (0..n * n)
        .into_par_iter()
        .map(|k| f(plane.pos([(k / n) as i32, (k % n) as i32])))
        .collect();
    if let Some(k) = v.iter().position(|x| x.is_nan()) {
        return Err(Error::InvalidField {
            name: "level-set function".into(),
            msg: format!(
                "NaN at grid node {:?} (local position {:?})",
                [k / n, k % n],
                plane.pos([(k / n) as i32, (k % n) as i32])
            ),
        });
    }
    Ok((0..(n - 1) * (n - 1))
        .into_par_iter()
        .filter_map(|k| {
            let (i, j) = (k / (n - 1), k % (n - 1));
            let c = [
                v[i * n + j],
                v[(i + 1) * n + j],
                v[i * n + j + 1],
                v[(i + 1) * n + j + 1],
            ];
            crosses(&c).then_some([i as i32, j as i32])
        })
        .collect())
}

/// The cells of `band` (all four corners band nodes) crossed by the zero level of the band
/// field `phi`, sorted, with their corner indices.
pub fn crossing_cells_of_band(band: &Grid2, phi: &[f64]) -> Vec<(C2, [u32; 4])> {
    band.cells()
        .filter(|(_, idx)| crosses(&idx.map(|i| phi[i as usize])))
        .collect()
}

/// Per band node, the indices of its `3 × 3` neighbourhood (`k = 3 (dy + 1) + (dx + 1)`,
/// [`NONE`] where absent; entry 4 is the node itself).
pub fn neighbours(band: &Grid2) -> Vec<[u32; 9]> {
    let coords: Vec<C2> = band.coords().collect();
    coords
        .par_iter()
        .map(|&c| {
            std::array::from_fn(|k| {
                let q = [c[0] + k as i32 % 3 - 1, c[1] + k as i32 / 3 - 1];
                band.index(q).map_or(NONE, |i| i as u32)
            })
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_band_layers_and_errors() {
        let plane = Plane::new(65, 1.0 / 64.0).unwrap();
        let f = |p: DVec2| (p - DVec2::splat(0.5)).length() - 0.3;
        let cross = crossing_cells_of_fn(&plane, &f).unwrap();
        let b1 = band_around(&plane, &cross, 1).unwrap();
        let b2 = band_around(&plane, &cross, 2).unwrap();
        // The interior nodes of j = 2 are the band nodes of j = 1.
        assert_eq!(b2.interior.iter().filter(|&&x| x).count(), b1.band.len());
        for c in b2.band.coords() {
            assert!(f(plane.pos(c)).abs() < 4.0 * 2f64.sqrt() * plane.h);
        }
        // Every node within 2h of the circle is in the band of half-width 1.
        for i in 0..65 {
            for j in 0..65 {
                if f(plane.pos([i, j])).abs() < plane.h {
                    assert!(b1.band.index([i, j]).is_some());
                }
            }
        }
        let nb = neighbours(&b1.band);
        let inner = b1.band.coords().position(|c| c == cross[0]).unwrap();
        assert_eq!(nb[inner][4] as usize, inner);
        let big = crossing_cells_of_fn(&plane, &|p| (p - DVec2::splat(0.5)).length() - 0.48);
        assert!(band_around(&plane, &big.unwrap(), 2).is_err());
        assert!(matches!(
            band_around(&plane, &[], 1),
            Err(Error::EmptyLevelSet(_))
        ));
        assert!(matches!(
            crossing_cells_of_fn(&plane, &|_| f64::NAN),
            Err(Error::InvalidField { .. })
        ));
    }
}
