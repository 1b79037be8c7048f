//! Triangle surfaces in 3D and the zero level of a P1 field on tetrahedra (marching
//! tetrahedra): each tetrahedron cut by the zero level contributes a triangle (one vertex
//! separated from three) or a quadrilateral split into two triangles (two against two), with
//! vertices where the field's linear interpolant vanishes on the cut edges.

use crate::geom::DVec3;

/// A triangulated surface in 3D: the zero level of a 3D level-set function. Triangles are oriented with
/// the inside (`u < 0`) behind them (normals `(b − a) × (c − a)` point outward).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct TriangleSurface {
    /// The vertices.
    pub points: Vec<DVec3>,
    /// Three vertex indices per triangle.
    pub triangles: Vec<[u32; 3]>,
}

impl TriangleSurface {
    /// The total area of the triangles.
    pub fn area(&self) -> f64 {
        self.triangles
            .iter()
            .map(|&[a, b, c]| {
                let (a, b, c) = (
                    self.points[a as usize],
                    self.points[b as usize],
                    self.points[c as usize],
                );
                0.5 * (b - a).cross(c - a).length()
            })
            .sum()
    }

    /// The volume enclosed by a closed, outward-oriented surface (the divergence theorem:
    /// `Σ a · (b × c) / 6`).
    pub fn enclosed_volume(&self) -> f64 {
        self.triangles
            .iter()
            .map(|&[a, b, c]| {
                let (a, b, c) = (
                    self.points[a as usize],
                    self.points[b as usize],
                    self.points[c as usize],
                );
                a.dot(b.cross(c)) / 6.0
            })
            .sum()
    }
}

impl TriangleSurface {
    /// Appends the zero level of the linear interpolant of `values` on the tetrahedron `points`
    /// (any orientation), oriented with `u < 0` behind the triangles. Vertices are not shared
    /// with other tetrahedra (call [`TriangleSurface::weld`] afterwards). A vertex with value
    /// exactly 0 counts as positive, so the pieces of neighbouring tetrahedra match.
    pub fn add_tet_zero_level(&mut self, points: [DVec3; 4], values: [f64; 4]) {
        let inside: Vec<usize> = (0..4).filter(|&i| values[i] < 0.0).collect();
        let outside: Vec<usize> = (0..4).filter(|&i| values[i] >= 0.0).collect();
        let cut = |a: usize, b: usize| {
            let (ua, ub) = (values[a], values[b]);
            let s = ua / (ua - ub);
            points[a] + s * (points[b] - points[a])
        };
        let poly: Vec<DVec3> = match (inside.len(), outside.len()) {
            (1, 3) => outside.iter().map(|&o| cut(inside[0], o)).collect(),
            (3, 1) => inside.iter().map(|&i| cut(i, outside[0])).collect(),
            (2, 2) => vec![
                cut(inside[0], outside[0]),
                cut(inside[0], outside[1]),
                cut(inside[1], outside[1]),
                cut(inside[1], outside[0]),
            ],
            _ => return,
        };
        // Orient: the normal must point from the inside towards the outside.
        let centre_in = inside.iter().map(|&i| points[i]).sum::<DVec3>() / inside.len() as f64;
        let centre_out = outside.iter().map(|&i| points[i]).sum::<DVec3>() / outside.len() as f64;
        let n = (poly[1] - poly[0]).cross(poly[2] - poly[0])
            + if poly.len() == 4 {
                (poly[2] - poly[0]).cross(poly[3] - poly[0])
            } else {
                DVec3::ZERO
            };
        let flip = n.dot(centre_out - centre_in) < 0.0;
        let base = self.points.len() as u32;
        self.points.extend_from_slice(&poly);
        let mut push = |a: u32, b: u32, c: u32| {
            let t = if flip { [a, c, b] } else { [a, b, c] };
            self.triangles.push([base + t[0], base + t[1], base + t[2]]);
        };
        push(0, 1, 2);
        if poly.len() == 4 {
            push(0, 2, 3);
        }
    }

    /// Merges vertices closer than `tol` (on a grid of cells of size `tol`, so the result does
    /// not depend on the order of the triangles beyond which copy is kept) and drops triangles
    /// that became degenerate.
    pub fn weld(&mut self, tol: f64) {
        use std::collections::HashMap;
        let key = |p: DVec3| {
            (
                (p.x / tol).round() as i64,
                (p.y / tol).round() as i64,
                (p.z / tol).round() as i64,
            )
        };
        let mut map: HashMap<(i64, i64, i64), u32> = HashMap::new();
        let mut points = Vec::new();
        let remap: Vec<u32> = self
            .points
            .iter()
            .map(|&p| {
                *map.entry(key(p)).or_insert_with(|| {
                    points.push(p);
                    points.len() as u32 - 1
                })
            })
            .collect();
        self.triangles = self
            .triangles
            .iter()
            .map(|t| t.map(|v| remap[v as usize]))
            .filter(|t| t[0] != t[1] && t[1] != t[2] && t[0] != t[2])
            .collect();
        self.points = points;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The zero level of `|p| − r` on the six Kuhn tetrahedra of a cube grid approximates the
    /// sphere: enclosed volume and area converge at second order, the surface is closed.
    #[test]
    fn marching_tetrahedra_on_a_sphere() {
        let err = |n: usize| {
            let (r, h) = (0.6, 2.0 / n as f64);
            let f = |p: DVec3| p.length() - r;
            let mut s = TriangleSurface::default();
            // Kuhn subdivision: the six paths from corner 0 to corner 7.
            let perms = [
                [0, 1, 2],
                [0, 2, 1],
                [1, 0, 2],
                [1, 2, 0],
                [2, 0, 1],
                [2, 1, 0],
            ];
            for i in 0..n {
                for j in 0..n {
                    for k in 0..n {
                        let lo = DVec3::new(i as f64, j as f64, k as f64) * h - DVec3::ONE;
                        for perm in perms {
                            let mut c = [0usize; 3];
                            let mut pts = [lo; 4];
                            for (step, &axis) in perm.iter().enumerate() {
                                c[axis] = 1;
                                pts[step + 1] =
                                    lo + h * DVec3::new(c[0] as f64, c[1] as f64, c[2] as f64);
                            }
                            s.add_tet_zero_level(pts, pts.map(f));
                        }
                    }
                }
            }
            s.weld(1e-9);
            // Closed: every edge is shared by exactly two triangles, in opposite directions.
            let mut edges = std::collections::HashMap::new();
            for t in &s.triangles {
                for e in 0..3 {
                    *edges.entry((t[e], t[(e + 1) % 3])).or_insert(0) += 1;
                }
            }
            for (&(a, b), &m) in &edges {
                assert_eq!(m, 1);
                assert_eq!(edges.get(&(b, a)), Some(&1), "open edge");
            }
            let v_exact = 4.0 / 3.0 * std::f64::consts::PI * r * r * r;
            ((s.enclosed_volume() - v_exact) / v_exact).abs()
        };
        let (e1, e2) = (err(16), err(32));
        assert!(e2 < 1e-2, "relative volume error {e2}");
        eprintln!("marching tetrahedra volume errors {e1:.3e} -> {e2:.3e}");
        let order = (e1 / e2).log2();
        assert!(order > 1.7, "order {order} ({e1} -> {e2})");
    }
}
