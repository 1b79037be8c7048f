//! The planar DT-Grid narrow band through the level-set back-end contract: a circle shrinking
//! by curvature against R(t) = √(R0² − 2t) with its order between grids, the enclosed area of a
//! circle, the curvature of a circle and of an ellipse given by a non-distance function,
//! Zalesak's disk under rotation, and the typed errors.

use anisomesh::backends::dtgrid::plane::{DtGrid2Backend, DtGrid2Options};
use anisomesh::backends::{BuildSpec, FnShape, LevelSetBackend};
use anisomesh::levelset::{Circle, Shape, Zalesak};
use anisomesh::{DVec2, Error};
use std::f64::consts::PI;

const LO: DVec2 = DVec2::new(-0.5, -0.5);
const HI: DVec2 = DVec2::new(0.5, 0.5);

fn build_with(shape: &dyn Shape, h: f64, o: DtGrid2Options) -> anisomesh::Result<DtGrid2Backend> {
    DtGrid2Backend::new(
        &BuildSpec {
            function: shape,
            domain: (LO, HI),
            resolution: h,
        },
        o,
    )
}

fn build(shape: &dyn Shape, h: f64) -> anisomesh::Result<DtGrid2Backend> {
    build_with(shape, h, DtGrid2Options::default())
}

fn circle(r: f64) -> Circle {
    Circle {
        centre: DVec2::new(0.03, -0.02),
        radius: r,
    }
}

/// The radius of the disk with the back end's enclosed area.
fn radius(b: &DtGrid2Backend) -> f64 {
    (b.enclosed_measure().unwrap() / PI).sqrt()
}

fn order(e: &[f64]) -> Vec<f64> {
    e.windows(2).map(|w| (w[0] / w[1]).log2()).collect()
}

/// The circle R0 = 0.3 to t = 0.005 at h = 1/32, 1/64 (and 1/128 with `fine`) under `o`.
fn circle_errors(o: DtGrid2Options, levels: usize) -> Vec<f64> {
    let (r0, t): (f64, f64) = (0.3, 0.005);
    let exact = (r0 * r0 - 2.0 * t).sqrt();
    (0..levels)
        .map(|k| {
            let h = 1.0 / (32 << k) as f64;
            let mut b = build_with(&circle(r0), h, o).unwrap();
            for _ in 0..4 {
                let rep = b.advance_mean_curvature(t / 4.0).unwrap();
                assert!(rep.inner_iterations > 0 && rep.dof == b.dof());
            }
            assert!((b.time() - t).abs() < 1e-15);
            (radius(&b) - exact).abs()
        })
        .collect()
}

#[test]
fn circle_shrinks_at_second_order_with_tau_h2() {
    let best = DtGrid2Options {
        tau_per_h: f64::INFINITY,
        tau_per_h2: 1.0,
        ..DtGrid2Options::default()
    };
    let e2 = circle_errors(best, 2);
    // Measured 1.72e-4 -> 4.57e-5 (1.91). The default τ ≤ h/8 (first order) is checked by the
    // cross-check, which refines the time step with h.
    eprintln!("tau = h²: {e2:?} {:?}", order(&e2));
    assert!(order(&e2)[0] >= 1.7 && e2[1] < 1e-4, "{e2:?}");
}

#[test]
fn enclosed_area_length_and_redistancing_of_a_circle() {
    let r = 0.31;
    let mut errs = Vec::new();
    for h in [1.0 / 32.0, 1.0 / 64.0] {
        let b = build(&circle(r), h).unwrap();
        errs.push((b.enclosed_measure().unwrap() / (PI * r * r) - 1.0).abs());
        assert!((b.interface_measure().unwrap() / (2.0 * PI * r) - 1.0).abs() < 1e-3);
        let z = b.zero_level().unwrap();
        assert_eq!(z.len(), 1);
        assert!(z[0].closed);
        // Point values: the signed distance near the circle, None far from it.
        let c = circle(r).centre;
        let v = b
            .evaluate(&[c + DVec2::new(r + 0.01, 0.0), c, DVec2::splat(3.0)])
            .unwrap();
        assert!((v[0].unwrap() - 0.01).abs() < 1e-3 && v[1].is_none() && v[2].is_none());
    }
    eprintln!("area errors {errs:?}");
    assert!(errs[1] < 2e-5 && errs[1] < errs[0] / 4.0, "{errs:?}");
    // Redistancing a field that is already a distance moves the area by little.
    let mut b = build(&circle(r), 1.0 / 64.0).unwrap();
    let a0 = b.enclosed_measure().unwrap();
    for _ in 0..10 {
        b.redistance().unwrap();
    }
    let drift = (b.enclosed_measure().unwrap() / a0 - 1.0).abs();
    eprintln!("area drift after 10 redistancings {drift:.2e}");
    assert!(drift < 1e-3, "{drift}");
}

/// Mean relative curvature error of the samples against `exact`.
fn curvature_error(b: &DtGrid2Backend, exact: impl Fn(DVec2) -> f64) -> f64 {
    let s = b.interface_curvature().unwrap();
    assert!(s.len() > 10);
    s.points
        .iter()
        .zip(&s.values)
        .map(|(&p, &k)| ((k - exact(p)) / exact(p)).abs())
        .sum::<f64>()
        / s.len() as f64
}

#[test]
fn curvature_of_a_circle_and_of_an_ellipse_converges() {
    let (a, bb) = (0.35, 0.2);
    let ell = FnShape::new("ellipse", move |p: DVec2| {
        p.x * p.x / (a * a) + p.y * p.y / (bb * bb) - 1.0
    });
    let ell_k = |p: DVec2| {
        let (fx, fy) = (2.0 * p.x / (a * a), 2.0 * p.y / (bb * bb));
        let g = (fx * fx + fy * fy).sqrt();
        (2.0 / (a * a) * fy * fy + 2.0 / (bb * bb) * fx * fx) / (g * g * g)
    };
    let c = circle(0.3);
    let (mut ec, mut ee) = (Vec::new(), Vec::new());
    for h in [1.0 / 40.0, 1.0 / 80.0, 1.0 / 160.0] {
        ec.push(curvature_error(&build(&c, h).unwrap(), |p| {
            1.0 / (p - c.centre).length()
        }));
        ee.push(curvature_error(&build(&ell, h).unwrap(), ell_k));
    }
    eprintln!(
        "circle {ec:?} {:?}; ellipse {ee:?} {:?}",
        order(&ec),
        order(&ee)
    );
    // Measured: circle 1.09e-3, 2.61e-4, 6.86e-5 (2.06, 1.93), ellipse 6.80e-3, 1.68e-3,
    // 4.22e-4 (2.02, 1.99): the distance to the O(h⁴) Hermite zero level read by central
    // differences is second order.
    for e in [&ec, &ee] {
        assert!(order(e).iter().all(|&o| o >= 1.7) && e[2] < 1e-3, "{e:?}");
    }
}

#[test]
fn zalesak_rotation_keeps_the_area() {
    let shape = Zalesak::default();
    let exact = shape.exact_area().unwrap();
    let mut errs = Vec::new();
    for h in [0.02, 0.01] {
        let mut b = DtGrid2Backend::new(
            &BuildSpec {
                function: &shape,
                domain: (DVec2::splat(-2.0), DVec2::splat(2.0)),
                resolution: h,
            },
            DtGrid2Options::default(),
        )
        .unwrap();
        let perimeter = shape.exact_perimeter().unwrap();
        let p0 = b.interface_measure().unwrap() / perimeter - 1.0;
        let v = |_t: f64, x: DVec2| DVec2::new(-x.y, x.x);
        for _ in 0..16 {
            b.advect(&v, 2.0 * PI / 16.0).unwrap();
        }
        errs.push((b.enclosed_measure().unwrap() / exact - 1.0).abs());
        let p1 = b.interface_measure().unwrap() / perimeter - 1.0;
        // The slotted disk's perimeter before and after the revolution (measured −5.2e-3 →
        // −1.83e-2 at h = 0.02, −4.6e-3 → −1.24e-2 at h = 0.01): the zero level is short
        // already before any motion (its corners are rounded), and the transport rounds
        // them further; the unslotted disk's zero level has the exact length to 2e-5.
        let disk = Circle {
            centre: DVec2::new(0.0, 0.75),
            radius: 0.5,
        };
        let d = DtGrid2Backend::new(
            &BuildSpec {
                function: &disk,
                domain: (DVec2::splat(-2.0), DVec2::splat(2.0)),
                resolution: h,
            },
            DtGrid2Options::default(),
        )
        .unwrap();
        let pd = d.interface_measure().unwrap() / (PI * 1.0) - 1.0;
        eprintln!("h {h}: perimeter initial {p0:+.3e}, final {p1:+.3e}; disk {pd:+.3e}");
        assert!(
            p0 < 0.0 && p0 > -8e-3 && p1 < p0 && pd.abs() < 1e-4,
            "{p0} {p1} {pd}"
        );
    }
    eprintln!("zalesak area errors {errs:?}");
    assert!(
        errs.iter().all(|&e| e < 2e-2) && errs[1] < errs[0],
        "{errs:?}"
    );
}

#[test]
fn typed_errors() {
    let c = circle(0.3);
    // No zero level in the domain.
    let none = FnShape::new("nothing", |p: DVec2| p.length() + 1.0);
    assert!(matches!(build(&none, 0.05), Err(Error::EmptyLevelSet(_))));
    // A band wider than the grid.
    assert!(matches!(build(&c, 0.3), Err(Error::InvalidInput(_))));
    // A NaN of the function.
    let nan = FnShape::new("nan", |p: DVec2| if p.x > 0.2 { f64::NAN } else { p.x });
    assert!(matches!(build(&nan, 0.05), Err(Error::InvalidField { .. })));
    // A shape that does not fit, bad options, bad steps.
    assert!(matches!(
        build(&circle(0.49), 0.02),
        Err(Error::InvalidInput(_))
    ));
    let bad = DtGrid2Options {
        cfl: f64::NAN,
        ..DtGrid2Options::default()
    };
    assert!(build_with(&c, 0.05, bad).is_err());
    let mut b = build(&circle(0.1), 0.02).unwrap();
    assert!(b.advance_mean_curvature(f64::NAN).is_err());
    let v = |_t: f64, _x: DVec2| DVec2::splat(f64::NAN);
    assert!(matches!(b.advect(&v, 0.1), Err(Error::InvalidField { .. })));
    // The circle vanishes at t = r²/2 = 0.005.
    let mut b = build(&circle(0.1), 0.02).unwrap();
    assert!(matches!(
        b.advance_mean_curvature(0.01),
        Err(Error::EmptyLevelSet(_))
    ));
}

/// The heat equation on the circle R = 1/3 to t = 0.01 (000 Table 2.1 in the plane): the
/// eigenfunction cos 2θ decaying as e^{−4t/R²}, L² error on the discrete circle at τ = h², on
/// 33², 65², 129² nodes. Measured (transparent / natural):
/// j = 1: 1.07e-3, 6.66e-4, 2.76e-4 / 6.37e-3, 1.33e-2, 1.91e-2;
/// j = 2: 1.86e-3, 7.52e-4, 8.77e-4 / 4.59e-3, 5.25e-3, 3.01e-3;
/// j = 4: 2.17e-3, 7.14e-4, 1.25e-4 / 2.16e-3, 3.01e-4, 2.76e-3.
/// Natural conditions do not converge; transparent ones do, but not monotonically (as in
/// 000's Table 2.1, the band's cells meet the circle differently on each grid), and not yet at
/// second order.
#[test]
fn circle_heat_transparent_conditions_beat_natural_ones() {
    use anisomesh::backends::dtgrid::plane::heat::{circle_heat, CircleHeatOptions};
    use anisomesh::backends::dtgrid::scheme::Bc;
    let run = |j: usize, bc: Bc| -> Vec<f64> {
        [33, 65, 129]
            .iter()
            .map(|&n| {
                circle_heat(&CircleHeatOptions::table(n, j, bc))
                    .unwrap()
                    .error
            })
            .collect()
    };
    for j in [1, 2, 4] {
        let t = run(j, Bc::Transparent);
        let nat = run(j, Bc::Natural);
        eprintln!(
            "j = {j}: transparent {t:?} orders {:.2?}; natural {nat:?} orders {:.2?}",
            order(&t),
            order(&nat)
        );
        assert!(t.iter().all(|&e| e < 2.5e-3), "j = {j}: {t:?}");
        assert!(
            t[2] < t[0] / 2.0 && t[2] < nat[2] / 3.0,
            "j = {j}: {t:?} {nat:?}"
        );
    }
}

/// Transparent conditions for mean curvature motion (000 (2.11), one solve per step on the
/// band of `Φ^k`) against Dirichlet conditions with up to 5 inner solves, at τ = h/8 on the
/// circle R0 = 0.5 to T = 0.06 at h = 0.02 in [−1, 1]². The Dirichlet data of a step's first
/// solve are the distance moved by the zero level's predicted motion `τκ₀`, so the inner
/// iteration starts `O(τ²)` from its fixed point. Measured: transparent 4.6e-3 with 24 solves,
/// Dirichlet 3.9e-4 with 49 (with the unmoved data every step took all 5 solves, 120, and the
/// error was 8.3e-3: at τ ≫ (jh)² the Dirichlet data pin the zero level and each solve gains
/// only O((jh)²/τ)).
#[test]
fn transparent_mean_curvature_steps_take_one_solve() {
    use anisomesh::backends::dtgrid::scheme::Bc;
    let (r0, t): (f64, f64) = (0.5, 0.06);
    let exact = (r0 * r0 - 2.0 * t).sqrt();
    let run = |bc: Bc| {
        let mut o = DtGrid2Options::default();
        o.mcf.bc = bc;
        let c = Circle {
            centre: DVec2::new(0.1, -0.05),
            radius: r0,
        };
        let mut b = DtGrid2Backend::new(
            &BuildSpec {
                function: &c,
                domain: (DVec2::splat(-1.0), DVec2::splat(1.0)),
                resolution: 0.02,
            },
            o,
        )
        .unwrap();
        let mut solves = 0;
        for _ in 0..8 {
            solves += b.advance_mean_curvature(t / 8.0).unwrap().inner_iterations;
        }
        ((radius(&b) - exact).abs(), solves)
    };
    let (et, st) = run(Bc::Transparent);
    let (ed, sd) = run(Bc::Dirichlet);
    eprintln!("transparent {et:.3e} ({st} solves), dirichlet {ed:.3e} ({sd} solves)");
    assert!(st == 24 && sd <= 60, "{st} {sd}");
    assert!(et < 6e-3 && ed < 1e-3, "{et} {ed}");
}

#[test]
fn redistancing_exact_distances_keeps_the_circle() {
    use anisomesh::backends::dtgrid::plane::cubic::Field;
    use anisomesh::backends::dtgrid::plane::distance::Keep;
    use anisomesh::backends::dtgrid::plane::lattice::{band_around, crossing_cells_of_fn};
    use anisomesh::backends::dtgrid::plane::level::zero_level;
    use anisomesh::backends::dtgrid::plane::mcf::rebuild;
    use anisomesh::backends::dtgrid::plane::Plane;
    use anisomesh::backends::dtgrid::Band;
    let mut drift = Vec::new();
    for n in [33, 65, 129] {
        let plane = Plane::new(n, 1.0 / (n - 1) as f64).unwrap();
        let radius_of = |band: &_, phi: &[f64]| -> f64 {
            let z = zero_level(&Field {
                plane: &plane,
                band,
                u: phi,
            });
            (z.enclosed_area() / PI).sqrt()
        };
        let (c, r) = (DVec2::new(0.49, 0.52), 0.27);
        let f = |p: DVec2| (p - c).length() - r;
        let mut nb = band_around(&plane, &crossing_cells_of_fn(&plane, &f).unwrap(), 2).unwrap();
        let mut phi: Vec<f64> = nb.band.coords().map(|q| f(plane.pos(q))).collect();
        let r0 = radius_of(&nb.band, &phi);
        let mut steps = Vec::new();
        for _ in 0..4 {
            let (b, d) = rebuild(&plane, &nb, &phi, Keep::Crossing).unwrap();
            nb = b;
            phi = d;
            steps.push(radius_of(&nb.band, &phi) - r0);
        }
        eprintln!(
            "n = {n}: r0 - r = {:.3e}, drift {:?}",
            r0 - r,
            steps
                .iter()
                .map(|x| format!("{x:+.3e}"))
                .collect::<Vec<_>>()
        );
        drift.push(steps[3]);
    }
    eprintln!("drift after 4 redistancings {drift:?}");
    // Measured −6.8e-9, −2.9e-10, −5.9e-12: the kept crossing values sit on the bicubic zero
    // level, whose offset from the circle is O(h⁴), so the factor fitted through the origin
    // carries no O(hκ) bias (unlike the trilinear level in 3D).
    assert!(
        drift[0].abs() < 5e-8 && drift[2].abs() < drift[0].abs() / 100.0,
        "{drift:?}"
    );
}
