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

/// Distance from `p` to the triangle `(a, b, c)` (possibly degenerate): the closest point is
/// found by the Voronoi regions of the vertices, edges and face (Ericson, *Real-Time Collision
/// Detection*, §5.1.5).
pub fn point_triangle_distance(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> f64 {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return ap.length();
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return bp.length();
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 && d1 - d3 > 0.0 {
        let v = d1 / (d1 - d3);
        return (p - (a + v * ab)).length();
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return cp.length();
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 && d2 - d6 > 0.0 {
        let w = d2 / (d2 - d6);
        return (p - (a + w * ac)).length();
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 && (d4 - d3) + (d5 - d6) > 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (p - (b + w * (c - b))).length();
    }
    let denom = va + vb + vc;
    if denom.abs() <= f64::MIN_POSITIVE {
        // Fully degenerate (collinear) triangle: nearest of the three edges.
        let seg = |x: DVec3, y: DVec3| {
            let d = y - x;
            let l2 = d.length_squared();
            let t = if l2 > 0.0 {
                ((p - x).dot(d) / l2).clamp(0.0, 1.0)
            } else {
                0.0
            };
            (x + t * d - p).length()
        };
        return seg(a, b).min(seg(b, c)).min(seg(a, c));
    }
    let v = vb / denom;
    let w = vc / denom;
    (p - (a + ab * v + ac * w)).length()
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
