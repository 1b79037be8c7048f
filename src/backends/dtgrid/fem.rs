//! Q1 finite elements on a narrow band (000 §2): the elements are the cells touching an interior
//! node (the cells of `Ω_n^j`, all of whose corners are band nodes), the weighted lumped mass and
//! stiffness of the surface heat equation (000 §2.1, weight `|∇Φ|`, tangential projection
//! `P[Φ] = I − n ⊗ n`) and of mean curvature motion (000 (2.6)–(2.7), weight `|∇Φ|_ε⁻¹`),
//! assembled into CSR over the band nodes, and the transparent boundary vector `Γ` of 000 (2.9)
//! (boundary faces of the element set, 2 × 2 Gauss points per face).
//!
//! Element matrices are computed in parallel and added in element order, so the matrices do
//! not depend on the number of threads.

use super::band::Band;
use super::lattice::{Lattice, NarrowBand, C3};
use crate::error::Result;
use crate::fem::q1::{shape, shape_grad, Q1};
use crate::fem::Csr;
use rayon::prelude::*;

/// One element: its lowest corner and the band indices of its 8 corners.
pub type Element = (C3, [u32; 8]);

/// Which problem's weights the band matrices carry.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Weight {
    /// The surface heat equation: mass `I_h⁰(|∇Φ|)`, stiffness `|∇Φ| P[Φ]` (000 §2.1).
    Heat,
    /// Mean curvature motion: mass `I_h⁰(|∇Φ|_ε⁻¹)`, stiffness `|∇Φ|_ε⁻¹`
    /// (000 (2.6)–(2.7)), `|x|_ε = √(ε² + |x|²)`.
    Mcf {
        /// The regularisation `ε`.
        eps: f64,
    },
}

impl Weight {
    /// The coefficient tensor of the stiffness for the gradient `g` of `Φ`.
    fn tensor(self, g: [f64; 3]) -> [[f64; 3]; 3] {
        let len2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
        match self {
            Weight::Heat => {
                let len = len2.sqrt();
                let mut a = [[0.0; 3]; 3];
                for (r, ar) in a.iter_mut().enumerate() {
                    for (s, ars) in ar.iter_mut().enumerate() {
                        let id = if r == s { len } else { 0.0 };
                        *ars = id - if len > 0.0 { g[r] * g[s] / len } else { 0.0 };
                    }
                }
                a
            }
            Weight::Mcf { eps } => {
                let w = 1.0 / (eps * eps + len2).sqrt();
                [[w, 0.0, 0.0], [0.0, w, 0.0], [0.0, 0.0, w]]
            }
        }
    }

    /// The mass weight for the gradient `g` of `Φ` at a cell's centre.
    fn mass(self, g: [f64; 3]) -> f64 {
        let len2 = g[0] * g[0] + g[1] * g[1] + g[2] * g[2];
        match self {
            Weight::Heat => len2.sqrt(),
            Weight::Mcf { eps } => 1.0 / (eps * eps + len2).sqrt(),
        }
    }
}

/// The elements of the band: the cells touching an interior node, in lexicographic order.
pub fn elements<B: Band<Coord = C3>>(nb: &NarrowBand<B>) -> Vec<Element> {
    nb.band
        .cells()
        .filter(|(_, idx)| idx.iter().any(|&i| nb.interior[i as usize]))
        .collect()
}

/// The gradient of the Q1 function with corner values `v` at reference point `xi`.
fn grad_at(v: &[f64; 8], xi: &[f64], h: f64) -> [f64; 3] {
    let mut g = [0.0; 3];
    for (k, vk) in v.iter().enumerate() {
        let gk = shape_grad(3, k, xi);
        for a in 0..3 {
            g[a] += vk * gk[a] / h;
        }
    }
    g
}

/// The band matrices of one problem: the lumped mass (a vector over band nodes) and the
/// stiffness.
#[derive(Debug, Clone)]
pub struct BandMatrices {
    /// The weighted lumped mass per band node.
    pub mass: Vec<f64>,
    /// The weighted stiffness.
    pub stiff: Csr,
}

/// Assembles the lumped mass and the stiffness over `n` band nodes with the weights of `w`
/// computed from the band field `phi`.
/// Error: only when an element refers to a node `≥ n`.
pub fn assemble(
    lat: &Lattice,
    elems: &[Element],
    n: usize,
    phi: &[f64],
    w: Weight,
) -> Result<BandMatrices> {
    let (mass, stiff) = super::stencil::assemble_scaled(lat, elems, n, phi, w, 1.0, false)?;
    Ok(BandMatrices { mass, stiff })
}

/// The weighted lumped mass of the cell with corner values `v` (000 (2.6): the weight at the
/// cell's centre).
pub(crate) fn element_mass(w: Weight, v: &[f64; 8], h: f64) -> f64 {
    // The shape gradients at the centre are `±¼` (a table, the same sums as `grad_at`).
    const CENTRE: [[f64; 3]; 8] = {
        let mut t = [[0.0; 3]; 8];
        let mut k = 0;
        while k < 8 {
            let mut a = 0;
            while a < 3 {
                t[k][a] = if (k >> a) & 1 == 1 { 0.25 } else { -0.25 };
                a += 1;
            }
            k += 1;
        }
        t
    };
    let mut g = [0.0; 3];
    for (vk, gk) in v.iter().zip(&CENTRE) {
        for a in 0..3 {
            g[a] += vk * gk[a] / h;
        }
    }
    w.mass(g) * h * h * h / 8.0
}

/// The element stiffness of the cell with corner values `v` (2 × 2 × 2 Gauss points), row-major.
pub(crate) fn element_stiffness(q1: &Q1, w: Weight, v: &[f64; 8], h: f64, ke: &mut [f64; 64]) {
    match w {
        Weight::Mcf { .. } => q1.stiffness(h, |q| w.mass(q1.gradient(q, h, v)), &mut ke[..]),
        Weight::Heat => q1.stiffness_tensor(h, |q| w.tensor(q1.gradient(q, h, v)), &mut ke[..]),
    }
}

/// The transparent boundary vector `Γ_j = ∫_{∂Ω_n} A[Φ] ∇U · ν Θ_j da` of 000 (2.9) (heat) and
/// of 000 (2.11) (mean curvature motion) over the faces of the element set that no other element
/// shares, with `A[Φ]` the stiffness coefficient of `w` and `U` the band field `u`.
pub fn transparent_vector(
    lat: &Lattice,
    elems: &[Element],
    n: usize,
    phi: &[f64],
    u: &[f64],
    w: Weight,
) -> Vec<f64> {
    let h = lat.h;
    let g = 0.5 / 3f64.sqrt();
    let gp = [0.5 - g, 0.5 + g];
    let is_element = |c: C3| elems.binary_search_by(|e| e.0.cmp(&c)).is_ok();
    let contributions: Vec<Vec<(u32, f64)>> = elems
        .par_iter()
        .map(|(c, idx)| {
            let mut out = Vec::new();
            let v: [f64; 8] = std::array::from_fn(|k| phi[idx[k] as usize]);
            let uu: [f64; 8] = std::array::from_fn(|k| u[idx[k] as usize]);
            for axis in 0..3 {
                for side in 0..2 {
                    let mut nb = *c;
                    nb[axis] += if side == 1 { 1 } else { -1 };
                    if is_element(nb) {
                        continue;
                    }
                    let sign = if side == 1 { 1.0 } else { -1.0 };
                    let (b, cc) = ((axis + 1) % 3, (axis + 2) % 3);
                    let mut acc = [0.0; 8];
                    for &s in &gp {
                        for &t in &gp {
                            let mut xi = [0.0; 3];
                            xi[axis] = side as f64;
                            xi[b] = s;
                            xi[cc] = t;
                            let a = w.tensor(grad_at(&v, &xi, h));
                            let gu = grad_at(&uu, &xi, h);
                            let flux = sign
                                * (a[axis][0] * gu[0] + a[axis][1] * gu[1] + a[axis][2] * gu[2]);
                            for (k, acck) in acc.iter_mut().enumerate() {
                                *acck += 0.25 * h * h * flux * shape(3, k, &xi);
                            }
                        }
                    }
                    for (k, &ak) in acc.iter().enumerate() {
                        if ak != 0.0 {
                            out.push((idx[k], ak));
                        }
                    }
                }
            }
            out
        })
        .collect();
    let mut gamma = vec![0.0; n];
    for list in contributions {
        for (i, v) in list {
            gamma[i as usize] += v;
        }
    }
    gamma
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::backends::dtgrid::lattice::{band_around, crossing_cells_of_fn};
    use crate::backends::dtgrid::SortedBand;
    use crate::geom::DVec3;

    #[test]
    fn tabulated_centre_mass_is_the_shape_gradient_mass() {
        // Bit for bit the weight of the gradient from the shape functions at the centre.
        let h = 1.0 / 96.0;
        for s in 0..50u32 {
            let v: [f64; 8] = std::array::from_fn(|k| ((s * 8 + k as u32) as f64 * 0.7).sin() * h);
            for w in [Weight::Mcf { eps: 1e-3 }, Weight::Heat] {
                let reference = w.mass(grad_at(&v, &[0.5; 3], h)) * h * h * h / 8.0;
                assert_eq!(element_mass(w, &v, h).to_bits(), reference.to_bits());
            }
        }
    }

    #[test]
    fn band_matrices_and_the_divergence_theorem() {
        let lat = Lattice::unit(17).unwrap();
        let f = |p: DVec3| p.length() - 0.3;
        let cross = crossing_cells_of_fn(&lat, &f).unwrap();
        let nb: NarrowBand<SortedBand<C3>> = band_around(&lat, &cross, 2).unwrap();
        let n = nb.band.len();
        let phi: Vec<f64> = nb.band.coords().map(|c| f(lat.pos(c))).collect();
        let el = elements(&nb);
        let w = Weight::Mcf { eps: 1e-3 };
        let m = assemble(&lat, &el, n, &phi, w).unwrap();
        // Stiffness rows sum to zero; the mass is the element volume weighted by ≈ 1.
        for s in m.stiff.row_sums() {
            assert!(s.abs() < 1e-12);
        }
        let vol = el.len() as f64 * lat.h.powi(3);
        let total: f64 = m.mass.iter().sum();
        assert!((total / vol - 1.0).abs() < 0.05, "{total} {vol}");
        // For linear u, L u = Γ[u] (Green's formula with constant ∇u, weight ≈ constant): check
        // with the weight 1 (eps huge makes it ≈ 1/eps uniformly).
        let w1 = Weight::Mcf { eps: 1e8 };
        let m1 = assemble(&lat, &el, n, &phi, w1).unwrap();
        let u: Vec<f64> = nb
            .band
            .coords()
            .map(|c| {
                let p = lat.pos(c);
                p.x + 2.0 * p.y - p.z
            })
            .collect();
        let lu = m1.stiff.mul(&u);
        let gamma = transparent_vector(&lat, &el, n, &phi, &u, w1);
        for (a, b) in lu.iter().zip(&gamma) {
            assert!((a - b).abs() < 1e-9 * 1e-8, "{a} {b}");
        }
    }
}
