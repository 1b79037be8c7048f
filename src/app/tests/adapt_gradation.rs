//! Size gradation during the adaptation (`AdaptOptions::gradation`, as mmg2d's `-hgrad`) on the
//! speed case: a metric known on a coarse background grid.

use anisomesh::adapt::AdaptOptions;
use anisomesh::metric::Sym2;
use anisomesh::{DVec2, GridPattern, Mesh2};

fn square(n: usize) -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::UnionJack).unwrap()
}

#[test]
fn gradation_during_adaptation_removes_the_jumps_of_a_coarse_background_metric() {
    use crate::app::repro::speed::{read_mesh_and_metric, write_speed_case};
    use anisomesh::adapt::adapt;
    use anisomesh::adapt::metric_file_options;
    // The speed case at eps 3e-4: the eq. (6) Zalesak metric given on a 100 x 100
    // grid of [-2, 2]^2, whose normal size goes from 3e-4 to 0.2 within one grid cell.
    let dir = std::env::temp_dir().join(format!("anisomesh_hgrad_{}", std::process::id()));
    let (bg, sol) = write_speed_case(&dir, 100, 3e-4).unwrap();
    let mut results = Vec::new();
    for hgrad in [None, Some(1.3)] {
        let (mut mesh, mut metric) = read_mesh_and_metric(&bg, &sol).unwrap();
        let opts = metric_file_options().gradation(hgrad);
        let rep = adapt(&mut mesh, &mut metric, &mut [], None, &opts).unwrap();
        mesh.check().unwrap();
        let q = anisomesh::metric::quality_stats(&mesh, &metric);
        // How far the final metric is from graded: vertices a new grading would still change.
        let mut regraded = metric.clone();
        anisomesh::metric::gradate(&mesh, &mut regraded, 1.3).unwrap();
        // The largest factor by which a new grading would shrink an element's area.
        let shrink = regraded
            .iter()
            .zip(&metric)
            .map(|(r, m)| (r.det() / m.det()).sqrt())
            .fold(1.0, f64::max);
        println!(
            "hgrad {hgrad:?}: {} vertices, {:.1}% in range, Q mean {:.3} max {:.2}, \
             regrading would shrink an area by up to {shrink:.3}x, gradation {:.2} s",
            mesh.n_points(),
            100.0 * q.edge_length_in_range,
            q.q_ani_mean,
            q.q_ani_max,
            rep.gradation_seconds
        );
        assert!(rep.converged, "{hgrad:?}");
        assert!(q.edge_length_in_range >= 0.97, "{hgrad:?}: {q:?}");
        results.push((q.q_ani_max, shrink));
    }
    let _ = std::fs::remove_dir_all(&dir);
    let ((q_raw, shrink_raw), (q_graded, shrink_graded)) = (results[0], results[1]);
    assert!(
        q_graded <= 2.0 && q_graded < 0.5 * q_raw,
        "worst Q {q_raw} -> {q_graded}"
    );
    assert!(
        shrink_graded < 2.0 && shrink_raw > 20.0 * shrink_graded,
        "area shrink of a regrading: {shrink_raw} -> {shrink_graded}"
    );
    // A factor <= 1 is refused, naming the option.
    let mut mesh = square(4);
    let mut metric = vec![Sym2::iso(1.0); mesh.n_points()];
    let err = adapt(
        &mut mesh,
        &mut metric,
        &mut [],
        None,
        &AdaptOptions::default().gradation(Some(1.0)),
    )
    .unwrap_err();
    assert!(err.to_string().contains("gradation"), "{err}");
}
