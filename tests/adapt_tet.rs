//! The tetrahedral adaptation: conformity to an analytic metric with the mesh checked after
//! every pass, a shape target, and independence of the thread count.

use anisomesh::adapt::{run3, AdaptOptions, Run3Options, Target3};
use anisomesh::geom::DVec3;
use anisomesh::levelset::Sphere;
use anisomesh::metric::Sym3;

/// The UGAWG cube-linear metric with a coarser `h0`: `h_x = h_y = 0.1`,
/// `h_z = h0 + 2 (0.1 − h0) |z − 0.5|`.
fn cube_linear(h0: f64) -> impl Fn(DVec3) -> Sym3 + Sync {
    move |p: DVec3| {
        let hz = h0 + 2.0 * (0.1 - h0) * (p.z - 0.5).abs();
        Sym3 {
            xx: 100.0,
            yy: 100.0,
            zz: 1.0 / (hz * hz),
            ..Sym3::default()
        }
    }
}

fn unit_cube(cells: usize) -> Run3Options {
    Run3Options {
        lo: DVec3::ZERO,
        hi: DVec3::ONE,
        cells,
        adapt: AdaptOptions::default().check_each_pass(true),
        ..Run3Options::default()
    }
}

#[test]
fn cube_linear_coarse_conformity() {
    let f = cube_linear(0.05);
    let a = run3(Target3::Metric(&f), None, &unit_cube(4)).unwrap();
    // h0 = 0.05: about 2,600 vertices; measured 98.8 % in range, worst mean ratio 0.548.
    a.mesh.check().unwrap();
    let r = &a.report;
    eprintln!(
        "cube-linear h0 0.05: {} vertices, {} tets, in range {:.4}, qmin {:.3}, qmean {:.3}, {:.2}s, {} cycles",
        r.vertices, r.tetrahedra, r.edge_length_in_range, r.quality_min, r.stats.quality_mean, r.seconds, r.adapt.cycles
    );
    assert!((a.mesh.volume() - 1.0).abs() < 1e-12);
    assert!(r.edge_length_in_range > 0.96, "{}", r.edge_length_in_range);
    assert!(r.quality_min > 0.52, "{}", r.quality_min);
}

#[test]
fn sphere_volume_and_area() {
    let s = Sphere {
        centre: DVec3::ZERO,
        radius: 0.5,
    };
    let mut o = Run3Options::default();
    o.metric.eps = 1e-2;
    o.metric.hmin = 5e-2;
    o.metric.hmax = 0.3;
    o.metric.band = 2e-2;
    o.adapt = o.adapt.check_each_pass(true);
    let a = run3(Target3::Shape(&s), None, &o).unwrap();
    let r = &a.report;
    let vol = r.volume.unwrap();
    let area = r.surface_area.unwrap();
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    eprintln!(
        "sphere eps 1e-2: {} vertices, volume {vol:.5} (exact {exact:.5}), area {area:.5}, in range {:.3}, qmin {:.3}, {:.2}s",
        r.vertices, r.edge_length_in_range, r.quality_min, r.seconds
    );
    assert!((vol - exact).abs() / exact < 0.05);
    assert!((area - std::f64::consts::PI).abs() / std::f64::consts::PI < 0.05);
}

#[test]
fn same_mesh_on_one_and_two_threads() {
    let f = cube_linear(0.05);
    let run = |threads: usize| {
        rayon::ThreadPoolBuilder::new()
            .num_threads(threads)
            .build()
            .unwrap()
            .install(|| run3(Target3::Metric(&f), None, &unit_cube(4)).unwrap())
    };
    let (a, b) = (run(1), run(2));
    assert_eq!(a.mesh.tets, b.mesh.tets);
    assert_eq!(a.mesh.points, b.mesh.points);
}

/// The 004 star at ε = 1e-2 (hmin 1e-2, band 5e-3; about 20,000 vertices): its deep valleys,
/// where the metric is strongly anisotropic and turns fast, used to end with tetrahedra of
/// mean ratio 1e-13 (four vertices on one line, each refinement pass halving a child); the
/// split's quality guard keeps the worst above 0.1 (measured 0.15). The P1 zero level stays
/// within ε of the exact surface at the 99th percentile (measured 2.6e-3) and the enclosed
/// volume within 5e-3 (measured −2.9e-3).
#[test]
fn star_without_degenerate_tetrahedra() {
    use anisomesh::levelset::compare_radial::{
        compare_to_radial, zero_level_triangles, RadialSurface,
    };
    use anisomesh::levelset::{Shape, StarSurface};
    let star = StarSurface::PAPER;
    let mut o = Run3Options::default();
    o.metric.eps = 1e-2;
    o.metric.hmin = 1e-2;
    o.metric.band = 5e-3;
    let a = run3(Target3::Shape(&star), None, &o).unwrap();
    a.mesh.check().unwrap();
    let r = &a.report;
    let u = a.level_set.as_ref().unwrap();
    let (t, v) = zero_level_triangles(&a.mesh.points, &a.mesh.tets, u).unwrap();
    let rho = move |d: DVec3| star.radius_towards(d);
    let exact = RadialSurface {
        centre: DVec3::ZERO,
        rho: &rho,
        volume: star.exact_area().unwrap(),
    };
    let c = compare_to_radial(&t, v, &exact, 5).unwrap();
    eprintln!(
        "star eps 1e-2: {} vertices, qmin {:.3}, in range {:.4}, p99 {:.3e} / {:.3e}, volume error {:+.3e}, {:.1}s",
        r.vertices,
        r.quality_min,
        r.edge_length_in_range,
        c.exact_to_discrete.p99,
        c.discrete_to_exact.p99,
        c.volume_error,
        r.seconds
    );
    // Degenerate tetrahedra (four vertices on a line, mean ratio 3e-13 before the split's
    // quality guard) must not come back. The worst element itself scatters with the last bits
    // of the input: at ε = (0.999, 1, 1.001, 1.003)·10⁻² it measured 0.43, 0.087, 0.074, 0.16
    // (0.078, 0.27, 0.039, 0.28 with the iterative eigen-solver), so the bound is well below
    // that scatter and far above degenerate.
    assert!(r.quality_min > 0.02, "{}", r.quality_min);
    assert!(
        c.exact_to_discrete.p99 < 1e-2,
        "{}",
        c.exact_to_discrete.p99
    );
    assert!(c.volume_error.abs() < 5e-3, "{}", c.volume_error);
}
