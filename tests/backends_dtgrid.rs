//! The DT-Grid narrow-band back end through the level-set back-end contract: a sphere shrinking
//! by mean curvature against R(t) = √(R0² − 4t) with its order between two grids, volume and
//! position under a rigid rotation, redistancing, curvature, point values, and the typed errors;
//! the band heat equation of 000 Table 2.1 with second-order time stepping (BDF2): its order in
//! time and its spatial order with transparent conditions.

use anisomesh::backends::{BuildSpec, DtGridBackend, DtGridOptions, LevelSetBackend, D3};
use anisomesh::{DVec3, Error};
use std::f64::consts::PI;

const LO: DVec3 = DVec3::splat(-0.5);
const HI: DVec3 = DVec3::splat(0.5);

fn build(f: &(dyn Fn(DVec3) -> f64 + Send + Sync), h: f64) -> anisomesh::Result<DtGridBackend> {
    <DtGridBackend as LevelSetBackend<D3>>::build(&BuildSpec {
        function: f,
        domain: (LO, HI),
        resolution: h,
    })
}

/// The radius of the ball with the back end's enclosed volume.
fn radius(b: &DtGridBackend) -> f64 {
    (3.0 * b.enclosed_measure().unwrap() / (4.0 * PI)).cbrt()
}

/// Mean of `||∇u| − 1|` by central differences of `evaluate` at points within `w` of the zero
/// level of a sphere `(c, r)` (points on rays through the centre).
fn gradient_defect(b: &DtGridBackend, c: DVec3, r: f64, w: f64) -> f64 {
    let e = 1e-3;
    let mut sum = 0.0;
    let mut count = 0;
    for i in 0..40 {
        let (th, ph) = (
            0.7 + i as f64 * 2.39996,
            (i as f64 / 40.0 * 2.0 - 1.0).asin(),
        );
        let d = DVec3::new(ph.cos() * th.cos(), ph.cos() * th.sin(), ph.sin());
        for s in [-w, 0.0, w] {
            let p = c + (r + s) * d;
            let q: Vec<DVec3> = (0..3)
                .flat_map(|a| {
                    let mut o = DVec3::ZERO;
                    o[a] = e;
                    [p + o, p - o]
                })
                .collect();
            let v = b.evaluate(&q).unwrap();
            if v.iter().any(|x| x.is_none()) {
                continue;
            }
            let g = DVec3::new(
                v[0].unwrap() - v[1].unwrap(),
                v[2].unwrap() - v[3].unwrap(),
                v[4].unwrap() - v[5].unwrap(),
            ) / (2.0 * e);
            sum += (g.length() - 1.0).abs();
            count += 1;
        }
    }
    assert!(count > 60, "{count} points evaluated");
    sum / count as f64
}

#[test]
fn sphere_shrinks_by_mean_curvature_at_first_order() {
    let (r0, t_end): (f64, f64) = (0.25, 0.0059);
    let c = DVec3::new(0.02, -0.01, 0.03);
    let exact = (r0 * r0 - 4.0 * t_end).sqrt();
    let mut errors = Vec::new();
    for h in [1.0 / 16.0, 1.0 / 32.0] {
        let f = move |p: DVec3| (p - c).length() - r0;
        let mut b = build(&f, h).unwrap();
        for _ in 0..2 {
            let rep = b.advance_mean_curvature(0.5 * t_end).unwrap();
            assert!(rep.inner_iterations >= 1 && rep.dof == b.dof());
        }
        assert!((b.time() - t_end).abs() < 1e-15);
        let r = radius(&b);
        errors.push((r - exact).abs());
        eprintln!("h = {h}: radius {r:.5}, exact {exact:.5}, dof {}", b.dof());
    }
    let order = (errors[0] / errors[1]).log2();
    eprintln!("errors {errors:?}, order {order:.2}");
    assert!(order >= 1.0, "order {order} ({errors:?})");
    assert!(errors[1] < 0.25 / 32.0, "{errors:?}");
}

#[test]
fn rigid_rotation_keeps_volume_and_moves_the_centre() {
    let (r, c0) = (0.15, DVec3::new(0.2, 0.0, 0.0));
    let f = move |p: DVec3| (p - c0).length() - r;
    let h = 1.0 / 32.0;
    let mut b = build(&f, h).unwrap();
    let v0 = b.enclosed_measure().unwrap();
    let v = |_t: f64, p: DVec3| DVec3::new(-p.y, p.x, 0.0);
    let rep = b.advect(&v, 0.5 * PI).unwrap();
    assert!(rep.inner_iterations > 10);
    let v1 = b.enclosed_measure().unwrap();
    let rel = (v1 / v0 - 1.0).abs();
    let s = b.zero_level().unwrap();
    let centre = s.points.iter().copied().sum::<DVec3>() / s.points.len() as f64;
    let moved = (centre - DVec3::new(0.0, 0.2, 0.0)).length();
    eprintln!("volume change {rel:.3e}, centre off by {moved:.3e}");
    assert!(rel < 0.01, "volume change {rel}");
    assert!(moved < 0.25 * h, "centre {centre:?}");
}

#[test]
fn redistance_restores_unit_gradient() {
    let (r, c) = (0.2, DVec3::ZERO);
    let f = move |p: DVec3| (p - c).length() - r;
    let mut b = build(&f, 1.0 / 32.0).unwrap();
    let before_build = gradient_defect(&b, c, r, 0.03);
    // A radial stretching velocity v = x / (2 |x|²)·... keeps the sphere a sphere but makes u
    // steeper than a distance: v = 0.5 x moves the radius as r e^{t/2}.
    let v = |_t: f64, p: DVec3| 0.5 * p;
    b.advect(&v, 0.2).unwrap();
    let r1 = r * (0.1f64).exp();
    let stretched = gradient_defect(&b, c, r1, 0.03);
    b.redistance().unwrap();
    let after = gradient_defect(&b, c, r1, 0.03);
    eprintln!(
        "|∇u|−1: built {before_build:.2e}, advected {stretched:.2e}, redistanced {after:.2e}"
    );
    assert!(
        before_build < 0.02 && after < 0.02,
        "{before_build} {after}"
    );
    assert!(stretched > 3.0 * after, "{stretched} {after}");
    assert!(
        (radius(&b) / r1 - 1.0).abs() < 0.02,
        "radius {}",
        radius(&b)
    );
}

#[test]
fn curvature_area_and_values_of_a_sphere() {
    let (r, c) = (0.3, DVec3::new(0.01, 0.02, -0.03));
    let f = move |p: DVec3| (p - c).length() - r;
    let b = build(&f, 1.0 / 40.0).unwrap();
    let k = b.interface_curvature().unwrap();
    let area = b.interface_measure().unwrap();
    eprintln!(
        "curvature mean {:.4} (exact {:.4}), max rel error {:.3e}; area rel error {:.2e}",
        k.mean(),
        2.0 / r,
        k.max_rel_error(2.0 / r),
        area / (4.0 * PI * r * r) - 1.0
    );
    assert!((k.mean() * r / 2.0 - 1.0).abs() < 0.01);
    assert!(k.max_rel_error(2.0 / r) < 0.05);
    assert!((area / (4.0 * PI * r * r) - 1.0).abs() < 0.01);
    for p in &k.points {
        assert!(((*p - c).length() - r).abs() < 0.01);
    }
    let v = b
        .evaluate(&[c, c + DVec3::new(r + 0.01, 0.0, 0.0), DVec3::splat(0.6)])
        .unwrap();
    assert_eq!(v[0], None, "the centre is outside the band");
    assert!((v[1].unwrap() - 0.01).abs() < 2e-3, "{v:?}");
    assert_eq!(v[2], None, "outside the domain");
    let s = b.zero_level().unwrap();
    assert!((s.enclosed_volume() - b.enclosed_measure().unwrap()).abs() < 1e-9);
}

#[test]
fn typed_errors() {
    let h = 1.0 / 16.0;
    // No zero level.
    let none = |p: DVec3| p.length() + 1.0;
    assert!(matches!(build(&none, h), Err(Error::EmptyLevelSet(_))));
    // NaN in the function.
    let nan = |p: DVec3| {
        if p.x > 0.2 {
            f64::NAN
        } else {
            p.length() - 0.3
        }
    };
    assert!(matches!(build(&nan, h), Err(Error::InvalidField { .. })));
    // A sphere whose band does not fit in the grid.
    let big = |p: DVec3| p.length() - 0.46;
    assert!(matches!(build(&big, h), Err(Error::InvalidInput(_))));
    // A band wider than the grid.
    let small = |p: DVec3| p.length() - 0.2;
    assert!(matches!(build(&small, 0.25), Err(Error::InvalidInput(_))));
    // A box thinner than the shape along z.
    let spec = BuildSpec::<D3> {
        function: &small,
        domain: (DVec3::new(-0.5, -0.5, -0.1), DVec3::new(0.5, 0.5, 0.1)),
        resolution: h,
    };
    assert!(matches!(
        DtGridBackend::new(&spec, DtGridOptions::default()),
        Err(Error::InvalidInput(_))
    ));
    // A sphere that vanishes during the motion (R0² / 4 = 0.0025).
    let tiny = |p: DVec3| p.length() - 0.1;
    let mut b = build(&tiny, 1.0 / 32.0).unwrap();
    assert!(matches!(
        b.advance_mean_curvature(0.004),
        Err(Error::EmptyLevelSet(_))
    ));
    // Bad time steps and velocities.
    let mut b = build(&small, h).unwrap();
    assert!(matches!(
        b.advance_mean_curvature(f64::NAN),
        Err(Error::InvalidInput(_))
    ));
    let bad = |_t: f64, p: DVec3| if p.x > 0.0 { DVec3::NAN } else { DVec3::X };
    assert!(matches!(
        b.advect(&bad, 0.01),
        Err(Error::InvalidField { .. })
    ));
}

/// The heat error of 000 Table 2.1 (sphere r = 1/3, t = 0.01) on `n³` with half-width `j`,
/// transparent conditions, time discretisation `time` and step `tau` (`None`: `h²`).
fn heat_error(
    n: usize,
    j: usize,
    time: anisomesh::backends::dtgrid::heat::TimeScheme,
    tau: Option<f64>,
) -> f64 {
    use anisomesh::backends::dtgrid::heat::{sphere_heat, HeatOptions};
    use anisomesh::backends::dtgrid::{lattice::C3, scheme::Bc, DtGrid};
    let o = HeatOptions {
        time,
        tau,
        ..HeatOptions::paper(n, j, Bc::Transparent)
    };
    let r = sphere_heat::<DtGrid<C3>>(&o).unwrap();
    eprintln!(
        "heat {} n = {n}, j = {j}, tau = {:.3e}: error {:.4e}",
        time.name(),
        r.tau,
        r.error
    );
    r.error
}

#[test]
fn band_heat_bdf2_is_second_order_in_time() {
    use anisomesh::backends::dtgrid::heat::TimeScheme;
    // 17³, j = 2: the time error is the distance to the error at a step 16 times smaller
    // (measured 3.16e-4 and 8.56e-5: order 1.88).
    let e: Vec<f64> = [2e-3, 1e-3, 6.25e-5]
        .iter()
        .map(|&t| heat_error(17, 2, TimeScheme::Bdf2, Some(t)))
        .collect();
    let order = ((e[0] - e[2]) / (e[1] - e[2])).log2();
    assert!(order > 1.8, "time order {order} from {e:?}");
    // Backward Euler at the same step is far from converged in time.
    let euler = heat_error(17, 2, TimeScheme::Euler, Some(1e-3));
    assert!(
        (euler - e[2]).abs() > 5.0 * (e[1] - e[2]).abs(),
        "{euler} {e:?}"
    );
}

#[test]
fn band_heat_transparent_is_second_order_in_space_with_bdf2() {
    use anisomesh::backends::dtgrid::heat::TimeScheme;
    // τ = h², BDF2: j = 2 from 17³ to 33³ (measured 3.37e-3, 7.68e-4: order 2.13; 000
    // Table 2.1: 6.79e-3, 1.83e-3) and j = 4 from 33³ to 49³ (7.84e-4, 3.26e-4: order 2.16).
    for (j, n0, n1) in [(2, 17, 33), (4, 33, 49)] {
        let (e0, e1) = (
            heat_error(n0, j, TimeScheme::Bdf2, None),
            heat_error(n1, j, TimeScheme::Bdf2, None),
        );
        let order = (e0 / e1).ln() / ((n1 - 1) as f64 / (n0 - 1) as f64).ln();
        assert!(order > 1.7, "j = {j}: order {order} ({e0:.3e}, {e1:.3e})");
    }
}
