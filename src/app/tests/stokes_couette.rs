//! Uzawa iteration counts against mesh size and viscosity ratio (the pressure Schur complement
//! preconditioned by the viscosity-weighted pressure mass), the rigid-motion fit, and the
//! Couette disk of 004 §5.1 on a uniform criss-cross mesh.

use crate::app::repro::couette::build_mesh;
use crate::app::repro::couette_sweep::adapted_options;
use anisomesh::flows::{
    negative_fraction, rigid_motion_fit, CouetteCase, InterfaceViscosity, StokesSolver,
};
use anisomesh::{DVec2, GridPattern, Mesh2};

fn criss_cross(n: usize) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::CrissCross).unwrap()
}

/// The Schur-complement preconditioner is the pressure mass matrix weighted by `1/μ_T`
/// (`μ_T` the mean viscosity of the element). Outer iterations (rtol 1e-8) for the Couette
/// disk on criss-cross meshes of growing size and on adapted anisotropic meshes (004 eq. (6),
/// scales 2 and 1 of `bench::couette_sweep`), for viscosity ratios 1, 1e-3, 1e-6, with the
/// harmonic cut-element viscosity (the default) and the quadrature-sign one.
#[test]
fn uzawa_iterations_do_not_grow_with_mesh_or_viscosity_ratio() {
    let solver = StokesSolver::Uzawa {
        rtol: 1e-8,
        max_iter: 1000,
    };
    let mut meshes: Vec<(String, Mesh2)> = [16, 32, 64]
        .iter()
        .map(|&n| (format!("criss-cross {n}"), criss_cross(n)))
        .collect();
    for s in [2.0, 1.0] {
        let o = adapted_options(s, InterfaceViscosity::Harmonic);
        meshes.push((format!("adapted s={s}"), build_mesh(&o).unwrap().0));
    }
    println!("\nUzawa/Schur-CG outer iterations (rtol 1e-8), Couette disk r = 0.1, mu_in = 1");
    println!(
        "{:>16} {:>6} {:>9} | {:>5} {:>5} {:>5} | {:>5} {:>5} {:>5}",
        "mesh", "verts", "max aniso", "h 1", "h 1e3", "h 1e6", "q 1", "q 1e3", "q 1e6"
    );
    let mut harmonic = vec![];
    let mut quadrature = vec![];
    for (name, mesh) in &meshes {
        let mut its = vec![];
        for rule in [InterfaceViscosity::Harmonic, InterfaceViscosity::Quadrature] {
            for mu_out in [1.0, 1e-3, 1e-6] {
                let case = CouetteCase {
                    mu_out,
                    interface: rule,
                    ..Default::default()
                };
                let r = case.solve(mesh, solver).unwrap();
                assert!(
                    r.report.converged && r.report.residual < 1e-6,
                    "{name}: {:?}",
                    r.report
                );
                its.push(r.report.uzawa_iterations);
            }
        }
        println!(
            "{:>16} {:>6} {:>9.0} | {:>5} {:>5} {:>5} | {:>5} {:>5} {:>5}",
            name,
            mesh.n_points(),
            max_aspect_ratio(mesh),
            its[0],
            its[1],
            its[2],
            its[3],
            its[4],
            its[5]
        );
        harmonic.extend_from_slice(&its[..3]);
        quadrature.extend_from_slice(&its[3..]);
    }
    // Criss-cross rows: both rules; the count neither grows with N nor with the ratio.
    let uniform = &harmonic[..9];
    let (lo, hi) = (uniform.iter().min().unwrap(), uniform.iter().max().unwrap());
    assert!(
        *hi <= 40 && *hi <= 2 * lo,
        "criss-cross, harmonic {uniform:?}"
    );
    assert!(quadrature[..9].iter().all(|&i| i <= 40), "{quadrature:?}");
    // Adapted anisotropic meshes: bounded with the harmonic rule; the quadrature-sign rule
    // (viscosity varying inside cut elements) needs more.
    assert!(harmonic.iter().all(|&i| i <= 45), "harmonic {harmonic:?}");
    let (h_ad, q_ad) = (&harmonic[9..], &quadrature[9..]);
    assert!(q_ad.iter().max() > h_ad.iter().max(), "{h_ad:?} {q_ad:?}");
}

/// Largest ratio of longest edge to smallest height over the triangles.
fn max_aspect_ratio(mesh: &Mesh2) -> f64 {
    mesh.live_tris()
        .map(|t| {
            let p = mesh.tri_points(t);
            let lmax = (0..3)
                .map(|i| (p[(i + 1) % 3] - p[i]).length())
                .fold(0.0, f64::max);
            lmax * lmax / (2.0 * mesh.tri_area(t))
        })
        .fold(0.0, f64::max)
}

#[test]
fn negative_fraction_is_the_exact_cut_area() {
    // Corner cut: φ = x + y - 0.5 on the unit right triangle → corner of legs 0.5: area 1/8
    // of the triangle's 1/2, fraction 1/4.
    let f = [-0.5, 0.5, 0.5];
    assert!((negative_fraction(f) - 0.25).abs() < 1e-15);
    assert!((negative_fraction([0.5, -0.5, -0.5]) - 0.75).abs() < 1e-15);
    assert_eq!(negative_fraction([1.0, 2.0, 0.0]), 0.0);
    assert_eq!(negative_fraction([-1.0, -2.0, -3.0]), 1.0);
    assert_eq!(negative_fraction([-1.0, 0.0, 0.0]), 1.0);
    // Against a fine sampling of a skewed cut.
    let f = [-0.3, 0.7, 0.2];
    let n = 2000;
    let mut inside = 0usize;
    let mut total = 0usize;
    for i in 0..n {
        for j in 0..n - i {
            let (l1, l2) = (
                (i as f64 + 1.0 / 3.0) / n as f64,
                (j as f64 + 1.0 / 3.0) / n as f64,
            );
            let l0 = 1.0 - l1 - l2;
            total += 1;
            if l0 * f[0] + l1 * f[1] + l2 * f[2] < 0.0 {
                inside += 1;
            }
        }
    }
    let sampled = inside as f64 / total as f64;
    assert!((negative_fraction(f) - sampled).abs() < 2e-3, "{sampled}");
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
