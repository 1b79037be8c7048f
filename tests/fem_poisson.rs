//! P1 Poisson convergence on the unit square with a manufactured solution
//! `u = sin(πx) sin(πy) + x²`: the L2 error must decrease at order 2 and the H1 seminorm error at
//! order 1 (each within 0.1), with PCG (IC(0) and Jacobi) and with the sparse direct solver, for
//! the Laplacian and for a constant anisotropic tensor coefficient. The convergence table is
//! printed (run with `--nocapture` to see it).

use anisomesh::fem::dirichlet::{apply_dirichlet, boundary_mask};
use anisomesh::fem::p1::{self, Coef};
use anisomesh::fem::solve::{cg, solve_spd, CgOptions, PrecondKind};
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};
use std::f64::consts::PI;

fn u(p: DVec2) -> f64 {
    (PI * p.x).sin() * (PI * p.y).sin() + p.x * p.x
}

fn grad_u(p: DVec2) -> DVec2 {
    let (sx, cx) = (PI * p.x).sin_cos();
    let (sy, cy) = (PI * p.y).sin_cos();
    DVec2::new(PI * cx * sy + 2.0 * p.x, PI * sx * cy)
}

/// `-div(K ∇u)` for a constant tensor `K`.
fn rhs(k: Sym2, p: DVec2) -> f64 {
    let (sx, cx) = (PI * p.x).sin_cos();
    let (sy, cy) = (PI * p.y).sin_cos();
    let uxx = -PI * PI * sx * sy + 2.0;
    let uyy = -PI * PI * sx * sy;
    let uxy = PI * PI * cx * cy;
    -(k.xx * uxx + 2.0 * k.xy * uxy + k.yy * uyy)
}

#[derive(Clone, Copy, Debug)]
enum Solver {
    Cg(PrecondKind),
    Direct,
}

struct Row {
    cells: usize,
    dofs: usize,
    l2: f64,
    h1: f64,
    iterations: usize,
}

fn solve_poisson(n: usize, k: Sym2, tensor: bool, solver: Solver) -> Row {
    let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::Right).unwrap();
    let ks = vec![k; mesh.n_tris()];
    let coef = if tensor {
        Coef::Tensor(&ks)
    } else {
        Coef::Const(k.xx)
    };
    let mut a = p1::stiffness(&mesh, &coef).unwrap();
    let mut b = p1::load(&mesh, |p| rhs(k, p)).unwrap();
    let fixed = boundary_mask(&mesh, &[]);
    let g = p1::interpolate(&mesh, u);
    apply_dirichlet(&mut a, &mut b, &fixed, &g).unwrap();
    assert!(a.asymmetry() < 1e-14);
    let (uh, iterations) = match solver {
        Solver::Cg(pk) => {
            let mut x = vec![0.0; mesh.n_points()];
            let opts = CgOptions {
                rtol: 1e-12,
                precond: pk,
                ..Default::default()
            };
            let rep = cg(&a, &b, &mut x, &opts).unwrap();
            assert!(rep.converged, "{rep:?}");
            (x, rep.iterations)
        }
        Solver::Direct => (solve_spd(&a, &b).unwrap(), 0),
    };
    Row {
        cells: mesh.n_tris(),
        dofs: mesh.n_points(),
        l2: p1::l2_error(&mesh, &uh, u).unwrap(),
        h1: p1::h1_seminorm_error(&mesh, &uh, grad_u).unwrap(),
        iterations,
    }
}

/// Runs the sequence of meshes, prints the table, returns the (L2, H1) rates between
/// consecutive meshes.
fn convergence(label: &str, k: Sym2, tensor: bool, solver: Solver) -> Vec<(f64, f64)> {
    let rows: Vec<Row> = [8, 16, 32, 64, 128]
        .iter()
        .map(|&n| solve_poisson(n, k, tensor, solver))
        .collect();
    println!("\n{label} ({solver:?})");
    println!(
        "{:>7} {:>7} {:>11} {:>5} {:>11} {:>5} {:>6}",
        "cells", "dofs", "L2", "rate", "H1-semi", "rate", "iters"
    );
    let mut rates = vec![];
    for (i, r) in rows.iter().enumerate() {
        let (rl, rh) = if i == 0 {
            (f64::NAN, f64::NAN)
        } else {
            let p = &rows[i - 1];
            ((p.l2 / r.l2).log2(), (p.h1 / r.h1).log2())
        };
        if i > 0 {
            rates.push((rl, rh));
        }
        println!(
            "{:>7} {:>7} {:>11.3e} {:>5.2} {:>11.3e} {:>5.2} {:>6}",
            r.cells, r.dofs, r.l2, rl, r.h1, rh, r.iterations
        );
    }
    rates
}

fn assert_rates(rates: &[(f64, f64)]) {
    for &(rl, rh) in rates {
        assert!((rl - 2.0).abs() <= 0.1, "L2 rate {rl} (rates {rates:?})");
        assert!((rh - 1.0).abs() <= 0.1, "H1 rate {rh} (rates {rates:?})");
    }
}

#[test]
fn poisson_converges_with_ic0_cg() {
    assert_rates(&convergence(
        "Laplacian",
        Sym2::IDENTITY,
        false,
        Solver::Cg(PrecondKind::Ic0),
    ));
}

#[test]
fn poisson_converges_with_direct_solver() {
    assert_rates(&convergence(
        "Laplacian",
        Sym2::IDENTITY,
        false,
        Solver::Direct,
    ));
}

#[test]
fn poisson_converges_with_jacobi_cg_and_tensor_coefficient() {
    let k = Sym2::new(2.0, 0.6, 0.5);
    assert_rates(&convergence(
        "tensor K = [[2, 0.6], [0.6, 0.5]]",
        k,
        true,
        Solver::Cg(PrecondKind::Jacobi),
    ));
    assert_rates(&convergence(
        "tensor K = [[2, 0.6], [0.6, 0.5]]",
        k,
        true,
        Solver::Direct,
    ));
}

#[test]
fn cg_and_direct_agree_and_ic0_beats_jacobi() {
    let iters = |pk| solve_poisson(64, Sym2::IDENTITY, false, Solver::Cg(pk));
    let (ic, jac) = (iters(PrecondKind::Ic0), iters(PrecondKind::Jacobi));
    let direct = solve_poisson(64, Sym2::IDENTITY, false, Solver::Direct);
    println!(
        "N = 64: IC(0) {} iterations, Jacobi {} iterations",
        ic.iterations, jac.iterations
    );
    assert!(ic.iterations * 2 < jac.iterations);
    assert!((ic.l2 - direct.l2).abs() < 1e-9 * direct.l2);
    assert!((jac.l2 - direct.l2).abs() < 1e-9 * direct.l2);
}
