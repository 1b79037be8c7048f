//! Band matrix assembly without searching (000 §3.3): the Q1 couplings of a band node are among
//! its `3³` grid neighbours, so a row's pattern is a 27-bit mask of neighbour offsets and the
//! position of a coupling in the row is a population count. Elements are streamed in storage
//! order and every corner index is non-decreasing along that order, so the rows are split into
//! ranges and each range adds the contributions of the elements touching it in element order:
//! the matrices do not depend on the number of threads.

use super::fem::{element_mass, element_stiffness, Element, Weight};
use super::lattice::Lattice;
use crate::error::{Error, Result};
use crate::fem::q1::Q1;
use crate::fem::Csr;
use rayon::prelude::*;

/// The offset code `(dx + 1)·9 + (dy + 1)·3 + (dz + 1)` of corner `b` seen from corner `a`
/// (corner bits: 1 = x, 2 = y, 4 = z); codes grow with the lexicographic order of the nodes.
const fn code(a: usize, b: usize) -> u32 {
    (axis(a, b, 0) * 9 + axis(a, b, 1) * 3 + axis(a, b, 2)) as u32
}

/// The offset of corner `b` from corner `a` along axis `k`, plus one.
const fn axis(a: usize, b: usize, k: usize) -> i32 {
    ((b >> k) & 1) as i32 - ((a >> k) & 1) as i32 + 1
}

const fn codes() -> [[u32; 8]; 8] {
    let mut t = [[0u32; 8]; 8];
    let mut a = 0;
    while a < 8 {
        let mut b = 0;
        while b < 8 {
            t[a][b] = code(a, b);
            b += 1;
        }
        a += 1;
    }
    t
}

const CODE: [[u32; 8]; 8] = codes();

/// The mask of the codes of every corner seen from corner `a`.
fn corner_mask(a: usize) -> u32 {
    CODE[a].iter().fold(0, |m, &c| m | 1 << c)
}

/// The pairs `a ≤ b` of the upper triangle of an element matrix, row by row.
const UPPER: [(usize, usize); 36] = upper();

const fn upper() -> [(usize, usize); 36] {
    let mut t = [(0, 0); 36];
    let (mut a, mut k) = (0, 0);
    while a < 8 {
        let mut b = a;
        while b < 8 {
            t[k] = (a, b);
            k += 1;
            b += 1;
        }
        a += 1;
    }
    t
}

/// The isotropic element stiffness at the 2 × 2 × 2 Gauss points, `K = Σ_q a_q G_q` with the
/// products `G_q[a][b] = w_q h ∇ψ_a(ξ_q) · ∇ψ_b(ξ_q)` tabulated once (000 (2.7)).
struct Kernel {
    /// Per upper-triangle pair `(a, b)` (see [`UPPER`]): the products at the 8 Gauss points
    /// (contiguous, so the weighted sum is one short dot product).
    g: [[f64; 8]; 36],
    /// Per Gauss point: the reference gradients of the 8 shape functions, over `h`.
    grad: [[[f64; 3]; 8]; 8],
}

impl Kernel {
    /// Error: [`Error::InvalidInput`] unless `q1` has the 8 Gauss points of the cube.
    fn new(q1: &Q1, h: f64) -> Result<Kernel> {
        if q1.weights.len() != 8 || q1.grads.len() != 64 {
            return Err(Error::InvalidInput(format!(
                "band stiffness kernel: {} quadrature points (8 expected)",
                q1.weights.len()
            )));
        }
        let mut g = [[0.0; 8]; 36];
        let mut grad = [[[0.0; 3]; 8]; 8];
        for (q, gq) in grad.iter_mut().enumerate() {
            let gr = &q1.grads[q * 8..(q + 1) * 8];
            for a in 0..8 {
                for k in 0..3 {
                    gq[a][k] = gr[a][k] / h;
                }
            }
            for (gk, &(a, b)) in g.iter_mut().zip(&UPPER) {
                let dot = gr[a][0] * gr[b][0] + gr[a][1] * gr[b][1] + gr[a][2] * gr[b][2];
                gk[q] = q1.weights[q] * h * dot;
            }
        }
        Ok(Kernel { g, grad })
    }

    /// The stiffness weighted by `|∇Φ|_ε⁻¹` at the Gauss points for the corner values `v`
    /// (the upper triangle summed, the lower one mirrored: `G_q` is symmetric).
    #[inline]
    fn mcf(&self, eps: f64, v: &[f64; 8], ke: &mut [f64; 64]) {
        let mut w = [0.0; 8];
        for (wq, grq) in w.iter_mut().zip(&self.grad) {
            let mut d = [0.0; 3];
            for (vk, gk) in v.iter().zip(grq) {
                d[0] += vk * gk[0];
                d[1] += vk * gk[1];
                d[2] += vk * gk[2];
            }
            *wq = 1.0 / (eps * eps + d[0] * d[0] + d[1] * d[1] + d[2] * d[2]).sqrt();
        }
        for (gk, &(a, b)) in self.g.iter().zip(&UPPER) {
            let mut s = [0.0; 4];
            for q in 0..4 {
                s[q] = w[q] * gk[q] + w[q + 4] * gk[q + 4];
            }
            let k = (s[0] + s[2]) + (s[1] + s[3]);
            ke[a * 8 + b] = k;
            ke[b * 8 + a] = k;
        }
    }
}

/// The rows `[lo, hi)` of a partition of `0..n` into about `parts` ranges.
fn ranges(n: usize, parts: usize) -> Vec<(usize, usize)> {
    let parts = parts.max(1);
    let step = n.div_ceil(parts).max(1);
    (0..n)
        .step_by(step)
        .map(|lo| (lo, (lo + step).min(n)))
        .collect()
}

/// The elements `[first, last)` that have a corner in the rows `[lo, hi)` (corner 0 is the
/// smallest index of an element, corner 7 the largest; both are non-decreasing).
fn touching(elems: &[Element], lo: usize, hi: usize) -> (usize, usize) {
    let first = elems.partition_point(|e| (e.1[7] as usize) < lo);
    let last = elems.partition_point(|e| (e.1[0] as usize) < hi);
    (first, last.max(first))
}

/// The lumped mass and `τ` times the stiffness of the band elements with the weights of `w`
/// from the band field `phi` (000 (2.6)–(2.7), §2.1); with `with_mass` the mass is added to the
/// diagonal, giving the system matrix `M + τ L` of 000 (2.5).
/// Error: [`Error::InvalidInput`] when an element refers to a node `≥ n` or the elements are
/// not in storage order.
pub fn assemble_scaled(
    lat: &Lattice,
    elems: &[Element],
    n: usize,
    phi: &[f64],
    w: Weight,
    tau: f64,
    with_mass: bool,
) -> Result<(Vec<f64>, Csr)> {
    if n >= u32::MAX as usize || phi.len() != n {
        return Err(Error::InvalidInput(format!(
            "band assembly: {n} nodes, {} values",
            phi.len()
        )));
    }
    if let Some(e) = elems.iter().find(|e| e.1.iter().any(|&i| i as usize >= n)) {
        return Err(Error::InvalidInput(format!(
            "band element at {:?} refers to a node beyond {n}",
            e.0
        )));
    }
    if elems.windows(2).any(|p| p[0].0 >= p[1].0) {
        return Err(Error::InvalidInput(
            "band elements are not in storage order".into(),
        ));
    }
    let q1 = Q1::new(3, 2)?;
    let h = lat.h;
    let kernel = Kernel::new(&q1, h)?;
    let parts = 4 * rayon::current_num_threads();
    let rows = ranges(n, parts);
    let cmask: [u32; 8] = std::array::from_fn(corner_mask);
    // Row patterns: the diagonal plus the offsets covered by the node's elements.
    let masks: Vec<Vec<u32>> = rows
        .par_iter()
        .map(|&(lo, hi)| {
            let mut m = vec![1u32 << 13; hi - lo];
            let (f, l) = touching(elems, lo, hi);
            for e in &elems[f..l] {
                for (a, &i) in e.1.iter().enumerate() {
                    let i = i as usize;
                    if (lo..hi).contains(&i) {
                        m[i - lo] |= cmask[a];
                    }
                }
            }
            m
        })
        .collect();
    let mask: Vec<u32> = masks.into_iter().flatten().collect();
    let mut row_ptr = Vec::with_capacity(n + 1);
    row_ptr.push(0usize);
    let mut nnz = 0usize;
    for m in &mask {
        nnz += m.count_ones() as usize;
        row_ptr.push(nnz);
    }
    let pos = |i: usize, c: u32| row_ptr[i] + (mask[i] & ((1u32 << c) - 1)).count_ones() as usize;
    // Values and columns, one row range per task, elements in storage order, written in place
    // (each range owns its slice of the arrays: no per-range buffers to copy together).
    let mut val = vec![0.0; nnz];
    let mut col = vec![0u32; nnz];
    let mut mass = vec![0.0; n];
    let mut tasks = Vec::with_capacity(rows.len());
    {
        let (mut val, mut col, mut mass) = (&mut val[..], &mut col[..], &mut mass[..]);
        for &(lo, hi) in &rows {
            let len = row_ptr[hi] - row_ptr[lo];
            let (v, rest_v) = std::mem::take(&mut val).split_at_mut(len);
            let (c, rest_c) = std::mem::take(&mut col).split_at_mut(len);
            let (m, rest_m) = std::mem::take(&mut mass).split_at_mut(hi - lo);
            (val, col, mass) = (rest_v, rest_c, rest_m);
            tasks.push((lo, hi, v, c, m));
        }
    }
    tasks.into_par_iter().for_each(|(lo, hi, val, col, mass)| {
        let base = row_ptr[lo];
        for i in lo..hi {
            col[pos(i, 13) - base] = i as u32;
        }
        let (f, l) = touching(elems, lo, hi);
        let mut ke = [0.0; 64];
        for e in &elems[f..l] {
            let v: [f64; 8] = std::array::from_fn(|k| phi[e.1[k] as usize]);
            match w {
                Weight::Mcf { eps } => kernel.mcf(eps, &v, &mut ke),
                Weight::Heat => element_stiffness(&q1, w, &v, h, &mut ke),
            }
            let mw = element_mass(w, &v, h);
            for (a, &ia) in e.1.iter().enumerate() {
                let ia = ia as usize;
                if !(lo..hi).contains(&ia) {
                    continue;
                }
                mass[ia - lo] += mw;
                // The row's start and pattern, loaded once for its eight couplings.
                let (start, m) = (row_ptr[ia] - base, mask[ia]);
                for (b, &ib) in e.1.iter().enumerate() {
                    let p = start + (m & ((1u32 << CODE[a][b]) - 1)).count_ones() as usize;
                    val[p] += tau * ke[a * 8 + b];
                    col[p] = ib;
                }
            }
        }
        if with_mass {
            for i in lo..hi {
                val[pos(i, 13) - base] += mass[i - lo];
            }
        }
    });
    Ok((
        mass,
        Csr {
            n,
            row_ptr,
            col,
            val,
        },
    ))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::fem::elements;
    use crate::backends::dtgrid::lattice::{band_around, crossing_cells_of_fn, NarrowBand, C3};
    use crate::backends::dtgrid::{Band, DtGrid};
    use crate::geom::DVec3;

    #[test]
    fn masks_give_the_element_by_element_matrix() {
        let lat = Lattice::unit(17).unwrap();
        let f = |p: DVec3| (p - DVec3::new(0.03, -0.02, 0.01)).length() - 0.29;
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
        let n = nb.band.len();
        let phi: Vec<f64> = nb
            .band
            .coords()
            .map(|c| f(lat.pos(c)) * (1.0 + 0.3 * lat.pos(c).x))
            .collect();
        let el = elements(&nb);
        let q1 = Q1::new(3, 2).unwrap();
        for w in [Weight::Mcf { eps: 1e-3 }, Weight::Heat] {
            let tau = 0.37;
            let (mass, a) = assemble_scaled(&lat, &el, n, &phi, w, tau, true).unwrap();
            // Reference: the pattern by sorting, entries added by search.
            let mut r = Csr::from_element_iter(n, el.iter().map(|(_, idx)| &idx[..])).unwrap();
            let mut m = vec![0.0; n];
            let mut ke = [0.0; 64];
            for (_, idx) in &el {
                let v: [f64; 8] = std::array::from_fn(|k| phi[idx[k] as usize]);
                element_stiffness(&q1, w, &v, lat.h, &mut ke);
                for (a, &ia) in idx.iter().enumerate() {
                    m[ia as usize] += element_mass(w, &v, lat.h);
                    for (b, &ib) in idx.iter().enumerate() {
                        r.add(ia as usize, ib as usize, tau * ke[a * 8 + b])
                            .unwrap();
                    }
                }
            }
            for (i, mi) in m.iter().enumerate() {
                r.add(i, i, *mi).unwrap();
            }
            assert_eq!((&a.row_ptr, &a.col), (&r.row_ptr, &r.col));
            let scale = r.val.iter().fold(0.0f64, |s, v| s.max(v.abs()));
            for (x, y) in a.val.iter().zip(&r.val) {
                assert!((x - y).abs() <= 1e-12 * scale, "{x} {y}");
            }
            for (x, y) in mass.iter().zip(&m) {
                assert!((x - y).abs() <= 1e-14 * y.abs().max(1e-300), "{x} {y}");
            }
        }
        // Elements out of order are refused.
        let mut bad = el.clone();
        bad.swap(0, 1);
        assert!(assemble_scaled(&lat, &bad, n, &phi, Weight::Heat, 1.0, false).is_err());
    }
}
