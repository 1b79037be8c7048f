//! The mean-curvature system `(M[Φ^k] + τ L[Φ^k]) x` of 000 (2.5) applied without a matrix:
//! the weighted lumped mass of 000 (2.6) and the stiffness weighted by `|∇Φ^k|_ε⁻¹` at the
//! `2 × 2 × 2` Gauss points of 000 (2.7), element by element while the band's cells stream by
//! (000 §3.3), with `Φ^k` and the vectors in `f32` and every element's arithmetic and every
//! accumulation in `f64`.
//!
//! The assembled matrix costs about 27 entries of 12 bytes per band node (30 GB for a sphere band
//! in a `4096³` grid); this operator keeps only the lumped mass and the diagonal (4 bytes each
//! per node). The gradients at the Gauss points are computed by sum factorisation: the
//! `x`-derivative of a trilinear function is bilinear in `(y, z)` and the same at both `x` Gauss
//! points, so the 8 gradients of `Φ^k` and of `x` take 60 operations each, and the transposed
//! sums as many.
//!
//! The product runs over slabs of cells (fixed ranges of the first coordinate, independent of the
//! thread count); a slab's cells touch the nodes of its own first coordinates and of the next
//! one, so the even slabs run in parallel, then the odd ones, on disjoint parts of the output:
//! the result does not depend on the number of threads.

use super::band::Band;
use super::grid::{CellIter, DtGrid};
use super::lattice::{Lattice, NarrowBand, C3};
use crate::error::{Error, Result};
use rayon::prelude::*;

/// Slabs of cells per product (fixed, so results do not depend on the thread count).
const SLABS: usize = 64;

/// The 2-point Gauss rule on `[0, 1]`: the 1D shape functions `1 − t`, `t` at its points.
pub(super) fn basis() -> [[f64; 2]; 2] {
    let g = 0.5 / 3f64.sqrt();
    let p = [0.5 - g, 0.5 + g];
    [[1.0 - p[0], p[0]], [1.0 - p[1], p[1]]]
}

/// The reference gradients of a trilinear function with corner values `v` (corner bits: 1 = x,
/// 2 = y, 4 = z) at the Gauss points `(qx, qy, qz)`: `d[0][qy][qz]`, `d[1][qx][qz]`,
/// `d[2][qx][qy]` (each component is constant along its own axis).
#[inline(always)]
pub(super) fn gauss_gradients(b: &[[f64; 2]; 2], v: &[f64; 8]) -> [[[f64; 2]; 2]; 3] {
    let mut d = [[[0.0; 2]; 2]; 3];
    // Edge differences along each axis, indexed by the other two corner bits (lower axis first).
    let ex = [[v[1] - v[0], v[5] - v[4]], [v[3] - v[2], v[7] - v[6]]]; // [y][z]
    let ey = [[v[2] - v[0], v[6] - v[4]], [v[3] - v[1], v[7] - v[5]]]; // [x][z]
    let ez = [[v[4] - v[0], v[6] - v[2]], [v[5] - v[1], v[7] - v[3]]]; // [x][y]
    for (comp, e) in [ex, ey, ez].iter().enumerate() {
        for q1 in 0..2 {
            for q2 in 0..2 {
                d[comp][q1][q2] = b[q1][0] * (b[q2][0] * e[0][0] + b[q2][1] * e[0][1])
                    + b[q1][1] * (b[q2][0] * e[1][0] + b[q2][1] * e[1][1]);
            }
        }
    }
    d
}

/// `out[a] += Σ_q ∇ψ_a(q) · F(q)` for the Gauss-point fluxes `f[qx][qy][qz]` (reference
/// gradients), the transpose of [`gauss_gradients`].
#[inline(always)]
pub(super) fn scatter_fluxes(b: &[[f64; 2]; 2], f: &[[[[f64; 3]; 2]; 2]; 2], out: &mut [f64; 8]) {
    // Sums of each component along its own axis.
    let mut s = [[[0.0; 2]; 2]; 3];
    for q1 in 0..2 {
        for q2 in 0..2 {
            s[0][q1][q2] = f[0][q1][q2][0] + f[1][q1][q2][0];
            s[1][q1][q2] = f[q1][0][q2][1] + f[q1][1][q2][1];
            s[2][q1][q2] = f[q1][q2][0][2] + f[q1][q2][1][2];
        }
    }
    for (comp, sc) in s.iter().enumerate() {
        // t[i][k] = Σ_{q1,q2} b[q1][i] b[q2][k] s[q1][q2]: the other two corner bits.
        let mut t = [[0.0; 2]; 2];
        for (i, ti) in t.iter_mut().enumerate() {
            for (k, tik) in ti.iter_mut().enumerate() {
                *tik = b[0][i] * (b[0][k] * sc[0][0] + b[1][k] * sc[0][1])
                    + b[1][i] * (b[0][k] * sc[1][0] + b[1][k] * sc[1][1]);
            }
        }
        let bit = 1 << comp;
        let (lo_bit, hi_bit) = match comp {
            0 => (2, 4),
            1 => (1, 4),
            _ => (1, 2),
        };
        for (i, ti) in t.iter().enumerate() {
            for (k, &tik) in ti.iter().enumerate() {
                let base = i * lo_bit + k * hi_bit;
                out[base + bit] += tik;
                out[base] -= tik;
            }
        }
    }
}

/// The matrix-free system `M[Φ^k] + τ L[Φ^k]` on a band (see the module documentation), with
/// its lumped mass and diagonal.
pub struct MatFree<'a> {
    h: f64,
    eps: f64,
    tau: f64,
    interior: &'a [bool],
    phik: &'a [f32],
    /// Per slab: the cell stream, the end of its first-coordinate range, its node range start.
    slabs: Vec<(CellIter<'a, C3>, i32, usize)>,
    /// The weighted lumped mass per band node (000 (2.6)).
    pub mass: Vec<f32>,
    /// The diagonal of `M + τ L`.
    pub diag: Vec<f32>,
}

impl<'a> MatFree<'a> {
    /// The operator for the band `nb` of `lat`, the field `phik` on it, regularisation `eps`
    /// and time step `tau`; one pass over the cells computes the mass and the diagonal.
    /// Error: [`Error::InvalidInput`] when `phik` does not match the band.
    pub fn new(
        lat: &Lattice,
        nb: &'a NarrowBand<DtGrid<C3>>,
        phik: &'a [f32],
        eps: f64,
        tau: f64,
    ) -> Result<MatFree<'a>> {
        let n = nb.band.len();
        if phik.len() != n || nb.interior.len() != n {
            return Err(Error::InvalidInput(format!(
                "matrix-free band operator: {n} nodes, {} values, {} flags",
                phik.len(),
                nb.interior.len()
            )));
        }
        // Slab boundaries: SLABS equal ranges of the first coordinate; node starts by one pass.
        let (x0, x1) = match (nb.band.coords().next(), nb.band.levels[0].starts.last()) {
            (Some(c), Some(_)) => (c[0], last_first_coord(&nb.band)),
            _ => (0, 0),
        };
        let width = ((x1 - x0 + 1) as usize).div_ceil(SLABS).max(1) as i32;
        let xs: Vec<i32> = (x0..=x1).step_by(width as usize).collect();
        let mut starts = vec![0usize; xs.len()];
        let (mut k, mut i) = (0usize, 0usize);
        for c in nb.band.coords() {
            while k < xs.len() && xs[k] <= c[0] {
                starts[k] = i;
                k += 1;
            }
            i += 1;
        }
        let iters = CellIter::slabs(&nb.band, &xs);
        let slabs = iters
            .into_iter()
            .enumerate()
            .map(|(k, it)| (it, xs.get(k + 1).copied().unwrap_or(i32::MAX), starts[k]))
            .collect();
        let mut op = MatFree {
            h: lat.h,
            eps,
            tau,
            interior: &nb.interior,
            phik,
            slabs,
            mass: Vec::new(),
            diag: Vec::new(),
        };
        let mut md = vec![[0.0f64; 2]; n];
        op.for_elements(&mut md, |op, v, _, mut out| {
            let (m, d) = op.element_mass_diag(v);
            for (o, dk) in out.iter_mut().zip(d) {
                o[0] += m;
                o[1] += m + dk;
            }
        });
        op.mass = md.iter().map(|x| x[0] as f32).collect();
        op.diag = md.iter().map(|x| x[1] as f32).collect();
        Ok(op)
    }

    /// The band node count.
    pub fn len(&self) -> usize {
        self.phik.len()
    }

    /// Whether the band is empty.
    pub fn is_empty(&self) -> bool {
        self.phik.is_empty()
    }

    /// `Φ^k` at the corners of an element, the Gauss weights `|∇Φ^k|_ε⁻¹`.
    #[inline(always)]
    fn weights(&self, b: &[[f64; 2]; 2], v: &[f64; 8]) -> [[[f64; 2]; 2]; 2] {
        let d = gauss_gradients(b, v);
        let s = 1.0 / (self.h * self.h);
        let mut a = [[[0.0; 2]; 2]; 2];
        for (qx, ax) in a.iter_mut().enumerate() {
            for (qy, axy) in ax.iter_mut().enumerate() {
                for (qz, w) in axy.iter_mut().enumerate() {
                    let g2 = (d[0][qy][qz] * d[0][qy][qz]
                        + d[1][qx][qz] * d[1][qx][qz]
                        + d[2][qx][qy] * d[2][qx][qy])
                        * s;
                    *w = 1.0 / (self.eps * self.eps + g2).sqrt();
                }
            }
        }
        a
    }

    /// The lumped mass of each corner and `τ` times the stiffness diagonal of one element.
    fn element_mass_diag(&self, v: &[f64; 8]) -> (f64, [f64; 8]) {
        let h = self.h;
        let e = [
            v[1] - v[0] + v[3] - v[2] + v[5] - v[4] + v[7] - v[6],
            v[2] - v[0] + v[3] - v[1] + v[6] - v[4] + v[7] - v[5],
            v[4] - v[0] + v[5] - v[1] + v[6] - v[2] + v[7] - v[3],
        ];
        let g2 = (e[0] * e[0] + e[1] * e[1] + e[2] * e[2]) / (16.0 * h * h);
        let m = h * h * h / 8.0 / (self.eps * self.eps + g2).sqrt();
        let b = basis();
        let a = self.weights(&b, v);
        let mut d = [0.0; 8];
        for (c, dc) in d.iter_mut().enumerate() {
            let (i, j, k) = (c & 1, (c >> 1) & 1, (c >> 2) & 1);
            for (qx, bx) in b.iter().enumerate() {
                for (qy, by) in b.iter().enumerate() {
                    for (qz, bz) in b.iter().enumerate() {
                        let g = [by[j] * bz[k], bx[i] * bz[k], bx[i] * by[j]];
                        *dc += a[qx][qy][qz] * (g[0] * g[0] + g[1] * g[1] + g[2] * g[2]);
                    }
                }
            }
            *dc *= self.tau * h / 8.0;
        }
        (m, d)
    }

    /// Calls `f(self, Φ^k corners, corner indices, outputs)` for every element (a cell with an
    /// interior corner), slab by slab: the even slabs in parallel, then the odd ones, each on
    /// its own part of `out`; the element order within a slab is the storage order.
    fn for_elements<T: Send>(
        &self,
        out: &mut [T],
        f: impl Fn(&Self, &[f64; 8], &[u32; 8], [&mut T; 8]) + Sync,
    ) {
        let ns = self.slabs.len();
        let start = |k: usize| {
            if k < ns {
                self.slabs[k].2
            } else {
                out.len()
            }
        };
        let starts: Vec<usize> = (0..=ns + 1).map(start).collect();
        for parity in 0..2 {
            // Disjoint output parts [start(k), start(k + 2)) for the slabs k of this parity.
            let mut parts: Vec<(usize, &mut [T])> = Vec::new();
            let mut rest: &mut [T] = &mut out[..];
            let mut offset = 0;
            let mut k = parity;
            while k < ns {
                let (lo, hi) = (starts[k], starts[(k + 2).min(ns + 1)]);
                let (_, tail) = rest.split_at_mut(lo - offset);
                let (part, tail) = tail.split_at_mut(hi - lo);
                parts.push((k, part));
                rest = tail;
                offset = hi;
                k += 2;
            }
            parts.into_par_iter().for_each(|(k, part)| {
                let (it, x_end, _) = &self.slabs[k];
                let lo = starts[k];
                for (c, idx) in it.clone() {
                    if c[0] >= *x_end {
                        break;
                    }
                    if !idx.iter().any(|&i| self.interior[i as usize]) {
                        continue;
                    }
                    let v: [f64; 8] = std::array::from_fn(|m| self.phik[idx[m] as usize] as f64);
                    let refs = corner_refs(part, &idx, lo);
                    f(self, &v, &idx, refs);
                }
            });
        }
    }

    /// `y = (M + τ L) x`, accumulated in `f64`.
    /// Panics only if `x` or `y` does not have one entry per band node (a caller error).
    pub fn apply(&self, x: &[f32], y: &mut [f64]) {
        assert!(x.len() == self.len() && y.len() == self.len());
        y.par_iter_mut()
            .zip(x.par_iter().zip(&self.mass))
            .for_each(|(y, (&x, &m))| *y = m as f64 * x as f64);
        let b = basis();
        let scale = self.tau * self.h / 8.0;
        self.for_elements(y, |op, v, idx, out| {
            let a = op.weights(&b, v);
            let u: [f64; 8] = std::array::from_fn(|m| x[idx[m] as usize] as f64);
            let d = gauss_gradients(&b, &u);
            let mut fl = [[[[0.0; 3]; 2]; 2]; 2];
            for (qx, fx) in fl.iter_mut().enumerate() {
                for (qy, fxy) in fx.iter_mut().enumerate() {
                    for (qz, f) in fxy.iter_mut().enumerate() {
                        let w = scale * a[qx][qy][qz];
                        *f = [w * d[0][qy][qz], w * d[1][qx][qz], w * d[2][qx][qy]];
                    }
                }
            }
            let mut r = [0.0; 8];
            scatter_fluxes(&b, &fl, &mut r);
            for (o, rk) in out.into_iter().zip(r) {
                *o += rk;
            }
        });
    }
}

/// The first coordinate of the band's last node.
fn last_first_coord(g: &DtGrid<C3>) -> i32 {
    let l0 = &g.levels[0];
    let r = l0.starts.len() - 1;
    l0.end(r)
}

/// Mutable references to the 8 corner entries of `part` (which starts at node `lo`); the corner
/// indices of a cell are distinct.
fn corner_refs<'b, T>(part: &'b mut [T], idx: &[u32; 8], lo: usize) -> [&'b mut T; 8] {
    let ptr = part.as_mut_ptr();
    let len = part.len();
    std::array::from_fn(|m| {
        let i = (idx[m] as usize).wrapping_sub(lo);
        assert!(i < len, "element corner outside its slab's nodes");
        // SAFETY: `i < len`, and the 8 corners of a cell are 8 distinct nodes, so the references
        // do not alias.
        unsafe { &mut *ptr.add(i) }
    })
}
