//! Measured properties of a tiny convergence sweep on the circle of radius 0.5 (issue 3 item 7):
//! the uniform-grid Hausdorff error of the nodal interpolant of the distance decreases like
//! `h² ~ 1/vertices` (log-log slope -1 ± 0.25), and at every `ε` the anisotropic mesh of
//! 004 eq. (6) has fewer vertices than its isotropic version.

use anisomesh::bench::convergence::{run, vertices_at_error, ConvergenceOptions, Family};

#[test]
fn circle_quick_sweep_orders_and_anisotropy() {
    let rep = run(&ConvergenceOptions {
        shape: "circle".into(),
        out_dir: None,
        points: 2,
        quick: true,
    })
    .unwrap();
    print!("{}", rep.table());
    let uni = rep.fit(Family::Uniform).unwrap();
    assert!(
        (uni.hausdorff_slope + 1.0).abs() <= 0.25,
        "uniform Hausdorff slope {} not -1 ± 0.25",
        uni.hausdorff_slope
    );
    // Area error of the nodal interpolant: also O(h²).
    assert!(
        (uni.area_slope + 1.0).abs() <= 0.3,
        "uniform area slope {}",
        uni.area_slope
    );
    let ani = rep.family(Family::Anisotropic);
    let iso = rep.family(Family::Isotropic);
    assert_eq!(ani.len(), 2);
    assert_eq!(iso.len(), 2);
    assert_eq!(rep.family(Family::Uniform).len(), 3);
    for (a, i) in ani.iter().zip(&iso) {
        assert_eq!(a.parameter, i.parameter);
        assert!(
            a.vertices < i.vertices,
            "eps {:e}: anisotropic {} vertices >= isotropic {}",
            a.parameter,
            a.vertices,
            i.vertices
        );
        // eq. (6) bounds the interface error by about eps (4 eps margin for the corner/band).
        assert!(
            a.hausdorff < 4.0 * a.parameter,
            "eps {:e}: d_H {:e}",
            a.parameter,
            a.hausdorff
        );
    }
    // Smaller eps, more vertices and smaller error.
    assert!(ani.windows(2).all(|w| w[1].vertices > w[0].vertices));
    assert!(ani.first().unwrap().hausdorff > ani.last().unwrap().hausdorff);
}

#[test]
fn log_log_interpolation_of_vertex_counts() {
    // e = 10 / n on two points: exact on the power law.
    let pts = [(100.0, 0.1), (10000.0, 0.001)];
    let n = vertices_at_error(&pts, 0.01).unwrap();
    assert!((n - 1000.0).abs() < 1e-9 * 1000.0, "{n}");
    assert!(vertices_at_error(&pts, 1.0).is_none());
}
