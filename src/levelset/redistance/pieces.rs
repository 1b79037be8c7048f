//! The zero level of a P1 field cut out of one simplex as a soup of facets (segments in a
//! triangle, triangles in a tetrahedron): the per-dimension part of geometric redistancing
//! (004 §2.2). Everything else in [`super::geometric`] is written once for both dimensions.
//!
//! A vertex with `u = 0` lies on the zero level: it contributes a point (a degenerate facet) so
//! that distances to it count, and a cell whose vertices are all zero contributes its boundary
//! facets. Crossing points on an edge with `u_a u_b < 0` are computed from the lower-numbered end,
//! so every cell sharing the edge gets the same bits.

use crate::geom::{DVec2, DVec3, Point};
use crate::levelset::measure::crossing;

/// The per-dimension cut of a simplex of `N = D + 1` vertices by the zero level of a P1 field,
/// implemented for `DVec2` (triangles, segment pieces) and `DVec3` (tetrahedra, triangle pieces).
pub trait ZeroLevelPieces<const D: usize, const N: usize>: Point<D> {
    /// Appends to `out` the pieces (facets of `D` corners, possibly degenerate) of the zero level
    /// of the P1 field `u` in the cell `cell`, whose vertex `v` is at `x(v)`. Nothing is appended
    /// for a cell with all values of one strict sign.
    fn zero_pieces(cell: &[u32; N], u: &[f64], x: impl Fn(u32) -> Self, out: &mut Vec<[Self; D]>);
}

/// Whether a cell with these values meets the zero level (a zero value, or both strict signs).
#[inline]
fn meets_zero(s: &[f64]) -> bool {
    let neg = s.iter().any(|&v| v < 0.0);
    let pos = s.iter().any(|&v| v > 0.0);
    let zeros = s.contains(&0.0);
    zeros || (neg && pos)
}

/// Triangles: one segment per cut triangle, walking the edges `(0,1), (1,2), (2,0)` and taking a
/// zero vertex or the crossing point of a sign change; a degenerate segment for a triangle
/// touching the level at one vertex, three segments for a triangle whose three values are 0.
impl ZeroLevelPieces<2, 3> for DVec2 {
    fn zero_pieces(tri: &[u32; 3], u: &[f64], x: impl Fn(u32) -> Self, out: &mut Vec<[Self; 2]>) {
        let s = tri.map(|v| u[v as usize]);
        if !meets_zero(&s) {
            return;
        }
        let mut pts: [DVec2; 3] = [DVec2::ZERO; 3];
        let mut n = 0;
        for i in 0..3 {
            let (a, b) = (tri[i], tri[(i + 1) % 3]);
            let (ua, ub) = (u[a as usize], u[b as usize]);
            if ua == 0.0 {
                pts[n] = x(a);
                n += 1;
            } else if ua * ub < 0.0 {
                pts[n] = crossing(a, b, u, &x);
                n += 1;
            }
        }
        match n {
            1 => out.push([pts[0], pts[0]]),
            2 => out.push([pts[0], pts[1]]),
            3 => {
                out.push([pts[0], pts[1]]);
                out.push([pts[1], pts[2]]);
                out.push([pts[2], pts[0]]);
            }
            _ => {}
        }
    }
}

/// Tetrahedra: zero vertices first, then the crossing points of the sign-changing edges; three
/// points make a triangle, four (a quadrilateral cut, or four zero vertices) are ordered around
/// their centroid in the plane of the cut and fanned into two triangles; one or two points make
/// degenerate triangles so that those points count for distances.
impl ZeroLevelPieces<3, 4> for DVec3 {
    fn zero_pieces(tet: &[u32; 4], u: &[f64], x: impl Fn(u32) -> Self, out: &mut Vec<[Self; 3]>) {
        const EDGES: [(usize, usize); 6] = [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)];
        let s = tet.map(|v| u[v as usize]);
        if !meets_zero(&s) {
            return;
        }
        let mut pts = [DVec3::ZERO; 6];
        let mut n = 0;
        for (i, &v) in tet.iter().enumerate() {
            if s[i] == 0.0 {
                pts[n] = x(v);
                n += 1;
            }
        }
        for &(i, j) in &EDGES {
            if s[i] * s[j] < 0.0 {
                pts[n] = crossing(tet[i], tet[j], u, &x);
                n += 1;
            }
        }
        match n {
            0 => {}
            1 => out.push([pts[0]; 3]),
            2 => out.push([pts[0], pts[1], pts[1]]),
            3 => out.push([pts[0], pts[1], pts[2]]),
            _ => {
                let c = pts[..n].iter().copied().sum::<DVec3>() / n as f64;
                let nrm = (pts[1] - pts[0]).cross(pts[2] - pts[0]);
                let nrm = if nrm.length_squared() > 0.0 {
                    nrm
                } else {
                    (pts[1] - pts[0]).cross(pts[3] - pts[0])
                };
                let e1 = (pts[0] - c).normalize_or_zero();
                let e2 = nrm.cross(e1).normalize_or_zero();
                let mut idx: Vec<usize> = (0..n).collect();
                idx.sort_by(|&a, &b| {
                    let ang = |k: usize| (pts[k] - c).dot(e2).atan2((pts[k] - c).dot(e1));
                    ang(a).total_cmp(&ang(b))
                });
                for k in 1..n - 1 {
                    out.push([pts[idx[0]], pts[idx[k]], pts[idx[k + 1]]]);
                }
            }
        }
    }
}
