//! The uniform grid behind a 3D band and the band of half-width `j` around a zero level
//! (000 (2.8)): `I¹` holds the corners of the cells the zero level crosses, `I^{j+1}` adds the
//! nodes of the `3³` neighbourhood of `I^j`; the band domain `Ω_n^j` is the union of the cells
//! that touch `I^j`, whose corners are the band nodes `I^{j+1}`. Nodes of `I^j` are the interior
//! nodes, the others the boundary nodes (the Dirichlet nodes of 000 §2.4).

use super::band::Band;
use super::grid::DtGrid;
use crate::error::{Error, Result};
use crate::geom::DVec3;
use rayon::prelude::*;

/// A grid coordinate in 3D.
pub type C3 = [i32; 3];

/// The uniform grid with `n` nodes per side on `[lo, lo + (n − 1) h]³`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lattice {
    /// Nodes per side.
    pub n: usize,
    /// The grid spacing.
    pub h: f64,
    /// The lowest coordinate along every axis.
    pub lo: f64,
}

impl Lattice {
    /// The grid with `n` nodes per side on the paper's domain `[−½, ½]³` (000 §2), `h = 1/(n − 1)`.
    /// Error: [`Error::InvalidInput`] for `n < 3` or more than `2^30` nodes per side.
    pub fn unit(n: usize) -> Result<Lattice> {
        if !(3..=1 << 30).contains(&n) {
            return Err(Error::InvalidInput(format!(
                "grid of {n} nodes per side (3 to 2^30)"
            )));
        }
        Ok(Lattice {
            n,
            h: 1.0 / (n - 1) as f64,
            lo: -0.5,
        })
    }

    /// The position of node `c` (coordinate 0 along x).
    #[inline]
    pub fn pos(&self, c: C3) -> DVec3 {
        DVec3::new(
            self.lo + self.h * c[0] as f64,
            self.lo + self.h * c[1] as f64,
            self.lo + self.h * c[2] as f64,
        )
    }

    /// Whether `c` is a node of the grid.
    pub fn contains(&self, c: C3) -> bool {
        c.iter().all(|&x| x >= 0 && (x as usize) < self.n)
    }
}

/// A band with its interior flags: `interior[i]` is whether band node `i` lies in `I^j`.
#[derive(Debug, Clone)]
pub struct NarrowBand<B> {
    /// The band nodes `I^{j+1}`.
    pub band: B,
    /// Per band node: in `I^j` (interior) or on the boundary layer.
    pub interior: Vec<bool>,
    /// The half-width `j` in cells.
    pub j: usize,
}

/// `g` grown by `minus..=plus` along every axis, checked to stay in the grid (`what` names the
/// failure).
fn grow_in(lat: &Lattice, g: &DtGrid<C3>, minus: i32, plus: i32, what: &str) -> Result<DtGrid<C3>> {
    let (out, lo, hi) = g.grow(minus, plus)?;
    if lo.iter().any(|&v| v < 0) || hi.iter().any(|&v| v as usize >= lat.n) {
        let c = if lo.iter().any(|&v| v < 0) { lo } else { hi };
        return Err(Error::InvalidInput(format!(
            "{what} at coordinates {c:?} (the shape does not fit in the grid with this band width)"
        )));
    }
    Ok(out)
}

/// The band of half-width `j ≥ 1` around the cells `crossing` (lowest corners of the cells the
/// zero level passes through, any order).
///
/// Computed on runs (000 §3): the corners of the crossed cells (`I¹`), grown `j − 1` times by
/// the `3³` neighbourhood (`I^j`, the interior nodes), and once more (the band `I^{j+1}`); the
/// cost is proportional to the runs of the band.
/// Errors: [`Error::EmptyLevelSet`] when `crossing` is empty, [`Error::InvalidInput`] when the
/// band leaves the grid or `j = 0`.
pub fn band_around<B: Band<Coord = C3>>(
    lat: &Lattice,
    crossing: &[C3],
    j: usize,
) -> Result<NarrowBand<B>> {
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
    let cells: DtGrid<C3> = if crossing.windows(2).all(|p| p[0] < p[1]) {
        DtGrid::from_sorted(crossing.iter().copied())?
    } else {
        let mut c = crossing.to_vec();
        c.par_sort_unstable();
        c.dedup();
        DtGrid::from_sorted(c)?
    };
    let corners = grow_in(
        lat,
        &cells,
        0,
        1,
        "the zero level reaches the grid boundary",
    )?;
    let inner = if j > 1 {
        grow_in(
            lat,
            &corners,
            j as i32 - 1,
            j as i32 - 1,
            "the narrow band leaves the grid",
        )?
    } else {
        corners
    };
    let all = grow_in(lat, &inner, 1, 1, "the narrow band leaves the grid")?;
    let mut interior = Vec::with_capacity(all.len());
    let mut it = inner.coords().peekable();
    for c in all.coords() {
        while it.next_if(|x| *x < c).is_some() {}
        interior.push(it.next_if(|x| *x == c).is_some());
    }
    Ok(NarrowBand {
        band: B::from_sorted(all.coords())?,
        interior,
        j,
    })
}

/// Whether the values at a cell's corners change sign (one negative, one non-negative — the
/// convention of the marching tetrahedra in [`crate::levelset::TriangleSurface`]).
pub fn crosses(v: &[f64]) -> bool {
    v.iter().any(|&x| x < 0.0) && v.iter().any(|&x| x >= 0.0)
}

/// The cells of the whole grid crossed by the zero level of `f`, evaluated at the nodes one
/// `z`-slice pair at a time (memory `O(n²)`).
/// Error: [`Error::InvalidField`] when `f` is NaN at a node.
pub fn crossing_cells_of_fn(lat: &Lattice, f: &(impl Fn(DVec3) -> f64 + Sync)) -> Result<Vec<C3>> {
    let n = lat.n;
    let slice = |k: usize| -> Vec<f64> {
        (0..n * n)
            .into_par_iter()
            .map(|ij| f(lat.pos([(ij / n) as i32, (ij % n) as i32, k as i32])))
            .collect()
    };
    let mut out = Vec::new();
    let mut below = slice(0);
    for k in 0..n {
        let above = if k == 0 { below.clone() } else { slice(k) };
        if let Some(p) = above.iter().position(|v| v.is_nan()) {
            return Err(Error::InvalidField {
                name: "level-set function".into(),
                msg: format!("NaN at node {:?}", [p / n, p % n, k]),
            });
        }
        if k == 0 {
            continue;
        }
        let cells: Vec<C3> = (0..(n - 1) * (n - 1))
            .into_par_iter()
            .filter_map(|ij| {
                let (i, jj) = (ij / (n - 1), ij % (n - 1));
                let mut v = [0.0; 8];
                for (c, vc) in v.iter_mut().enumerate() {
                    let (a, b) = (i + (c & 1), jj + ((c >> 1) & 1));
                    *vc = if c >> 2 == 1 {
                        above[a * n + b]
                    } else {
                        below[a * n + b]
                    };
                }
                crosses(&v).then_some([i as i32, jj as i32, k as i32 - 1])
            })
            .collect();
        out.extend(cells);
        below = above;
    }
    out.sort_unstable();
    Ok(out)
}

/// The lattice cells of `band` (all 8 corners in the band) crossed by the zero level of the
/// band field `phi`.
pub fn crossing_cells_of_band<B: Band<Coord = C3>>(band: &B, phi: &[f64]) -> Vec<C3> {
    band.cells()
        .filter(|(_, idx)| crosses(&idx.map(|i| phi[i as usize])))
        .map(|(c, _)| c)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::SortedBand;

    #[test]
    fn sphere_band_layers() {
        let lat = Lattice::unit(17).unwrap();
        let cross = crossing_cells_of_fn(&lat, &|p: DVec3| p.length() - 0.3).unwrap();
        let b1: NarrowBand<SortedBand<C3>> = band_around(&lat, &cross, 1).unwrap();
        let b2: NarrowBand<SortedBand<C3>> = band_around(&lat, &cross, 2).unwrap();
        let n_int1 = b1.interior.iter().filter(|&&x| x).count();
        assert!(n_int1 < b1.band.len() && b1.band.len() < b2.band.len());
        // Interior nodes of j = 2 are the band nodes of j = 1.
        assert_eq!(b2.interior.iter().filter(|&&x| x).count(), b1.band.len());
        for c in b1.band.coords() {
            assert!((lat.pos(c).length() - 0.3).abs() < 3.0 * 3f64.sqrt() * lat.h);
        }
        let too_big = crossing_cells_of_fn(&lat, &|p: DVec3| p.length() - 0.45).unwrap();
        assert!(band_around::<SortedBand<C3>>(&lat, &too_big, 2).is_err());
        assert!(matches!(
            band_around::<SortedBand<C3>>(&lat, &[], 1),
            Err(Error::EmptyLevelSet(_))
        ));
        assert!(crossing_cells_of_fn(&lat, &|_| f64::NAN).is_err());
    }
}
