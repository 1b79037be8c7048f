//! Quality and accuracy of the default Zalesak run (004 §4.2 eq. (6), hmin 0.001, hmax 0.2,
//! eps 1e-4, band 5e-4, gradation 2): the metric conformity targets (>= 95% of edges with metric
//! length in [1/sqrt2, sqrt2], mean Q_ani <= 1.10, worst Q_ani <= 5) and the accuracy targets
//! (<= 5,000 vertices, two-sided Hausdorff distance <= 5e-4, relative area error <= 5e-5).
//! Peers on the same problem: mmg2d 92% in range, worst Q ~20, 4,465 vertices with area error
//! 3.7e-4; BAMG 5,720 vertices, Hausdorff 4.5e-4, area error 5.5e-5.

use anisomesh::adapt::{adapt_to_shape, mesh_report, AnalyticLevelSetSource, ShapeAdaptOptions};
use anisomesh::levelset::{Shape, Zalesak};
use anisomesh::DVec2;

#[test]
fn zalesak_default_run_meets_quality_and_accuracy_targets() {
    let shape = Zalesak::default();
    let opts = ShapeAdaptOptions::default();
    let domain = (DVec2::splat(-2.0), DVec2::splat(2.0));
    let (mesh, u, rep) = adapt_to_shape(&shape, domain, &opts).unwrap();
    mesh.check().unwrap();
    assert!(rep.converged, "{rep:?}");
    let src = AnalyticLevelSetSource::new(
        |p| (shape.distance(p), shape.gradient(p), shape.hessian(p)),
        opts.metric,
    );
    let (mut metric, _) = src.evaluate(&mesh);
    anisomesh::metric::gradate(&mesh, &mut metric, opts.gradation.unwrap()).unwrap();
    let r = mesh_report(&mesh, &metric, &u, Some(&shape)).unwrap();
    eprintln!("{r:?}");
    assert!(r.edge_length_in_range >= 0.95, "{}", r.edge_length_in_range);
    assert!(r.q_ani_mean <= 1.10, "{}", r.q_ani_mean);
    assert!(r.q_ani_max <= 5.0, "{}", r.q_ani_max);
    assert!(r.vertices <= 5000, "{}", r.vertices);
    assert!(r.hausdorff.unwrap() <= 5e-4, "{:?}", r.hausdorff);
    assert!(r.area_rel_error.unwrap() <= 5e-5, "{:?}", r.area_rel_error);
}

/// Regression: the isotropic circle mesh of size 0.005 with a band of half-width 0.0025 (a band
/// narrower than the elements: the graded metric interpolated from the previous round's mesh can
/// miss it) stopped, under a settling guard of 90% of edges in range, at 91% in range with
/// 2,259 vertices and Hausdorff 5.8e-5, twice the error of the coarser size 0.007. With the
/// default guard of 95% it settles at 98.5% in range (2,595 vertices, Hausdorff 1.1e-5).
#[test]
fn isotropic_circle_with_a_band_narrower_than_the_elements_settles_in_range() {
    use anisomesh::adapt::LevelSetMetric;
    use anisomesh::levelset::shape_by_name;
    let shape = shape_by_name("circle").unwrap();
    let domain = (DVec2::splat(-1.0), DVec2::splat(1.0));
    let opts = ShapeAdaptOptions {
        metric: LevelSetMetric {
            eps: 1.0,
            hmin: 0.005,
            band: 0.0025,
            isotropic: true,
            ..LevelSetMetric::default()
        },
        ..ShapeAdaptOptions::default()
    };
    assert_eq!(opts.min_in_range, 0.95);
    let (mesh, u, rep) = adapt_to_shape(shape.as_ref(), domain, &opts).unwrap();
    mesh.check().unwrap();
    assert!(rep.converged);
    let src = AnalyticLevelSetSource::new(
        |p| (shape.distance(p), shape.gradient(p), shape.hessian(p)),
        opts.metric,
    );
    let (mut metric, _) = src.evaluate(&mesh);
    anisomesh::metric::gradate(&mesh, &mut metric, opts.gradation.unwrap()).unwrap();
    let r = mesh_report(&mesh, &metric, &u, Some(shape.as_ref())).unwrap();
    assert!(r.edge_length_in_range >= 0.95, "{}", r.edge_length_in_range);
    assert!(r.hausdorff.unwrap() < 2e-5, "{:?}", r.hausdorff);
}
