//! The Stefan loop of 001 §6 on an interface-fitted mesh: per step the zero level of the P1 level
//! set is fitted into the base mesh, the heat equation (6.1) is advanced on the fitted mesh with
//! `T = 0` on the interface (the Gibbs–Thomson relation (6.2) without surface tension or kinetic
//! undercooling), the normal velocity comes from the Stefan condition (6.4), it is extended off
//! the interface, the level set is moved and redistanced, and the temperature is restricted back
//! to the base mesh.
//!
//! The extension of `v_n` gives every base vertex near the interface the length-weighted mean of
//! `v_n` over the interface vertices around its nearest one (constant along the normals up to
//! the smoothing length, first-order accurate; see [`stefan_step`]). The level set, a signed distance (`|∇φ| = 1`), moves by `φ ← φ − Δt v_ext`, and is
//! then replaced by the exact distance to its P1 zero level
//! ([`crate::levelset::redistance::redistance_geometric`]), negative in the solid.

use super::fit::{fit, FitOptions, FittedMesh, REF_INSIDE};
use crate::error::{Error, Result};
use crate::flows::stefan::{heat_step, stefan_velocity};
use crate::geom::{simplex, DVec2};
use crate::levelset::redistance::redistance_geometric;
use crate::mesh::{check_p1_field, Mesh2};

/// The state of the Stefan loop on the base mesh.
#[derive(Debug, Clone)]
pub struct StefanState {
    /// Signed distance to the interface at the base vertices, negative in the solid.
    pub phi: Vec<f64>,
    /// Temperature at the base vertices.
    pub temperature: Vec<f64>,
    /// Current time.
    pub time: f64,
}

/// What one step of [`stefan_step`] did.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StefanStepReport {
    /// Vertices of the fitted mesh.
    pub fitted_vertices: usize,
    /// Largest `|v_n|` over the interface vertices.
    pub max_vn: f64,
    /// Conjugate-gradient iterations of the heat step.
    pub cg_iterations: usize,
}

/// The outward unit normals `∇φ/|∇φ|` of the fitted level set at its interface vertices (zero
/// elsewhere): the area-weighted mean of the P1 gradients around each vertex.
fn interface_normals(fm: &FittedMesh, on: &[bool]) -> Vec<DVec2> {
    let m = &fm.mesh;
    let mut g = vec![DVec2::ZERO; m.n_points()];
    for t in m.live_tris() {
        let tri = m.tris[t];
        if !tri.iter().any(|&v| on[v as usize]) {
            continue;
        }
        let p = m.tri_points(t);
        let f = tri.map(|v| fm.u[v as usize]);
        let gt = simplex::p1_gradient(&p, &f) * m.tri_area(t).abs();
        for &v in &tri {
            if on[v as usize] {
                g[v as usize] += gt;
            }
        }
    }
    g.into_iter()
        .map(|x| {
            let l = x.length();
            if l > 0.0 {
                x / l
            } else {
                DVec2::new(1.0, 0.0)
            }
        })
        .collect()
}

/// One step of the Stefan loop (001 §6 steps 1–10) of length `dt` on `base`.
///
/// `boundary` optionally prescribes the temperature on the outer boundary vertices at the new
/// time, `boundary(p, t)` (for an exact solution); without it the walls are insulated (6.3).
/// Only the base vertices within `band` of the interface move with the extended velocity; the
/// others keep their sign and get their new distance from the redistancing. The velocity given
/// to a base vertex at distance `d` from the nearest interface vertex is the mean of `v_n` over the
/// interface vertices within `d + smoothing`, weighted by their share of the interface length
/// (`smoothing = 0`: the nearest vertex's value; three mesh sizes average out the
/// first-order noise of the one-sided gradients at the cut vertices).
///
/// Errors: a non-positive or non-finite `dt` or `band`, fields of the wrong size or with
/// non-finite values, a level set with no zero level ([`Error::EmptyLevelSet`]), the solver's
/// errors.
pub fn stefan_step(
    base: &Mesh2,
    state: &mut StefanState,
    dt: f64,
    band: f64,
    smoothing: f64,
    boundary: Option<&dyn Fn(DVec2, f64) -> f64>,
) -> Result<StefanStepReport> {
    if !(dt.is_finite() && dt > 0.0) {
        return Err(Error::InvalidInput(format!(
            "Stefan step: the time step must be finite and positive (got {dt})"
        )));
    }
    if !(smoothing.is_finite() && smoothing >= 0.0) {
        return Err(Error::InvalidInput(format!(
            "Stefan step: the smoothing length must be finite and non-negative (got {smoothing})"
        )));
    }
    if !(band.is_finite() && band > 0.0) {
        return Err(Error::InvalidInput(format!(
            "Stefan step: the velocity band must be finite and positive (got {band})"
        )));
    }
    check_p1_field(base.n_points(), &state.phi, "level set")?;
    check_p1_field(base.n_points(), &state.temperature, "temperature")?;
    let fm = fit(base, &state.phi, &FitOptions::default())?;
    let m = &fm.mesh;
    let n = m.n_points();
    let mut on = vec![false; n];
    for [a, b] in fm.interface_edges() {
        on[a as usize] = true;
        on[b as usize] = true;
    }
    for (o, &u) in on.iter_mut().zip(&fm.u) {
        if u == 0.0 {
            *o = true;
        }
    }
    let t_new = state.time + dt;
    let temp = fm.extend_from_base(&state.temperature)?;
    let mut fixed = on.clone();
    let mut values = vec![0.0; n];
    if let Some(bc) = boundary {
        for (v, &b) in m.boundary_vertex_flags().iter().enumerate() {
            if b && !on[v] {
                fixed[v] = true;
                values[v] = bc(m.points[v], t_new);
            }
        }
    }
    let (temp, cg) = heat_step(m, &fixed, &values, &temp, dt)?;
    let normals = interface_normals(&fm, &on);
    let vn = stefan_velocity(m, REF_INSIDE, &on, &normals, &temp)?;
    let iface: Vec<usize> = (0..n).filter(|&v| on[v]).collect();
    let max_vn = iface.iter().fold(0.0f64, |a, &v| a.max(vn[v].abs()));
    // Dual length of each interface vertex: half the lengths of its interface edges.
    let mut weight = vec![0.0f64; n];
    for [a, b] in fm.interface_edges() {
        let l = 0.5 * (m.points[a as usize] - m.points[b as usize]).length();
        weight[a as usize] += l;
        weight[b as usize] += l;
    }
    let mut phi = fm.u[..fm.n_base_vertices].to_vec();
    for (v, p) in phi.iter_mut().enumerate() {
        if p.abs() > band {
            continue;
        }
        let x = m.points[v];
        let d2: Vec<f64> = iface
            .iter()
            .map(|&w| (m.points[w] - x).length_squared())
            .collect();
        let dmin = d2.iter().fold(f64::INFINITY, |a, &b| a.min(b)).sqrt();
        let reach = (dmin + smoothing).powi(2);
        let (mut sw, mut sv) = (0.0f64, 0.0f64);
        for (k, &w) in iface.iter().enumerate() {
            if d2[k] <= reach {
                sw += weight[w];
                sv += weight[w] * vn[w];
            }
        }
        if sw > 0.0 {
            *p -= dt * sv / sw;
        }
    }
    state.phi = redistance_geometric(base, &phi)?;
    state.temperature = fm.restrict_to_base(&temp)?;
    state.time = t_new;
    Ok(StefanStepReport {
        fitted_vertices: n,
        max_vn,
        cg_iterations: cg.iterations,
    })
}

/// The deviation of the zero level of `phi` on `base` from the circle of radius `r` centred at
/// the origin: the mean and the largest `||p| − r|` over the vertices of the fitted interface, and
/// the radius `√(A/π)` of the disc with the enclosed area `A`.
///
/// Errors: those of [`fit`].
pub fn circle_deviation(base: &Mesh2, phi: &[f64], r: f64) -> Result<(f64, f64, f64)> {
    let fm = fit(base, phi, &FitOptions::default())?;
    let mut seen = vec![false; fm.mesh.n_points()];
    let (mut sum, mut max, mut count) = (0.0f64, 0.0f64, 0usize);
    for [a, b] in fm.interface_edges() {
        for v in [a as usize, b as usize] {
            if !seen[v] {
                seen[v] = true;
                let e = (fm.mesh.points[v].length() - r).abs();
                sum += e;
                max = max.max(e);
                count += 1;
            }
        }
    }
    let mean = if count > 0 { sum / count as f64 } else { 0.0 };
    Ok((mean, max, (fm.area_inside() / std::f64::consts::PI).sqrt()))
}
