//! The error sources of the Zalesak rotation measured separately (004 §5.1, §2.2).
//!
//! With `u_e(t)` the exact signed distance of the rotated slotted disk and `I_h` nodal
//! interpolation on a mesh:
//! - **representation**: `I_h u_e` on the initial and on the final mesh against the exact area
//!   and perimeter (the P1 zero level cuts the corners and chords the arcs);
//! - **foot**: per period, `I_h u_e(t_n)` on `T^n` advected to `T^{n+1}` with the scheme's feet
//!   (RK4) minus the same with the exact feet (the rotation by `-Δt`); summed over the periods,
//!   and the largest foot position error;
//! - **evaluation at the feet / transfer**: per period, `I_h u_e(t_n)` on `T^n` carried to
//!   `T^{n+1}` with the exact feet (004 eq. (2): evaluation of the P1 field at the feet and, in
//!   the L2 form, projection) minus `I_h u_e(t_{n+1})` on `T^{n+1}`; summed over the periods.
//!   In this scheme the advection *is* the transfer: `u^{n+1}` is computed on the new mesh
//!   directly from `(T^n, u^n)`, so there is no separate mesh-to-mesh interpolation step;
//! - **redistancing**: the change of area and perimeter made by each geometric redistancing
//!   (004 §2.2), summed (zero when redistancing is off);
//! - **accumulated**: the final `u` against `I_h u_e` on the final mesh (everything but the
//!   representation).
//!
//! All numbers are relative to the exact area / perimeter.

use super::exact::{exact_level_set, EXACT_AREA, EXACT_PERIMETER};
use anisomesh::advect::galerkin::{limit_to_feet, pull_back, Form};
use anisomesh::advect::{self, foot, AdvectOptions, FieldEvaluator, Rotation};
use anisomesh::error::Result;
use anisomesh::geom::DVec2;
use anisomesh::levelset::shapes::Zalesak;
use anisomesh::mesh::Mesh2;
use rayon::prelude::*;
use serde::Serialize;

/// Relative area and perimeter errors of each source (see the module documentation).
#[derive(Debug, Clone, Default, Serialize)]
pub struct ErrorSources {
    pub initial_area: f64,
    pub initial_perimeter: f64,
    pub final_representation_area: f64,
    pub final_representation_perimeter: f64,
    pub foot_area: f64,
    pub foot_perimeter: f64,
    /// Largest distance between a scheme foot and the exact foot over all periods.
    pub foot_max_distance: f64,
    pub transfer_area: f64,
    pub transfer_perimeter: f64,
    pub redistance_area: f64,
    pub redistance_perimeter: f64,
    pub accumulated_area: f64,
    pub accumulated_perimeter: f64,
}

fn measures(mesh: &Mesh2, u: &[f64]) -> Result<(f64, f64)> {
    Ok((
        advect::enclosed_area(mesh, u)? / EXACT_AREA,
        advect::interface_length(mesh, u)? / EXACT_PERIMETER,
    ))
}

impl ErrorSources {
    /// Adds the one-step foot and transfer errors of the period `[t0, t1]` from `old` to `new`.
    /// `a` is the advection step of the run.
    pub(super) fn period(
        &mut self,
        shape: &Zalesak,
        old: &Mesh2,
        new: &Mesh2,
        t0: f64,
        t1: f64,
        a: &AdvectOptions,
    ) -> Result<()> {
        let ue0 = exact_level_set(shape, old, t0);
        let ue1 = exact_level_set(shape, new, t1);
        let (s, c) = (t1 - t0).sin_cos();
        let exact_foot = move |x: DVec2| DVec2::new(c * x.x + s * x.y, -s * x.x + c * x.y);
        let eval = FieldEvaluator::new(old, &ue0, a.interp, a.inflow.clone())?;
        let mut ux = pull_back(&eval, new, &exact_foot, a.form, a.cg_tol)?;
        if a.limit && a.form != Form::Nodal {
            limit_to_feet(old, &ue0, new, &exact_foot, &mut ux)?;
        }
        let v = Rotation { omega: 1.0 };
        let ur = advect::advect(old, &ue0, new, &v, t0, t1, a)?;
        let (ar, pr) = measures(new, &ue1)?;
        let (ax, px) = measures(new, &ux)?;
        let (af, pf) = measures(new, &ur)?;
        self.transfer_area += ax - ar;
        self.transfer_perimeter += px - pr;
        self.foot_area += af - ax;
        self.foot_perimeter += pf - px;
        let d = new
            .points
            .par_iter()
            .map(|&x| (foot(&v, x, t0, t1, &a.foot) - exact_foot(x)).length())
            .reduce(|| 0.0, f64::max);
        self.foot_max_distance = self.foot_max_distance.max(d);
        Ok(())
    }

    /// Adds the change made by redistancing `u` into `r`.
    pub(super) fn redistance(&mut self, mesh: &Mesh2, u: &[f64], r: &[f64]) -> Result<()> {
        let (a0, p0) = measures(mesh, u)?;
        let (a1, p1) = measures(mesh, r)?;
        self.redistance_area += a1 - a0;
        self.redistance_perimeter += p1 - p0;
        Ok(())
    }

    /// Representation errors at the start and the end, and the accumulated error of the final
    /// `u` (at time `t`) on `mesh`.
    pub(super) fn finish(
        &mut self,
        shape: &Zalesak,
        mesh: &Mesh2,
        u: &[f64],
        t: f64,
        area_initial: f64,
        perimeter_initial: f64,
    ) -> Result<()> {
        self.initial_area = area_initial / EXACT_AREA - 1.0;
        self.initial_perimeter = perimeter_initial / EXACT_PERIMETER - 1.0;
        let ue = exact_level_set(shape, mesh, t);
        let (ar, pr) = measures(mesh, &ue)?;
        let (a, p) = measures(mesh, u)?;
        self.final_representation_area = ar - 1.0;
        self.final_representation_perimeter = pr - 1.0;
        self.accumulated_area = a - ar;
        self.accumulated_perimeter = p - pr;
        Ok(())
    }

    /// The table printed by `anisomesh zalesak --sources`.
    pub fn table(&self) -> String {
        let row = |name: &str, a: f64, p: f64| format!("{name:<44} {a:>+11.3e} {p:>+11.3e}\n");
        let mut s = format!(
            "{:<44} {:>11} {:>11}\n",
            "error source (relative)", "area", "perimeter"
        );
        s += &row(
            "initial P1 representation",
            self.initial_area,
            self.initial_perimeter,
        );
        s += &row(
            "final-mesh P1 representation",
            self.final_representation_area,
            self.final_representation_perimeter,
        );
        s += &row(
            "evaluation at feet / transfer (sum of steps)",
            self.transfer_area,
            self.transfer_perimeter,
        );
        s += &row(
            "feet: scheme vs exact (sum of steps)",
            self.foot_area,
            self.foot_perimeter,
        );
        s += &row(
            "redistancing (sum of steps)",
            self.redistance_area,
            self.redistance_perimeter,
        );
        s += &row(
            "accumulated (final u vs I_h u_exact)",
            self.accumulated_area,
            self.accumulated_perimeter,
        );
        s += &format!("largest foot error {:.2e}\n", self.foot_max_distance);
        s
    }
}
