//! The two-phase Couette flow of 004 §5.1: unit square, a disk of radius 0.1 at the centre with
//! viscosity `μ1 = 1` inside and `μ2 = 1e-6` outside, `u = (2(y - 0.5), 0)` on the whole
//! boundary. The very viscous disk should move as a rigid body. The boundary data is the sum of
//! a rigid rotation `ω = -1` (half the vorticity of the shear) and a pure strain; with the
//! stress-form operator the rotation part is an exact solution, and the strain part cannot
//! turn the centred disk (reflection across the diagonal maps the strain to itself and `ω` to
//! `-ω`), so `ω = -1` exactly whatever the confinement and viscosity ratio, on any mesh
//! symmetric about the diagonal. The informative measure is the rigidity
//! ([`RigidFit::max_deviation_rel`]) from [`rigid_motion_fit`] on the vertices inside the disk.

use super::stokes::{rigid_motion_fit, RigidFit, StokesProblem, StokesReport, StokesSolver};
use super::stokes::{StokesSolution, Viscosity};
use crate::error::Result;
use crate::geom::DVec2;
use crate::mesh::Mesh2;

/// Parameters of the Couette case.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CouetteCase {
    /// Centre of the disk.
    pub centre: DVec2,
    /// Radius of the disk.
    pub radius: f64,
    /// Viscosity inside the disk.
    pub mu_in: f64,
    /// Viscosity of the surrounding fluid.
    pub mu_out: f64,
    /// Smoothed-Heaviside half-width (0 = sharp sign at the quadrature points); used by
    /// [`InterfaceViscosity::Quadrature`] only.
    pub width: f64,
    /// How the triangles cut by the interface get their viscosity.
    pub interface: InterfaceViscosity,
}

/// How the Couette viscosity treats the triangles cut by the interface.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, serde::Serialize)]
pub enum InterfaceViscosity {
    /// One viscosity per triangle, the harmonic mean over the exact areas of the two phases
    /// ([`Viscosity::TwoPhaseHarmonic`]). The default: `ω` depends least on the mesh and the
    /// Uzawa iteration count stays low on anisotropic meshes (measured in
    /// `examples/couette_sweep.rs`).
    #[default]
    Harmonic,
    /// The sign (or the smoothed Heaviside of half-width `width`) of the level set at each
    /// quadrature point ([`Viscosity::TwoPhase`]).
    Quadrature,
}

impl Default for CouetteCase {
    /// The values of 004 §5.1.
    fn default() -> Self {
        CouetteCase {
            centre: DVec2::splat(0.5),
            radius: 0.1,
            mu_in: 1.0,
            mu_out: 1e-6,
            width: 0.0,
            interface: InterfaceViscosity::Harmonic,
        }
    }
}

/// Result of a Couette solve.
#[derive(Debug, Clone)]
pub struct CouetteResult {
    /// The Stokes solution.
    pub solution: StokesSolution,
    /// Statistics of the solve.
    pub report: StokesReport,
    /// Rigid-motion fit on the vertices strictly inside the disk.
    pub fit: RigidFit,
}

impl CouetteCase {
    /// Signed distance to the disk boundary (negative inside), at the mesh vertices.
    pub fn level_set(&self, mesh: &Mesh2) -> Vec<f64> {
        mesh.points
            .iter()
            .map(|p| (*p - self.centre).length() - self.radius)
            .collect()
    }

    /// Solves the case on `mesh` (boundary labels 1..4 all Dirichlet) and fits a rigid motion
    /// inside the disk.
    pub fn solve(&self, mesh: &Mesh2, solver: StokesSolver) -> Result<CouetteResult> {
        self.solve_with(mesh, self.viscosity(self.level_set(mesh)), solver)
    }

    /// The two-phase viscosity of the case for the level set `phi` at the vertices.
    pub fn viscosity(&self, phi: Vec<f64>) -> Viscosity {
        let (mu_in, mu_out) = (self.mu_in, self.mu_out);
        match self.interface {
            InterfaceViscosity::Harmonic => Viscosity::TwoPhaseHarmonic { phi, mu_in, mu_out },
            InterfaceViscosity::Quadrature => Viscosity::TwoPhase {
                phi,
                mu_in,
                mu_out,
                width: self.width,
            },
        }
    }

    /// As [`CouetteCase::solve`] with a given viscosity (e.g. [`Viscosity::PerElement`] from the
    /// sub-domain labels of a body-fitted mesh, whose interface vertices have `φ ≈ 0`).
    pub fn solve_with(
        &self,
        mesh: &Mesh2,
        viscosity: Viscosity,
        solver: StokesSolver,
    ) -> Result<CouetteResult> {
        let shear = |p: DVec2| DVec2::new(2.0 * (p.y - 0.5), 0.0);
        let mut problem = StokesProblem::new(mesh).viscosity(viscosity);
        for label in 1..=4 {
            problem = problem.dirichlet(label, &shear);
        }
        let (solution, report) = problem.solve(solver)?;
        let (c, r) = (self.centre, self.radius);
        // Strictly inside, with a relative margin so that vertices on the circle are excluded
        // whichever way their distance rounds (keeps the fitted set symmetric).
        let fit = rigid_motion_fit(mesh, &solution.velocity, |p| {
            (p - c).length() < r * (1.0 - 1e-9)
        })?;
        Ok(CouetteResult {
            solution,
            report,
            fit,
        })
    }
}
