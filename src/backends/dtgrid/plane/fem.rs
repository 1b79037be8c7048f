//! Q1 finite elements on a planar band (000 §2): the elements are the cells with an interior
//! corner (all four corners are then band nodes), the lumped mass `I_h⁰(|∇Φ|_ε⁻¹)` and the
//! stiffness weighted by `|∇Φ|_ε⁻¹` of mean curvature motion (000 (2.6)–(2.7),
//! `|x|_ε = √(ε² + |x|²)`), with the Q1 element of [`crate::fem::q1`] (2 × 2 Gauss points),
//! assembled into CSR over the band nodes as [`BandMatrices`].
//!
//! Element matrices are computed in parallel and added in element order, so the matrices do
//! not depend on the number of threads.

use super::{Grid2, Plane, C2};
use crate::backends::dtgrid::band::Band;
use crate::backends::dtgrid::fem::BandMatrices;
use crate::backends::dtgrid::lattice::NarrowBand;
use crate::error::Result;
use crate::fem::q1::Q1;
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

/// The weight `|g|_ε⁻¹ = 1/√(ε² + |g|²)`.
#[inline]
fn weight(g: [f64; 3], eps: f64) -> f64 {
    1.0 / (eps * eps + g[0] * g[0] + g[1] * g[1]).sqrt()
}

/// The lumped mass and stiffness of mean curvature motion over `n` band nodes with the weights
/// `|∇Φ|_ε⁻¹` of the band field `phi` (000 (2.6)–(2.7)).
/// Error: when an element refers to a node `≥ n`.
pub fn assemble(
    plane: &Plane,
    elems: &[Element],
    n: usize,
    phi: &[f64],
    eps: f64,
) -> Result<BandMatrices> {
    let q1 = Q1::new(2, 2)?;
    let centre = Q1::new(2, 1)?;
    let h = plane.h;
    let local: Vec<(f64, [f64; 16])> = elems
        .par_iter()
        .map(|(_, idx)| {
            let v: [f64; 4] = idx.map(|i| phi[i as usize]);
            let mut ke = [0.0; 16];
            q1.stiffness(h, |q| weight(q1.gradient(q, h, &v), eps), &mut ke);
            let mw = weight(centre.gradient(0, h, &v), eps) * q1.lumped_mass(h);
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
        let m = assemble(&plane, &el, n, &phi, 1e-3).unwrap();
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
}
