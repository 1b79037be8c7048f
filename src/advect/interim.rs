//! Interim numerical helpers used by `advect` until the owning modules land on `main`:
//! quadrature and P1 mass matrix + Jacobi–CG (→ `crate::fem`), exact P1 area and length of the zero level
//! (→ `crate::levelset::interface`). Each function here is small and private to the crate; it
//! is replaced by a call to the owning module once that module is available.

use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::mesh::Mesh2;
use rayon::prelude::*;

/// A quadrature rule on the reference triangle: barycentric points and weights summing to 1.
pub(crate) struct TriRule {
    pub pts: &'static [[f64; 3]],
    pub w: &'static [f64],
}

const A1: f64 = 0.445_948_490_915_965;
const B1: f64 = 1.0 - 2.0 * A1;
const A2: f64 = 0.091_576_213_509_771;
const B2: f64 = 1.0 - 2.0 * A2;
const W1: f64 = 0.223_381_589_678_011;
const W2: f64 = 0.109_951_743_655_322;

/// Dunavant's 6-point rule, exact for polynomials of degree 4.
pub(crate) const DUNAVANT4: TriRule = TriRule {
    pts: &[
        [B1, A1, A1],
        [A1, B1, A1],
        [A1, A1, B1],
        [B2, A2, A2],
        [A2, B2, A2],
        [A2, A2, B2],
    ],
    w: &[W1, W1, W1, W2, W2, W2],
};

/// A compressed-row symmetric matrix with the sparsity of the P1 vertex graph.
pub(crate) struct Csr {
    pub offsets: Vec<usize>,
    pub cols: Vec<u32>,
    pub vals: Vec<f64>,
}

impl Csr {
    fn mul(&self, x: &[f64], y: &mut [f64]) {
        y.par_iter_mut().enumerate().for_each(|(i, yi)| {
            let mut s = 0.0;
            for k in self.offsets[i]..self.offsets[i + 1] {
                s += self.vals[k] * x[self.cols[k] as usize];
            }
            *yi = s;
        });
    }
}

/// The P1 mass matrix `M_ij = ∫ φ_i φ_j` of `mesh` (local matrix `|K|/12 [2 1 1; 1 2 1; 1 1 2]`).
pub(crate) fn mass_matrix(mesh: &Mesh2) -> Csr {
    let n = mesh.n_points();
    let (off, nb) = mesh.v2v();
    // Rows hold the vertex itself then its sorted ring; merge into one sorted column list.
    let mut offsets = vec![0usize; n + 1];
    let mut cols = Vec::with_capacity(nb.len() + n);
    for v in 0..n {
        let ring = &nb[off[v]..off[v + 1]];
        let mut placed = false;
        for &w in ring {
            if !placed && w as usize > v {
                cols.push(v as u32);
                placed = true;
            }
            cols.push(w);
        }
        if !placed {
            cols.push(v as u32);
        }
        offsets[v + 1] = cols.len();
    }
    let mut vals = vec![0.0; cols.len()];
    let find = |i: usize, j: u32, cols: &[u32]| -> usize {
        let row = &cols[offsets[i]..offsets[i + 1]];
        offsets[i] + row.binary_search(&j).unwrap_or(0)
    };
    for t in mesh.live_tris() {
        let a = mesh.tri_area(t) / 12.0;
        let tri = mesh.tris[t];
        for i in 0..3 {
            for j in 0..3 {
                let k = find(tri[i] as usize, tri[j], &cols);
                vals[k] += if i == j { 2.0 * a } else { a };
            }
        }
    }
    Csr {
        offsets,
        cols,
        vals,
    }
}

/// Solves `A x = b` for a symmetric positive definite `A` by Jacobi-preconditioned conjugate
/// gradients from the initial guess in `x`; relative residual tolerance `tol`.
pub(crate) fn pcg(a: &Csr, b: &[f64], x: &mut [f64], tol: f64, max_iter: usize) -> Result<usize> {
    let n = b.len();
    let diag: Vec<f64> = (0..n)
        .map(|i| {
            (a.offsets[i]..a.offsets[i + 1])
                .find(|&k| a.cols[k] as usize == i)
                .map(|k| a.vals[k])
                .unwrap_or(1.0)
        })
        .collect();
    if diag.iter().any(|&d| d <= 0.0 || !d.is_finite()) {
        return Err(Error::InvalidInput(
            "pcg: the matrix has a non-positive diagonal entry (unreferenced vertex?)".into(),
        ));
    }
    let mut r = vec![0.0; n];
    a.mul(x, &mut r);
    r.par_iter_mut().zip(b).for_each(|(ri, bi)| *ri = bi - *ri);
    let bnorm = b.iter().map(|v| v * v).sum::<f64>().sqrt().max(1e-300);
    let mut z: Vec<f64> = r.iter().zip(&diag).map(|(r, d)| r / d).collect();
    let mut p = z.clone();
    let mut rz: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
    let mut q = vec![0.0; n];
    for it in 0..max_iter {
        let rnorm = r.iter().map(|v| v * v).sum::<f64>().sqrt();
        if rnorm <= tol * bnorm {
            return Ok(it);
        }
        a.mul(&p, &mut q);
        let pq: f64 = p.iter().zip(&q).map(|(a, b)| a * b).sum();
        let alpha = rz / pq;
        for i in 0..n {
            x[i] += alpha * p[i];
            r[i] -= alpha * q[i];
            z[i] = r[i] / diag[i];
        }
        let rz_new: f64 = r.iter().zip(&z).map(|(a, b)| a * b).sum();
        let beta = rz_new / rz;
        rz = rz_new;
        for i in 0..n {
            p[i] = z[i] + beta * p[i];
        }
    }
    Err(Error::NotConverged(format!(
        "mass-matrix CG: no convergence to {tol:e} in {max_iter} iterations"
    )))
}

/// The zero crossing on the edge `(pa, ua)`–`(pb, ub)` of a P1 field.
#[inline]
fn crossing(pa: DVec2, ua: f64, pb: DVec2, ub: f64) -> DVec2 {
    let t = ua / (ua - ub);
    pa + t * (pb - pa)
}

/// Area of the negative part `{u < 0}` of the P1 field `u` inside triangle `t`, and the length
/// of the zero-level segment in it (vertices with `u = 0` count as non-negative).
pub(crate) fn tri_negative_part(mesh: &Mesh2, t: usize, u: &[f64]) -> (f64, f64) {
    let tri = mesh.tris[t];
    let p = mesh.tri_points(t);
    let v = [u[tri[0] as usize], u[tri[1] as usize], u[tri[2] as usize]];
    let neg: Vec<usize> = (0..3).filter(|&i| v[i] < 0.0).collect();
    let area = mesh.tri_area(t);
    match neg.len() {
        0 => (0.0, 0.0),
        3 => (area, 0.0),
        1 | 2 => {
            // The lone vertex (the one whose sign differs from the other two).
            let lone = if neg.len() == 1 {
                neg[0]
            } else {
                (0..3).find(|i| !neg.contains(i)).unwrap_or(0)
            };
            let (j, k) = ((lone + 1) % 3, (lone + 2) % 3);
            let qj = crossing(p[lone], v[lone], p[j], v[j]);
            let qk = crossing(p[lone], v[lone], p[k], v[k]);
            let corner = crate::geom::signed_area(p[lone], qj, qk).abs();
            let len = (qj - qk).length();
            if neg.len() == 1 {
                (corner, len)
            } else {
                (area - corner, len)
            }
        }
        _ => (0.0, 0.0),
    }
}

/// Exact area of `{u < 0}` for a P1 field (→ `levelset::interface::enclosed_area`).
pub(crate) fn enclosed_area(mesh: &Mesh2, u: &[f64]) -> f64 {
    mesh.live_tris()
        .map(|t| tri_negative_part(mesh, t, u).0)
        .sum()
}

/// Exact length of the zero level of a P1 field (→ `levelset::interface::interface_length`).
pub(crate) fn interface_length(mesh: &Mesh2, u: &[f64]) -> f64 {
    mesh.live_tris()
        .map(|t| tri_negative_part(mesh, t, u).1)
        .sum()
}

/// The zero-level segments of a P1 field, one per cut triangle.
pub(crate) fn zero_level_segments(mesh: &Mesh2, u: &[f64]) -> Vec<[DVec2; 2]> {
    let mut out = Vec::new();
    for t in mesh.live_tris() {
        let tri = mesh.tris[t];
        let p = mesh.tri_points(t);
        let v = [u[tri[0] as usize], u[tri[1] as usize], u[tri[2] as usize]];
        let mut q = Vec::with_capacity(2);
        for i in 0..3 {
            let (a, b) = ((i + 1) % 3, (i + 2) % 3);
            if (v[a] < 0.0) != (v[b] < 0.0) {
                q.push(crossing(p[a], v[a], p[b], v[b]));
            }
        }
        if q.len() == 2 {
            out.push([q[0], q[1]]);
        }
    }
    out
}
