//! Example 1 of 003 §8: the torus `r = 0.2`, `R = 0.4` in `[-1, 1]³` on Kuhn meshes refined
//! near it, the 3D tables 8.1-8.3.

use super::cases::{q_alpha, table_opts, H0};
use super::types::CaseResult;
use anisomesh::error::Result;
use anisomesh::fem::lagrange::P2Dofs;
use anisomesh::geom::DVec3;
use anisomesh::levelset::redistance::redistance_ppr_cells;
use anisomesh::mesh3::Mesh3;

/// Exact signed distance to the torus of 003 §8, Example 1.
pub fn torus_distance(p: DVec3) -> f64 {
    let (r, big_r) = (0.2, 0.4);
    (p.z * p.z + ((p.x * p.x + p.y * p.y).sqrt() - big_r).powi(2)).sqrt() - r
}

/// The level-`ℓ` mesh of `[-1, 1]³` refined near the zero level of `dist` (nested bands of width
/// `2 h_j`, `j = 1..=ℓ`): Kuhn mesh with `h_0 = 2/3` and 3 bisections per level.
pub fn refined_box(level: u32, dist: impl Fn(DVec3) -> f64 + Copy) -> Result<Mesh3> {
    let mut m = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::splat(1.0), [3, 3, 3])?;
    for j in 1..=level {
        let h = H0 / f64::from(1u32 << j);
        m.refine_near(dist, 2.0 * h, (3 * j) as u8);
    }
    Ok(m)
}

/// Node positions of a P1/P2 field on tetrahedra (vertices, then [`P2Dofs::for_tets`] edges).
pub(super) fn nodes3(m: &Mesh3, k: usize) -> Vec<DVec3> {
    let mut x = m.points.clone();
    if k == 2 {
        let d = P2Dofs::for_tets(&m.tets, m.n_points());
        x.extend(
            d.edges
                .iter()
                .map(|&[a, b]| 0.5 * (m.points[a as usize] + m.points[b as usize])),
        );
    }
    x
}

#[cfg(test)]
/// Example 1 of 003 §8 at level `ℓ`, degree `k`, parameter `α` (initialisation phase only).
pub fn torus_case(level: u32, k: usize, alpha: f64) -> Result<CaseResult> {
    torus_case_on(&refined_box(level, torus_distance)?, level, k, alpha)
}

/// [`torus_case`] on the given level-`ℓ` mesh (from [`refined_box`] with [`torus_distance`]).
pub fn torus_case_on(m: &Mesh3, level: u32, k: usize, alpha: f64) -> Result<CaseResult> {
    let x = nodes3(m, k);
    let phi: Vec<f64> = x
        .iter()
        .map(|p| torus_distance(*p) * q_alpha(alpha, p.x, p.y, p.length()))
        .collect();
    let out = redistance_ppr_cells(&m.points, &m.tets, &phi, &table_opts(k))?;
    let e_inf = x
        .iter()
        .enumerate()
        .filter(|(i, _)| out.band[*i])
        .map(|(i, p)| (out.values[i] - torus_distance(*p)).abs())
        .fold(0.0, f64::max);
    Ok((
        H0 / f64::from(1u32 << level),
        e_inf,
        out.report.e_grad,
        out.report,
    ))
}
