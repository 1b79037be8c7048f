//! Least-squares recovery on tetrahedra (`recovery::recover_ls3`) and the banded eq. (6) metric
//! (`metric::band`): exact for quadratics, converging for a sphere's distance, and the 2D banded
//! metric equal to `adapt`'s `LevelSetMetric::metric`.

use anisomesh::adapt::LevelSetMetric;
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::band::{banded_metric, BandedMetric};
use anisomesh::metric::{Sym2, Sym3};
use anisomesh::recovery::recover_ls3;
use anisomesh::{DVec2, DVec3};

fn kuhn(n: usize) -> Mesh3 {
    Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [n; 3]).unwrap()
}

#[test]
fn quadratics_are_recovered_exactly_at_every_vertex() {
    let mesh = kuhn(5);
    let h = Sym3::new(2.0, -0.7, 0.3, 1.1, 0.4, -1.6);
    let g = DVec3::new(0.3, -1.2, 0.8);
    let u: Vec<f64> = mesh
        .points
        .iter()
        .map(|&p| 0.7 + g.dot(p) + 0.5 * h.quad(p))
        .collect();
    let r = recover_ls3(&mesh.points, &mesh.tets, &u).unwrap();
    for (i, p) in mesh.points.iter().enumerate() {
        let ge = g + h.mul_vec(*p);
        assert!(
            (r.gradient[i] - ge).length() < 1e-9,
            "{i}: {}",
            r.gradient[i]
        );
        assert!(
            r.hessian[i].sub(&h).norm() < 1e-8,
            "{i}: {:?}",
            r.hessian[i]
        );
    }
}

#[test]
fn sphere_distance_derivatives_converge() {
    let c = DVec3::splat(0.5);
    let mut errs = Vec::new();
    for n in [8, 16, 32] {
        let mesh = kuhn(n);
        let u: Vec<f64> = mesh
            .points
            .iter()
            .map(|p| (*p - c).length() - 0.3)
            .collect();
        let r = recover_ls3(&mesh.points, &mesh.tets, &u).unwrap();
        let (mut eg, mut eh) = (0.0f64, 0.0f64);
        for (i, p) in mesh.points.iter().enumerate() {
            let x = *p - c;
            let rr = x.length();
            // Away from the centre and from the boundary (one-sided patches).
            if !(0.2..=0.4).contains(&rr) {
                continue;
            }
            let nrm = x / rr;
            let hess = Sym3::IDENTITY.sub(&Sym3::outer(nrm)).scale(1.0 / rr);
            eg = eg.max((r.gradient[i] - nrm).length());
            eh = eh.max(r.hessian[i].sub(&hess).norm());
        }
        errs.push((eg, eh));
    }
    eprintln!("sphere distance: (gradient, Hessian) max errors {errs:?}");
    for w in errs.windows(2) {
        let (og, oh) = ((w[0].0 / w[1].0).log2(), (w[0].1 / w[1].1).log2());
        eprintln!("orders: gradient {og:.2}, Hessian {oh:.2}");
        assert!(og > 1.5, "gradient order {og}");
        assert!(oh > 0.7, "Hessian order {oh}");
    }
}

#[test]
fn banded_metric_in_2d_is_the_adapt_metric() {
    let lm = LevelSetMetric {
        eps: 1e-3,
        hmin: 2e-3,
        hmax: 0.1,
        band: 4e-3,
        grade: 0.5,
        ..LevelSetMetric::default()
    };
    let p = BandedMetric {
        eps: lm.eps,
        bounds: lm.bounds(),
        band: lm.band,
        grade: lm.grade,
    };
    let mut k = 0.0f64;
    for i in 0..200 {
        k += 0.618_033_988_749_895;
        let u = (k.fract() - 0.5) * 0.05;
        let g = DVec2::new((3.0 * k).cos(), (3.0 * k).sin());
        let h = Sym2::new(
            5.0 * (7.0 * k).sin(),
            2.0 * (5.0 * k).cos(),
            9.0 * k.fract(),
        );
        let a = lm.metric(u, g, &h);
        let b = banded_metric(&p, u, g, &h);
        assert!(a.sub(&b).norm() <= 1e-12 * a.norm(), "{i}: {a:?} {b:?}");
    }
}

#[test]
fn banded_metric_in_3d_has_the_sphere_sizes() {
    // At a point of the sphere of radius R: size hmin across, sqrt(eps R) along.
    let (r, eps, hmin) = (0.3, 1e-3, 1e-3);
    let p = BandedMetric {
        eps,
        bounds: anisomesh::metric::MetricBounds::new(hmin, 0.5, 1e4).unwrap(),
        band: 0.01,
        grade: 1.0,
    };
    let n = DVec3::new(0.0, 0.6, 0.8);
    let hess = Sym3::IDENTITY.sub(&Sym3::outer(n)).scale(1.0 / r);
    let m = banded_metric(&p, 0.0, n, &hess);
    assert!((m.quad(n) - 1.0 / (hmin * hmin) - 0.0).abs() < 1e-6 / (hmin * hmin));
    let t = DVec3::new(1.0, 0.0, 0.0);
    assert!((1.0 / m.quad(t).sqrt() - (eps * r).sqrt()).abs() < 1e-12);
    // Outside the band the sizes grow at the grade rate, up to hmax.
    let far = banded_metric(&p, 0.11, n, &hess);
    assert!((1.0 / far.quad(n).sqrt() - (hmin + 0.1)).abs() < 1e-9);
}
