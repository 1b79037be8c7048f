//! The zero level of a band field and the signed distance to it: the discrete surface
//! `M_h = [Φ = 0]` of 000 §2 as triangles (marching tetrahedra on the six Kuhn tetrahedra of each
//! cell along its main diagonal), surface integrals of Q1 band fields over it, and the signed
//! distance of band nodes to it (exact for the triangles: the closest point on the nearest
//! triangle, searched in growing shells of cells) — the extension operator of 000 §2.4.

use super::band::Band;
use super::lattice::{crosses, Lattice, C3};
use crate::fem::q1::shape;
use crate::geom::DVec3;
use crate::levelset::TriangleSurface;
use std::collections::HashMap;

/// The Kuhn tetrahedra of a cube: corners `0, 2^a, 2^a + 2^b, 7` for each axis order `(a, b)`.
pub(super) const KUHN: [[usize; 4]; 6] = [
    [0, 1, 3, 7],
    [0, 1, 5, 7],
    [0, 2, 3, 7],
    [0, 2, 6, 7],
    [0, 4, 5, 7],
    [0, 4, 6, 7],
];

/// The zero level of a band field with, per triangle, the lowest corner of its cell.
#[derive(Debug, Clone, Default)]
pub struct ZeroLevel {
    /// The triangles (vertices not shared between cells).
    pub surface: TriangleSurface,
    /// Per triangle: the lowest corner of the grid cell that holds it.
    pub cell: Vec<C3>,
}

/// The zero level of `phi` on the cells of `band` (marching tetrahedra).
pub fn zero_level<B: Band<Coord = C3>>(lat: &Lattice, band: &B, phi: &[f64]) -> ZeroLevel {
    let mut z = ZeroLevel::default();
    for (c, idx) in band.cells() {
        let v: [f64; 8] = std::array::from_fn(|k| phi[idx[k] as usize]);
        if !crosses(&v) {
            continue;
        }
        let p0 = lat.pos(c);
        let before = z.surface.triangles.len();
        for t in KUHN {
            let pts = t.map(|k| {
                p0 + lat.h * DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, (k >> 2) as f64)
            });
            z.surface.add_tet_zero_level(pts, t.map(|k| v[k]));
        }
        let added = z.surface.triangles.len() - before;
        z.cell.extend(std::iter::repeat(c).take(added));
    }
    z
}

/// `(∫_{M_h} f(x, U(x)) da)` where `U` is the Q1 interpolant of the band field `u` in the cell of
/// each triangle (three-point rule, exact for quadratics on each triangle).
pub fn surface_integral<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    z: &ZeroLevel,
    u: &[f64],
    f: impl Fn(DVec3, f64) -> f64,
) -> f64 {
    let mut total = 0.0;
    for (t, &c) in z.surface.triangles.iter().zip(&z.cell) {
        let [a, b, cc] = t.map(|i| z.surface.points[i as usize]);
        let area = 0.5 * (b - a).cross(cc - a).length();
        let vals: Option<Vec<f64>> = (0..8)
            .map(|k| {
                band.index(super::band::GridCoord::corner(c, k))
                    .map(|i| u[i])
            })
            .collect();
        let Some(vals) = vals else { continue };
        let p0 = lat.pos(c);
        for (wa, wb, wc) in [(4.0, 1.0, 1.0), (1.0, 4.0, 1.0), (1.0, 1.0, 4.0)] {
            let x = (wa * a + wb * b + wc * cc) / 6.0;
            let xi = (x - p0) / lat.h;
            let xi = [xi.x, xi.y, xi.z];
            let ux: f64 = (0..8).map(|k| vals[k] * shape(3, k, &xi)).sum();
            total += area / 3.0 * f(x, ux);
        }
    }
    total
}

/// The closest point to `p` on the triangle `a b c`.
pub(crate) fn closest_on_triangle(p: DVec3, a: DVec3, b: DVec3, c: DVec3) -> DVec3 {
    let (ab, ac, ap) = (b - a, c - a, p - a);
    let (d1, d2) = (ab.dot(ap), ac.dot(ap));
    if d1 <= 0.0 && d2 <= 0.0 {
        return a;
    }
    let bp = p - b;
    let (d3, d4) = (ab.dot(bp), ac.dot(bp));
    if d3 >= 0.0 && d4 <= d3 {
        return b;
    }
    let vc = d1 * d4 - d3 * d2;
    if vc <= 0.0 && d1 >= 0.0 && d3 <= 0.0 {
        return a + d1 / (d1 - d3) * ab;
    }
    let cp = p - c;
    let (d5, d6) = (ab.dot(cp), ac.dot(cp));
    if d6 >= 0.0 && d5 <= d6 {
        return c;
    }
    let vb = d5 * d2 - d1 * d6;
    if vb <= 0.0 && d2 >= 0.0 && d6 <= 0.0 {
        return a + d2 / (d2 - d6) * ac;
    }
    let va = d3 * d6 - d5 * d4;
    if va <= 0.0 && (d4 - d3) >= 0.0 && (d5 - d6) >= 0.0 {
        return b + (d4 - d3) / ((d4 - d3) + (d5 - d6)) * (c - b);
    }
    let denom = 1.0 / (va + vb + vc);
    a + ab * (vb * denom) + ac * (vc * denom)
}

/// The signed distance of every node of `band` to the triangles of `z` (negative behind them),
/// searched up to `max_shells` cells away (farther nodes get `±max_shells · h`). Where
/// `sign_of(i)` is `Some(s)`, node `i` takes the sign of `s` (0 counts as positive); elsewhere the
/// side of the nearest triangle decides.
pub fn signed_distance<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    z: &ZeroLevel,
    max_shells: i32,
    sign_of: impl Fn(usize) -> Option<f64> + Sync,
) -> Vec<f64> {
    use rayon::prelude::*;
    let mut buckets: HashMap<C3, Vec<u32>> = HashMap::new();
    for (t, &c) in z.cell.iter().enumerate() {
        buckets.entry(c).or_default().push(t as u32);
    }
    let coords: Vec<C3> = band.coords().collect();
    let pts = &z.surface.points;
    coords
        .par_iter()
        .enumerate()
        .map(|(i, &c)| {
            let p = lat.pos(c);
            // (distance, |cos| of the offset with the normal, signed side)
            let mut best = (f64::INFINITY, 0.0f64, 1.0f64);
            for r in 0..=max_shells {
                if best.0 <= r as f64 * lat.h {
                    break;
                }
                for dz in -1 - r..=r {
                    for dy in -1 - r..=r {
                        for dx in -1 - r..=r {
                            let on_shell = [dx, dy, dz].iter().any(|&d| d == -1 - r || d == r);
                            if !on_shell {
                                continue;
                            }
                            let Some(ts) = buckets.get(&[c[0] + dx, c[1] + dy, c[2] + dz]) else {
                                continue;
                            };
                            for &t in ts {
                                let [a, b, cc] =
                                    z.surface.triangles[t as usize].map(|k| pts[k as usize]);
                                let q = closest_on_triangle(p, a, b, cc);
                                let d = (p - q).length();
                                let n = (b - a).cross(cc - a);
                                let s = (p - q).dot(n);
                                let cos = if d > 0.0 && n.length() > 0.0 {
                                    (s / (d * n.length())).abs()
                                } else {
                                    0.0
                                };
                                let tie = (d - best.0).abs() <= 1e-12 * lat.h;
                                if d < best.0 - 1e-12 * lat.h || (tie && cos > best.1) {
                                    best = (d, cos, if s < 0.0 { -1.0 } else { 1.0 });
                                }
                            }
                        }
                    }
                }
            }
            let d = best.0.min(max_shells as f64 * lat.h);
            let side = match sign_of(i) {
                Some(s) => {
                    if s < 0.0 {
                        -1.0
                    } else {
                        1.0
                    }
                }
                None => best.2,
            };
            side * d
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::lattice::{band_around, crossing_cells_of_fn, NarrowBand};
    use crate::backends::dtgrid::SortedBand;

    #[test]
    fn sphere_zero_level_and_distance() {
        let lat = Lattice::unit(33).unwrap();
        let r = 0.3;
        let f = |p: DVec3| p.length() - r;
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<SortedBand<C3>> = band_around(&lat, &cross, 2).unwrap();
        let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
        let z = zero_level(&lat, &nb.band, &phi);
        let area = z.surface.area();
        let exact = 4.0 * std::f64::consts::PI * r * r;
        assert!((area / exact - 1.0).abs() < 0.01, "area {area} vs {exact}");
        let vol = z.surface.enclosed_volume();
        assert!((vol / (4.0 / 3.0 * std::f64::consts::PI * r.powi(3)) - 1.0).abs() < 0.01);
        let one = surface_integral(&lat, &nb.band, &z, &phi, |_, _| 1.0);
        assert!((one - area).abs() < 1e-12 * area);
        // Distances from the triangles agree with the exact ones within the chord error, and the
        // side of the nearest triangle gives the right sign without hints.
        let d = signed_distance(&lat, &nb.band, &z, 8, |_| None);
        for (c, di) in nb.band.coords().zip(&d) {
            let e = f(lat.pos(c));
            assert!(
                (di - e).abs() < 0.5 * lat.h * lat.h / r + 1e-12,
                "{c:?} {di} {e}"
            );
        }
    }
}
