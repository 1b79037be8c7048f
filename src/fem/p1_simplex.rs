//! Continuous P1 elements on simplices of any dimension (triangles over `DVec2`, tetrahedra over
//! `DVec3`), given as points and cells `[u32; D + 1]`: the weighted lumped mass, the stiffness
//! with a constant coefficient per cell, and the cell gradients of a P1 field. These are the
//! matrices of the semi-implicit level-set mean curvature scheme of 000 eq. (2.4)–(2.7) on an
//! unstructured simplicial mesh; [`super::p1`] has the richer triangle-only layer.
//!
//! Each cell contributes `w_c |c| / (D + 1)` to the lumped mass of its corners and
//! `w_c |c| ∇λ_i · ∇λ_j` to the stiffness, with `λ_i` the barycentric coordinates
//! ([`crate::geom::simplex::p1_gradients`]). Assembly is element by element in parallel and
//! scattered in cell order ([`super::assembly`]), so the result does not depend on the number of
//! threads.

use super::assembly::{assemble_matrix, assemble_vector};
use super::csr::Csr;
use crate::error::{Error, Result};
use crate::geom::simplex::{p1_gradients, volume, Point};
use crate::mesh::check_p1_field;
use rayon::prelude::*;

/// The corners of cell `c`.
#[inline]
fn corners<const D: usize, const N: usize, P: Point<D>>(points: &[P], c: &[u32; N]) -> [P; N] {
    c.map(|v| points[v as usize])
}

/// Checks that every cell refers to existing points and has positive volume (every P1
/// computation needs it). Errors name the first bad cell.
pub fn check_cells<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: &[[u32; N]],
) -> Result<()> {
    for (t, c) in cells.iter().enumerate() {
        if let Some(&v) = c.iter().find(|&&v| v as usize >= points.len()) {
            return Err(Error::InvalidInput(format!(
                "cell {t} refers to vertex {v}, but there are {} points",
                points.len()
            )));
        }
        let vol = volume(&corners(points, c));
        if vol.is_nan() || vol <= 0.0 {
            return Err(Error::InvalidInput(format!(
                "cell {t} has volume {vol:e} (need a positive volume)"
            )));
        }
    }
    Ok(())
}

fn check_weights(name: &str, w: &[f64], n_cells: usize) -> Result<()> {
    if w.len() != n_cells || w.iter().any(|x| !x.is_finite()) {
        return Err(Error::InvalidField {
            name: name.into(),
            msg: format!(
                "{} values for {n_cells} cells (need one finite value per cell)",
                w.len()
            ),
        });
    }
    Ok(())
}

/// The pattern (values zero) of the P1 vertex–vertex coupling of `cells` over `n` points.
pub fn pattern<const N: usize>(n: usize, cells: &[[u32; N]]) -> Result<Csr> {
    Csr::from_elements(n, cells)
}

/// The lumped mass `m_i = Σ_{c ∋ i} w_c |c| / (D + 1)` (`w_c = 1` when `weights` is `None`).
/// Errors: bad cells, a weight count other than one per cell.
pub fn lumped_mass<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: &[[u32; N]],
    weights: Option<&[f64]>,
) -> Result<Vec<f64>> {
    check_cells(points, cells)?;
    if let Some(w) = weights {
        check_weights("mass weights", w, cells.len())?;
    }
    let mut m = vec![0.0; points.len()];
    assemble_vector(&mut m, cells, |e| {
        let w = weights.map_or(1.0, |w| w[e]);
        [w * volume(&corners(points, &cells[e])) / N as f64; N]
    })?;
    Ok(m)
}

/// Adds the stiffness `∫ w ∇φ_j · ∇φ_i` with `w = weights[c]` on cell `c` to `a` (whose pattern
/// must contain [`pattern`]). Errors: bad cells, a weight count other than one per cell, a
/// pattern without the couplings.
pub fn add_stiffness<const D: usize, const N: usize, P: Point<D>>(
    a: &mut Csr,
    points: &[P],
    cells: &[[u32; N]],
    weights: &[f64],
) -> Result<()> {
    check_cells(points, cells)?;
    check_weights("stiffness weights", weights, cells.len())?;
    assemble_matrix(a, cells, |e| {
        let p = corners(points, &cells[e]);
        let g = p1_gradients(&p);
        let s = weights[e] * volume(&p);
        let mut k = [[0.0; N]; N];
        for i in 0..N {
            for j in i..N {
                k[i][j] = s * g[i].dot(g[j]);
                k[j][i] = k[i][j];
            }
        }
        k
    })
}

/// The (constant) gradient of the P1 field `u` on each cell. Errors: bad cells, a field without
/// one finite value per point.
pub fn cell_gradients<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: &[[u32; N]],
    u: &[f64],
) -> Result<Vec<P>> {
    check_cells(points, cells)?;
    check_p1_field(points.len(), u, "P1 field")?;
    Ok(cells
        .par_iter()
        .map(|c| {
            let g = p1_gradients(&corners(points, c));
            let mut out = P::ZERO;
            for i in 0..N {
                out += g[i] * u[c[i] as usize];
            }
            out
        })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::fem::p1;
    use crate::geom::{DVec2, DVec3};
    use crate::mesh::Mesh2;
    use crate::mesh3::Mesh3;

    /// On triangles the generic layer gives the matrices of the triangle layer.
    #[test]
    fn triangles_match_the_triangle_layer() {
        let mesh = Mesh2::rectangle(
            DVec2::ZERO,
            DVec2::new(1.0, 2.0),
            5,
            7,
            crate::mesh::GridPattern::UnionJack,
        )
        .unwrap();
        let cells: Vec<[u32; 3]> = mesh.live_tris().map(|t| mesh.tris[t]).collect();
        let w: Vec<f64> = (0..cells.len()).map(|c| 1.0 + 0.1 * c as f64).collect();
        let mut a = pattern(mesh.n_points(), &cells).unwrap();
        add_stiffness(&mut a, &mesh.points, &cells, &w).unwrap();
        let wt: Vec<f64> = {
            let mut v = vec![0.0; mesh.n_tris()];
            for (k, t) in mesh.live_tris().enumerate() {
                v[t] = w[k];
            }
            v
        };
        let b = p1::stiffness(&mesh, &p1::Coef::PerElement(&wt)).unwrap();
        for i in 0..a.n {
            for j in 0..a.n {
                assert!((a.get(i, j) - b.get(i, j)).abs() < 1e-12);
            }
        }
        let m = lumped_mass(&mesh.points, &cells, None).unwrap();
        let m1 = p1::lumped_mass(&mesh).unwrap();
        assert!(m.iter().zip(&m1).all(|(x, y)| (x - y).abs() < 1e-14));
    }

    /// On tetrahedra: the lumped mass sums to the volume, the stiffness annihilates constants
    /// and reproduces `∫ |∇u|² = |Ω|` for an affine `u` with a unit gradient, and the cell
    /// gradients of an affine field are exact; bad input is a typed error.
    #[test]
    fn tetrahedra_mass_stiffness_gradients() {
        let m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::new(1.0, 2.0, 0.5), [3, 4, 2]).unwrap();
        let w = vec![2.0; m.n_tets()];
        let mass = lumped_mass(&m.points, &m.tets, Some(&w)).unwrap();
        assert!((mass.iter().sum::<f64>() - 2.0).abs() < 1e-12);
        let mut a = pattern(m.n_points(), &m.tets).unwrap();
        add_stiffness(&mut a, &m.points, &m.tets, &vec![1.0; m.n_tets()]).unwrap();
        let ones = vec![1.0; m.n_points()];
        assert!(a.mul(&ones).iter().all(|v| v.abs() < 1e-12));
        let n = DVec3::new(1.0, 2.0, 2.0) / 3.0;
        let u: Vec<f64> = m.points.iter().map(|p| n.dot(*p) + 0.3).collect();
        let au = a.mul(&u);
        let energy: f64 = u.iter().zip(&au).map(|(x, y)| x * y).sum();
        assert!((energy - 1.0).abs() < 1e-12, "{energy}");
        let g = cell_gradients(&m.points, &m.tets, &u).unwrap();
        assert!(g.iter().all(|g| (*g - n).length() < 1e-12));
        assert!(lumped_mass(&m.points, &m.tets, Some(&w[1..])).is_err());
        let mut flat = m.tets.clone();
        flat[0].swap(0, 1);
        assert!(lumped_mass(&m.points, &flat, None).is_err());
        flat[0][0] = 10_000;
        assert!(cell_gradients(&m.points, &flat, &u).is_err());
    }
}
