//! The energy balance of the Stefan loop (001 §6): with latent heat 1 and insulated walls
//! `∫T − A` is conserved. The plain loop (P1-mean one-sided gradients, the base vertices keeping
//! their values) gains heat: the front's latent heat falls short of the heat the interface
//! condition supplies. The residual velocity with the conservative transfer balances the two.

use anisomesh::backends::fitted::{
    pentagon_seed, stefan_step, Coefficient, StefanBudget, StefanFlux, StefanOptions, StefanState,
};
use anisomesh::fem::p1::lumped_mass;
use anisomesh::levelset::interface::enclosed_area;
use anisomesh::mesh::{GridPattern, Mesh2};
use anisomesh::DVec2;

const N: usize = 64;
const HALF: f64 = 1.5;
const DT: f64 = 5e-4;
const STEPS: usize = 100;

/// `(∫T − A)` at the end minus at the start, the budget's sum of the terms, the solid area
/// grown; the pentagon of circumradius 0.2 on 65² base vertices of (−1.5, 1.5)², ε_C = 0.001,
/// `STEPS` steps of `DT`, redistancing that keeps the interface.
fn run(flux: StefanFlux, conservative: bool) -> (f64, StefanBudget, f64) {
    let base = Mesh2::rectangle(
        DVec2::new(-HALF, -HALF),
        DVec2::new(HALF, HALF),
        N,
        N,
        GridPattern::UnionJack,
    )
    .unwrap();
    let phi = pentagon_seed(&base, 0.2).unwrap();
    let temperature = phi
        .iter()
        .map(|&f| if f < 0.0 { 0.0 } else { -0.5 })
        .collect();
    let mut st = StefanState::new(phi, temperature, 0.0);
    let h = 2.0 * HALF / N as f64;
    let mut o = StefanOptions::new(DT, h);
    o.keep_interface = true;
    o.flux = flux;
    o.conservative_transfer = conservative;
    o.eps_c = Coefficient {
        mean: 1e-3,
        ..Coefficient::ZERO
    };
    let mass = lumped_mass(&base).unwrap();
    let energy = |st: &StefanState| {
        let heat: f64 = mass.iter().zip(&st.temperature).map(|(m, t)| m * t).sum();
        (heat, enclosed_area(&base, &st.phi).unwrap())
    };
    let (h0, a0) = energy(&st);
    let mut budget = StefanBudget::default();
    for _ in 0..STEPS {
        let r = stefan_step(&base, &mut st, &o).unwrap();
        budget = budget.add(&r.budget);
    }
    let (h1, a1) = energy(&st);
    ((h1 - a1) - (h0 - a0), budget, a1 - a0)
}

#[test]
fn the_residual_velocity_with_the_conservative_transfer_conserves_the_energy() {
    let (plain, bp, grown_p) = run(StefanFlux::P1Mean, false);
    let (cons, bc, grown_c) = run(
        StefanFlux::Residual {
            smoothing_passes: 8,
        },
        true,
    );
    for (name, drift, b, grown) in [
        ("P1 mean, plain transfer", plain, bp, grown_p),
        ("residual, conservative", cons, bc, grown_c),
    ] {
        println!(
            "{name}: drift {drift:.3e} ({:.2} % of the area grown {grown:.4}); {b:?}",
            100.0 * drift / grown
        );
        // The budget accounts for every change of the energy.
        assert!(
            (b.energy_change() - drift).abs() < 1e-9,
            "{name}: budget {} against {drift}",
            b.energy_change()
        );
    }
    // The conservative scheme: the transfer keeps ∫T, the front's latent heat is the heat the
    // interface supplied, and the drift is a small fraction of the area grown.
    assert!(bc.transfer_out.abs() < 1e-10, "{bc:?}");
    assert!(
        (bc.front_heat - bc.interface_heat).abs() < 0.02 * bc.interface_heat,
        "{bc:?}"
    );
    assert!(cons.abs() < 0.01 * grown_c, "drift {cons} of {grown_c}");
    // The plain loop's drift is several times larger.
    assert!(plain > 5.0 * cons.abs(), "{plain} against {cons}");
}
