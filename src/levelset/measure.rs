//! The enclosed measure (area in 2D, volume in 3D) of `{u_h < 0}` and the interface measure
//! (length in 2D, area in 3D) of the zero level of a P1 field `u_h`, written once for triangles
//! and tetrahedra: each simplex is clipped by the zero level of its affine function, which is
//! exact for P1 (the measures of 004 §5.1 and 003 §8: area, perimeter and volume conservation).
//!
//! Sign rule (that of [`super::interface`]): a vertex is *negative* when `u < 0` and
//! *non-negative* otherwise. A simplex is cut when it has vertices of both kinds; the crossing
//! points lie on the edges whose ends differ in kind (a zero vertex is its own crossing point),
//! computed from the lower-numbered end so that neighbouring cells share them bit for bit.
//!
//! With `k` negative vertices in a simplex of `N = D + 1` vertices the negative fraction of its
//! volume is, for a lone vertex of value `a` against the values `b_j` of the others, the corner
//! `a^D / Π_j (a - b_j)` (`k = 1`, and `1 -` the corner of the lone non-negative vertex for
//! `k = N - 1`); for the two-and-two split of a tetrahedron (negative `a_1, a_2`, non-negative
//! `b_1, b_2`, `s = b_1 + b_2`, `p = b_1 b_2`) it is
//! `(a_1² a_2² - s a_1 a_2 (a_1 + a_2) + p (a_1² + a_1 a_2 + a_2²)) / Π_{i,j} (a_i - b_j)`, a sum
//! of non-negative terms over a product of non-zero factors (no cancellation, no division by a
//! difference of values of one kind). These are the truncated-power divided differences of the
//! distribution of an affine function on a simplex, in forms without cancellation.

use crate::error::{Error, Result};
use crate::geom::simplex::{self, simplex_edges};
use crate::geom::Point;

/// The point where the zero level crosses the edge `(a, b)` whose ends differ in sign (or kind),
/// computed from the lower-numbered end so that every cell sharing the edge gets the same bits.
#[inline]
pub(crate) fn crossing<const D: usize, P: Point<D>>(
    a: u32,
    b: u32,
    u: &[f64],
    x: impl Fn(u32) -> P,
) -> P {
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    let (ua, ub) = (u[a as usize], u[b as usize]);
    let t = ua / (ua - ub);
    x(a) + (x(b) - x(a)) * t
}

/// Checks that `u` holds one value per point and is finite at every vertex of `cells`.
pub(crate) fn check_level_set<const N: usize>(
    n_points: usize,
    cells: impl Iterator<Item = [u32; N]>,
    u: &[f64],
) -> Result<()> {
    if u.len() != n_points {
        return Err(Error::InvalidField {
            name: "level set".into(),
            msg: format!("{} values for a mesh of {} vertices", u.len(), n_points),
        });
    }
    for cell in cells {
        for v in cell {
            if v as usize >= n_points {
                return Err(Error::InvalidInput(format!(
                    "cell vertex {v} out of range ({n_points} points)"
                )));
            }
            if !u[v as usize].is_finite() {
                return Err(Error::InvalidField {
                    name: "level set".into(),
                    msg: format!("value {} at vertex {v}", u[v as usize]),
                });
            }
        }
    }
    Ok(())
}

/// The fraction of a simplex where the affine function with vertex values `vals` is negative
/// (module documentation).
pub(crate) fn negative_fraction<const N: usize>(vals: &[f64; N]) -> f64 {
    let n_neg = vals.iter().filter(|&&v| v < 0.0).count();
    if n_neg == 0 {
        return 0.0;
    }
    if n_neg == N {
        return 1.0;
    }
    if n_neg == 1 || n_neg == N - 1 {
        // The odd vertex (the one alone on its side).
        let lone_neg = n_neg == 1;
        let k = (0..N).find(|&i| (vals[i] < 0.0) == lone_neg).unwrap_or(0);
        let a = vals[k];
        let mut num = a;
        let mut den = 1.0;
        for j in 1..N {
            if j > 1 {
                num *= a;
            }
            den *= a - vals[(k + j) % N];
        }
        let corner = num / den;
        return if lone_neg { corner } else { 1.0 - corner };
    }
    // Two and two (tetrahedra only).
    let mut a = [0.0; 2];
    let mut b = [0.0; 2];
    let (mut na, mut nb) = (0, 0);
    for &v in vals {
        if v < 0.0 {
            a[na.min(1)] = v;
            na += 1;
        } else {
            b[nb.min(1)] = v;
            nb += 1;
        }
    }
    let (a1, a2, b1, b2) = (a[0], a[1], b[0], b[1]);
    let (s, p) = (b1 + b2, b1 * b2);
    let num = a1 * a1 * a2 * a2 - s * a1 * a2 * (a1 + a2) + p * (a1 * a1 + a1 * a2 + a2 * a2);
    num / ((a1 - b1) * (a1 - b2) * (a2 - b1) * (a2 - b2))
}

/// Sum over `cells` of the negative fraction times the cell's volume. Checks nothing.
pub(crate) fn enclosed_sum<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: impl Iterator<Item = [u32; N]>,
    u: &[f64],
) -> f64 {
    let mut total = 0.0;
    for cell in cells {
        let vals = cell.map(|v| u[v as usize]);
        let frac = negative_fraction(&vals);
        total += frac * simplex::volume::<D, N, P>(&cell.map(|v| points[v as usize]));
    }
    total
}

/// The measure of the zero level of `u` in one cell (`None` when the cell is not cut).
pub(crate) fn cell_interface_measure<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cell: &[u32; N],
    u: &[f64],
) -> Option<f64> {
    let neg = cell.map(|v| u[v as usize] < 0.0);
    if neg.iter().all(|&n| n == neg[0]) {
        return None;
    }
    let x = |v: u32| points[v as usize];
    // At most four crossing points (a quadrilateral in a tetrahedron), with their edges.
    let mut q = [P::ZERO; 4];
    let mut e = [[0usize; 2]; 4];
    let mut n = 0;
    for &[i, j] in simplex_edges(N) {
        if neg[i] != neg[j] && n < 4 {
            q[n] = crossing(cell[i], cell[j], u, x);
            e[n] = [i, j];
            n += 1;
        }
    }
    if n == D {
        return Some(P::facet_measure(&q[..D]));
    }
    // A quadrilateral (two and two in a tetrahedron): the crossing point on the edge disjoint
    // from the first point's edge is opposite to it; fan from the first point.
    let disjoint = |k: usize| !e[k].iter().any(|v| e[0].contains(v));
    let opp = (1..4).find(|&k| disjoint(k)).unwrap_or(2);
    q.swap(2, opp);
    Some(P::facet_measure(&[q[0], q[1], q[2]]) + P::facet_measure(&[q[0], q[2], q[3]]))
}

/// Volume (area in 2D) of `{u_h < 0}` for the P1 field `u` on the simplices `cells` over `points`
/// (triangles over `DVec2`, tetrahedra over `DVec3`), exact up to round-off: each cell is clipped
/// by its affine function (module documentation). Works when the interface meets the boundary.
///
/// Errors: [`Error::InvalidField`] for a wrong length or a NaN/infinite value at a cell vertex;
/// [`Error::InvalidInput`] for a cell vertex out of range. An empty level set is not an error.
pub fn enclosed_measure<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: &[[u32; N]],
    u: &[f64],
) -> Result<f64> {
    check_level_set(points.len(), cells.iter().copied(), u)?;
    Ok(enclosed_sum(points, cells.iter().copied(), u))
}

/// Measure of the zero level (length in 2D, area in 3D) of the P1 field `u` on the simplices
/// `cells` over `points`: the sum over cut cells of the measure of the planar piece through the
/// crossing points (a segment; a triangle or a quadrilateral), exact up to round-off. Zero for an
/// empty level set. Errors as [`enclosed_measure`].
pub fn interface_measure<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: &[[u32; N]],
    u: &[f64],
) -> Result<f64> {
    check_level_set(points.len(), cells.iter().copied(), u)?;
    Ok(cells
        .iter()
        .filter_map(|c| cell_interface_measure(points, c, u))
        .sum())
}
