//! First-order redistancing by fast marching alone: the vertices of the cut cells start from the
//! distance of the cell's affine function, `|u_i| / |∇u_T|` (the smallest over the cut cells
//! around vertex `i`), and the fast marching of the extension phase (`fmm.rs`, the local eikonal
//! equation 004 eq. (5)) carries the distance to every other vertex; the sign of `u` is kept.
//!
//! The band values are exact for a planar zero level and first order otherwise; the marching adds
//! an `O(h)` error away from the band. It is the cheap alternative to the exact geometric distance
//! ([`super::redistance_geometric_cells`]) and to PPR ([`super::redistance_ppr_cells`]).

use super::fmm::fast_marching;
use crate::error::{Error, Result};
use crate::geom::simplex::p1_gradient;
use crate::geom::Point;
use crate::mesh::check_p1_field;

/// Fast-marching signed distance at every point of the simplices `cells` over `points`
/// (triangles over `DVec2`, tetrahedra over `DVec3`) from the zero level of the P1 field `u`,
/// sign of `u` kept (module documentation). Points not connected to a cut cell get `±inf`.
///
/// Errors: [`Error::InvalidField`] if `u` does not hold one finite value per point;
/// [`Error::EmptyLevelSet`] if no cell meets the zero level.
pub fn redistance_fmm_cells<const D: usize, const N: usize, P: Point<D>>(
    points: &[P],
    cells: &[[u32; N]],
    u: &[f64],
) -> Result<Vec<f64>> {
    check_p1_field(points.len(), u, "u")?;
    let mut known: Vec<Option<f64>> = vec![None; points.len()];
    for c in cells {
        let s = c.map(|v| u[v as usize]);
        let neg = s.iter().any(|&x| x < 0.0);
        let pos = s.iter().any(|&x| x > 0.0);
        if !(s.contains(&0.0) || neg && pos) {
            continue;
        }
        let g = p1_gradient(&c.map(|v| points[v as usize]), &s).length();
        for (&v, &x) in c.iter().zip(&s) {
            let d = if x == 0.0 { 0.0 } else { x.abs() / g };
            let k = &mut known[v as usize];
            if d.is_finite() && k.map_or(true, |o| d < o) {
                *k = Some(d);
            }
        }
    }
    if known.iter().all(Option::is_none) {
        return Err(Error::EmptyLevelSet(format!(
            "the field has no zero crossing on the {} cells of the mesh",
            cells.len()
        )));
    }
    let pts: Vec<_> = points.iter().map(|p| p.to_xyz()).collect();
    let flat: Vec<u32> = cells.iter().flatten().copied().collect();
    let d = fast_marching(&pts, &flat, N, &known);
    Ok(d.iter()
        .zip(u)
        .map(|(&d, &x)| if x < 0.0 { -d } else { d })
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec2;
    use crate::mesh::{GridPattern, Mesh2};

    #[test]
    fn plane_is_reproduced_and_circle_is_first_order() {
        let mut errs = Vec::new();
        for n in [21, 41, 81] {
            let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::Right).unwrap();
            let cells: Vec<[u32; 3]> = mesh.live_tris().map(|t| mesh.tris[t]).collect();
            let plane: Vec<f64> = mesh.points.iter().map(|p| 3.0 * (p.x - 0.31)).collect();
            let d = redistance_fmm_cells(&mesh.points, &cells, &plane).unwrap();
            for (p, d) in mesh.points.iter().zip(&d) {
                assert!((d - (p.x - 0.31)).abs() < 1e-12, "{p} {d}");
            }
            let c = DVec2::splat(0.5);
            let u: Vec<f64> = mesh
                .points
                .iter()
                .map(|p| (*p - c).length_squared() - 0.09)
                .collect();
            let d = redistance_fmm_cells(&mesh.points, &cells, &u).unwrap();
            let e = mesh
                .points
                .iter()
                .zip(&d)
                .map(|(p, d)| (d - ((*p - c).length() - 0.3)).abs())
                .fold(0.0, f64::max);
            errs.push(e);
        }
        assert!(errs[2] < 0.7 * errs[0], "{errs:?}");
        assert!(errs[2] < 0.02, "{errs:?}");
        let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 4, 4, GridPattern::Right).unwrap();
        let cells: Vec<[u32; 3]> = mesh.live_tris().map(|t| mesh.tris[t]).collect();
        assert!(redistance_fmm_cells(&mesh.points, &cells, &[1.0; 25]).is_err());
    }
}
