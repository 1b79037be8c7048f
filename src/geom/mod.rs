//! Points, robust geometric predicates and per-simplex kernels.
//!
//! Points are `glam::DVec2` / `DVec3`. The orientation and in-circle tests are Shewchuk's adaptive
//! exact predicates (through the `robust` crate), so topological decisions never depend on
//! round-off. [`simplex`] holds the kernels written once for triangles and tetrahedra (volume,
//! barycentric coordinates, P1 gradients) over the [`Point`] trait.

pub mod simplex;

pub use glam::{DVec2, DVec3};
pub use simplex::Point;

#[inline]
fn coord(p: DVec2) -> robust::Coord<f64> {
    robust::Coord { x: p.x, y: p.y }
}

/// Exact sign of the orientation of `(a, b, c)`: twice the signed area, with the correct sign even
/// when round-off would give the wrong one. Positive for counter-clockwise.
#[inline]
pub fn orient2d(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    robust::orient2d(coord(a), coord(b), coord(c))
}

/// Exact in-circle test: positive when `d` lies inside the circle through the counter-clockwise
/// triangle `(a, b, c)`.
#[inline]
pub fn incircle(a: DVec2, b: DVec2, c: DVec2, d: DVec2) -> f64 {
    robust::incircle(coord(a), coord(b), coord(c), coord(d))
}

/// Signed area of the triangle `(a, b, c)` in floating point (positive when counter-clockwise).
#[inline]
pub fn signed_area(a: DVec2, b: DVec2, c: DVec2) -> f64 {
    0.5 * (b - a).perp_dot(c - a)
}

/// Barycentric coordinates of `p` in the triangle `(a, b, c)`.
#[inline]
pub fn barycentric(a: DVec2, b: DVec2, c: DVec2, p: DVec2) -> [f64; 3] {
    let det = (b - a).perp_dot(c - a);
    let l1 = (c - b).perp_dot(p - b) / det;
    let l2 = (a - c).perp_dot(p - c) / det;
    [l1, l2, 1.0 - l1 - l2]
}

/// Distance from `p` to the segment `[a, b]`, and the parameter `t` in `[0, 1]` of the closest point.
#[inline]
pub fn point_segment_distance(p: DVec2, a: DVec2, b: DVec2) -> (f64, f64) {
    let ab = b - a;
    let len2 = ab.length_squared();
    let t = if len2 > 0.0 {
        ((p - a).dot(ab) / len2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    ((a + t * ab - p).length(), t)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn orientation_is_exact_near_collinear() {
        let a = DVec2::new(0.5, 0.5);
        let b = DVec2::new(12.0, 12.0);
        let c = DVec2::new(24.0, 24.0 + 1e-14 * 24.0);
        assert!(orient2d(a, b, c) > 0.0);
        assert_eq!(orient2d(a, b, DVec2::new(24.0, 24.0)), 0.0);
    }

    #[test]
    fn barycentric_reproduces_point() {
        let (a, b, c) = (DVec2::ZERO, DVec2::new(2.0, 0.1), DVec2::new(0.3, 1.7));
        let p = DVec2::new(0.7, 0.4);
        let l = barycentric(a, b, c, p);
        let q = l[0] * a + l[1] * b + l[2] * c;
        assert!((q - p).length() < 1e-14);
        assert!((l.iter().sum::<f64>() - 1.0).abs() < 1e-14);
    }

    #[test]
    fn segment_distance() {
        let (d, t) = point_segment_distance(DVec2::new(0.5, 1.0), DVec2::ZERO, DVec2::X);
        assert!((d - 1.0).abs() < 1e-15 && (t - 0.5).abs() < 1e-15);
        let (d, t) = point_segment_distance(DVec2::new(2.0, 0.0), DVec2::ZERO, DVec2::X);
        assert!((d - 1.0).abs() < 1e-15 && t == 1.0);
    }
}
