//! How far a transported interface is from a reference shape: the area of the symmetric
//! difference of the two interiors and the (sampled) Hausdorff distance between the two
//! interfaces. Used when the flow is time-reversed, so that the exact final shape is the initial
//! one.

use crate::error::{Error, Result};
use crate::geom::{point_segment_distance, DVec2};
use crate::levelset::interface::Polyline;
use crate::mesh::{check_p1_field, Mesh2};
use rayon::prelude::*;
use rstar::primitives::Line;
use rstar::RTree;

/// `|{u < 0} Δ {phi < 0}|`: the area where the P1 field `u` on `mesh` and the function `phi`
/// disagree in sign. On every triangle where `u` or `phi` may change sign (a sign change at the
/// vertices, or `|phi|` at a vertex below the triangle's diameter, `phi` taken as roughly
/// 1-Lipschitz) the triangle is split `4^levels` times, `u` is linear on each piece and `phi` is
/// replaced by its linear interpolant there, and the two half-plane cuts are clipped exactly.
/// The error is that of interpolating `phi` on the pieces: `O((h / 2^levels)²)` times its
/// curvature along the interface.
pub fn symmetric_difference<F: Fn(DVec2) -> f64 + Sync + ?Sized>(
    mesh: &Mesh2,
    u: &[f64],
    phi: &F,
    levels: u32,
) -> Result<f64> {
    check_p1_field(mesh.n_points(), u, "level set")?;
    if levels > 8 {
        return Err(Error::InvalidInput(format!(
            "symmetric difference: at most 8 subdivision levels (got {levels})"
        )));
    }
    let tris: Vec<usize> = mesh.live_tris().collect();
    let area = tris
        .par_iter()
        .map(|&t| {
            let tri = mesh.tris[t];
            let p = tri.map(|v| mesh.points[v as usize]);
            let a = tri.map(|v| u[v as usize]);
            let b = p.map(phi);
            let diam = (p[0] - p[1])
                .length()
                .max((p[1] - p[2]).length())
                .max((p[2] - p[0]).length());
            let sa = a.iter().filter(|&&x| x < 0.0).count();
            let sb = b.iter().filter(|&&x| x < 0.0).count();
            let near = b.iter().any(|x| x.abs() < diam);
            if sa % 3 == 0 && sb % 3 == 0 && !near {
                // Both signs constant on the triangle.
                return if (sa == 0) != (sb == 0) {
                    mesh.tri_area(t)
                } else {
                    0.0
                };
            }
            piece(p, a, b, phi, levels)
        })
        .sum();
    Ok(area)
}

/// The disagreement area on one triangle split `levels` more times (`u` linear, `phi` sampled).
fn piece<F: Fn(DVec2) -> f64 + ?Sized>(
    p: [DVec2; 3],
    a: [f64; 3],
    b: [f64; 3],
    phi: &F,
    levels: u32,
) -> f64 {
    if levels == 0 {
        return disagreement(p, a, b);
    }
    let mid = |i: usize, j: usize| 0.5 * (p[i] + p[j]);
    let (m01, m12, m20) = (mid(0, 1), mid(1, 2), mid(2, 0));
    let (a01, a12, a20) = (
        0.5 * (a[0] + a[1]),
        0.5 * (a[1] + a[2]),
        0.5 * (a[2] + a[0]),
    );
    let (b01, b12, b20) = (phi(m01), phi(m12), phi(m20));
    piece(
        [p[0], m01, m20],
        [a[0], a01, a20],
        [b[0], b01, b20],
        phi,
        levels - 1,
    ) + piece(
        [m01, p[1], m12],
        [a01, a[1], a12],
        [b01, b[1], b12],
        phi,
        levels - 1,
    ) + piece(
        [m20, m12, p[2]],
        [a20, a12, a[2]],
        [b20, b12, b[2]],
        phi,
        levels - 1,
    ) + piece(
        [m01, m12, m20],
        [a01, a12, a20],
        [b01, b12, b20],
        phi,
        levels - 1,
    )
}

/// A polygon vertex with the values of the two linear functions there.
type Node = (DVec2, f64, f64);

/// Exact area of `{a < 0, b ≥ 0} ∪ {a ≥ 0, b < 0}` on a triangle with linear `a`, `b`.
fn disagreement(p: [DVec2; 3], a: [f64; 3], b: [f64; 3]) -> f64 {
    let poly: Vec<Node> = (0..3).map(|i| (p[i], a[i], b[i])).collect();
    let one = |sa: f64, sb: f64| {
        let q = clip(&poly, |n| sa * n.1);
        polygon_area(&clip(&q, |n| sb * n.2))
    };
    // {a < 0} ∩ {b > 0} and {a > 0} ∩ {b < 0}.
    one(1.0, -1.0) + one(-1.0, 1.0)
}

/// The part of a convex polygon where the linear function `f` (given at its vertices) is `≤ 0`.
fn clip(poly: &[Node], f: impl Fn(&Node) -> f64) -> Vec<Node> {
    let mut out = Vec::with_capacity(poly.len() + 1);
    for i in 0..poly.len() {
        let (c, n) = (poly[i], poly[(i + 1) % poly.len()]);
        let (fc, fn_) = (f(&c), f(&n));
        if fc <= 0.0 {
            out.push(c);
        }
        if (fc < 0.0 && fn_ > 0.0) || (fc > 0.0 && fn_ < 0.0) {
            let s = fc / (fc - fn_);
            out.push((
                c.0 + s * (n.0 - c.0),
                c.1 + s * (n.1 - c.1),
                c.2 + s * (n.2 - c.2),
            ));
        }
    }
    out
}

fn polygon_area(poly: &[Node]) -> f64 {
    if poly.len() < 3 {
        return 0.0;
    }
    let mut s = 0.0;
    for i in 0..poly.len() {
        let (p, q) = (poly[i].0, poly[(i + 1) % poly.len()].0);
        s += p.perp_dot(q);
    }
    0.5 * s.abs()
}

/// Sampled Hausdorff distance between two sets of polylines: every segment of each set is
/// sampled at `samples` equally spaced points (ends included) and measured against an R-tree of
/// the other set's segments. Infinite when exactly one of the sets is empty, 0 when both are.
pub fn hausdorff(a: &[Polyline], b: &[Polyline], samples: usize) -> f64 {
    let (sa, sb) = (segments(a), segments(b));
    match (sa.is_empty(), sb.is_empty()) {
        (true, true) => return 0.0,
        (true, false) | (false, true) => return f64::INFINITY,
        _ => {}
    }
    one_sided(&sa, &sb, samples).max(one_sided(&sb, &sa, samples))
}

fn segments(lines: &[Polyline]) -> Vec<(DVec2, DVec2)> {
    let mut out = Vec::new();
    for l in lines {
        if l.points.len() == 1 {
            out.push((l.points[0], l.points[0]));
        }
        out.extend(l.segments());
    }
    out
}

/// `max over samples p of from: dist(p, to)`.
fn one_sided(from: &[(DVec2, DVec2)], to: &[(DVec2, DVec2)], samples: usize) -> f64 {
    let k = samples.max(2);
    let tree = RTree::bulk_load(
        to.iter()
            .map(|(a, b)| Line::new(a.to_array(), b.to_array()))
            .collect(),
    );
    from.par_iter()
        .map(|&(a, b)| {
            (0..k)
                .map(|i| {
                    let p = a + (b - a) * (i as f64 / (k - 1) as f64);
                    tree.nearest_neighbor(p.to_array())
                        .map_or(f64::INFINITY, |l| {
                            point_segment_distance(
                                p,
                                DVec2::from_array(l.from),
                                DVec2::from_array(l.to),
                            )
                            .0
                        })
                })
                .fold(0.0, f64::max)
        })
        .reduce(|| 0.0, f64::max)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levelset::interface::extract_zero_level;
    use crate::mesh::GridPattern;

    fn disk(c: DVec2, r: f64) -> impl Fn(DVec2) -> f64 + Sync {
        move |p: DVec2| (p - c).length() - r
    }

    #[test]
    fn shifted_disks() {
        let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 64, 64, GridPattern::UnionJack).unwrap();
        let (r, d) = (0.2, 0.01);
        let a = disk(DVec2::splat(0.5), r);
        let b = disk(DVec2::new(0.5 + d, 0.5), r);
        let u: Vec<f64> = m.points.iter().map(|&p| a(p)).collect();
        // Two disks of radius r at distance d: |A Δ B| = 2 (π r² − lens), ≈ 4 r d for small d.
        let lens = 2.0 * r * r * (d / (2.0 * r)).acos() - 0.5 * d * (4.0 * r * r - d * d).sqrt();
        let exact = 2.0 * (std::f64::consts::PI * r * r - lens);
        let s = symmetric_difference(&m, &u, &b, 3).unwrap();
        assert!((s - exact).abs() < 0.03 * exact, "{s} vs {exact}");
        // Same function: only the P1 representation of u differs from the exact disk.
        let s0 = symmetric_difference(&m, &u, &a, 3).unwrap();
        assert!(s0 < 0.05 * exact, "{s0}");
        let v: Vec<f64> = m.points.iter().map(|&p| b(p)).collect();
        let la = extract_zero_level(&m, &u).unwrap();
        let lb = extract_zero_level(&m, &v).unwrap();
        let h = hausdorff(&la, &lb, 4);
        assert!((h - d).abs() < 2e-3, "hausdorff {h}");
        assert!(hausdorff(&la, &la, 4) < 1e-12);
        assert!(hausdorff(&la, &[], 4).is_infinite());
    }

    #[test]
    fn clipping_is_exact_for_linear_fields() {
        // a = x - 0.3, b = x - 0.5 on the unit right triangle: the strip 0.3 < x < 0.5.
        let p = [DVec2::ZERO, DVec2::X, DVec2::Y];
        let a = p.map(|q| q.x - 0.3);
        let b = p.map(|q| q.x - 0.5);
        let exact = 0.5 * (0.7f64 * 0.7 - 0.5 * 0.5);
        assert!((disagreement(p, a, b) - exact).abs() < 1e-14);
    }
}
