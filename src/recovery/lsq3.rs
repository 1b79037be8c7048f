//! Least-squares gradient and Hessian recovery on tetrahedral meshes: the 3D form of the Taylor
//! fit of 004 §4.3. At vertex `i`, with `δ_j = (x_j - x_i) / h` over the patch (`h` the patch
//! radius), the nine coefficients `g`, `H` of
//!
//! ```text
//! u_j - u_i ≈ g·δ_j + ½ δ_jᵀ H δ_j
//! ```
//!
//! are fitted in the least-squares sense (value kept), by a singular value decomposition of the
//! scaled system, and rescaled to `∇u = g / h`, `D²u = H / h²`. The patch is the vertex's
//! neighbours, widened ring by ring until it holds [`MIN_PATCH`] vertices (boundary vertices
//! usually need the second ring). Exact for quadratic fields; for smooth fields the gradient is
//! second order and the Hessian first order on regular meshes.

use rayon::prelude::*;

use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::mesh::check_p1_field;
use crate::metric::Sym3;
use nalgebra::{DMatrix, DVector};

/// Smallest patch (vertices besides the centre) of a fit: 1.5 times the nine unknowns.
pub const MIN_PATCH: usize = 14;
/// Largest number of rings the patch grows to.
const MAX_RINGS: usize = 3;

/// Recovered gradient and Hessian at every vertex.
#[derive(Debug, Clone, PartialEq)]
pub struct Recovered3 {
    /// `∇u` per vertex.
    pub gradient: Vec<DVec3>,
    /// `D²u` per vertex.
    pub hessian: Vec<Sym3>,
}

/// Vertex adjacency (sorted neighbours) of the tetrahedra `cells` over `n` points.
fn adjacency(n: usize, cells: &[[u32; 4]]) -> Vec<Vec<u32>> {
    let mut nb: Vec<Vec<u32>> = vec![Vec::new(); n];
    for t in cells {
        for i in 0..4 {
            for j in 0..4 {
                if i != j {
                    nb[t[i] as usize].push(t[j]);
                }
            }
        }
    }
    nb.par_iter_mut().for_each(|l| {
        l.sort_unstable();
        l.dedup();
    });
    nb
}

/// The patch of `v`: its rings of neighbours until at least [`MIN_PATCH`] vertices.
fn patch(v: u32, nb: &[Vec<u32>]) -> Vec<u32> {
    let mut seen = vec![v];
    let mut front = vec![v];
    for _ in 0..MAX_RINGS {
        let mut next = Vec::new();
        for &f in &front {
            for &w in &nb[f as usize] {
                if !seen.contains(&w) {
                    seen.push(w);
                    next.push(w);
                }
            }
        }
        front = next;
        if seen.len() > MIN_PATCH || front.is_empty() {
            break;
        }
    }
    seen.remove(0);
    seen
}

fn fit(i: usize, points: &[DVec3], u: &[f64], p: &[u32]) -> Option<(DVec3, Sym3)> {
    if p.len() < 9 {
        return None;
    }
    let x0 = points[i];
    let h = p
        .iter()
        .map(|&j| (points[j as usize] - x0).length())
        .fold(0.0, f64::max);
    if h.is_nan() || h <= 0.0 {
        return None;
    }
    let mut a = DMatrix::<f64>::zeros(p.len(), 9);
    let mut b = DVector::<f64>::zeros(p.len());
    for (r, &j) in p.iter().enumerate() {
        let d = (points[j as usize] - x0) / h;
        let row = [
            d.x,
            d.y,
            d.z,
            0.5 * d.x * d.x,
            0.5 * d.y * d.y,
            0.5 * d.z * d.z,
            d.x * d.y,
            d.x * d.z,
            d.y * d.z,
        ];
        for (c, v) in row.iter().enumerate() {
            a[(r, c)] = *v;
        }
        b[r] = u[j as usize] - u[i];
    }
    let svd = a.svd(true, true);
    let smax = svd.singular_values.max();
    if svd.singular_values.min() <= 1e-10 * smax {
        return None;
    }
    let c = svd.solve(&b, 0.0).ok()?;
    let (h1, h2) = (h, h * h);
    Some((
        DVec3::new(c[0], c[1], c[2]) / h1,
        Sym3::new(
            c[3] / h2,
            c[6] / h2,
            c[7] / h2,
            c[4] / h2,
            c[8] / h2,
            c[5] / h2,
        ),
    ))
}

/// Least-squares gradient and Hessian of the P1 field `u` at every vertex of the tetrahedra
/// `cells` over `points` (module documentation). Runs in parallel; deterministic.
///
/// Errors: [`Error::InvalidField`] if `u` does not hold one finite value per point;
/// [`Error::InvalidInput`] for a cell vertex out of range or a vertex whose patch (after
/// three rings) cannot determine a quadratic (fewer than nine neighbours, or all of them
/// on a quadric through the vertex).
pub fn recover_ls3(points: &[DVec3], cells: &[[u32; 4]], u: &[f64]) -> Result<Recovered3> {
    check_p1_field(points.len(), u, "u")?;
    if let Some(c) = cells
        .iter()
        .position(|c| c.iter().any(|&v| v as usize >= points.len()))
    {
        return Err(Error::InvalidInput(format!(
            "tetrahedron {c} has a vertex index out of range ({} vertices)",
            points.len()
        )));
    }
    let nb = adjacency(points.len(), cells);
    let fits: Vec<Option<(DVec3, Sym3)>> = (0..points.len())
        .into_par_iter()
        .map(|i| fit(i, points, u, &patch(i as u32, &nb)))
        .collect();
    let mut out = Recovered3 {
        gradient: Vec::with_capacity(points.len()),
        hessian: Vec::with_capacity(points.len()),
    };
    for (i, f) in fits.into_iter().enumerate() {
        let (g, h) = f.ok_or_else(|| {
            Error::InvalidInput(format!(
                "3D recovery: the patch of vertex {i} cannot determine a quadratic (isolated or \
                 too few neighbours)"
            ))
        })?;
        out.gradient.push(g);
        out.hessian.push(h);
    }
    Ok(out)
}
