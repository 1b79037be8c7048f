//! The closest point of a triangle to a point, with the feature (face, edge or vertex) it lies
//! on: the Voronoi-region case analysis of the triangle's vertices and edges, exact up to
//! round-off.

use crate::geom::DVec3;

/// The feature of a triangle `[a, b, c]` that holds a closest point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Feature {
    /// The interior of the triangle.
    Face,
    /// The open edge from local vertex `i` to local vertex `(i + 1) % 3`.
    Edge(u8),
    /// Local vertex `i`.
    Vertex(u8),
}

/// The point of the triangle `[a, b, c]` closest to `p` and the feature it lies on.
pub fn closest_point(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> (DVec3, Feature) {
    let ab = b - a;
    let ac = c - a;
    let ap = p - a;
    let d1 = ab.dot(ap);
    let d2 = ac.dot(ap);
    if d1 <= 0.0 && d2 <= 0.0 {
        return (a, Feature::Vertex(0));
    }
    let bp = p - b;
    let d3 = ab.dot(bp);
    let d4 = ac.dot(bp);
    if d3 >= 0.0 && d4 <= d3 {
        return (b, Feature::Vertex(1));
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        let v = d1 / (d1 - d3);
        return (a + v * ab, Feature::Edge(0));
    }
    let cp = p - c;
    let d5 = ab.dot(cp);
    let d6 = ac.dot(cp);
    if d6 >= 0.0 && d5 <= d6 {
        return (c, Feature::Vertex(2));
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        let w = d2 / (d2 - d6);
        return (a + w * ac, Feature::Edge(2));
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        let w = (d4 - d3) / ((d4 - d3) + (d5 - d6));
        return (b + w * (c - b), Feature::Edge(1));
    }
    let denom = 1.0 / (va + vb + vc);
    let v = vb * denom;
    let w = vc * denom;
    (a + v * ab + w * ac, Feature::Face)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The closest point beats every point of a fine barycentric sampling, and the reported
    /// feature matches the barycentric coordinates of the result.
    #[test]
    fn closest_point_beats_sampling() {
        let (a, b, c) = (
            DVec3::new(0.1, -0.2, 0.3),
            DVec3::new(1.2, 0.1, -0.1),
            DVec3::new(0.3, 0.9, 0.4),
        );
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) * 4.0 - 2.0
        };
        let n = 60;
        for _ in 0..200 {
            let p = DVec3::new(rnd(), rnd(), rnd());
            let (q, _) = closest_point(p, a, b, c);
            let d = (p - q).length();
            let mut best = f64::INFINITY;
            for i in 0..=n {
                for j in 0..=(n - i) {
                    let (u, v) = (i as f64 / n as f64, j as f64 / n as f64);
                    let s = a + u * (b - a) + v * (c - a);
                    best = best.min((p - s).length());
                }
            }
            assert!(d <= best + 1e-12, "{d} > {best}");
            assert!(best - d < 0.05, "{d} much below sampled {best}");
        }
        // Feature checks: a point above the face, beyond an edge and beyond a vertex.
        let centroid = (a + b + c) / 3.0;
        let n = (b - a).cross(c - a).normalize();
        assert_eq!(closest_point(centroid + n, a, b, c).1, Feature::Face);
        let mid = 0.5 * (b + c);
        let out = (mid - centroid).normalize();
        assert_eq!(closest_point(mid + out, a, b, c).1, Feature::Edge(1));
        assert_eq!(
            closest_point(a + (a - centroid), a, b, c).1,
            Feature::Vertex(0)
        );
    }
}
