//! MINI-element Stokes: patch test, manufactured convergence, Uzawa vs direct, determinism.

use anisomesh::flows::{stokes_errors, StokesProblem, StokesSolver, Viscosity};
use anisomesh::{DVec2, GridPattern, Mesh2};
use std::f64::consts::PI;

fn skewed_mesh(n: usize) -> Mesh2 {
    let mut m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::UnionJack).unwrap();
    for p in &mut m.points {
        let q = *p;
        let bump = q.x * (1.0 - q.x) * q.y * (1.0 - q.y);
        *p = q + 0.6 * bump * DVec2::new((9.0 * q.y).sin(), (7.0 * q.x).cos());
    }
    m.check().unwrap();
    m
}

#[test]
fn patch_test_reproduces_linear_shear() {
    let mesh = skewed_mesh(9);
    let shear = |p: DVec2| DVec2::new(2.0 * (p.y - 0.5), 0.0);
    let mut pb = StokesProblem::new(&mesh);
    for l in 1..=4 {
        pb = pb.dirichlet(l, &shear);
    }
    for solver in [StokesSolver::Direct, StokesSolver::default()] {
        let (sol, rep) = pb.solve(solver).unwrap();
        let eu = mesh
            .points
            .iter()
            .zip(&sol.velocity)
            .map(|(p, u)| (*u - shear(*p)).length())
            .fold(0.0, f64::max);
        let eb = sol.bubbles.iter().map(|b| b.length()).fold(0.0, f64::max);
        let ep = sol.pressure.iter().map(|p| p.abs()).fold(0.0, f64::max);
        println!("{solver:?}: max |u - u_exact| = {eu:.2e}, max |bubble| = {eb:.2e}, max |p| = {ep:.2e}, {rep:?}");
        assert!(eu < 1e-9 && eb < 1e-9 && ep < 1e-9);
    }
}

fn u_exact(p: DVec2) -> DVec2 {
    let (sx, cx) = (PI * p.x).sin_cos();
    let (sy, cy) = (PI * p.y).sin_cos();
    DVec2::new(sx * cy, -cx * sy)
}

fn p_exact(p: DVec2) -> f64 {
    (PI * p.x).cos() * (PI * p.y).cos()
}

const MU: f64 = 0.5;

fn force(p: DVec2) -> DVec2 {
    let (sx, cx) = (PI * p.x).sin_cos();
    let (sy, cy) = (PI * p.y).sin_cos();
    // -μ Δu + ∇p
    DVec2::new(
        2.0 * MU * PI * PI * sx * cy - PI * sx * cy,
        -2.0 * MU * PI * PI * cx * sy - PI * cx * sy,
    )
}

/// Exact traction σ n = (2μ ε(u) - p I) n on the right side x = 1 (n = e_x).
fn traction_right(p: DVec2) -> DVec2 {
    let (sx, cx) = (PI * p.x).sin_cos();
    let (sy, cy) = (PI * p.y).sin_cos();
    let ux_x = PI * cx * cy;
    let ux_y = -PI * sx * sy;
    let uy_x = PI * sx * sy;
    DVec2::new(2.0 * MU * ux_x - p_exact(p), MU * (ux_y + uy_x))
}

fn manufactured(n: usize, neumann: bool, solver: StokesSolver) -> (f64, f64, usize) {
    let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::Right).unwrap();
    let mut pb = StokesProblem::new(&mesh)
        .viscosity(Viscosity::Constant(MU))
        .force(&force);
    for l in 1..=4 {
        if neumann && l == 2 {
            pb = pb.neumann(2, &traction_right);
        } else {
            pb = pb.dirichlet(l, &u_exact);
        }
    }
    let (sol, rep) = pb.solve(solver).unwrap();
    assert!(rep.converged && rep.residual < 1e-8, "{rep:?}");
    let (eu, ep) = stokes_errors(&mesh, &sol, u_exact, p_exact);
    (eu, ep, rep.uzawa_iterations)
}

fn convergence(neumann: bool) {
    let ns = [8, 16, 32, 64];
    let res: Vec<_> = ns
        .iter()
        .map(|&n| manufactured(n, neumann, StokesSolver::default()))
        .collect();
    println!("\nMINI manufactured solution, neumann on x = 1: {neumann}");
    println!(
        "{:>4} {:>11} {:>5} {:>11} {:>5}",
        "N", "|u|L2", "rate", "|p|L2", "rate"
    );
    for i in 0..ns.len() {
        let (ru, rp) = if i == 0 {
            (f64::NAN, f64::NAN)
        } else {
            (
                (res[i - 1].0 / res[i].0).log2(),
                (res[i - 1].1 / res[i].1).log2(),
            )
        };
        println!(
            "{:>4} {:>11.3e} {:>5.2} {:>11.3e} {:>5.2}",
            ns[i], res[i].0, ru, res[i].1, rp
        );
        if i >= 2 {
            assert!(ru >= 1.9, "velocity L2 rate {ru}");
            assert!(rp >= 1.0, "pressure L2 rate {rp}");
        }
    }
}

#[test]
fn manufactured_solution_converges_dirichlet() {
    convergence(false);
}

#[test]
fn manufactured_solution_converges_with_neumann_side() {
    convergence(true);
}

#[test]
fn uzawa_agrees_with_direct_and_is_thread_count_independent() {
    let mesh = skewed_mesh(24);
    let phi: Vec<f64> = mesh
        .points
        .iter()
        .map(|p| (*p - DVec2::splat(0.5)).length() - 0.2)
        .collect();
    uzawa_vs_direct(
        &mesh,
        Viscosity::TwoPhase {
            phi: phi.clone(),
            mu_in: 1.0,
            mu_out: 1e-3,
            width: 0.0,
        },
    );
    uzawa_vs_direct(
        &mesh,
        Viscosity::TwoPhaseHarmonic {
            phi,
            mu_in: 1.0,
            mu_out: 1e-3,
        },
    );
}

fn uzawa_vs_direct(mesh: &Mesh2, visc: Viscosity) {
    let shear = |p: DVec2| DVec2::new(2.0 * (p.y - 0.5), 0.0);
    let mut pb = StokesProblem::new(mesh)
        .viscosity(visc)
        .force(&|p: DVec2| DVec2::new(0.0, -p.x));
    for l in 1..=4 {
        pb = pb.dirichlet(l, &shear);
    }
    let uzawa = StokesSolver::Uzawa {
        rtol: 1e-12,
        max_iter: 500,
    };
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| pb.solve(uzawa).unwrap())
    };
    let (s1, r1) = run(1);
    let (s2, r2) = run(2);
    assert_eq!(s1, s2, "1 and 2 threads give different results");
    assert_eq!(r1.uzawa_iterations, r2.uzawa_iterations);
    let (sd, rd) = pb.solve(StokesSolver::Direct).unwrap();
    let du = s1
        .velocity
        .iter()
        .zip(&sd.velocity)
        .map(|(a, b)| (*a - *b).length())
        .fold(0.0, f64::max);
    let umax = sd.velocity.iter().map(|u| u.length()).fold(0.0, f64::max);
    let dp = s1
        .pressure
        .iter()
        .zip(&sd.pressure)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let pmax = sd.pressure.iter().map(|p| p.abs()).fold(0.0, f64::max);
    println!(
        "Uzawa {r1:?}\ndirect {rd:?}\nmax du/|u| = {:.2e}, max dp/|p| = {:.2e}",
        du / umax,
        dp / pmax
    );
    assert!(r1.converged && r1.residual < 1e-9 && rd.residual < 1e-10);
    assert!(du < 1e-8 * umax && dp < 1e-7 * pmax);
}
