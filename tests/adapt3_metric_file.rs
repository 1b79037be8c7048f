//! A metric given at the vertices of a background tetrahedral mesh (what a `.sol` file holds)
//! is conformed to as the analytic field it samples: a small UGAWG-like cube-linear field
//! (sizes linear in |z − 1/2|, a kink on a plane of the background mesh), adapted through the
//! vertex metric ([`run3_to_field`], linear sizes between the background's vertices) and
//! directly from the analytic function ([`run3`]), both rated in the analytic field with lengths
//! integrated along the edges (as `anisomesh measure --ugawg` rates).

use anisomesh::adapt::{run3, run3_to_field, MetricField3, Run3Options, Target3};
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::{conformity_analytic, Sym3};
use anisomesh::DVec3;

/// cube-linear with h0 = 0.02 and 0.25 away from the layer.
fn field(p: DVec3) -> Sym3 {
    let (h0, far) = (0.02, 0.25);
    let hz = h0 + 2.0 * (far - h0) * (p.z - 0.5).abs();
    Sym3::new(
        1.0 / (far * far),
        0.0,
        0.0,
        1.0 / (far * far),
        0.0,
        1.0 / (hz * hz),
    )
}

#[test]
fn file_metric_adapts_as_the_analytic_field() {
    let bg = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [4, 4, 4]).unwrap();
    let vertex_metric: Vec<Sym3> = bg.points.iter().map(|&p| field(p)).collect();
    let opts = Run3Options::default();
    let file = run3_to_field(&bg, vertex_metric, &opts, None).unwrap();
    let exact = run3(Target3::Metric(&field), Some(&bg), &opts).unwrap();
    let rate = |m: &Mesh3| conformity_analytic(&m.points, &m.tets, &field).unwrap();
    let (cf, ce) = (rate(&file.mesh), rate(&exact.mesh));
    file.mesh.check().unwrap();
    // Both conform to the same field: the same share in range within a point, vertex counts
    // within 5 %.
    assert!(
        cf.edge_length_in_range >= 0.95 && cf.mean_ratio_min >= 0.3,
        "through the vertex metric: {:.4} in range, worst {:.3}",
        cf.edge_length_in_range,
        cf.mean_ratio_min
    );
    assert!(
        (cf.edge_length_in_range - ce.edge_length_in_range).abs() <= 0.01,
        "{:.4} vs {:.4}",
        cf.edge_length_in_range,
        ce.edge_length_in_range
    );
    let (nf, ne) = (file.mesh.n_points() as f64, exact.mesh.n_points() as f64);
    assert!((nf / ne - 1.0).abs() <= 0.05, "{nf} vs {ne} vertices");
    // Log-Euclidean interpolation of the same vertex metrics asks for a finer field between
    // the background's vertices: many more vertices, fewer edges in range in the analytic
    // field.
    let vertex_metric: Vec<Sym3> = bg.points.iter().map(|&p| field(p)).collect();
    let log = MetricField3::new(&bg.points, &bg.tets, &vertex_metric).unwrap();
    let f = |p: DVec3| log.at(p);
    let logm = run3(Target3::Metric(&f), Some(&bg), &opts).unwrap();
    let cl = rate(&logm.mesh);
    let nl = logm.mesh.n_points() as f64;
    eprintln!(
        "in range / worst / vertices: file {:.4} / {:.3} / {nf}, analytic {:.4} / {:.3} / {ne}, \
         log-Euclidean {:.4} / {:.3} / {nl}",
        cf.edge_length_in_range,
        cf.mean_ratio_min,
        ce.edge_length_in_range,
        ce.mean_ratio_min,
        cl.edge_length_in_range,
        cl.mean_ratio_min
    );
    assert!(nl > 1.1 * ne && cl.edge_length_in_range < ce.edge_length_in_range - 0.03);
}
