//! Cubic and quartic least-squares fits of a P1 field on a two-ring vertex patch: the gradient
//! and Hessian at the vertex with an error of the order of the patch diameter squared (cubed for
//! the quartic fit), whatever the patch's symmetry.
//!
//! The quadratic fit of 004 §4.3 ([`crate::recovery::recover_ls`]) recovers the Hessian to
//! `O(|∇³u| d)` on a patch of diameter `d` unless the patch is symmetric. On the adapted mesh the
//! patch of a vertex near the interface is `d ~ √(ε R)` long along the interface (004 eq. (6)),
//! so the Hessian error — and the curvature `div(∇u/|∇u|)` built from it — decays only like
//! `√h` where the curvature of the zero level varies along it (an ellipse). Fitting the cubic
//! terms as well leaves `O(|∇⁴u| d²) = O(h)`, the quartic terms `O(|∇⁵u| d³) = O(h^{3/2})`.
//! The interface curvature uses the quartic fit: on the circle of the cross-check (R = 0.5,
//! h = 0.02 / 0.01 / 0.005) its mean relative error is 2.3e-4 / 6.8e-5 / 2.9e-5 (orders 1.79,
//! 1.24) against the cubic fit's 2.6e-3 / 1.4e-3 / 7.4e-4 (0.87, 0.95); on the ellipse
//! `x²/0.25 + y²/0.09 = 1` 1.9e-3 / 5.2e-4 / 2.6e-4 (1.88, 1.01) against 5.2e-3 / 2.1e-3 /
//! 1.3e-3. The mean curvature speed keeps the cubic fit.
//!
//! The offsets are whitened by the patch's second-moment tensor (as in the quadratic fit), so
//! the `9 × 9` normal equations stay well conditioned at any aspect ratio; cubics are mapped to
//! cubics by the whitening, so the fit reproduces cubic fields exactly.

use crate::geom::DVec2;
use crate::mesh::Mesh2;
use crate::metric::Sym2;

/// Unknowns of the cubic fit: gradient (2), Hessian (3), cubic terms (4).
const N_CUBIC: usize = 9;

/// Unknowns of the quartic fit: the cubic ones and five quartic terms.
const N: usize = 14;

/// Fewest neighbours before the patch is widened to a third ring.
const MIN_POINTS: usize = 14;

/// Smallest accepted pivot of the column-scaled elimination (relative).
const MIN_PIVOT: f64 = 1e-10;

/// The vertices of the `rings`-ring patch around `v` (`v` first), in `verts`.
fn patch(mesh: &Mesh2, v: u32, rings: usize, verts: &mut Vec<u32>) {
    verts.clear();
    verts.push(v);
    let mut start = 0;
    for _ in 0..rings {
        let end = verts.len();
        for i in start..end {
            let w = verts[i];
            mesh.for_each_fan_triangle(w, |t| {
                for &x in &mesh.tris[t as usize] {
                    if !verts.contains(&x) {
                        verts.push(x);
                    }
                }
            });
        }
        start = end;
    }
}

/// The gradient and Hessian of the cubic least-squares fit of `u` at vertex `v` (module
/// documentation), with `u(v)` kept; `None` when the patch cannot determine a cubic.
pub(crate) fn cubic_fit(
    mesh: &Mesh2,
    u: &[f64],
    v: u32,
    verts: &mut Vec<u32>,
) -> Option<(DVec2, Sym2)> {
    poly_fit(mesh, u, v, verts, false)
}

/// As [`cubic_fit`] with the quartic terms as well (Hessian error `O(|∇⁵u| d³)`), on a patch of
/// at least [`MIN_POINTS_QUARTIC`] neighbours (two or three rings); `None` when the patch cannot
/// determine a quartic.
pub(crate) fn quartic_fit(
    mesh: &Mesh2,
    u: &[f64],
    v: u32,
    verts: &mut Vec<u32>,
) -> Option<(DVec2, Sym2)> {
    poly_fit(mesh, u, v, verts, true)
}

/// Fewest neighbours of a quartic fit before the patch is widened to a third ring: the 14
/// unknowns and two more. Widening further (22 or more neighbours) made the interface curvature
/// of the cross-check's ellipse ten times worse (2.0e-2 against 1.9e-3 at h = 0.02): the third
/// ring is `~√(εR)` further along the interface.
const MIN_POINTS_QUARTIC: usize = 16;

fn poly_fit(
    mesh: &Mesh2,
    u: &[f64],
    v: u32,
    verts: &mut Vec<u32>,
    quartic: bool,
) -> Option<(DVec2, Sym2)> {
    let (n, min_points) = if quartic {
        (N, MIN_POINTS_QUARTIC)
    } else {
        (N_CUBIC, MIN_POINTS)
    };
    patch(mesh, v, 2, verts);
    if verts.len() - 1 < min_points {
        patch(mesh, v, 3, verts);
    }
    if verts.len() - 1 < n + 2 {
        return None;
    }
    let x0 = mesh.points[v as usize];
    let u0 = u[v as usize];
    // Second-moment tensor C of the offsets and its eigen-decomposition C = Q Λ Qᵀ.
    let k = (verts.len() - 1) as f64;
    let (mut cxx, mut cxy, mut cyy) = (0.0, 0.0, 0.0);
    for &w in &verts[1..] {
        let d = mesh.points[w as usize] - x0;
        cxx += d.x * d.x;
        cxy += d.x * d.y;
        cyy += d.y * d.y;
    }
    let (cxx, cxy, cyy) = (cxx / k, cxy / k, cyy / k);
    let mean = 0.5 * (cxx + cyy);
    let rad = (0.25 * (cxx - cyy).powi(2) + cxy * cxy).sqrt();
    let (l1, l2) = (mean + rad, mean - rad);
    if !(l2 > 0.0 && l1.is_finite()) {
        return None;
    }
    let angle = 0.5 * (2.0 * cxy).atan2(cxx - cyy);
    let q1 = DVec2::new(angle.cos(), angle.sin());
    let q2 = q1.perp();
    // Whitening T = Λ^{-1/2} Qᵀ: rows r1, r2.
    let (r1, r2) = (q1 / l1.sqrt(), q2 / l2.sqrt());
    let mut ata = [[0.0; N]; N];
    let mut atb = [0.0; N];
    for &w in &verts[1..] {
        let d = mesh.points[w as usize] - x0;
        let (x, y) = (r1.dot(d), r2.dot(d));
        let row = [
            x,
            y,
            0.5 * x * x,
            x * y,
            0.5 * y * y,
            x * x * x,
            x * x * y,
            x * y * y,
            y * y * y,
            x * x * x * x,
            x * x * x * y,
            x * x * y * y,
            x * y * y * y,
            y * y * y * y,
        ];
        let b = u[w as usize] - u0;
        for i in 0..n {
            atb[i] += row[i] * b;
            for j in 0..n {
                ata[i][j] += row[i] * row[j];
            }
        }
    }
    let c = solve(ata, atb, n)?;
    // Back to physical coordinates: g = Tᵀ g', H = Tᵀ H' T.
    let g = r1 * c[0] + r2 * c[1];
    let hxx = |a: DVec2, b: DVec2| {
        c[2] * r1.dot(a) * r1.dot(b)
            + c[3] * (r1.dot(a) * r2.dot(b) + r2.dot(a) * r1.dot(b))
            + c[4] * r2.dot(a) * r2.dot(b)
    };
    let (ex, ey) = (DVec2::X, DVec2::Y);
    let h = Sym2::new(hxx(ex, ex), hxx(ex, ey), hxx(ey, ey));
    (g.is_finite() && h.xx.is_finite() && h.xy.is_finite() && h.yy.is_finite()).then_some((g, h))
}

/// Solves the symmetric normal equations by Gaussian elimination with partial pivoting after
/// scaling to a unit diagonal, on the leading `n × n` block; `None` when a pivot is below
/// [`MIN_PIVOT`].
fn solve(mut a: [[f64; N]; N], mut b: [f64; N], n: usize) -> Option<[f64; N]> {
    let mut s = [0.0; N];
    for i in 0..n {
        if a[i][i].is_nan() || a[i][i] <= 0.0 {
            return None;
        }
        s[i] = 1.0 / a[i][i].sqrt();
    }
    for i in 0..n {
        for j in 0..n {
            a[i][j] *= s[i] * s[j];
        }
        b[i] *= s[i];
    }
    for col in 0..n {
        let p = (col..n).max_by(|&i, &j| a[i][col].abs().total_cmp(&a[j][col].abs()))?;
        if a[p][col].abs() < MIN_PIVOT {
            return None;
        }
        a.swap(col, p);
        b.swap(col, p);
        let pivot = a[col];
        for r in col + 1..n {
            let f = a[r][col] / pivot[col];
            if f != 0.0 {
                for (x, p) in a[r][col..].iter_mut().zip(&pivot[col..]) {
                    *x -= f * p;
                }
                b[r] -= f * b[col];
            }
        }
    }
    let mut x = [0.0; N];
    for i in (0..n).rev() {
        let mut v = b[i];
        for j in i + 1..n {
            v -= a[i][j] * x[j];
        }
        x[i] = v / a[i][i];
    }
    for i in 0..n {
        x[i] *= s[i];
    }
    Some(x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh::Mesh2;

    #[test]
    fn cubics_are_reproduced_on_a_stretched_grid() {
        // A 12 x 12 grid stretched 50:1 and sheared.
        let n = 12;
        let mut points = Vec::new();
        for j in 0..=n {
            for i in 0..=n {
                let (x, y) = (i as f64 * 0.05, j as f64 * 0.001);
                points.push(DVec2::new(x + 3.0 * y, y));
            }
        }
        let mut tris = Vec::new();
        for j in 0..n {
            for i in 0..n {
                let a = (j * (n + 1) + i) as u32;
                let (b, c, d) = (a + 1, a + n as u32 + 1, a + n as u32 + 2);
                tris.push([a, b, d]);
                tris.push([a, d, c]);
            }
        }
        let mesh = Mesh2::from_triangles(points, tris).unwrap();
        let f = |p: DVec2| {
            0.3 + p.x - 2.0 * p.y + p.x * p.x + 3.0 * p.x * p.y - p.y * p.y + 2.0 * p.x.powi(3)
                - p.x * p.x * p.y
                + 5.0 * p.y.powi(3)
        };
        let u: Vec<f64> = mesh.points.iter().map(|&p| f(p)).collect();
        let v = (6 * (n + 1) + 6) as u32;
        let p = mesh.points[v as usize];
        let (g, h) = cubic_fit(&mesh, &u, v, &mut Vec::new()).unwrap();
        let ge = DVec2::new(
            1.0 + 2.0 * p.x + 3.0 * p.y + 6.0 * p.x * p.x - 2.0 * p.x * p.y,
            -2.0 + 3.0 * p.x - 2.0 * p.y - p.x * p.x + 15.0 * p.y * p.y,
        );
        let he = Sym2::new(
            2.0 + 12.0 * p.x - 2.0 * p.y,
            3.0 - 2.0 * p.x,
            -2.0 + 30.0 * p.y,
        );
        assert!((g - ge).length() < 1e-7, "{g} {ge}");
        assert!(
            (h.xx - he.xx).abs() < 1e-6
                && (h.xy - he.xy).abs() < 1e-6
                && (h.yy - he.yy).abs() < 1e-5,
            "{h:?} {he:?}"
        );
    }
}
