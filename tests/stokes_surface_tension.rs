//! Surface tension (interface condition (8) of 004 with `K = γ κ`): a static circular drop
//! must carry the Laplace pressure jump `p_in - p_out = γ / R`, with small spurious velocities.

use anisomesh::flows::{StokesProblem, StokesSolver, Viscosity};
use anisomesh::{DVec2, GridPattern, Mesh2};

#[test]
fn static_drop_has_laplace_pressure_jump() {
    let (r, gamma) = (0.25, 1.0);
    println!(
        "\nstatic drop R = {r}, gamma = {gamma}: expected jump {}",
        gamma / r
    );
    let mut errs = vec![];
    let mut umaxs = vec![];
    for n in [16, 32, 64] {
        let mesh =
            Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::CrissCross).unwrap();
        let c = DVec2::splat(0.5);
        let phi: Vec<f64> = mesh.points.iter().map(|p| (*p - c).length() - r).collect();
        let zero = |_: DVec2| DVec2::ZERO;
        let mut pb = StokesProblem::new(&mesh)
            .viscosity(Viscosity::TwoPhase {
                phi: phi.clone(),
                mu_in: 1.0,
                mu_out: 1.0,
                width: 0.0,
            })
            .surface_tension(gamma);
        for l in 1..=4 {
            pb = pb.dirichlet(l, &zero);
        }
        let (sol, rep) = pb.solve(StokesSolver::default()).unwrap();
        assert!(rep.converged);
        let mean = |sel: &dyn Fn(f64) -> bool| {
            let v: Vec<f64> = (0..mesh.n_points())
                .filter(|&i| sel(phi[i]))
                .map(|i| sol.pressure[i])
                .collect();
            v.iter().sum::<f64>() / v.len() as f64
        };
        let jump = mean(&|f| f < -0.1) - mean(&|f| f > 0.1);
        let umax = sol.velocity.iter().map(|u| u.length()).fold(0.0, f64::max);
        println!(
            "N {n}: jump {jump:.5} (rel. error {:.2e}), max |u| {umax:.2e}",
            (jump - gamma / r) / (gamma / r)
        );
        errs.push(((jump - gamma / r) / (gamma / r)).abs());
        assert!(umax < 0.05 * gamma);
        umaxs.push(umax);
    }
    assert!(errs.iter().all(|&e| e < 1e-2), "{errs:?}");
    // spurious currents shrink with h
    assert!(umaxs.windows(2).all(|w| w[1] < 0.8 * w[0]), "{umaxs:?}");
}
