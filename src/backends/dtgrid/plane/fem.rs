//! Q1 finite elements on a planar band (000 §2): the elements are the cells with an interior
//! corner (all four corners are then band nodes), the weighted lumped mass and stiffness of
//! the heat equation on the zero level (000 §2.1: mass `I_h⁰(|∇Φ|)`, stiffness `|∇Φ| P[Φ]`,
//! `P = I − n ⊗ n`) or of mean curvature motion (000 (2.6)–(2.7): `I_h⁰(|∇Φ|_ε⁻¹)` and
//! `|∇Φ|_ε⁻¹`, `|x|_ε = √(ε² + |x|²)`), with the Q1 element of [`crate::fem::q1`] (2 × 2 Gauss
//! points), assembled into CSR over the band nodes as [`BandMatrices`]; and the transparent
//! boundary vector `Γ` of 000 (2.9), (2.11) over the band's boundary edges.
//!
//! Element matrices are computed in parallel and added in element order, so the matrices do
//! not depend on the number of threads.

use super::{Grid2, Plane, C2};
use crate::backends::dtgrid::band::Band;
use crate::backends::dtgrid::fem::{BandMatrices, Weight};
use crate::backends::dtgrid::lattice::NarrowBand;
use crate::error::Result;
use crate::fem::q1::{shape, shape_grad, Q1};
use crate::fem::Csr;
use rayon::prelude::*;

/// One element: its lowest corner and the band indices of its 4 corners.
pub type Element = (C2, [u32; 4]);

/// The elements of the band: the cells with an interior corner, in lexicographic order.
pub fn elements(nb: &NarrowBand<Grid2>) -> Vec<Element> {
    nb.band
        .cells()
        .filter(|(_, idx)| idx.iter().any(|&i| nb.interior[i as usize]))
        .collect()
}

/// The scalar weight of the mass for the gradient `g` of `Φ`: `|g|` (heat) or `|g|_ε⁻¹`.
#[inline]
fn mass_weight(w: Weight, g: [f64; 3]) -> f64 {
    let len2 = g[0] * g[0] + g[1] * g[1];
    match w {
        Weight::Heat => len2.sqrt(),
        Weight::Mcf { eps } => 1.0 / (eps * eps + len2).sqrt(),
    }
}

/// The stiffness coefficient for the gradient `g` of `Φ` (leading `2 × 2` block): `|g| P`
/// (heat) or `|g|_ε⁻¹ I`.
fn tensor(w: Weight, g: [f64; 3]) -> [[f64; 3]; 3] {
    match w {
        Weight::Heat => {
            let len = (g[0] * g[0] + g[1] * g[1]).sqrt();
            let mut a = [[0.0; 3]; 3];
            for r in 0..2 {
                for s in 0..2 {
                    let id = if r == s { len } else { 0.0 };
                    a[r][s] = id - if len > 0.0 { g[r] * g[s] / len } else { 0.0 };
                }
            }
            a
        }
        Weight::Mcf { .. } => {
            let m = mass_weight(w, g);
            [[m, 0.0, 0.0], [0.0, m, 0.0], [0.0; 3]]
        }
    }
}

/// The gradient of the Q1 function with corner values `v` at reference point `xi`.
fn grad_at(v: &[f64; 4], xi: &[f64; 2], h: f64) -> [f64; 3] {
    let mut g = [0.0; 3];
    for (k, vk) in v.iter().enumerate() {
        let gk = shape_grad(2, k, xi);
        g[0] += vk * gk[0] / h;
        g[1] += vk * gk[1] / h;
    }
    g
}

/// The lumped mass and stiffness over `n` band nodes with the weights of `w` computed from the
/// band field `phi` (the mass weight at each cell's centre).
/// Error: when an element refers to a node `≥ n`.
pub fn assemble(
    plane: &Plane,
    elems: &[Element],
    n: usize,
    phi: &[f64],
    w: Weight,
) -> Result<BandMatrices> {
    let q1 = Q1::new(2, 2)?;
    let h = plane.h;
    let local: Vec<(f64, [f64; 16])> = elems
        .par_iter()
        .map(|(_, idx)| {
            let v: [f64; 4] = idx.map(|i| phi[i as usize]);
            let mut ke = [0.0; 16];
            match w {
                Weight::Mcf { .. } => {
                    q1.stiffness(h, |q| mass_weight(w, q1.gradient(q, h, &v)), &mut ke)
                }
                Weight::Heat => {
                    q1.stiffness_tensor(h, |q| tensor(w, q1.gradient(q, h, &v)), &mut ke)
                }
            }
            let mw = mass_weight(w, grad_at(&v, &[0.5; 2], h)) * q1.lumped_mass(h);
            (mw, ke)
        })
        .collect();
    let mut stiff = Csr::from_element_iter(n, elems.iter().map(|(_, idx)| &idx[..]))?;
    let mut mass = vec![0.0; n];
    for ((_, idx), (mw, ke)) in elems.iter().zip(&local) {
        for (a, &ia) in idx.iter().enumerate() {
            mass[ia as usize] += mw;
            for (b, &ib) in idx.iter().enumerate() {
                stiff.add(ia as usize, ib as usize, ke[a * 4 + b])?;
            }
        }
    }
    Ok(BandMatrices { mass, stiff })
}

/// The transparent boundary vector `Γ_i = ∫_{∂Ω_n} A[Φ] ∇U · ν ψ_i ds` of 000 (2.9) (heat) and
/// 000 (2.11) (mean curvature motion) over the edges of the element set that no other element
/// shares (2 Gauss points per edge), `A[Φ]` the stiffness coefficient of `w`, `U` the band
/// field `u` (`U_approx`, the last step's solution).
pub fn transparent_vector(
    plane: &Plane,
    elems: &[Element],
    n: usize,
    phi: &[f64],
    u: &[f64],
    w: Weight,
) -> Vec<f64> {
    let h = plane.h;
    let g = 0.5 / 3f64.sqrt();
    let gp = [0.5 - g, 0.5 + g];
    let is_element = |c: C2| elems.binary_search_by(|e| e.0.cmp(&c)).is_ok();
    let contributions: Vec<Vec<(u32, f64)>> = elems
        .par_iter()
        .map(|(c, idx)| {
            let mut out = Vec::new();
            let v: [f64; 4] = idx.map(|i| phi[i as usize]);
            let uu: [f64; 4] = idx.map(|i| u[i as usize]);
            for axis in 0..2 {
                for side in 0..2 {
                    let mut nb = *c;
                    nb[axis] += if side == 1 { 1 } else { -1 };
                    if is_element(nb) {
                        continue;
                    }
                    let sign = if side == 1 { 1.0 } else { -1.0 };
                    let mut acc = [0.0; 4];
                    for &s in &gp {
                        let mut xi = [s; 2];
                        xi[axis] = side as f64;
                        let a = tensor(w, grad_at(&v, &xi, h));
                        let gu = grad_at(&uu, &xi, h);
                        let flux = sign * (a[axis][0] * gu[0] + a[axis][1] * gu[1]);
                        for (k, acck) in acc.iter_mut().enumerate() {
                            *acck += 0.5 * h * flux * shape(2, k, &xi);
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
    use crate::backends::dtgrid::plane::lattice::{band_around, crossing_cells_of_fn};
    use crate::geom::DVec2;

    #[test]
    fn band_matrices_of_a_circle() {
        let plane = Plane::new(33, 1.0 / 32.0).unwrap();
        let f = |p: DVec2| (p - DVec2::splat(0.5)).length() - 0.3;
        let nb = band_around(&plane, &crossing_cells_of_fn(&plane, &f).unwrap(), 2).unwrap();
        let n = nb.band.len();
        let phi: Vec<f64> = nb.band.coords().map(|c| f(plane.pos(c))).collect();
        let el = elements(&nb);
        let m = assemble(&plane, &el, n, &phi, Weight::Mcf { eps: 1e-3 }).unwrap();
        for s in m.stiff.row_sums() {
            assert!(s.abs() < 1e-12);
        }
        // |∇Φ| = 1: the mass is the area of the elements, the stiffness the Laplacian's.
        let area = el.len() as f64 * plane.h * plane.h;
        let total: f64 = m.mass.iter().sum();
        assert!((total / area - 1.0).abs() < 0.01, "{total} {area}");
        let x: Vec<f64> = nb.band.coords().map(|c| plane.pos(c).x).collect();
        let energy: f64 = m.stiff.mul(&x).iter().zip(&x).map(|(a, b)| a * b).sum();
        assert!((energy / area - 1.0).abs() < 0.01);
    }

    #[test]
    fn transparent_vector_is_greens_formula_for_linear_fields() {
        // For a linear u and a constant coefficient, L u = Γ[u] node by node (Green's formula
        // on the element set: the interior edges cancel).
        let plane = Plane::new(33, 1.0 / 32.0).unwrap();
        let f = |p: DVec2| (p - DVec2::new(0.47, 0.52)).length() - 0.27;
        let nb = band_around(&plane, &crossing_cells_of_fn(&plane, &f).unwrap(), 2).unwrap();
        let n = nb.band.len();
        let el = elements(&nb);
        let u: Vec<f64> = nb
            .band
            .coords()
            .map(|c| {
                let p = plane.pos(c);
                3.0 * p.x - 2.0 * p.y
            })
            .collect();
        // |∇Φ| = 1 exactly for a plane Φ: the heat tensor is P = I − n ⊗ n, constant.
        let flat: Vec<f64> = nb
            .band
            .coords()
            .map(|c| {
                let p = plane.pos(c);
                0.6 * p.x + 0.8 * p.y
            })
            .collect();
        for (phi, w) in [(&flat, Weight::Heat), (&u, Weight::Mcf { eps: 1e8 })] {
            let m = assemble(&plane, &el, n, phi, w).unwrap();
            let lu = m.stiff.mul(&u);
            let gamma = transparent_vector(&plane, &el, n, phi, &u, w);
            let scale = lu.iter().map(|x| x.abs()).fold(0.0, f64::max);
            assert!(scale > 0.0);
            for (a, b) in lu.iter().zip(&gamma) {
                assert!((a - b).abs() <= 1e-10 * scale, "{a} {b}");
            }
        }
    }
}
