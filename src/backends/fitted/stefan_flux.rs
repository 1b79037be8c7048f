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

use super::fit::FittedMesh;
use super::stefan_energy::interface_dual_lengths;
use crate::error::{Error, Result};
use crate::flows::stefan::check_velocity_inputs;
use crate::geom::simplex;
use crate::geom::DVec2;
use crate::mesh::{check_p1_field, Mesh2};
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

/// The normal velocity from the discrete heat balance of the heat step: at every interface
/// vertex `i` of the fitted mesh `fm` with dual length `L_i > 0` (half its interface edges), `v_n = R_i / (Δt L_i)`,
/// `R_i = M_i (Tⁿ⁺¹_i − Tⁿ_i) + Δt (K Tⁿ⁺¹)_i` the residual of the implicit Euler step
/// (lumped mass `M`, stiffness `K`) that the prescribed value at `i` leaves: the heat that step
/// supplied through the interface near `i`, the weak form of `−[∂T/∂n]` (001 (6.4)) integrated
/// over the step. `Σ v_n,i L_i Δt` is exactly the heat the interface supplied, so the latent heat of
/// the front's motion balances it (the energy `∫T − A` is conserved up to the advection's
/// error). The residuals are noisy from vertex to vertex (the split of the flux between two
/// neighbouring interface vertices depends on how the cut triangles are shaped), so they are
/// smoothed along the interface edges by `smoothing_passes` passes of a
/// conservative diffusion (the sum of the residuals is kept). `t_old` is the temperature the step started from, before the interface values were
/// set. Other vertices get 0.
///
/// Errors: sizes that do not match the mesh, non-finite values, a non-positive `dt`.
pub fn stefan_velocity_residual(
    fm: &FittedMesh,
    on_interface: &[bool],
    t_old: &[f64],
    t_new: &[f64],
    dt: f64,
    smoothing_passes: usize,
) -> Result<Vec<f64>> {
    let mesh = &fm.mesh;
    let interface_edges = fm.interface_edges();
    let dual_length = interface_dual_lengths(fm);
    let n = mesh.n_points();
    check_p1_field(n, t_old, "temperature")?;
    check_p1_field(n, t_new, "temperature")?;
    if on_interface.len() != n {
        return Err(Error::InvalidInput(format!(
            "Stefan velocity: the mesh has {n} vertices but the interface mask has {}",
            on_interface.len()
        )));
    }
    if !(dt.is_finite() && dt > 0.0) {
        return Err(Error::InvalidInput(format!(
            "Stefan velocity: the time step must be finite and positive (got {dt})"
        )));
    }
    let mut r = vec![0.0f64; n];
    for t in mesh.live_tris() {
        let tri = mesh.tris[t];
        if !tri.iter().any(|&v| on_interface[v as usize]) {
            continue;
        }
        let p = mesh.tri_points(t);
        let a = mesh.tri_area(t).abs();
        let g = simplex::p1_gradients(&p);
        let grad_t = simplex::p1_gradient(&p, &tri.map(|v| t_new[v as usize]));
        for (k, &v) in tri.iter().enumerate() {
            let v = v as usize;
            if on_interface[v] {
                r[v] += a / 3.0 * (t_new[v] - t_old[v]) + dt * a * grad_t.dot(g[k]);
            }
        }
    }
    // Conservative smoothing along the interface: per pass and interface edge `(a, b)`, the heat
    // `½ (q_b − q_a) L_a L_b / (L_a + L_b)` (`q = R / L`) moves from `b` to `a`; the sum of `R`
    // is unchanged and every `q` moves at most half-way towards its neighbours' (stable).
    for _ in 0..smoothing_passes {
        let q: Vec<f64> = (0..n)
            .map(|v| {
                if dual_length[v] > 0.0 {
                    r[v] / dual_length[v]
                } else {
                    0.0
                }
            })
            .collect();
        let mut next = r.clone();
        for &[a, b] in &interface_edges {
            let (a, b) = (a as usize, b as usize);
            let (la, lb) = (dual_length[a], dual_length[b]);
            if la > 0.0 && lb > 0.0 {
                let f = 0.25 * (q[b] - q[a]) * la * lb / (la + lb);
                next[a] += f;
                next[b] -= f;
            }
        }
        r = next;
    }
    Ok((0..n)
        .map(|v| {
            if on_interface[v] && dual_length[v] > 0.0 {
                r[v] / (dt * dual_length[v])
            } else {
                0.0
            }
        })
        .collect())
}
