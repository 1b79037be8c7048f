//! Uzawa iteration counts against mesh size and viscosity ratio (the pressure Schur complement
//! preconditioned by the viscosity-weighted pressure mass), the rigid-motion fit, and the
//! Couette disk of 004 §5.1 on a uniform criss-cross mesh.

use anisomesh::flows::{rigid_motion_fit, CouetteCase, StokesSolver};
use anisomesh::{DVec2, GridPattern, Mesh2};

fn criss_cross(n: usize) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::CrissCross).unwrap()
}

#[test]
fn uzawa_iterations_do_not_grow_with_mesh_or_viscosity_ratio() {
    let solver = StokesSolver::Uzawa {
        rtol: 1e-8,
        max_iter: 1000,
    };
    println!("\nUzawa/Schur-CG outer iterations (rtol 1e-8), Couette disk r = 0.1, mu_in = 1");
    println!(
        "{:>4} {:>8} {:>12} {:>12} {:>12}",
        "N", "verts", "ratio 1", "ratio 1e3", "ratio 1e6"
    );
    let mut all = vec![];
    for n in [16, 32, 64] {
        let mesh = criss_cross(n);
        let its: Vec<usize> = [1.0, 1e-3, 1e-6]
            .iter()
            .map(|&mu_out| {
                let case = CouetteCase {
                    mu_out,
                    ..Default::default()
                };
                let r = case.solve(&mesh, solver).unwrap();
                assert!(
                    r.report.converged && r.report.residual < 1e-6,
                    "{:?}",
                    r.report
                );
                r.report.uzawa_iterations
            })
            .collect();
        println!(
            "{:>4} {:>8} {:>12} {:>12} {:>12}",
            n,
            mesh.n_points(),
            its[0],
            its[1],
            its[2]
        );
        all.extend(its);
    }
    let (lo, hi) = (*all.iter().min().unwrap(), *all.iter().max().unwrap());
    assert!(hi <= 40 && hi <= 2 * lo, "iteration counts {all:?}");
}

#[test]
fn rigid_fit_recovers_an_exact_rigid_motion() {
    let mesh = criss_cross(20);
    let (c0, omega, t) = (DVec2::new(0.4, 0.55), 0.7, DVec2::new(-0.3, 1.2));
    let u: Vec<DVec2> = mesh
        .points
        .iter()
        .map(|&p| t + omega * (p - c0).perp())
        .collect();
    let inside = |p: DVec2| (p - DVec2::new(0.45, 0.5)).length() < 0.2;
    let fit = rigid_motion_fit(&mesh, &u, inside).unwrap();
    assert!((fit.omega - omega).abs() < 1e-13, "{fit:?}");
    let expect_t = t + omega * (fit.centre - c0).perp();
    assert!((fit.translation - expect_t).length() < 1e-13);
    assert!(fit.max_deviation_rel < 1e-13);
    // A shear is not rigid: large deviation.
    let shear: Vec<DVec2> = mesh.points.iter().map(|p| DVec2::new(p.y, 0.0)).collect();
    assert!(
        rigid_motion_fit(&mesh, &shear, inside)
            .unwrap()
            .max_deviation_rel
            > 0.1
    );
    assert!(rigid_motion_fit(&mesh, &u, |_| false).is_err());
}

#[test]
fn couette_disk_moves_rigidly() {
    let mesh = criss_cross(40);
    let case = CouetteCase::default();
    let uz = case.solve(&mesh, StokesSolver::default()).unwrap();
    let sheared = CouetteCase {
        mu_out: 1.0,
        ..Default::default()
    }
    .solve(&mesh, StokesSolver::default())
    .unwrap();
    println!("Couette 40x40 criss-cross: {:?}\n{:?}", uz.fit, uz.report);
    println!("same with mu_out = mu_in: {:?}", sheared.fit);
    // ω = -1 by symmetry (see flows::couette); the disk is rigid to about the viscosity ratio.
    assert!((uz.fit.omega + 1.0).abs() < 1e-6);
    assert!(uz.fit.translation.length() < 1e-8);
    assert!(uz.fit.max_deviation_rel < 1e-4);
    assert!(sheared.fit.max_deviation_rel > 0.3);
}
