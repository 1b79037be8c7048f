//! Poisson reinitialisation (001 §4) beside the geometric redistancing: the zero level of the
//! base interpolant moves by the discretisation error (order 2 under refinement) with the
//! gradient-jump rows and visibly more without them (001 Figs. 4.1, 4.2); `|∇φ|` near Γ is
//! brought from a badly scaled input to about 1.

use anisomesh::advect::hausdorff;
use anisomesh::backends::fitted::{poisson_reinit, PoissonReinit};
use anisomesh::geom::simplex::p1_gradients;
use anisomesh::levelset::extract_zero_level;
use anisomesh::levelset::redistance::redistance_geometric;
use anisomesh::{DVec2, Error, GridPattern, Mesh2};

/// Mean and max of `||∇φ| − 1|` over the base triangles the zero level cuts.
fn gradient_defect(m: &Mesh2, phi: &[f64]) -> (f64, f64) {
    let (mut s, mut a, mut mx) = (0.0, 0.0, 0.0f64);
    for t in m.live_tris() {
        let tri = m.tris[t];
        let f = tri.map(|v| phi[v as usize]);
        let lo = f.iter().cloned().fold(f64::INFINITY, f64::min);
        let hi = f.iter().cloned().fold(f64::NEG_INFINITY, f64::max);
        if !(lo < 0.0 && hi > 0.0) {
            continue;
        }
        let g = p1_gradients(&m.tri_points(t));
        let d = ((g[0] * f[0] + g[1] * f[1] + g[2] * f[2]).length() - 1.0).abs();
        let area = m.tri_area(t);
        s += area * d;
        a += area;
        mx = mx.max(d);
    }
    (s / a, mx)
}

/// The input: a circle of radius 1/4 about (0.51, 0.48) in the unit square, given by a level
/// set that is far from a distance (gradient 0.6 to 5.4 on the circle).
fn input(n: usize) -> (Mesh2, Vec<f64>) {
    let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::Right).unwrap();
    let c = DVec2::new(0.51, 0.48);
    let u = m
        .points
        .iter()
        .map(|&p| 3.0 * ((p - c).length() - 0.25) * (1.0 + 0.8 * (4.0 * p.x).sin()))
        .collect();
    (m, u)
}

#[test]
fn poisson_reinitialisation_keeps_the_zero_level_to_second_order() {
    let ns = [32usize, 64, 128];
    let mut moved = Vec::new();
    eprintln!("n      moved(jump)  moved(no jump)  moved(geometric)  |∇φ|-1 mean/max: input, poisson, geometric");
    for &n in &ns {
        let (m, u) = input(n);
        let z0 = extract_zero_level(&m, &u).unwrap();
        let out = poisson_reinit(&m, &u, &PoissonReinit::default()).unwrap();
        out.fitted.mesh.check().unwrap();
        assert!(out.rows > out.unknowns);
        // Signs kept at every base vertex.
        for (a, b) in u.iter().zip(&out.values) {
            assert!(a * b >= 0.0, "{a} -> {b}");
        }
        let d_jump = hausdorff(&z0, &extract_zero_level(&m, &out.values).unwrap(), 4);
        let plain = PoissonReinit {
            jump: false,
            ..PoissonReinit::default()
        };
        let no_jump = plain.reinitialise(&m, &u).unwrap();
        let d_plain = hausdorff(&z0, &extract_zero_level(&m, &no_jump).unwrap(), 4);
        let geo = redistance_geometric(&m, &u).unwrap();
        let d_geo = hausdorff(&z0, &extract_zero_level(&m, &geo).unwrap(), 4);
        let (gi, gp, gg) = (
            gradient_defect(&m, &u),
            gradient_defect(&m, &out.values),
            gradient_defect(&m, &geo),
        );
        eprintln!(
            "{n:<6} {d_jump:.3e}    {d_plain:.3e}       {d_geo:.3e}         {:.3}/{:.3}  {:.3}/{:.3}  {:.1e}/{:.1e}",
            gi.0, gi.1, gp.0, gp.1, gg.0, gg.1
        );
        let h = 1.0 / n as f64;
        assert!(d_jump < 0.1 * h, "n {n}: moved {d_jump}");
        assert!(d_jump < d_plain, "n {n}: {d_jump} vs {d_plain}");
        // Gradient near Γ: from 0.6..5.4 to about 1 on average.
        assert!(gi.0 > 0.5 && gp.0 < 0.3, "n {n}: {gi:?} -> {gp:?}");
        moved.push(d_jump);
    }
    let order = (moved[0] / moved[2]).log2() / 2.0;
    eprintln!("order of the zero-level movement {order:.2}");
    assert!(order >= 1.5, "order {order} ({moved:?})");
}

#[test]
fn poisson_reinitialisation_refuses_bad_input() {
    let (m, u) = input(16);
    let bad = PoissonReinit {
        g: -1.0,
        ..PoissonReinit::default()
    };
    assert!(matches!(
        poisson_reinit(&m, &u, &bad),
        Err(Error::InvalidInput(_))
    ));
    let pos: Vec<f64> = u.iter().map(|x| x.abs() + 1.0).collect();
    assert!(matches!(
        poisson_reinit(&m, &pos, &PoissonReinit::default()),
        Err(Error::EmptyLevelSet(_))
    ));
}

#[test]
fn the_back_end_redistances_by_poisson_on_request() {
    use anisomesh::backends::fitted::{FittedBackend, FittedOptions, FittedRedistancing};
    use anisomesh::backends::{BuildSpec, FnShape, LevelSetBackend, D2};
    let c = DVec2::new(0.51, 0.48);
    // Not a distance: the build redistances by the chosen method.
    let f = FnShape::new("scaled circle", move |p: DVec2| {
        5.0 * ((p - c).length() - 0.25)
    });
    let spec = BuildSpec::<D2> {
        function: &f,
        domain: (DVec2::ZERO, DVec2::ONE),
        resolution: 1.0 / 64.0,
    };
    let opts = FittedOptions {
        redistancing: FittedRedistancing::Poisson(PoissonReinit::default()),
        ..FittedOptions::default()
    };
    let mut b = FittedBackend::new(&spec, opts).unwrap();
    let (m, u) = (b.base().clone(), b.values().to_vec());
    let (mean, _) = gradient_defect(&m, &u);
    assert!(mean < 0.1, "{mean}");
    let a0 = b.enclosed_measure().unwrap();
    b.redistance().unwrap();
    let a1 = b.enclosed_measure().unwrap();
    let exact = std::f64::consts::PI * 0.0625;
    eprintln!("area {a0:.8} -> {a1:.8} (exact {exact:.8}), |∇φ|-1 mean {mean:.3}");
    assert!((a1 - a0).abs() < 1e-3 * a0);
    assert!((a0 - exact).abs() < 2e-3 * exact);
}
