//! Point queries of a band field: trilinear (Q1) interpolation inside the cells whose corners
//! are all band nodes, and the curvature `κ = div(∇u/|∇u|)` at band nodes by central
//! differences on the `3³` neighbourhood, interpolated to points of the zero level (000 §2: the
//! band carries a signed distance, whose divergence of the normalised gradient is the sum of the
//! principal curvatures).

use super::band::{Band, GridCoord};
use super::lattice::{Lattice, C3};
use crate::geom::DVec3;
use std::collections::HashMap;

/// The cell holding the local point `x` and the reference coordinates in it, or `None`
/// outside the grid.
fn locate(lat: &Lattice, x: DVec3) -> Option<(C3, [f64; 3])> {
    let top = (lat.n - 1) as f64;
    let s = [x.x, x.y, x.z].map(|v| (v - lat.lo) / lat.h);
    if s.iter()
        .any(|v| !v.is_finite() || *v < -1e-9 || *v > top + 1e-9)
    {
        return None;
    }
    let cell = s.map(|v| (v.floor() as i32).clamp(0, lat.n as i32 - 2));
    let xi = [0, 1, 2].map(|a| (s[a] - cell[a] as f64).clamp(0.0, 1.0));
    Some((cell, xi))
}

/// The trilinear weight of corner `k` (bit `a` of `k`: the upper side along axis `a`).
fn weight(k: usize, xi: &[f64; 3]) -> f64 {
    (0..3)
        .map(|a| {
            if (k >> a) & 1 == 1 {
                xi[a]
            } else {
                1.0 - xi[a]
            }
        })
        .product()
}

/// The Q1 interpolant of the band field `phi` at the local point `x`, or `None` when `x` is
/// outside the grid or its cell has a corner outside the band.
pub fn sample<B: Band<Coord = C3>>(lat: &Lattice, band: &B, phi: &[f64], x: DVec3) -> Option<f64> {
    let (cell, xi) = locate(lat, x)?;
    let mut v = 0.0;
    for k in 0..8 {
        v += phi[band.index(cell.corner(k))?] * weight(k, &xi);
    }
    Some(v)
}

/// The Catmull–Rom weights of the nodes at offsets −1, 0, 1, 2 for the parameter `t ∈ [0, 1]`.
fn catmull_rom(t: f64) -> [f64; 4] {
    let (t2, t3) = (t * t, t * t * t);
    [
        0.5 * (-t3 + 2.0 * t2 - t),
        0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
        0.5 * (-3.0 * t3 + 4.0 * t2 + t),
        0.5 * (t3 - t2),
    ]
}

/// The tricubic Catmull–Rom interpolant of `phi` at the local point `x` (exact for quadratics,
/// interpolation error `O(h³)`) where the `4³` nodes around its cell are band nodes, else the Q1
/// interpolant ([`sample`]).
pub fn sample_cubic<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    phi: &[f64],
    x: DVec3,
) -> Option<f64> {
    let (cell, xi) = locate(lat, x)?;
    let w = xi.map(catmull_rom);
    let mut v = 0.0;
    for (dz, wz) in w[2].iter().enumerate() {
        for (dy, wy) in w[1].iter().enumerate() {
            for (dx, wx) in w[0].iter().enumerate() {
                let q = [
                    cell[0] + dx as i32 - 1,
                    cell[1] + dy as i32 - 1,
                    cell[2] + dz as i32 - 1,
                ];
                match band.index(q) {
                    Some(i) => v += phi[i] * wx * wy * wz,
                    None => return sample(lat, band, phi, x),
                }
            }
        }
    }
    Some(v)
}

/// `div(∇u/|∇u|)` at node `c` by second-order central differences, or `None` when a node of its
/// `3³` neighbourhood is outside the band or the gradient vanishes.
pub fn node_curvature<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    phi: &[f64],
    c: C3,
) -> Option<f64> {
    let mut u = [[[0.0; 3]; 3]; 3];
    for (dz, uz) in u.iter_mut().enumerate() {
        for (dy, uy) in uz.iter_mut().enumerate() {
            for (dx, ux) in uy.iter_mut().enumerate() {
                let q = [
                    c[0] + dx as i32 - 1,
                    c[1] + dy as i32 - 1,
                    c[2] + dz as i32 - 1,
                ];
                *ux = phi[band.index(q)?];
            }
        }
    }
    // u[z][y][x]; index 1 is the centre.
    let at = |x: usize, y: usize, z: usize| u[z][y][x];
    let h = lat.h;
    let gx = (at(2, 1, 1) - at(0, 1, 1)) / (2.0 * h);
    let gy = (at(1, 2, 1) - at(1, 0, 1)) / (2.0 * h);
    let gz = (at(1, 1, 2) - at(1, 1, 0)) / (2.0 * h);
    let c0 = at(1, 1, 1);
    let hxx = (at(2, 1, 1) - 2.0 * c0 + at(0, 1, 1)) / (h * h);
    let hyy = (at(1, 2, 1) - 2.0 * c0 + at(1, 0, 1)) / (h * h);
    let hzz = (at(1, 1, 2) - 2.0 * c0 + at(1, 1, 0)) / (h * h);
    let hxy = (at(2, 2, 1) - at(2, 0, 1) - at(0, 2, 1) + at(0, 0, 1)) / (4.0 * h * h);
    let hxz = (at(2, 1, 2) - at(2, 1, 0) - at(0, 1, 2) + at(0, 1, 0)) / (4.0 * h * h);
    let hyz = (at(1, 2, 2) - at(1, 2, 0) - at(1, 0, 2) + at(1, 0, 0)) / (4.0 * h * h);
    let g2 = gx * gx + gy * gy + gz * gz;
    if g2.is_nan() || g2 <= 0.0 {
        return None;
    }
    let num = (hyy + hzz) * gx * gx + (hxx + hzz) * gy * gy + (hxx + hyy) * gz * gz
        - 2.0 * (gx * gy * hxy + gx * gz * hxz + gy * gz * hyz);
    Some(num / (g2 * g2.sqrt()))
}

/// The nodal curvature smoothed by the binomial filter `(1, 2, 1)/4` along each axis over the
/// `3³` neighbourhood (damping the grid-scale oscillation of the curvature of a distance to a
/// triangulated surface; the smooth part changes by `O(h²)`), or the unsmoothed value where a
/// neighbour has none.
pub fn smoothed_curvature<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    phi: &[f64],
    c: C3,
) -> Option<f64> {
    let centre = node_curvature(lat, band, phi, c)?;
    let mut sum = 0.0;
    for k in 0..27i32 {
        let d = [k % 3 - 1, (k / 3) % 3 - 1, k / 9 - 1];
        let w: f64 = d.iter().map(|&o| if o == 0 { 0.5 } else { 0.25 }).product();
        let q = [c[0] + d[0], c[1] + d[1], c[2] + d[2]];
        match node_curvature(lat, band, phi, q) {
            Some(kq) => sum += w * kq,
            None => return Some(centre),
        }
    }
    Some(sum)
}

/// The curvature at the local point `x` in cell `cell`: the Q1 interpolant of the smoothed
/// nodal curvatures of its corners (memoised in `cache`), or `None` when a corner has none.
pub fn curvature_at<B: Band<Coord = C3>>(
    lat: &Lattice,
    band: &B,
    phi: &[f64],
    cell: C3,
    x: DVec3,
    cache: &mut HashMap<C3, Option<f64>>,
) -> Option<f64> {
    let p0 = lat.pos(cell);
    let s = (x - p0) / lat.h;
    let xi = [s.x, s.y, s.z].map(|v| v.clamp(0.0, 1.0));
    let mut k_sum = 0.0;
    for k in 0..8 {
        let c = cell.corner(k);
        let kc = *cache
            .entry(c)
            .or_insert_with(|| smoothed_curvature(lat, band, phi, c));
        k_sum += kc? * weight(k, &xi);
    }
    Some(k_sum)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::DtGrid;

    /// The full grid `0..n` per axis as a band (lattice on `[−½, ½]³`).
    fn full(n: usize) -> (Lattice, DtGrid<C3>, Vec<C3>) {
        let lat = Lattice::unit(n).unwrap();
        let m = n as i32;
        let coords: Vec<C3> = (0..m * m * m)
            .map(|k| [k / (m * m), (k / m) % m, k % m])
            .collect();
        (lat, DtGrid::from_sorted(coords.clone()).unwrap(), coords)
    }

    #[test]
    fn interpolation_exactness_and_curvature_of_a_sphere() {
        let (lat, band, coords) = full(17);
        let quad = |p: DVec3| 0.3 + p.x - 2.0 * p.y * p.z + 1.5 * p.x * p.x - p.z * p.z;
        let tril = |p: DVec3| 0.1 + p.x * p.y * p.z - 0.7 * p.y + p.x * p.z;
        let q: Vec<f64> = coords.iter().map(|&c| quad(lat.pos(c))).collect();
        let t: Vec<f64> = coords.iter().map(|&c| tril(lat.pos(c))).collect();
        for i in 0..50 {
            let s = i as f64;
            let p = DVec3::new(
                0.37 * (1.3 * s).sin(),
                0.37 * (2.1 * s).cos(),
                0.37 * (0.7 * s + 1.0).sin(),
            );
            // Catmull–Rom reproduces quadratics, Q1 reproduces trilinear functions.
            assert!((sample_cubic(&lat, &band, &q, p).unwrap() - quad(p)).abs() < 1e-12);
            assert!((sample(&lat, &band, &t, p).unwrap() - tril(p)).abs() < 1e-12);
        }
        assert_eq!(sample(&lat, &band, &t, DVec3::splat(0.6)), None);
        // The curvature of the distance to a sphere r = 0.3 at nodes near it: 2/r within O(h²).
        let r = 0.3;
        let d: Vec<f64> = coords.iter().map(|&c| lat.pos(c).length() - r).collect();
        let mut worst = 0.0f64;
        for &c in coords
            .iter()
            .filter(|&&c| (lat.pos(c).length() - r).abs() < lat.h)
        {
            let k = node_curvature(&lat, &band, &d, c).unwrap();
            let exact = 2.0 / lat.pos(c).length();
            worst = worst.max((k / exact - 1.0).abs());
        }
        assert!(worst < 0.02, "relative curvature error {worst}");
        assert_eq!(node_curvature(&lat, &band, &d, [0, 0, 0]), None);
    }
}
