//! Triangulations of closed surfaces for tests, pictures and shipped meshes: star-shaped
//! surfaces `r = ρ(direction)` on a refined icosahedron ([`radial_surface`], [`icosphere`]) and
//! the torus on a parametric grid ([`torus_surface`]).
//!
//! The icosahedron of level `L` has `20 · 4^L` triangles: each level splits every triangle into
//! four at its edge midpoints, projected to the unit sphere (shared midpoints, so the surface
//! stays closed). A radial surface moves each unit vertex `d` to `c + ρ(d) d`; its enclosed
//! volume converges to the exact one at second order in the edge length (halved per level).

use super::surface::TriangleSurface;
use crate::geom::DVec3;
use std::collections::HashMap;

/// The unit icosphere of `level` refinements (`20 · 4^level` triangles, outward oriented).
/// `level` is capped at 10 (about 21 million triangles).
pub fn icosphere(level: u32) -> TriangleSurface {
    let t = (1.0 + 5f64.sqrt()) / 2.0;
    let mut points: Vec<DVec3> = [
        (-1.0, t, 0.0),
        (1.0, t, 0.0),
        (-1.0, -t, 0.0),
        (1.0, -t, 0.0),
        (0.0, -1.0, t),
        (0.0, 1.0, t),
        (0.0, -1.0, -t),
        (0.0, 1.0, -t),
        (t, 0.0, -1.0),
        (t, 0.0, 1.0),
        (-t, 0.0, -1.0),
        (-t, 0.0, 1.0),
    ]
    .iter()
    .map(|&(x, y, z)| DVec3::new(x, y, z).normalize())
    .collect();
    let mut triangles: Vec<[u32; 3]> = vec![
        [0, 11, 5],
        [0, 5, 1],
        [0, 1, 7],
        [0, 7, 10],
        [0, 10, 11],
        [1, 5, 9],
        [5, 11, 4],
        [11, 10, 2],
        [10, 7, 6],
        [7, 1, 8],
        [3, 9, 4],
        [3, 4, 2],
        [3, 2, 6],
        [3, 6, 8],
        [3, 8, 9],
        [4, 9, 5],
        [2, 4, 11],
        [6, 2, 10],
        [8, 6, 7],
        [9, 8, 1],
    ];
    for _ in 0..level.min(10) {
        let mut mid: HashMap<(u32, u32), u32> = HashMap::with_capacity(triangles.len() * 3 / 2);
        let mut next = Vec::with_capacity(4 * triangles.len());
        for &[a, b, c] in &triangles {
            let mut m = |u: u32, v: u32| {
                *mid.entry((u.min(v), u.max(v))).or_insert_with(|| {
                    let p = (points[u as usize] + points[v as usize]).normalize();
                    points.push(p);
                    points.len() as u32 - 1
                })
            };
            let (ab, bc, ca) = (m(a, b), m(b, c), m(c, a));
            next.extend_from_slice(&[[a, ab, ca], [b, bc, ab], [c, ca, bc], [ab, bc, ca]]);
        }
        triangles = next;
    }
    TriangleSurface { points, triangles }
}

/// The star-shaped surface `{c + ρ(d) d : |d| = 1}` on the icosphere of `level`: every unit
/// vertex `d` moved to `centre + rho(d) d` (`rho` must be positive for a valid surface), e.g.
/// `radial_surface(DVec3::ZERO, |d| StarSurface::PAPER.radius_towards(d), 6)` for the 004 §5
/// star.
pub fn radial_surface(centre: DVec3, rho: impl Fn(DVec3) -> f64, level: u32) -> TriangleSurface {
    let mut s = icosphere(level);
    for p in &mut s.points {
        *p = centre + rho(*p) * *p;
    }
    s
}

/// The torus around the `z` axis through `centre` with major radius `major` and minor radius
/// `minor`, on an `nu × nv` grid of the angles (`u` around the axis, `v` around the tube; at
/// least 3 each), outward oriented: `2 nu nv` triangles.
pub fn torus_surface(
    centre: DVec3,
    major: f64,
    minor: f64,
    nu: usize,
    nv: usize,
) -> TriangleSurface {
    use std::f64::consts::TAU;
    let (nu, nv) = (nu.max(3), nv.max(3));
    let mut points = Vec::with_capacity(nu * nv);
    for i in 0..nu {
        let u = TAU * i as f64 / nu as f64;
        for j in 0..nv {
            let v = TAU * j as f64 / nv as f64;
            let r = major + minor * v.cos();
            points.push(centre + DVec3::new(r * u.cos(), r * u.sin(), minor * v.sin()));
        }
    }
    let id = |i: usize, j: usize| ((i % nu) * nv + j % nv) as u32;
    let mut triangles = Vec::with_capacity(2 * nu * nv);
    for i in 0..nu {
        for j in 0..nv {
            // ∂/∂u × ∂/∂v points outward (away from the tube's core circle).
            let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
            triangles.push([a, b, c]);
            triangles.push([a, c, d]);
        }
    }
    TriangleSurface { points, triangles }
}
