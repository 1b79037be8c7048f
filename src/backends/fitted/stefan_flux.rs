//! The Stefan velocity `v_n = −[∂T/∂n]` (001 (6.4)) at the interface vertices of a fitted mesh
//! from second-order one-sided gradients.
//!
//! The P1 gradient of a triangle is exact for linear fields only, and the area-weighted mean of
//! the P1 gradients of one side around an interface vertex is the gradient at the centroids of
//! those triangles, a fraction of `h` away from `Γ`: with the curvature of the temperature
//! profile at the front (`∂²T/∂n² ≠ 0`, the boundary layer of the undercooled liquid) that is a
//! systematic first-order error in `v_n`. Here each side's gradient at an interface vertex `v`
//! comes instead from the least-squares quadratic through `T(v)` fitted to the vertices of that
//! side within two rings of `v` (interface vertices included, whose values the Gibbs–Thomson
//! relation prescribes): exact for quadratics, so second order for smooth `T`. Where a side has
//! too few vertices for a quadratic (a thin arm, the outer boundary), the fit falls back to a
//! linear one, and without any vertex the side's gradient is zero (an insulated side).

use crate::error::Result;
use crate::flows::stefan::check_velocity_inputs;
use crate::geom::DVec2;
use crate::mesh::Mesh2;
use rayon::prelude::*;

/// Vertex-to-triangle incidence of the live triangles (CSR: `start`, `tris`).
fn vertex_triangles(m: &Mesh2) -> (Vec<usize>, Vec<u32>) {
    let n = m.n_points();
    let mut count = vec![0usize; n + 1];
    for t in m.live_tris() {
        for &v in &m.tris[t] {
            count[v as usize + 1] += 1;
        }
    }
    for i in 0..n {
        count[i + 1] += count[i];
    }
    let mut fill = count.clone();
    let mut tris = vec![0u32; count[n]];
    for t in m.live_tris() {
        for &v in &m.tris[t] {
            tris[fill[v as usize]] = t as u32;
            fill[v as usize] += 1;
        }
    }
    (count, tris)
}

/// Solves the symmetric `k × k` system `a x = b` (k ≤ 5) by Gaussian elimination with partial
/// pivoting; `None` when a pivot falls below `1e-10` of the largest diagonal entry.
fn solve_small(a: &mut [[f64; 5]; 5], b: &mut [f64; 5], k: usize) -> Option<[f64; 5]> {
    let scale = (0..k).fold(0.0f64, |s, i| s.max(a[i][i].abs()));
    if scale <= 0.0 {
        return None;
    }
    for c in 0..k {
        let p = (c..k).max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))?;
        if a[p][c].abs() < 1e-10 * scale {
            return None;
        }
        a.swap(c, p);
        b.swap(c, p);
        let pivot = a[c];
        for r in c + 1..k {
            let f = a[r][c] / pivot[c];
            for (x, &y) in a[r][c..k].iter_mut().zip(&pivot[c..k]) {
                *x -= f * y;
            }
            b[r] -= f * b[c];
        }
    }
    let mut x = [0.0; 5];
    for c in (0..k).rev() {
        let s: f64 = (c + 1..k).map(|j| a[c][j] * x[j]).sum();
        x[c] = (b[c] - s) / a[c][c];
    }
    Some(x)
}

/// The least-squares gradient at `x0` of the polynomial (quadratic, or linear when `k = 2`)
/// through `(x0, f0)` fitted to the samples `(x, f)`; offsets scaled by `scale`.
fn fit_gradient(
    x0: DVec2,
    f0: f64,
    samples: &[(DVec2, f64)],
    scale: f64,
    k: usize,
) -> Option<DVec2> {
    let mut a = [[0.0f64; 5]; 5];
    let mut b = [0.0f64; 5];
    for &(x, f) in samples {
        let d = (x - x0) / scale;
        let row = [d.x, d.y, 0.5 * d.x * d.x, d.x * d.y, 0.5 * d.y * d.y];
        for i in 0..k {
            for j in 0..k {
                a[i][j] += row[i] * row[j];
            }
            b[i] += row[i] * (f - f0);
        }
    }
    let c = solve_small(&mut a, &mut b, k)?;
    Some(DVec2::new(c[0], c[1]) / scale)
}

/// The normal velocity `v_n = −(∂T/∂n|₊ − ∂T/∂n|₋)` at every interface vertex (0 elsewhere) from
/// the one-sided least-squares quadratic gradients of the module documentation, `n =
/// normals[v]` pointing out of the solid (the triangles labelled `inside_label`).
///
/// Errors: sizes that do not match the mesh, non-finite temperatures, a normal that is not a
/// unit vector at an interface vertex.
pub fn stefan_velocity_quadratic(
    mesh: &Mesh2,
    inside_label: i32,
    on_interface: &[bool],
    normals: &[DVec2],
    temperature: &[f64],
) -> Result<Vec<f64>> {
    let n = mesh.n_points();
    check_velocity_inputs(n, on_interface, normals, temperature)?;
    let (start, vt) = vertex_triangles(mesh);
    let side_of = |t: usize| usize::from(mesh.tri_ref[t] != inside_label);
    let gradient = |v: usize, side: usize| -> DVec2 {
        let x0 = mesh.points[v];
        // Ring 1 and ring 2 of `v` through triangles of `side`.
        let mut ring: Vec<u32> = Vec::with_capacity(32);
        for &t in &vt[start[v]..start[v + 1]] {
            if side_of(t as usize) == side {
                ring.extend(
                    mesh.tris[t as usize]
                        .iter()
                        .copied()
                        .filter(|&w| w as usize != v),
                );
            }
        }
        ring.sort_unstable();
        ring.dedup();
        if ring.is_empty() {
            return DVec2::ZERO;
        }
        let scale = ring
            .iter()
            .map(|&w| (mesh.points[w as usize] - x0).length())
            .fold(0.0f64, f64::max);
        let first = ring.clone();
        for &w in &first {
            for &t in &vt[start[w as usize]..start[w as usize + 1]] {
                if side_of(t as usize) == side {
                    ring.extend(
                        mesh.tris[t as usize]
                            .iter()
                            .copied()
                            .filter(|&u| u as usize != v),
                    );
                }
            }
        }
        ring.sort_unstable();
        ring.dedup();
        let samples: Vec<(DVec2, f64)> = ring
            .iter()
            .map(|&w| (mesh.points[w as usize], temperature[w as usize]))
            .collect();
        let f0 = temperature[v];
        if samples.len() >= 7 {
            if let Some(g) = fit_gradient(x0, f0, &samples, scale, 5) {
                return g;
            }
        }
        let near: Vec<(DVec2, f64)> = first
            .iter()
            .map(|&w| (mesh.points[w as usize], temperature[w as usize]))
            .collect();
        fit_gradient(x0, f0, &near, scale, 2).unwrap_or(DVec2::ZERO)
    };
    Ok((0..n)
        .into_par_iter()
        .map(|v| {
            if !on_interface[v] {
                return 0.0;
            }
            -(gradient(v, 1) - gradient(v, 0)).dot(normals[v])
        })
        .collect())
}
