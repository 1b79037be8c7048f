//! Two-phase Stokes flow on a mesh adapted to the interface (Couette flow of 004 §5.1).
//!
//! A disk of radius 0.1 at the centre of the unit square is a million times more viscous than
//! the fluid around it; the walls impose the shear `u = (2(y - 0.5), 0)`. The disk turns as a
//! rigid body with angular velocity `ω = -1` exactly. The mesh is adapted to the disk's signed
//! distance (004 eq. (6)); the MINI element (P1-bubble / P1) is solved by Uzawa iterations
//! with the viscosity of each cut triangle the harmonic mean over the two phases.
//!
//! `cargo run --release --example stokes_two_phase`

use anisomesh::flows::{CouetteCase, StokesSolver};
use anisomesh::levelset::Circle;
use anisomesh::prelude::*;

fn main() -> anisomesh::Result<()> {
    let case = CouetteCase::default();
    let disk = Circle {
        centre: case.centre,
        radius: case.radius,
    };
    let options = RunOptions {
        metric: LevelSetMetric {
            hmax: 0.06,
            band: 1e-3,
            grade: 0.3,
            ..LevelSetMetric::default()
        },
        ..RunOptions::default()
    };
    let unit_square = (DVec2::ZERO, DVec2::ONE);
    let adapted = adapt::run(AdaptTarget::shape(disk, unit_square), &options)?;
    let flow = case.solve(&adapted.mesh, StokesSolver::default())?;
    println!(
        "{} vertices, {} Uzawa iterations: omega = {:.6} (exact -1), rigidity {:.1e}",
        adapted.mesh.n_points(),
        flow.report.uzawa_iterations,
        flow.fit.omega,
        flow.fit.max_deviation_rel
    );
    Ok(())
}
