//! Per-simplex kernels, generic over the dimension: edge vectors, signed volume, barycentric
//! coordinates, the constant gradients of the barycentric functions (P1 gradients), the diameter,
//! and the measure of a facet and the distance to it.
//!
//! A simplex in dimension `D` is an array `[P; N]` of `N = D + 1` corner points of a type `P`
//! implementing [`Point<D>`] (`glam::DVec2` for triangles, `glam::DVec3` for tetrahedra). The
//! few formulas that differ between dimensions (the determinant of the edge matrix through
//! `perp_dot` or the triple product, the measure of and distance to a facet) are the trait's
//! methods; the rest is written once here.
//! Local edges are numbered as [`TRI_EDGES`] and [`TET_EDGES`].

use std::fmt::Debug;
use std::ops::{Add, AddAssign, Div, Index, Mul, Neg, Sub};

use glam::{DVec2, DVec3};

/// Local edges of a triangle: (0,1), (1,2), (2,0) (the P2 edge-node order).
pub const TRI_EDGES: [[usize; 2]; 3] = [[0, 1], [1, 2], [2, 0]];
/// Local edges of a tetrahedron: (0,1), (1,2), (2,0), (0,3), (1,3), (2,3).
pub const TET_EDGES: [[usize; 2]; 6] = [[0, 1], [1, 2], [2, 0], [0, 3], [1, 3], [2, 3]];

/// The local edge table of a simplex with `n_vertices` corners (2: the segment itself, 3, 4).
#[inline]
pub fn simplex_edges(n_vertices: usize) -> &'static [[usize; 2]] {
    match n_vertices {
        2 => &TRI_EDGES[..1],
        3 => &TRI_EDGES,
        _ => &TET_EDGES,
    }
}

/// A point (or vector) of `R^D` with the arithmetic the simplex kernels need, implemented for
/// `DVec2` (`D = 2`) and `DVec3` (`D = 3`). The methods with a glam counterpart compute exactly
/// what glam computes.
pub trait Point<const D: usize>:
    Copy
    + Debug
    + Default
    + PartialEq
    + Send
    + Sync
    + 'static
    + Add<Output = Self>
    + Sub<Output = Self>
    + Mul<f64, Output = Self>
    + Div<f64, Output = Self>
    + Neg<Output = Self>
    + AddAssign
    + Index<usize, Output = f64>
{
    /// The origin.
    const ZERO: Self;

    /// The point with coordinates `a`.
    fn from_array(a: [f64; D]) -> Self;
    /// The coordinates.
    fn to_array(self) -> [f64; D];
    /// The point in `R^3` (`z = 0` for a planar point).
    fn to_xyz(self) -> DVec3;
    /// Euclidean inner product.
    fn dot(self, o: Self) -> f64;
    /// `|v|²`.
    #[inline]
    fn length_squared(self) -> f64 {
        self.dot(self)
    }
    /// `|v|`.
    #[inline]
    fn length(self) -> f64 {
        self.dot(self).sqrt()
    }
    /// Component-wise minimum.
    fn min(self, o: Self) -> Self;
    /// Component-wise maximum.
    fn max(self, o: Self) -> Self;
    /// Whether every coordinate is finite.
    fn is_finite(self) -> bool;
    /// The `i`-th unit vector.
    #[inline]
    fn unit(i: usize) -> Self {
        Self::from_array(std::array::from_fn(|k| if k == i { 1.0 } else { 0.0 }))
    }

    /// `D!` times the signed volume of the simplex `p` (`D + 1` points): the determinant of its
    /// edge vectors `p_i - p_0`.
    fn edge_det(p: &[Self]) -> f64;
    /// Signed volume (area in 2D) of the simplex `p`; positive for counter-clockwise triangles and
    /// for tetrahedra with `p_3` on the side of `(p_1 - p_0) × (p_2 - p_0)`.
    fn signed_volume(p: &[Self]) -> f64;
    /// Barycentric coordinates of `x` in the simplex `p`, into `out[..D + 1]`.
    fn barycentric_into(p: &[Self], x: Self, out: &mut [f64]);
    /// Gradients of the barycentric coordinates of the simplex `p` into `out[..D + 1]`
    /// (non-finite for a degenerate simplex).
    fn bary_grads_into(p: &[Self], out: &mut [Self]);
    /// The `(D - 1)`-measure of the facet `f` (`D` corners): the length of a segment in 2D, the
    /// area of a triangle in 3D.
    fn facet_measure(f: &[Self]) -> f64;
    /// Euclidean distance from `x` to the facet `f` (`D` corners, possibly degenerate): a segment
    /// in 2D, a triangle in 3D.
    fn facet_distance(x: Self, f: &[Self]) -> f64;
}

impl Point<2> for DVec2 {
    const ZERO: Self = DVec2::ZERO;
    #[inline]
    fn from_array(a: [f64; 2]) -> Self {
        DVec2::from_array(a)
    }
    #[inline]
    fn to_array(self) -> [f64; 2] {
        DVec2::to_array(&self)
    }
    #[inline]
    fn to_xyz(self) -> DVec3 {
        DVec3::new(self.x, self.y, 0.0)
    }
    #[inline]
    fn dot(self, o: Self) -> f64 {
        DVec2::dot(self, o)
    }
    #[inline]
    fn min(self, o: Self) -> Self {
        DVec2::min(self, o)
    }
    #[inline]
    fn max(self, o: Self) -> Self {
        DVec2::max(self, o)
    }
    #[inline]
    fn is_finite(self) -> bool {
        DVec2::is_finite(self)
    }
    #[inline]
    fn edge_det(p: &[Self]) -> f64 {
        (p[1] - p[0]).perp_dot(p[2] - p[0])
    }
    #[inline]
    fn signed_volume(p: &[Self]) -> f64 {
        super::signed_area(p[0], p[1], p[2])
    }
    #[inline]
    fn barycentric_into(p: &[Self], x: Self, out: &mut [f64]) {
        out[..3].copy_from_slice(&super::barycentric(p[0], p[1], p[2], x));
    }
    /// `∇λ_i` is the inward normal of the edge opposite `p_i` divided by twice the area.
    #[inline]
    fn bary_grads_into(p: &[Self], out: &mut [Self]) {
        let det = Self::edge_det(p);
        let g = |a: DVec2, b: DVec2| DVec2::new(a.y - b.y, b.x - a.x) / det;
        out[0] = g(p[1], p[2]);
        out[1] = g(p[2], p[0]);
        out[2] = g(p[0], p[1]);
    }
    #[inline]
    fn facet_measure(f: &[Self]) -> f64 {
        (f[1] - f[0]).length()
    }
    #[inline]
    fn facet_distance(x: Self, f: &[Self]) -> f64 {
        super::point_segment_distance(x, f[0], f[1]).0
    }
}

impl Point<3> for DVec3 {
    const ZERO: Self = DVec3::ZERO;
    #[inline]
    fn from_array(a: [f64; 3]) -> Self {
        DVec3::from_array(a)
    }
    #[inline]
    fn to_array(self) -> [f64; 3] {
        DVec3::to_array(&self)
    }
    #[inline]
    fn to_xyz(self) -> DVec3 {
        self
    }
    #[inline]
    fn dot(self, o: Self) -> f64 {
        DVec3::dot(self, o)
    }
    #[inline]
    fn min(self, o: Self) -> Self {
        DVec3::min(self, o)
    }
    #[inline]
    fn max(self, o: Self) -> Self {
        DVec3::max(self, o)
    }
    #[inline]
    fn is_finite(self) -> bool {
        DVec3::is_finite(self)
    }
    #[inline]
    fn edge_det(p: &[Self]) -> f64 {
        (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0]))
    }
    #[inline]
    fn signed_volume(p: &[Self]) -> f64 {
        Self::edge_det(p) / 6.0
    }
    /// Cramer's rule on the edge matrix `[p_1 - p_0, p_2 - p_0, p_3 - p_0]`.
    #[inline]
    fn barycentric_into(p: &[Self], x: Self, out: &mut [f64]) {
        let (e1, e2, e3, r) = (p[1] - p[0], p[2] - p[0], p[3] - p[0], x - p[0]);
        let det = e1.dot(e2.cross(e3));
        let l1 = r.dot(e2.cross(e3)) / det;
        let l2 = e1.dot(r.cross(e3)) / det;
        let l3 = e1.dot(e2.cross(r)) / det;
        out[..4].copy_from_slice(&[1.0 - l1 - l2 - l3, l1, l2, l3]);
    }
    /// The rows of the inverse edge matrix (cross products over the determinant);
    /// `∇λ_0 = -(∇λ_1 + ∇λ_2 + ∇λ_3)`.
    #[inline]
    fn bary_grads_into(p: &[Self], out: &mut [Self]) {
        let (e1, e2, e3) = (p[1] - p[0], p[2] - p[0], p[3] - p[0]);
        let det = e1.dot(e2.cross(e3));
        let g1 = e2.cross(e3) / det;
        let g2 = e3.cross(e1) / det;
        let g3 = e1.cross(e2) / det;
        out[..4].copy_from_slice(&[-(g1 + g2 + g3), g1, g2, g3]);
    }
    #[inline]
    fn facet_measure(f: &[Self]) -> f64 {
        0.5 * (f[1] - f[0]).cross(f[2] - f[0]).length()
    }
    #[inline]
    fn facet_distance(x: Self, f: &[Self]) -> f64 {
        super::point_triangle_distance(x, f[0], f[1], f[2])
    }
}

/// The `(D - 1)`-measure of the facet `f` ([`Point::facet_measure`]).
#[inline]
pub fn facet_measure<const D: usize, P: Point<D>>(f: &[P; D]) -> f64 {
    P::facet_measure(f)
}

/// Distance from `x` to the facet `f` ([`Point::facet_distance`]).
#[inline]
pub fn facet_distance<const D: usize, P: Point<D>>(x: P, f: &[P; D]) -> f64 {
    P::facet_distance(x, f)
}

/// Compile-time check that a simplex of `N` points lives in dimension `D = N - 1`.
macro_rules! assert_simplex {
    ($d:ident, $n:ident) => {
        const { assert!($n == $d + 1, "a simplex in dimension D has D + 1 corners") }
    };
}

/// Signed volume of the simplex `p` (signed area of a triangle, signed volume of a tetrahedron).
#[inline]
pub fn volume<const D: usize, const N: usize, P: Point<D>>(p: &[P; N]) -> f64 {
    assert_simplex!(D, N);
    P::signed_volume(p)
}

/// Barycentric coordinates of `x` in the simplex `p` (they sum to 1 and reproduce `x`).
#[inline]
pub fn barycentric<const D: usize, const N: usize, P: Point<D>>(p: &[P; N], x: P) -> [f64; N] {
    assert_simplex!(D, N);
    let mut out = [0.0; N];
    P::barycentric_into(p, x, &mut out);
    out
}

/// The constant gradients `∇λ_i` of the barycentric coordinates of the simplex `p`: the P1 basis
/// gradients. They sum to zero; `∇λ_i · (p_j - p_k) = δ_ij - δ_ik`.
#[inline]
pub fn p1_gradients<const D: usize, const N: usize, P: Point<D>>(p: &[P; N]) -> [P; N] {
    assert_simplex!(D, N);
    let mut out = [P::ZERO; N];
    P::bary_grads_into(p, &mut out);
    out
}

/// The gradient `Σ_i f_i ∇λ_i` of the affine function with values `f` at the corners of `p`.
#[inline]
pub fn p1_gradient<const D: usize, const N: usize, P: Point<D>>(p: &[P; N], f: &[f64; N]) -> P {
    let g = p1_gradients(p);
    let mut out = P::ZERO;
    for i in 0..N {
        out += g[i] * f[i];
    }
    out
}

/// The edge vectors `p_j - p_i` of the simplex `p`, in the order of [`simplex_edges`].
#[inline]
pub fn edge_vectors<const D: usize, const N: usize, P: Point<D>>(
    p: &[P; N],
) -> impl Iterator<Item = P> + '_ {
    assert_simplex!(D, N);
    simplex_edges(N).iter().map(move |&[i, j]| p[j] - p[i])
}

/// Longest edge of the simplex `p`.
#[inline]
pub fn diameter<const D: usize, const N: usize, P: Point<D>>(p: &[P; N]) -> f64 {
    edge_vectors(p).map(|e| e.length()).fold(0.0, f64::max)
}

/// The point with barycentric coordinates `lam` in the simplex `p`.
#[inline]
pub fn point_at<const D: usize, const N: usize, P: Point<D>>(p: &[P; N], lam: &[f64; N]) -> P {
    let mut out = P::ZERO;
    for i in 0..N {
        out += p[i] * lam[i];
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tri() -> [DVec2; 3] {
        [
            DVec2::new(0.1, -0.2),
            DVec2::new(2.0, 0.1),
            DVec2::new(0.3, 1.7),
        ]
    }

    fn tet() -> [DVec3; 4] {
        [
            DVec3::new(0.1, 0.0, -0.2),
            DVec3::new(1.3, 0.2, 0.1),
            DVec3::new(0.2, 1.1, 0.0),
            DVec3::new(0.3, 0.4, 0.9),
        ]
    }

    /// Barycentric coordinates reproduce the point and the gradients are dual to the edges, in
    /// both dimensions through the same generic code.
    fn check<const D: usize, const N: usize, P: Point<D>>(p: [P; N], x: P) {
        let l = barycentric(&p, x);
        assert!((l.iter().sum::<f64>() - 1.0).abs() < 1e-14);
        assert!((point_at(&p, &l) - x).length() < 1e-14);
        let g = p1_gradients(&p);
        for (i, gi) in g.iter().enumerate() {
            for j in 1..N {
                let want = f64::from(u8::from(i == j)) - f64::from(u8::from(i == 0));
                assert!((gi.dot(p[j] - p[0]) - want).abs() < 1e-13, "{i} {j}");
            }
        }
        // The gradient of an affine function is recovered exactly.
        let a = P::from_array(std::array::from_fn(|k| 0.5 + k as f64));
        let f = p.map(|q| 2.0 + a.dot(q));
        assert!((p1_gradient(&p, &f) - a).length() < 1e-13);
        assert!(volume(&p) > 0.0);
    }

    #[test]
    fn kernels_in_2d_and_3d() {
        check(tri(), DVec2::new(0.7, 0.4));
        check(tet(), DVec3::new(0.4, 0.3, 0.2));
        assert!(
            (volume(&tri()) - crate::geom::signed_area(tri()[0], tri()[1], tri()[2])).abs() == 0.0
        );
        // Unit right tetrahedron: volume 1/6, diameter sqrt(2).
        let t = [DVec3::ZERO, DVec3::X, DVec3::Y, DVec3::Z];
        assert!((volume(&t) - 1.0 / 6.0).abs() < 1e-16);
        assert!((diameter(&t) - 2f64.sqrt()).abs() < 1e-15);
        assert_eq!(edge_vectors(&t).count(), 6);
        assert_eq!(edge_vectors(&tri()).count(), 3);
    }
}
