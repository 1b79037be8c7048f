//! `anisomesh metric` writes the metric `adapt` uses: the file equals, bit for bit, the library's
//! [`level_set_metric`] on the input mesh, and the metric [`run`] returns on the adapted mesh is
//! the same function evaluated at the adapted vertices.

use anisomesh::adapt::{level_set_metric, run, AdaptTarget, LevelSetMetric, RunOptions};
use anisomesh::io::{self, Sol, SolField};
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};
use std::path::{Path, PathBuf};

mod common;
use common::{anisomesh_ok, s, scratch};

fn tmp(name: &str) -> PathBuf {
    scratch("cli-metric").join(name)
}

fn read_metric(p: &Path) -> Vec<Sym2> {
    match io::read_sol(p).unwrap().fields.remove(0) {
        SolField::Tensor2(m) => m,
        f => panic!("not a 2D metric: {f:?}"),
    }
}

fn bits(m: &[Sym2]) -> Vec<[u64; 3]> {
    m.iter()
        .map(|t| [t.xx.to_bits(), t.xy.to_bits(), t.yy.to_bits()])
        .collect()
}

/// A level set that is not a distance: a circle of radius 0.55 times a positive factor.
fn case() -> (Mesh2, Vec<f64>, PathBuf, PathBuf) {
    let mesh = Mesh2::rectangle(
        DVec2::splat(-1.0),
        DVec2::splat(1.0),
        24,
        24,
        GridPattern::Right,
    )
    .unwrap();
    let u: Vec<f64> = mesh
        .points
        .iter()
        .map(|p| (p.length_squared() - 0.3025) * (1.0 + 0.3 * p.x))
        .collect();
    let (m, f) = (tmp("ls.mesh"), tmp("ls.sol"));
    io::write_medit2(&m, &mesh).unwrap();
    io::write_sol(&f, &Sol::scalar(u.clone())).unwrap();
    // The files are what the library sees below.
    assert_eq!(io::read_mesh(&m).unwrap().points, mesh.points);
    (mesh, u, m, f)
}

#[test]
fn metric_command_writes_the_metric_adapt_adapts_to() {
    let (mesh, u, m, f) = case();
    let opts = RunOptions {
        metric: LevelSetMetric {
            eps: 1e-3,
            hmin: 0.01,
            hmax: 0.2,
            band: 5e-3,
            ..LevelSetMetric::default()
        },
        ..RunOptions::default()
    };
    let out = tmp("ls_metric.sol");
    anisomesh_ok(&[
        "metric",
        "--input",
        s(&m),
        "--sol",
        s(&f),
        "--eps",
        "1e-3",
        "--hmin",
        "0.01",
        "--hmax",
        "0.2",
        "--band",
        "5e-3",
        "-o",
        s(&out),
    ]);
    let from_file = read_metric(&out);
    let on_input = level_set_metric(&mesh, &u, None, &opts).unwrap();
    assert_eq!(bits(&from_file), bits(&on_input), "metric file != library");
    // The adaptation returns the same function at its own vertices.
    let adapted = run(
        AdaptTarget::LevelSet {
            mesh: mesh.clone(),
            u: u.clone(),
        },
        &opts,
    )
    .unwrap();
    let at_adapted = level_set_metric(&mesh, &u, Some(&adapted.mesh), &opts).unwrap();
    assert_eq!(bits(&adapted.metric), bits(&at_adapted));
    eprintln!(
        "metric file: {} vertices, bit-identical; adapt::run: {} vertices, metric bit-identical",
        from_file.len(),
        adapted.mesh.n_points()
    );
    // On the zero level the size across is hmin (eq. (6)).
    let h_min_seen = adapted
        .metric
        .iter()
        .map(|t| 1.0 / t.eigen().0[1].sqrt())
        .fold(f64::INFINITY, f64::min);
    assert!((0.009..0.011).contains(&h_min_seen), "{h_min_seen}");

    // The Hessian metric with a target vertex count: the same call as adapt's.
    let out_h = tmp("ls_hessian.sol");
    anisomesh_ok(&[
        "metric",
        "--input",
        s(&m),
        "--sol",
        s(&f),
        "--target-vertices",
        "800",
        "--hmin",
        "0.01",
        "-o",
        s(&out_h),
    ]);
    let h_opts = RunOptions {
        target_vertices: Some(800),
        metric: LevelSetMetric {
            hmin: 0.01,
            ..LevelSetMetric::default()
        },
        ..RunOptions::default()
    };
    let lib = level_set_metric(&mesh, &u, None, &h_opts).unwrap();
    assert_eq!(bits(&read_metric(&out_h)), bits(&lib));
}
