//! Hessian by double lumped L2 projection (the "dual L2 projection" alternative of 004 §4.3).
//!
//! 1. The piecewise-constant gradient `grad u_h` is projected onto P1 with the lumped mass matrix:
//!    at vertex `v`, `g(v) = sum_{T ni v} |T| grad u_h|_T / sum_{T ni v} |T|` (the lumped mass of
//!    `v` is `sum |T| / 3`, the load `sum |T| grad u_h|_T / 3`).
//! 2. The same projection is applied to the piecewise-constant gradients of both components of
//!    `g`, giving a (non-symmetric) Jacobian `J(v)`; the Hessian is `(J + J^T) / 2`.
//!
//! Exact (zero) for linear fields at every vertex. For smooth fields it is consistent in the
//! interior of structured meshes but, unlike the least-squares fit, not exact for quadratics on
//! general meshes and only first-order (or worse) on boundary vertices.

use super::input;
use crate::error::Result;
use crate::geom::DVec2;
use crate::mesh::{Mesh2, NONE};
use crate::metric::Sym2;
use rayon::prelude::*;

/// Gradient of the linear interpolant of `f` on triangle `t` (zero for a tombstone).
#[inline]
fn tri_gradient(mesh: &Mesh2, t: usize, f: impl Fn(usize) -> f64) -> DVec2 {
    if mesh.is_deleted(t) {
        return DVec2::ZERO;
    }
    let [a, b, c] = mesh.tris[t].map(|v| v as usize);
    let [pa, pb, pc] = [mesh.points[a], mesh.points[b], mesh.points[c]];
    let two_area = (pb - pa).perp_dot(pc - pa);
    // grad lambda_i = perp(opposite edge) / (2|T|), counter-clockwise.
    let grad = |p: DVec2, q: DVec2| DVec2::new(p.y - q.y, q.x - p.x);
    (f(a) * grad(pb, pc) + f(b) * grad(pc, pa) + f(c) * grad(pa, pb)) / two_area
}

/// Area-weighted average at vertex `v` of the per-triangle values `per_tri` (the lumped L2
/// projection onto P1). Zero for an unreferenced vertex.
#[inline]
fn lumped_average<T>(mesh: &Mesh2, areas: &[f64], per_tri: &[T], v: u32) -> T
where
    T: Copy + Default + std::ops::Add<Output = T> + std::ops::Mul<f64, Output = T>,
{
    let (mut sum, mut weight) = (T::default(), 0.0);
    if mesh.vert_tri[v as usize] != NONE {
        mesh.for_each_fan_triangle(v, |t| {
            sum = sum + per_tri[t as usize] * areas[t as usize];
            weight += areas[t as usize];
        });
    }
    if weight > 0.0 {
        sum * (1.0 / weight)
    } else {
        T::default()
    }
}

/// Hessian at every vertex by double lumped L2 projection (module docs; 004 §4.3 "dual L2
/// projection"). Parallel over triangles and vertices, deterministic.
///
/// Errors: [`crate::Error::InvalidField`] if `u` does not hold one finite value per vertex (naming
/// the first bad vertex); [`crate::Error::InvalidInput`] if a connected component of the mesh has
/// fewer than 6 vertices.
pub fn hessian_double_l2(mesh: &Mesh2, u: &[f64]) -> Result<Vec<Sym2>> {
    crate::mesh::check_p1_field(mesh.n_points(), u, "u")?;
    input::check_mesh(mesh)?;
    let nt = mesh.n_tris();
    let areas: Vec<f64> = (0..nt)
        .into_par_iter()
        .map(|t| {
            if mesh.is_deleted(t) {
                0.0
            } else {
                mesh.tri_area(t)
            }
        })
        .collect();
    let tri_grad: Vec<DVec2> = (0..nt)
        .into_par_iter()
        .map(|t| tri_gradient(mesh, t, |v| u[v]))
        .collect();
    let n = mesh.n_points() as u32;
    let g: Vec<DVec2> = (0..n)
        .into_par_iter()
        .map(|v| lumped_average(mesh, &areas, &tri_grad, v))
        .collect();
    // Per triangle: the gradients of g.x and g.y, i.e. the rows of the Jacobian.
    let tri_jac: Vec<Jac> = (0..nt)
        .into_par_iter()
        .map(|t| Jac {
            dgx: tri_gradient(mesh, t, |v| g[v].x),
            dgy: tri_gradient(mesh, t, |v| g[v].y),
        })
        .collect();
    Ok((0..n)
        .into_par_iter()
        .map(|v| {
            let j = lumped_average(mesh, &areas, &tri_jac, v);
            Sym2::new(j.dgx.x, 0.5 * (j.dgx.y + j.dgy.x), j.dgy.y)
        })
        .collect())
}

/// Rows of a 2x2 Jacobian: `dgx = grad g_x`, `dgy = grad g_y`.
#[derive(Clone, Copy, Default)]
struct Jac {
    dgx: DVec2,
    dgy: DVec2,
}

impl std::ops::Add for Jac {
    type Output = Jac;
    fn add(self, o: Jac) -> Jac {
        Jac {
            dgx: self.dgx + o.dgx,
            dgy: self.dgy + o.dgy,
        }
    }
}

impl std::ops::Mul<f64> for Jac {
    type Output = Jac;
    fn mul(self, s: f64) -> Jac {
        Jac {
            dgx: self.dgx * s,
            dgy: self.dgy * s,
        }
    }
}
