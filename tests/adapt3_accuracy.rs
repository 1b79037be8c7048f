//! The accuracy of the 3D adaptation to an implicit surface whose level-set function is not a
//! distance (004 eq. (6) through `u/|∇u|`, `adapt::run3`), measured against the exact surface
//! both ways (`levelset::compare_radial`): the sphere of radius 0.5 given as
//! `c (|x|² − 0.25)`, at a coarse ε so that the run takes seconds.

use anisomesh::adapt::{run3, Run3Options, Target3};
use anisomesh::geom::DVec3;
use anisomesh::levelset::compare_radial::{compare_to_radial, zero_level_triangles, RadialSurface};
use anisomesh::levelset::Shape;

/// `c (|x|² − R²)`: the sphere of radius `R`, not a distance (its gradient is `2c|x|`).
struct Quadric(f64, f64);

impl Shape<DVec3> for Quadric {
    fn distance(&self, p: DVec3) -> f64 {
        self.0 * (p.length_squared() - self.1 * self.1)
    }
    fn gradient(&self, p: DVec3) -> DVec3 {
        p * (2.0 * self.0)
    }
    fn hessian(&self, _p: DVec3) -> anisomesh::metric::Sym3 {
        anisomesh::metric::Sym3::scalar(2.0 * self.0)
    }
    fn is_distance(&self) -> bool {
        false
    }
    fn exact_area(&self) -> Option<f64> {
        Some(4.0 / 3.0 * std::f64::consts::PI * self.1.powi(3))
    }
    fn name(&self) -> String {
        "quadric sphere".into()
    }
}

#[test]
fn quadric_sphere_is_within_eps_and_independent_of_scale() {
    let (r, eps) = (0.5, 2e-2);
    let mut o = Run3Options::default();
    o.metric.eps = eps;
    o.metric.hmin = 2e-2;
    o.metric.band = 1e-2;
    o.adapt.check_each_pass = false;
    let mut counts = Vec::new();
    for c in [1.0, 40.0] {
        let a = run3(Target3::Shape(&Quadric(c, r)), None, &o).unwrap();
        a.mesh.check().unwrap();
        let u = a.level_set.as_ref().unwrap();
        let (tris, vol) = zero_level_triangles(&a.mesh.points, &a.mesh.tets, u).unwrap();
        let rho = |_: DVec3| r;
        let exact = RadialSurface {
            centre: DVec3::ZERO,
            rho: &rho,
            volume: 4.0 / 3.0 * std::f64::consts::PI * r.powi(3),
        };
        let cmp = compare_to_radial(&tris, vol, &exact, 5).unwrap();
        let (e2d, d2e) = (cmp.exact_to_discrete, cmp.discrete_to_exact);
        println!(
            "c = {c}: {} vertices; exact->discrete {:.2e}/{:.2e}/{:.2e}, discrete->exact \
             {:.2e}/{:.2e}/{:.2e}, volume error {:+.2e}",
            a.mesh.n_points(),
            e2d.median,
            e2d.p99,
            e2d.max,
            d2e.median,
            d2e.p99,
            d2e.max,
            cmp.volume_error
        );
        // The 99th percentile both ways within eps (004 eq. (6), Corollary 2), the volume
        // within the shell of half that thickness.
        assert!(e2d.p99 <= eps && d2e.p99 <= eps, "{e2d:?} {d2e:?}");
        let area = 4.0 * std::f64::consts::PI * r * r;
        assert!(
            cmp.volume_error.abs() <= 0.5 * eps * area,
            "{}",
            cmp.volume_error
        );
        assert!(a.mesh.n_points() < 20_000, "{}", a.mesh.n_points());
        counts.push(a.mesh.n_points());
    }
    // f and 40 f have the same zero level and, seen through f/|∇f|, the same metric.
    let (a, b) = (counts[0] as f64, counts[1] as f64);
    assert!((a - b).abs() <= 0.02 * a, "{counts:?}");
}

/// The 004 star `|x| = 0.45 + 0.3 cos 6θ cos² 3φ` at ε = 5·10⁻², `hmin` 3·10⁻² (a few seconds):
/// the 99th percentile of the distance within ε both ways, the volume within `ε/2 · area` of
/// the exact 0.4805422178, and the continuation's stages each within a factor of their metric's
/// complexity (`∫ sqrt(det M)`; about two vertices per unit), so that no stage overshoots its
/// metric.
#[test]
fn star_is_within_eps_and_every_stage_near_its_complexity() {
    use anisomesh::levelset::StarSurface;
    let eps = 5e-2;
    let mut o = Run3Options::default();
    o.metric.eps = eps;
    o.metric.hmin = 3e-2;
    o.metric.band = 1.5e-2;
    let star = StarSurface::PAPER;
    let a = run3(Target3::Shape(&star), None, &o).unwrap();
    a.mesh.check().unwrap();
    let u = a.level_set.as_ref().unwrap();
    let (tris, vol) = zero_level_triangles(&a.mesh.points, &a.mesh.tets, u).unwrap();
    let rho = move |d: DVec3| star.radius_towards(d);
    let exact = RadialSurface {
        centre: DVec3::ZERO,
        rho: &rho,
        volume: 0.4805422178,
    };
    let cmp = compare_to_radial(&tris, vol, &exact, 5).unwrap();
    let (e2d, d2e) = (cmp.exact_to_discrete, cmp.discrete_to_exact);
    println!(
        "{} vertices; exact->discrete {:.2e}/{:.2e}/{:.2e}, discrete->exact {:.2e}/{:.2e}/{:.2e}, \
         volume error {:+.2e}",
        a.mesh.n_points(),
        e2d.median,
        e2d.p99,
        e2d.max,
        d2e.median,
        d2e.p99,
        d2e.max,
        cmp.volume_error
    );
    assert!(e2d.p99 <= eps && d2e.p99 <= eps, "{e2d:?} {d2e:?}");
    let area = a.report.surface_area.unwrap();
    assert!(
        cmp.volume_error.abs() <= 0.5 * eps * area,
        "{}",
        cmp.volume_error
    );
    let stages = &a.report.stages;
    assert!(stages.len() >= 2, "{stages:?}");
    for s in stages {
        let ratio = s.vertices as f64 / s.complexity;
        println!("{s:?}: {ratio:.2} vertices per unit");
        assert!((1.0..4.0).contains(&ratio), "{s:?}");
        assert!(s.peak_vertices as f64 <= 6.0 * s.complexity, "{s:?}");
    }
    let last = stages.last().unwrap();
    assert!(last.scale == 1.0 && last.eps == Some(eps));
    let n = a.mesh.n_points() as f64;
    assert!((1.0..3.0).contains(&(n / last.complexity)), "{n} {last:?}");
}
