//! Measures of a Stokes solution: the rigid motion fitted to the velocity inside a region (the
//! rigidity of the Couette disk, 004 §5.1) and the L2 errors against exact fields.

use super::StokesSolution;
use crate::error::{Error, Result};
use crate::fem::p1::bary_point;
use crate::fem::quadrature::tri_rule;
use crate::geom::DVec2;
use crate::mesh::Mesh2;

/// A least-squares rigid motion `u(x) ≈ t + ω (x - c)^⊥` of a velocity field inside a region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidFit {
    /// Angular velocity `ω` (counter-clockwise positive).
    pub omega: f64,
    /// Velocity of the centroid `c` of the region.
    pub translation: DVec2,
    /// The centroid `c` of the fitted vertices (weighted).
    pub centre: DVec2,
    /// `max_i |u_i - t - ω (x_i - c)^⊥| / max_i |u_i|` over the fitted vertices.
    pub max_deviation_rel: f64,
    /// Number of vertices used.
    pub vertices: usize,
}

/// Fits a rigid motion to the P1 `velocity` at the vertices `x` with `inside(x)`, weighting each
/// vertex by its lumped-mass area (so the fit does not depend on how densely the region is
/// meshed). The measure of rigidity of the Couette disk of 004 §5.1. Errors when fewer than two
/// vertices are inside.
pub fn rigid_motion_fit(
    mesh: &Mesh2,
    velocity: &[DVec2],
    inside: impl Fn(DVec2) -> bool,
) -> Result<RigidFit> {
    if velocity.len() != mesh.n_points() {
        return Err(Error::InvalidField {
            name: "velocity".into(),
            msg: format!("{} values for {} vertices", velocity.len(), mesh.n_points()),
        });
    }
    let w = lumped_areas(mesh);
    let ids: Vec<usize> = (0..mesh.n_points())
        .filter(|&v| w[v] > 0.0 && inside(mesh.points[v]))
        .collect();
    if ids.len() < 2 {
        return Err(Error::InvalidInput(format!(
            "rigid-motion fit needs at least 2 vertices inside the region, found {}",
            ids.len()
        )));
    }
    let wsum: f64 = ids.iter().map(|&v| w[v]).sum();
    let c: DVec2 = ids.iter().map(|&v| w[v] * mesh.points[v]).sum::<DVec2>() / wsum;
    let t: DVec2 = ids.iter().map(|&v| w[v] * velocity[v]).sum::<DVec2>() / wsum;
    let (mut num, mut den) = (0.0, 0.0);
    for &v in &ids {
        let r = mesh.points[v] - c;
        num += w[v] * r.perp().dot(velocity[v] - t);
        den += w[v] * r.length_squared();
    }
    let omega = if den > 0.0 { num / den } else { 0.0 };
    let (mut dev, mut umax) = (0.0f64, 0.0f64);
    for &v in &ids {
        let r = mesh.points[v] - c;
        dev = dev.max((velocity[v] - t - omega * r.perp()).length());
        umax = umax.max(velocity[v].length());
    }
    Ok(RigidFit {
        omega,
        translation: t,
        centre: c,
        max_deviation_rel: if umax > 0.0 { dev / umax } else { 0.0 },
        vertices: ids.len(),
    })
}

/// The lumped-mass area of every vertex: a third of the area of each live triangle around it.
fn lumped_areas(mesh: &Mesh2) -> Vec<f64> {
    let mut w = vec![0.0; mesh.n_points()];
    for t in mesh.live_tris() {
        let a = mesh.tri_area(t) / 3.0;
        for v in mesh.tris[t] {
            w[v as usize] += a;
        }
    }
    w
}

/// The velocity error `‖u_h - u‖_{L2}` (P1 + bubble) and pressure error `‖p_h - p‖_{L2}` of a
/// solution against exact fields, with the degree-7 rule.
pub fn stokes_errors(
    mesh: &Mesh2,
    sol: &StokesSolution,
    u: impl Fn(DVec2) -> DVec2,
    p: impl Fn(DVec2) -> f64,
) -> (f64, f64) {
    let rule = tri_rule(7);
    let (mut eu, mut ep) = (0.0, 0.0);
    for t in mesh.live_tris() {
        let pts = mesh.tri_points(t);
        let area = mesh.tri_area(t);
        let pv = mesh.tris[t].map(|i| sol.pressure[i as usize]);
        eu += area
            * rule
                .mean(|l| (sol.velocity_at(mesh, t, l) - u(bary_point(&pts, l))).length_squared());
        ep += area
            * rule.mean(|l| {
                let e = l[0] * pv[0] + l[1] * pv[1] + l[2] * pv[2] - p(bary_point(&pts, l));
                e * e
            });
    }
    (eu.sqrt(), ep.sqrt())
}
