//! The mean curvature system `(M[Φ^k] + τ L[Φ^k]) x` of 000 (2.5) applied element by element in
//! `f64`, without an assembled matrix: the weighted lumped mass of 000 (2.6) and the stiffness
//! weighted by `|∇Φ^k|_ε⁻¹` at the `2 × 2 × 2` Gauss points of 000 (2.7).
//!
//! Setting it up computes, per element, the eight Gauss-point weights `τ h/8 · |∇Φ^k|_ε⁻¹` (64
//! bytes; the assembled matrix keeps about 27 entries of 12 bytes per band node), and per node
//! the lumped mass and the diagonal of `M + τ L` (for the preconditioner). A product gathers an
//! element's eight values, takes their reference gradients at the Gauss points by sum
//! factorisation, scales them by the weights and scatters the transposed sums back
//! ([`super::matfree`] does the same in `f32` storage with the weights recomputed each time).
//!
//! The nodes are split into ranges, and each range adds, in element order, the contributions of
//! the elements touching it to its own rows: every row is summed in the same order whatever the
//! number of threads, so the product does not depend on it. The product equals that of the
//! assembled matrix up to the order of summation (tested).

use super::fem::{element_mass, Element, Weight};
use super::matfree::{basis, gauss_gradients, scatter_fluxes};
use crate::error::{Error, Result};
use rayon::prelude::*;

/// `M[Φ^k] + τ L[Φ^k]` on the band elements, applied element by element.
pub struct ElementOperator {
    elems: Vec<Element>,
    /// Per element: `τ h/8 · |∇Φ^k|_ε⁻¹` at its Gauss points, index `qx + 2 qy + 4 qz`.
    weights: Vec<[f64; 8]>,
    /// Node ranges `[lo, hi)` with the elements `[first, last)` that touch them.
    ranges: Vec<(usize, usize, usize, usize)>,
    /// The weighted lumped mass per band node (000 (2.6)).
    pub mass: Vec<f64>,
    /// The diagonal of `M + τ L`.
    pub diag: Vec<f64>,
}

/// `|∇̂ψ_c(q)|²`: the squared reference gradient of the shape function of corner `c` at Gauss
/// point `q` (`qx + 2 qy + 4 qz`).
fn gradient_squares() -> [[f64; 8]; 8] {
    let b = basis();
    let mut t = [[0.0; 8]; 8];
    for (c, tc) in t.iter_mut().enumerate() {
        let (i, j, k) = (c & 1, (c >> 1) & 1, (c >> 2) & 1);
        for (q, tq) in tc.iter_mut().enumerate() {
            let (bx, by, bz) = (b[q & 1], b[(q >> 1) & 1], b[q >> 2]);
            let g = [by[j] * bz[k], bx[i] * bz[k], bx[i] * by[j]];
            *tq = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
        }
    }
    t
}

impl ElementOperator {
    /// The operator of the elements `elems` (see [`super::fem::elements`]; in storage order, corners among `n` nodes) for the
    /// field `phik`, grid spacing `h`, regularisation `eps` and time step `tau`.
    /// Error: [`Error::InvalidInput`] when `phik` does not have `n` values, an element refers to
    /// a node `≥ n`, or the elements are not in storage order.
    pub fn new(
        elems: Vec<Element>,
        n: usize,
        phik: &[f64],
        h: f64,
        eps: f64,
        tau: f64,
    ) -> Result<ElementOperator> {
        if phik.len() != n || n >= u32::MAX as usize {
            return Err(Error::InvalidInput(format!(
                "element operator: {n} nodes, {} values",
                phik.len()
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
        let b = basis();
        let scale = tau * h / 8.0;
        let weights: Vec<[f64; 8]> = elems
            .par_iter()
            .map(|(_, idx)| {
                let v: [f64; 8] = std::array::from_fn(|k| phik[idx[k] as usize]);
                let d = gauss_gradients(&b, &v);
                std::array::from_fn(|q| {
                    let (qx, qy, qz) = (q & 1, (q >> 1) & 1, q >> 2);
                    let g2 = (d[0][qy][qz] * d[0][qy][qz]
                        + d[1][qx][qz] * d[1][qx][qz]
                        + d[2][qx][qy] * d[2][qx][qy])
                        / (h * h);
                    scale / (eps * eps + g2).sqrt()
                })
            })
            .collect();
        let parts = 4 * rayon::current_num_threads();
        let step = n.div_ceil(parts).max(1);
        let ranges: Vec<(usize, usize, usize, usize)> = (0..n)
            .step_by(step)
            .map(|lo| {
                let hi = (lo + step).min(n);
                // Corner 0 is an element's smallest index, corner 7 its largest; both are
                // non-decreasing in storage order.
                let first = elems.partition_point(|e| (e.1[7] as usize) < lo);
                let last = elems.partition_point(|e| (e.1[0] as usize) < hi);
                (lo, hi, first, last.max(first))
            })
            .collect();
        let sq = gradient_squares();
        let w = Weight::Mcf { eps };
        let mut mass = vec![0.0; n];
        let mut diag = vec![0.0; n];
        let mut op = ElementOperator {
            elems,
            weights,
            ranges,
            mass: Vec::new(),
            diag: Vec::new(),
        };
        op.for_ranges2(&mut mass, &mut diag, |lo, hi, f, l, mass, diag| {
            for (e, wq) in op.elems[f..l].iter().zip(&op.weights[f..l]) {
                let v: [f64; 8] = std::array::from_fn(|k| phik[e.1[k] as usize]);
                let m = element_mass(w, &v, h);
                for (c, &i) in e.1.iter().enumerate() {
                    let i = i as usize;
                    if (lo..hi).contains(&i) {
                        let k: f64 = wq.iter().zip(&sq[c]).map(|(a, s)| a * s).sum();
                        mass[i - lo] += m;
                        diag[i - lo] += k;
                    }
                }
            }
        });
        diag.iter_mut().zip(&mass).for_each(|(d, m)| *d += m);
        op.mass = mass;
        op.diag = diag;
        Ok(op)
    }

    /// The band node count.
    pub fn len(&self) -> usize {
        self.mass.len()
    }

    /// Whether the band has no nodes.
    pub fn is_empty(&self) -> bool {
        self.mass.is_empty()
    }

    /// Calls `f(lo, hi, first, last, a, b)` for every node range with the range's parts of
    /// `a` and `b`, ranges in parallel.
    fn for_ranges2(
        &self,
        a: &mut [f64],
        b: &mut [f64],
        f: impl Fn(usize, usize, usize, usize, &mut [f64], &mut [f64]) + Sync,
    ) {
        let mut tasks = Vec::with_capacity(self.ranges.len());
        let (mut a, mut b) = (a, b);
        for &(lo, hi, first, last) in &self.ranges {
            let (pa, ra) = std::mem::take(&mut a).split_at_mut(hi - lo);
            let (pb, rb) = std::mem::take(&mut b).split_at_mut(hi - lo);
            (a, b) = (ra, rb);
            tasks.push((lo, hi, first, last, pa, pb));
        }
        tasks
            .into_par_iter()
            .for_each(|(lo, hi, first, last, pa, pb)| f(lo, hi, first, last, pa, pb));
    }

    /// `y = (M + τ L) x`, with `y` set to zero where `fixed` holds (the rows of Dirichlet
    /// nodes in CG, 000 (2.12)).
    /// Panics only if `x`, `y` or `fixed` does not have one entry per band node (a caller
    /// error).
    pub fn apply(&self, x: &[f64], y: &mut [f64], fixed: Option<&[bool]>) {
        let n = self.len();
        assert!(x.len() == n && y.len() == n && fixed.map_or(true, |f| f.len() == n));
        let b = basis();
        let mut tasks = Vec::with_capacity(self.ranges.len());
        let mut rest = y;
        for &(lo, hi, first, last) in &self.ranges {
            let (part, r) = std::mem::take(&mut rest).split_at_mut(hi - lo);
            rest = r;
            tasks.push((lo, hi, first, last, part));
        }
        tasks.into_par_iter().for_each(|(lo, hi, first, last, y)| {
            for ((y, x), m) in y.iter_mut().zip(&x[lo..hi]).zip(&self.mass[lo..hi]) {
                *y = m * x;
            }
            for (e, wq) in self.elems[first..last]
                .iter()
                .zip(&self.weights[first..last])
            {
                let u: [f64; 8] = std::array::from_fn(|k| x[e.1[k] as usize]);
                let d = gauss_gradients(&b, &u);
                let mut fl = [[[[0.0; 3]; 2]; 2]; 2];
                for (qx, fx) in fl.iter_mut().enumerate() {
                    for (qy, fxy) in fx.iter_mut().enumerate() {
                        for (qz, f) in fxy.iter_mut().enumerate() {
                            let w = wq[qx + 2 * qy + 4 * qz];
                            *f = [w * d[0][qy][qz], w * d[1][qx][qz], w * d[2][qx][qy]];
                        }
                    }
                }
                let mut r = [0.0; 8];
                scatter_fluxes(&b, &fl, &mut r);
                for (&i, rk) in e.1.iter().zip(r) {
                    let i = (i as usize).wrapping_sub(lo);
                    if i < hi - lo {
                        y[i] += rk;
                    }
                }
            }
            if let Some(fixed) = fixed {
                for (y, &f) in y.iter_mut().zip(&fixed[lo..hi]) {
                    if f {
                        *y = 0.0;
                    }
                }
            }
        });
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::fem::elements;
    use crate::backends::dtgrid::lattice::{band_around, crossing_cells_of_fn, Lattice};
    use crate::backends::dtgrid::lattice::{NarrowBand, C3};
    use crate::backends::dtgrid::stencil::assemble_scaled;
    use crate::backends::dtgrid::{Band, DtGrid};
    use crate::geom::DVec3;

    #[test]
    fn element_product_equals_the_assembled_matrix() {
        let lat = Lattice::unit(23).unwrap();
        let f = |p: DVec3| (p - DVec3::new(0.03, -0.02, 0.01)).length() - 0.29;
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<DtGrid<C3>> = band_around(&lat, &cross, 2).unwrap();
        let n = nb.band.len();
        // A field that is not a distance, with a flat spot (gradient below eps somewhere).
        let phi: Vec<f64> = nb
            .band
            .coords()
            .map(|c| f(lat.pos(c)) * (1.0 + 0.3 * lat.pos(c).x))
            .collect();
        let el = elements(&nb);
        let (eps, tau) = (1e-3, 0.37 * lat.h * lat.h);
        let (mass, a) =
            assemble_scaled(&lat, &el, n, &phi, Weight::Mcf { eps }, tau, true).unwrap();
        let op = ElementOperator::new(el.clone(), n, &phi, lat.h, eps, tau).unwrap();
        assert_eq!(op.mass, mass);
        let scale = a.val.iter().fold(0.0f64, |s, v| s.max(v.abs()));
        let d = a.diagonal();
        for (x, y) in op.diag.iter().zip(&d) {
            assert!((x - y).abs() <= 1e-13 * scale, "diagonal {x} {y}");
        }
        let x: Vec<f64> = (0..n)
            .map(|i| ((i * 7919) % 1000) as f64 / 500.0 - 1.0)
            .collect();
        let mut want = vec![0.0; n];
        a.matvec(&x, &mut want);
        let fixed: Vec<bool> = nb.interior.iter().map(|i| !i).collect();
        let mut got = vec![0.0; n];
        op.apply(&x, &mut got, Some(&fixed));
        let mut worst = 0.0f64;
        for ((g, w), &f) in got.iter().zip(&want).zip(&fixed) {
            if f {
                assert_eq!(*g, 0.0);
            } else {
                worst = worst.max((g - w).abs());
            }
        }
        assert!(worst <= 1e-12 * scale, "{worst} against {scale}");
        // The same on one thread and on three (other ranges, the same sums).
        let one = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .unwrap();
        let three = rayon::ThreadPoolBuilder::new()
            .num_threads(3)
            .build()
            .unwrap();
        let run = |pool: &rayon::ThreadPool| {
            pool.install(|| {
                let op = ElementOperator::new(el.clone(), n, &phi, lat.h, eps, tau).unwrap();
                let mut y = vec![0.0; n];
                op.apply(&x, &mut y, None);
                (y, op.diag.clone())
            })
        };
        assert_eq!(run(&one), run(&three));
        // Bad input is refused.
        assert!(ElementOperator::new(el.clone(), n, &phi[1..], lat.h, eps, tau).is_err());
        let mut bad = el.clone();
        bad.swap(0, 1);
        assert!(ElementOperator::new(bad, n, &phi, lat.h, eps, tau).is_err());
    }
}
