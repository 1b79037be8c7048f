//! `advect::run` on a shape and a velocity field that no built-in case uses (an ellipse in a
//! time-reversed shear), on adapted and uniform meshes, and its one-line typed errors for bad
//! input. Coarse settings: each run takes well under a second in release mode.

use anisomesh::adapt::{AdaptOptions, LevelSetMetric};
use anisomesh::advect::{
    hausdorff, run, symmetric_difference, ExprVelocity, FixedPointOptions, MeshFamily, RunOptions,
};
use anisomesh::error::Error;
use anisomesh::geom::DVec2;
use anisomesh::levelset::interface::extract_zero_level;
use anisomesh::levelset::Expr;

const ELLIPSE: &str = "sqrt(((x-0.5)/2)^2+(y-0.45)^2)-0.1";
/// A shear `u = 1.5 (y - 0.5) cos(π t)`, reversed at t = 1/2: back to the start at t = 1.
const SHEAR: &str = "1.5*(y-0.5)*cos(pi*t); 0";

fn options(mesh: MeshFamily) -> RunOptions {
    RunOptions {
        domain: (DVec2::ZERO, DVec2::ONE),
        t_start: 0.0,
        t_end: 1.0,
        periods: 8,
        mesh,
        fixed_point: FixedPointOptions {
            max_iterations: 2,
            ..FixedPointOptions::default()
        },
        redistance: true,
        mass_correction: false,
        snapshot_times: vec![0.5],
    }
}

fn adapted() -> MeshFamily {
    MeshFamily::Adapted {
        metric: LevelSetMetric {
            hmin: 1e-3,
            hmax: 0.1,
            eps: 1e-3,
            band: 4e-3,
            grade: 1.0,
            ..LevelSetMetric::default()
        },
        adapt: AdaptOptions::default().max_cycles(4),
        initial_n: 20,
        initial_rounds: 3,
    }
}

#[test]
fn an_ellipse_in_a_reversed_shear_returns_to_its_start() {
    let shape = Expr::parse(ELLIPSE).unwrap();
    let phi = |p: DVec2| shape.eval(p);
    let v = ExprVelocity::parse(SHEAR).unwrap();
    for (mesh, sd_max, h_max) in [
        // Measured: 0.38 % and 3.8e-4 (about 2,000 vertices); 0.40 % and 7.3e-4 (10,201).
        (adapted(), 0.0075, 1e-3),
        (MeshFamily::Uniform { n: 100 }, 0.008, 1.5e-3),
    ] {
        let r = run(&phi, &v, &options(mesh.clone())).unwrap();
        r.last.mesh.check().unwrap();
        assert_eq!(r.steps.len(), 9);
        assert_eq!(r.snapshots.len(), 1);
        let a0 = r.steps[0].area;
        let a1 = r.steps[8].area;
        // The exact area of the ellipse with semi-axes 0.2, 0.1.
        let exact = std::f64::consts::PI * 0.02;
        assert!(
            (a0 - exact).abs() < 0.01 * exact,
            "{mesh:?}: initial area {a0}"
        );
        assert!(
            ((a1 - a0) / a0).abs() < 0.006,
            "{mesh:?}: area {a0} -> {a1}"
        );
        // Halfway the ellipse is sheared: it is not at its start (measured 19 % of its area).
        let mid = &r.snapshots[0];
        let sd_mid = symmetric_difference(&mid.mesh, &mid.u, &phi, 3).unwrap();
        assert!(sd_mid > 0.1 * a0, "{mesh:?}: halfway {sd_mid}");
        let sd = symmetric_difference(&r.last.mesh, &r.last.u, &phi, 3).unwrap();
        assert!(sd < sd_max * a0, "{mesh:?}: symmetric difference {sd}");
        let h = hausdorff(
            &extract_zero_level(&r.initial.mesh, &r.initial.u).unwrap(),
            &extract_zero_level(&r.last.mesh, &r.last.u).unwrap(),
            4,
        );
        assert!(h < h_max, "{mesh:?}: Hausdorff {h}");
    }
}

fn one_line_invalid_input(e: Error) -> String {
    let s = e.to_string();
    assert!(matches!(e, Error::InvalidInput(_)), "{s}");
    assert!(!s.is_empty() && !s.contains('\n'), "{s:?}");
    s
}

#[test]
fn bad_input_gives_one_line_typed_errors() {
    let disk = |p: DVec2| (p - DVec2::splat(0.5)).length() - 0.2;
    let uni = || options(MeshFamily::Uniform { n: 20 });
    // A velocity that carries the shape out of the domain.
    let out = ExprVelocity::parse("1; 0").unwrap();
    let s = one_line_invalid_input(run(&disk, &out, &uni()).unwrap_err());
    assert!(s.contains("boundary"), "{s}");
    // A velocity that is not finite (at x = 0.5, a vertex line of the grid).
    let inf = ExprVelocity::parse("1/(x-0.5); 0").unwrap();
    let s = one_line_invalid_input(run(&disk, &inf, &uni()).unwrap_err());
    assert!(s.contains("not finite"), "{s}");
    let nan = ExprVelocity::parse("sqrt(-1-t); 0").unwrap();
    one_line_invalid_input(run(&disk, &nan, &uni()).unwrap_err());
    // A shape with no zero level, or not finite.
    let calm = ExprVelocity::parse("0; 0").unwrap();
    let s = one_line_invalid_input(
        run(&|p: DVec2| p.length_squared() + 1.0, &calm, &uni()).unwrap_err(),
    );
    assert!(s.contains("zero level"), "{s}");
    one_line_invalid_input(run(&|_p: DVec2| f64::NAN, &calm, &uni()).unwrap_err());
    // The adapted family reports the same error before adapting anything.
    one_line_invalid_input(
        run(
            &|p: DVec2| p.length_squared() + 1.0,
            &calm,
            &options(adapted()),
        )
        .unwrap_err(),
    );
    // Empty or malformed velocity expressions.
    for bad in [
        "", ";", "1; ", "x +; y", "x; y; t", "x; z", "sin(x; y", "x y; 1",
    ] {
        one_line_invalid_input(ExprVelocity::parse(bad).unwrap_err());
    }
    // Bad options: no period, reversed times, an empty domain.
    let mut o = uni();
    o.periods = 0;
    one_line_invalid_input(run(&disk, &calm, &o).unwrap_err());
    let mut o = uni();
    o.t_end = -1.0;
    one_line_invalid_input(run(&disk, &calm, &o).unwrap_err());
    let mut o = uni();
    o.domain = (DVec2::ONE, DVec2::ZERO);
    one_line_invalid_input(run(&disk, &calm, &o).unwrap_err());
}
