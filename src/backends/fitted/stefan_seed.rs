//! The pentagon seed of the solidification cases of 001 §6 (Figs. 6.1–6.3).

use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::levelset::redistance::redistance_geometric;
use crate::mesh::Mesh2;

/// The signed distance at the vertices of `base` to the regular pentagon of circumradius
/// `radius` centred at the origin with a vertex on the positive y axis (the seed of 001 Figs.
/// 6.1–6.3; its size is not given there), negative inside: the largest signed distance to the
/// five edge lines (negative exactly inside), redistanced to the P1 zero level
/// ([`redistance_geometric`]).
///
/// Errors: a radius that is not finite and positive, a pentagon with no vertex of `base` inside
/// or outside ([`Error::EmptyLevelSet`] from the redistancing).
pub fn pentagon_seed(base: &Mesh2, radius: f64) -> Result<Vec<f64>> {
    if !(radius.is_finite() && radius > 0.0) {
        return Err(Error::InvalidInput(format!(
            "pentagon seed: the radius must be finite and positive (got {radius})"
        )));
    }
    let corners: Vec<DVec2> = (0..5)
        .map(|k| {
            let a = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * k as f64 / 5.0;
            radius * DVec2::new(a.cos(), a.sin())
        })
        .collect();
    let phi0: Vec<f64> = base
        .points
        .iter()
        .map(|&p| {
            (0..5).fold(f64::NEG_INFINITY, |m, k| {
                let (a, b) = (corners[k], corners[(k + 1) % 5]);
                let e = (b - a).normalize();
                m.max((p - a).dot(DVec2::new(e.y, -e.x)))
            })
        })
        .collect();
    redistance_geometric(base, &phi0)
}
