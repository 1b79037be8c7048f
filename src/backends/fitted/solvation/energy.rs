//! The free energy 001 (7.1) of the solute region of an interface-fitted mesh (the triangles
//! labelled [`REF_INSIDE`]): the surface term `γ |Γ_h|` on the interface polyline, the van der
//! Waals term as the flux of the radial fields `F_i` through the boundary of the solvent region
//! (its interface edges and the box edges it touches; [`super::model`]), the pressure term
//! `P |Ω_s,h|`, and the Tolman term `−4πγτ χ` with `χ` the components of `Ω_s,h` minus its holes
//! (`∫_Γ κ ds = 2πχ` for a closed curve).

use super::model::System;
use crate::backends::fitted::{FittedMesh, REF_INSIDE};
use crate::error::{Error, Result};
use crate::geom::simplex;
use crate::mesh::{Mesh2, NONE};
use serde::Serialize;

/// The free energy 001 (7.1) of one surface and its parts.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Energy {
    /// `γ |Γ|`.
    pub surface: f64,
    /// `ρ_w Σ_i ∫_{Ω_w} U_i`.
    pub vdw: f64,
    /// `P |Ω_s|`.
    pub pressure: f64,
    /// `−2γτ ∫_Γ κ ds = −4πγτ χ(Ω_s)`.
    pub tolman: f64,
    /// The sum `G`.
    pub total: f64,
    /// `|Ω_s|`.
    pub area: f64,
    /// `|Γ|`.
    pub length: f64,
    /// Connected components of the solute region (across edges).
    pub components: usize,
    /// Components of the solvent region that do not touch the box boundary.
    pub holes: usize,
}

/// Connected components of the triangles with `inside(t)`, across shared edges; per component
/// whether it has an edge on the mesh boundary.
fn components(m: &Mesh2, inside: impl Fn(usize) -> bool) -> Vec<bool> {
    let mut seen = vec![false; m.tris.len()];
    let mut out = Vec::new();
    let mut stack = Vec::new();
    for t0 in m.live_tris() {
        if seen[t0] || !inside(t0) {
            continue;
        }
        seen[t0] = true;
        stack.push(t0);
        let mut touches = false;
        while let Some(t) = stack.pop() {
            for &nb in &m.neighbours[t] {
                if nb == NONE {
                    touches = true;
                } else if !seen[nb as usize] && inside(nb as usize) {
                    seen[nb as usize] = true;
                    stack.push(nb as usize);
                }
            }
        }
        out.push(touches);
    }
    out
}

/// The free energy of the solute region of `fm` in the system `sys` (module documentation).
///
/// Errors: a particle in the solvent region or on its boundary, where the van der Waals term is
/// infinite.
pub fn free_energy(fm: &FittedMesh, sys: &System) -> Result<Energy> {
    let m = &fm.mesh;
    let q = &sys.params;
    let is_in = |t: usize| m.tri_ref[t] == REF_INSIDE;
    for (i, p) in sys.particles.iter().enumerate() {
        let wet = m.live_tris().filter(|&t| !is_in(t)).any(|t| {
            let b = simplex::barycentric(&m.tri_points(t), p.x);
            b.iter().all(|&l| l >= -1e-12)
        });
        if wet {
            return Err(Error::InvalidInput(format!(
                "solvation: particle {i} at {} lies in the solvent, where the van der Waals \
                 energy is infinite",
                p.x
            )));
        }
    }
    let mut vdw = 0.0;
    for t in m.live_tris().filter(|&t| !is_in(t)) {
        for i in 0..3 {
            let nb = m.neighbours[t][i];
            if nb == NONE || is_in(nb as usize) {
                let [a, b] = m.edge_vertices(t, i);
                vdw += sys.segment_flux(m.points[a as usize], m.points[b as usize]);
            }
        }
    }
    let solute = components(m, is_in);
    let holes = components(m, |t| !is_in(t))
        .into_iter()
        .filter(|&touches| !touches)
        .count();
    let area = fm.area_inside();
    let length = fm.interface_length();
    let chi = solute.len() as f64 - holes as f64;
    let surface = q.gamma * length;
    let pressure = q.pressure * area;
    let tolman = -4.0 * std::f64::consts::PI * q.gamma * q.tolman * chi;
    Ok(Energy {
        surface,
        vdw,
        pressure,
        tolman,
        total: surface + vdw + pressure + tolman,
        area,
        length,
        components: solute.len(),
        holes,
    })
}
