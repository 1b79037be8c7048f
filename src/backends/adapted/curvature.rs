//! Curvature of the zero level of a P1 level set from its recovered derivatives: at every vertex
//! `κ = div(∇u/|∇u|) = (|g|² tr H − gᵀ H g) / |g|³ = tr(P H P)/|g|` with the gradient `g` and
//! Hessian `H` of a least-squares fit, then linear interpolation along each edge the zero level
//! crosses, at the crossing point. `κ` depends only on the level lines of `u`, so `u` need not be
//! a distance. Near the zero level the fit is the cubic one of [`super::cubic`] (Hessian error
//! `O(h)` on the stretched patches of the adapted mesh) for the speed of the flow and the quartic
//! one (`O(h^{3/2})`) for the curvature samples, elsewhere the quadratic fit of 004 §4.3.

use super::super::{CurvatureSamples, D2};
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::mesh::Mesh2;
use crate::metric::Sym2;
use crate::recovery::recover_ls;
use rayon::prelude::*;

/// `div(g/|g|)` for gradient `g` and Hessian `h` (0 where `g` vanishes).
fn level_curvature(g: DVec2, h: &Sym2) -> f64 {
    let n2 = g.length_squared();
    if n2 <= 0.0 {
        return 0.0;
    }
    let hg = DVec2::new(h.xx * g.x + h.xy * g.y, h.xy * g.x + h.yy * g.y);
    (n2 * (h.xx + h.yy) - g.dot(hg)) / (n2 * n2.sqrt())
}

/// `|∇u| div(∇u/|∇u|) = tr H − gᵀ H g / |g|²` at every vertex, from the least-squares gradient
/// and Hessian (004 §4.3): the right-hand side of the level-set mean curvature equation
/// `u_t = |∇u| div(∇u/|∇u|)` (000 eq. (2.4)). Errors: those of the recovery.
/// The cubic fit is used at the vertices with `|u| <= width` (when `cubic`).
pub(crate) fn mean_curvature_speed(
    mesh: &Mesh2,
    u: &[f64],
    width: f64,
    cubic: bool,
) -> Result<Vec<f64>> {
    let near: Vec<bool> = u.iter().map(|v| cubic && v.abs() <= width).collect();
    let (gradient, hessian) = derivatives(mesh, u, &near, false)?;
    Ok(gradient
        .iter()
        .zip(&hessian)
        .map(|(&g, h)| g.length() * level_curvature(g, h))
        .collect())
}

/// The recovered gradient and Hessian at every vertex: the cubic fit (the quartic one with
/// `quartic`) where `near` (falling back to the quadratic one where the patch cannot carry it),
/// the quadratic fit elsewhere.
pub(crate) fn derivatives(
    mesh: &Mesh2,
    u: &[f64],
    near: &[bool],
    quartic: bool,
) -> Result<(Vec<DVec2>, Vec<Sym2>)> {
    let rec = recover_ls(mesh, u)?;
    let (mut gradient, mut hessian) = (rec.gradient, rec.hessian);
    let fits: Vec<(usize, Option<(DVec2, Sym2)>)> = (0..mesh.n_points())
        .into_par_iter()
        .with_min_len(64)
        .filter(|&v| near[v])
        .map_init(Vec::new, |ws, v| {
            let fit = if quartic {
                super::cubic::quartic_fit(mesh, u, v as u32, ws)
                    .or_else(|| super::cubic::cubic_fit(mesh, u, v as u32, ws))
            } else {
                super::cubic::cubic_fit(mesh, u, v as u32, ws)
            };
            (v, fit)
        })
        .collect();
    for (v, fit) in fits {
        if let Some((g, h)) = fit {
            gradient[v] = g;
            hessian[v] = h;
        }
    }
    Ok((gradient, hessian))
}

/// Curvature samples at the crossings of the zero level of `u` with the edges of `mesh` (sign
/// rule of [`crate::levelset::interface`]: a vertex is negative when `u < 0`). Error:
/// [`Error::EmptyLevelSet`] when no edge is crossed, or those of the recovery.
/// With `cubic`, the derivatives at the ends of crossed edges come from the cubic fit.
pub(crate) fn curvature_samples(
    mesh: &Mesh2,
    u: &[f64],
    cubic: bool,
) -> Result<CurvatureSamples<D2>> {
    let mut near = vec![false; mesh.n_points()];
    if cubic {
        for ([a, b], _, _) in mesh.edges() {
            if (u[a as usize] < 0.0) != (u[b as usize] < 0.0) {
                near[a as usize] = true;
                near[b as usize] = true;
            }
        }
    }
    let (gradient, hessian) = derivatives(mesh, u, &near, cubic)?;
    let kappa: Vec<f64> = gradient
        .iter()
        .zip(&hessian)
        .map(|(&g, h)| level_curvature(g, h))
        .collect();
    let mut points = Vec::new();
    let mut values = Vec::new();
    for ([a, b], _, _) in mesh.edges() {
        let (ua, ub) = (u[a as usize], u[b as usize]);
        if (ua < 0.0) == (ub < 0.0) {
            continue;
        }
        let s = ua / (ua - ub);
        let (pa, pb) = (mesh.points[a as usize], mesh.points[b as usize]);
        points.push(pa + s * (pb - pa));
        values.push((1.0 - s) * kappa[a as usize] + s * kappa[b as usize]);
    }
    if values.is_empty() {
        return Err(Error::EmptyLevelSet(format!(
            "no edge of the {} vertices crosses the zero level",
            mesh.n_points()
        )));
    }
    Ok(CurvatureSamples { points, values })
}
