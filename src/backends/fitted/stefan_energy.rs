//! The energy balance of the Stefan loop (001 §6): with latent heat 1 and insulated walls the
//! Stefan problem conserves `E = ∫T − A` (the heat released where the solid grows, (6.4), is
//! the heat the liquid gains). [`StefanBudget`] splits the change of `E` over one step into the
//! loop's stages; [`restrict_conservative`] is the transfer of the temperature from the fitted
//! mesh to the base mesh that keeps `∫T`.

use super::fit::FittedMesh;
use crate::mesh::Mesh2;

/// The terms by which one [`super::stefan_step`] changes the energy `E = ∫T − A` of the Stefan problem
/// with latent heat 1 (conserved with insulated walls): heat contents `∫T` with the lumped P1
/// mass of the mesh the field lives on, areas of the solid `{φ < 0}` of the P1 level set. The
/// change of `E` is `transfer_in + interface_heat + transfer_out − area_snap − area_advection −
/// area_redistance`.
#[derive(Debug, Clone, Copy, PartialEq, Default, serde::Serialize)]
pub struct StefanBudget {
    /// Heat content on the fitted mesh of the interpolated temperature minus that on the base
    /// mesh (lumped quadrature of the same P1 function on two meshes).
    pub transfer_in: f64,
    /// Heat gained by the heat step on the fitted mesh: the sum of the residuals at the
    /// interface vertices, the heat the Gibbs–Thomson condition supplies.
    pub interface_heat: f64,
    /// The part of `interface_heat` from setting the interface vertices to their Gibbs–Thomson
    /// values (`Σ M_i (T_Γ,i − T_i)` over the interface vertices).
    pub assignment_heat: f64,
    /// The latent heat of the front's velocity, `Δt Σ v_n,i L_i` over the interface vertices
    /// (`L_i` half the length of the interface edges at `i`).
    pub front_heat: f64,
    /// Heat content on the base mesh of the restricted temperature minus that on the fitted mesh.
    pub transfer_out: f64,
    /// Area change by snapping cuts to base vertices.
    pub area_snap: f64,
    /// Area change by the level-set update.
    pub area_advection: f64,
    /// Area change by redistancing.
    pub area_redistance: f64,
}

impl StefanBudget {
    /// The change of `∫T − A` over the step.
    pub fn energy_change(&self) -> f64 {
        self.transfer_in + self.interface_heat + self.transfer_out
            - self.area_snap
            - self.area_advection
            - self.area_redistance
    }

    /// The sum of two budgets, term by term.
    pub fn add(&self, o: &StefanBudget) -> StefanBudget {
        StefanBudget {
            transfer_in: self.transfer_in + o.transfer_in,
            interface_heat: self.interface_heat + o.interface_heat,
            assignment_heat: self.assignment_heat + o.assignment_heat,
            front_heat: self.front_heat + o.front_heat,
            transfer_out: self.transfer_out + o.transfer_out,
            area_snap: self.area_snap + o.area_snap,
            area_advection: self.area_advection + o.area_advection,
            area_redistance: self.area_redistance + o.area_redistance,
        }
    }
}

/// Half the length of the interface edges at each fitted vertex (0 off the interface).
pub(crate) fn interface_dual_lengths(fm: &FittedMesh) -> Vec<f64> {
    let m = &fm.mesh;
    let mut w = vec![0.0f64; m.n_points()];
    for [a, b] in fm.interface_edges() {
        let l = 0.5 * (m.points[a as usize] - m.points[b as usize]).length();
        w[a as usize] += l;
        w[b as usize] += l;
    }
    w
}

/// The temperature `f` of the fitted mesh restricted to the base vertices with the same `∫T`
/// (P1 integrals, exact with the lumped mass `mass_base`): in every base triangle the heat that
/// the base interpolant misses (the kink of `T` across the interface, which the plain
/// restriction cuts off: `O(h² |∂T/∂n|)` per unit length of interface and step) is given back
/// to its three vertices in equal parts. Only the vertices of cut base triangles change.
pub(crate) fn restrict_conservative(
    fm: &FittedMesh,
    base: &Mesh2,
    f: &[f64],
    mass_base: &[f64],
) -> Vec<f64> {
    let m = &fm.mesh;
    let nb = fm.n_base_vertices;
    let mut fine = vec![0.0f64; base.tris.len()];
    let mut children = vec![0u32; base.tris.len()];
    for t in m.live_tris() {
        children[fm.parent[t] as usize] += 1;
        let s: f64 = m.tris[t].iter().map(|&v| f[v as usize]).sum();
        fine[fm.parent[t] as usize] += m.tri_area(t).abs() / 3.0 * s;
    }
    let mut out = f[..nb].to_vec();
    let mut add = vec![0.0f64; nb];
    for t in base.live_tris() {
        let tri = base.tris[t];
        if children[t] < 2 {
            continue;
        }
        let coarse: f64 =
            base.tri_area(t).abs() / 3.0 * tri.iter().map(|&v| f[v as usize]).sum::<f64>();
        let d = fine[t] - coarse;
        for &v in &tri {
            add[v as usize] += d / 3.0;
        }
    }
    for ((o, a), &mb) in out.iter_mut().zip(&add).zip(mass_base) {
        if mb > 0.0 {
            *o += a / mb;
        }
    }
    out
}
