//! Exactness properties of the characteristics-Galerkin scheme (004 eq. (2)), the transfer and
//! the mass correction (004 §5.1).

use anisomesh::advect::fixed_point::{advance_period, FixedPointOptions, IdentityAdapter};
use anisomesh::advect::transfer::{integral, interpolate, project};
use anisomesh::advect::{
    advect, correct_mass, enclosed_area, AdvectOptions, FootOptions, FootScheme, Form, Inflow,
    Interpolation,
};
use anisomesh::{DVec2, GridPattern, Mesh2};
use std::sync::Arc;

fn lin(p: DVec2) -> f64 {
    0.7 * p.x - 1.3 * p.y + 0.25
}

fn max_err(mesh: &Mesh2, u: &[f64], f: impl Fn(DVec2) -> f64) -> f64 {
    mesh.points
        .iter()
        .zip(u)
        .map(|(&p, &v)| (v - f(p)).abs())
        .fold(0.0, f64::max)
}

#[test]
fn translation_reproduces_constant_and_linear_fields() {
    let mesh = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        24,
        24,
        GridPattern::UnionJack,
    )
    .unwrap();
    let d = DVec2::new(0.13, -0.07);
    let v = move |_t: f64, _x: DVec2| d; // unit time: the foot of x is x - d, exactly.
    for interp in [Interpolation::P1, Interpolation::QUADRATIC] {
        for form in [Form::Nodal, Form::L2Projection { subdivisions: 0 }] {
            for (scheme, limit) in [
                (FootScheme::Euler, false),
                (FootScheme::Midpoint, false),
                (FootScheme::Rk4, false),
                (FootScheme::Rk4, true),
            ] {
                let opts = AdvectOptions {
                    foot: FootOptions {
                        scheme,
                        substeps: 3,
                    },
                    interp,
                    form,
                    inflow: Inflow::Function(Arc::new(move |p: DVec2| lin(p))),
                    cg_tol: 1e-14,
                    limit,
                };
                let c = vec![2.5; mesh.n_points()];
                let opts_c = AdvectOptions {
                    inflow: Inflow::Constant(2.5),
                    ..opts.clone()
                };
                let uc2 = advect(&mesh, &c, &mesh, &v, 0.0, 1.0, &opts_c).unwrap();
                let ec2 = max_err(&mesh, &uc2, |_| 2.5);
                let u0: Vec<f64> = mesh.points.iter().map(|&p| lin(p)).collect();
                let u1 = advect(&mesh, &u0, &mesh, &v, 0.0, 1.0, &opts).unwrap();
                let el = max_err(&mesh, &u1, |p| lin(p - d));
                let tol = if form == Form::Nodal { 1e-12 } else { 1e-9 };
                assert!(
                    ec2 < 1e-13 && el < tol,
                    "{interp:?} {form:?} {scheme:?}: constant {ec2}, linear {el}"
                );
            }
        }
    }
}

#[test]
fn transfer_of_a_linear_field_between_different_meshes_is_exact() {
    let lo = DVec2::new(-1.0, -0.5);
    let hi = DVec2::new(2.0, 1.5);
    let a = Mesh2::rectangle(lo, hi, 17, 13, GridPattern::Right).unwrap();
    let mut b = Mesh2::rectangle(lo, hi, 11, 19, GridPattern::CrissCross).unwrap();
    // Perturb the interior vertices of b so that no vertex of b is a vertex of a.
    let flags = b.boundary_vertex_flags();
    for (i, p) in b.points.iter_mut().enumerate() {
        if !flags[i] {
            *p += 0.011 * DVec2::new((i as f64 * 1.7).sin(), (i as f64 * 2.3).cos());
        }
    }
    b.check().unwrap();
    let ua: Vec<f64> = a.points.iter().map(|&p| lin(p)).collect();
    for interp in [Interpolation::P1, Interpolation::QUADRATIC] {
        let ub = interpolate(&a, &ua, &b, interp, Inflow::Nearest).unwrap();
        let e = max_err(&b, &ub, lin);
        assert!(e < 1e-12, "{interp:?}: interpolation error {e}");
        let ub = project(&a, &ua, &b, interp, 1, Inflow::Nearest).unwrap();
        let e = max_err(&b, &ub, lin);
        assert!(e < 1e-9, "{interp:?}: projection error {e}");
        assert!((integral(&b, &ub) - integral(&a, &ua)).abs() < 1e-9);
    }
}

#[test]
fn conservative_transfer_keeps_the_integral_to_quadrature_accuracy() {
    let lo = DVec2::splat(-1.0);
    let a = Mesh2::rectangle(lo, -lo, 40, 40, GridPattern::Right).unwrap();
    let b = Mesh2::rectangle(lo, -lo, 29, 33, GridPattern::Left).unwrap();
    let f = |p: DVec2| (p - DVec2::new(0.2, 0.1)).length() - 0.5;
    let ua: Vec<f64> = a.points.iter().map(|&p| f(p)).collect();
    let ia = integral(&a, &ua);
    let interp = interpolate(&a, &ua, &b, Interpolation::P1, Inflow::Nearest).unwrap();
    let e_interp = (integral(&b, &interp) - ia).abs();
    let mut errs = Vec::new();
    for s in 0..3 {
        let ub = project(&a, &ua, &b, Interpolation::P1, s, Inflow::Nearest).unwrap();
        errs.push((integral(&b, &ub) - ia).abs());
    }
    // Measured: interpolation ~1e-4, projection ~1e-5 (s = 0) falling ~4x per subdivision.
    assert!(
        errs[0] < 0.3 * e_interp,
        "projection {errs:?} vs interpolation {e_interp}"
    );
    assert!(
        errs[2] < 0.2 * errs[0],
        "subdivisions do not help: {errs:?}"
    );
}

#[test]
fn mass_correction_restores_the_area() {
    let lo = DVec2::splat(-1.0);
    let m = Mesh2::rectangle(lo, -lo, 50, 50, GridPattern::UnionJack).unwrap();
    let mut u: Vec<f64> = m
        .points
        .iter()
        .map(|&p| (p - DVec2::new(0.1, -0.2)).length() - 0.45 + 0.01 * (3.0 * p.x).sin())
        .collect();
    for target in [0.5, 0.63, 0.7] {
        let mut w = u.clone();
        let r = correct_mass(&m, &mut w, target, 1e-14).unwrap();
        let a = enclosed_area(&m, &w).unwrap();
        assert!(
            ((a - target) / target).abs() < 1e-12,
            "area {a} vs {target}"
        );
        assert!(r.iterations < 60, "{} evaluations", r.iterations);
    }
    assert!(correct_mass(&m, &mut u, 5.0, 1e-13).is_err());
}

#[test]
fn fixed_point_on_a_fixed_mesh_is_one_advection() {
    let lo = DVec2::splat(-1.0);
    let m = Mesh2::rectangle(lo, -lo, 30, 30, GridPattern::UnionJack).unwrap();
    let u: Vec<f64> = m
        .points
        .iter()
        .map(|&p| (p - DVec2::new(0.4, 0.0)).length() - 0.3)
        .collect();
    let v = anisomesh::advect::Rotation { omega: 1.0 };
    let mut opts = FixedPointOptions::default();
    opts.advect.form = Form::Nodal;
    let r = advance_period(&m, &u, &v, 0.0, 0.4, &mut IdentityAdapter, &opts).unwrap();
    let direct = advect(&m, &u, &m, &v, 0.0, 0.4, &opts.advect).unwrap();
    assert_eq!(r.iterations, 1);
    assert!(r.converged && r.l1_changes[0] < 1e-14);
    assert!(max_err(&m, &r.u, |_| 0.0) > 0.0);
    let diff =
        r.u.iter()
            .zip(&direct)
            .map(|(a, b)| (a - b).abs())
            .fold(0.0, f64::max);
    assert!(diff < 1e-15);
}
