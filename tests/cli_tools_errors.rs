//! Bad input to `redistance`, `metric` and `measure` beyond `tests/cli_tools.rs`: the P2 input's
//! flags, a 3D `.sol` with a 2D mesh and a 2D `.sol` with a 3D mesh, a metric where a level set
//! is needed in `metric`, meshes of two dimensions in `measure --against`: each one line on
//! stderr naming what is wrong, never a panic.

use anisomesh::io::{self, Medit3, Sol};
use anisomesh::mesh3::Mesh3;
use anisomesh::{DVec2, DVec3, GridPattern, Mesh2, Sym2};
use std::path::{Path, PathBuf};

mod common;
use common::{anisomesh, assert_clean_error, s, scratch};

fn tmp(name: &str) -> PathBuf {
    scratch("cli-errors").join(name)
}

#[test]
fn bad_inputs_to_the_user_file_tools_are_one_line_errors() {
    let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 4, 4, GridPattern::Right).unwrap();
    let m2 = tmp("m2.mesh");
    io::write_medit2(&m2, &mesh).unwrap();
    let u: Vec<f64> = mesh.points.iter().map(|p| p.x - 0.45).collect();
    let u2 = tmp("u2.sol");
    io::write_sol(&u2, &Sol::scalar(u.clone())).unwrap();
    let k = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [2; 3]).unwrap();
    let m3 = tmp("m3.mesh");
    io::write_medit3(
        &m3,
        &Medit3 {
            points: k.points.clone(),
            point_ref: vec![0; k.points.len()],
            tets: k.tets.clone(),
            tet_ref: k.tet_ref.clone(),
            ..Medit3::default()
        },
    )
    .unwrap();
    let u3: Vec<f64> = k.points.iter().map(|p| p.x - 0.45).collect();
    let u3p = tmp("u3.sol");
    io::write_sol(&u3p, &Sol::scalar_dim(3, u3)).unwrap();
    let o = tmp("out.sol");

    // P2 input: only for PPR, degree 1 or 2, with an expression.
    let red = |extra: &[&str]| {
        let mut a = vec!["redistance", "--input", s(&m2), "-o", s(&o)];
        a.extend(extra);
        anisomesh(&a)
    };
    assert_clean_error(
        &red(&["--expr", "x - 0.45", "--order", "2"]),
        "--method ppr",
    );
    assert_clean_error(
        &red(&["--expr", "x - 0.45", "--order", "3", "--method", "ppr"]),
        "--order 3",
    );
    assert_clean_error(&red(&["--expr", "1 + x^2", "--method", "ppr"]), "zero");
    assert_clean_error(&red(&["--expr", "log(x - 2)"]), "non-finite");
    // A 3D .sol with a 2D mesh, a 2D .sol with a 3D mesh, in each command.
    let metric_cmd = |mesh: &Path, sol: &Path| {
        anisomesh(&["metric", "--input", s(mesh), "--sol", s(sol), "-o", s(&o)])
    };
    assert_clean_error(&metric_cmd(&m2, &u3p), "u3.sol");
    assert_clean_error(&metric_cmd(&m3, &u2), "u2.sol");
    let n3 = tmp("n3.sol");
    io::write_sol(&n3, &Sol::scalar_dim(3, u.clone())).unwrap();
    assert_clean_error(&metric_cmd(&m2, &n3), "3D solution for a 2D mesh");
    // A metric where the level set is needed, a level set where the metric is needed.
    let met = tmp("met.sol");
    io::write_sol(&met, &Sol::metric(vec![Sym2::IDENTITY; mesh.n_points()])).unwrap();
    assert_clean_error(&metric_cmd(&m2, &met), "scalar level set is needed");
    assert_clean_error(
        &anisomesh(&["measure", s(&m3), "--metric", s(&u3p)]),
        "holds no metric",
    );
    // NaN in a level set for metric.
    let nan = tmp("nan.sol");
    let mut bad = u.clone();
    bad[3] = 12345.5;
    io::write_sol(&nan, &Sol::scalar(bad)).unwrap();
    let text = std::fs::read_to_string(&nan)
        .unwrap()
        .replace("12345.5", "NaN");
    std::fs::write(&nan, text).unwrap();
    assert_clean_error(&metric_cmd(&m2, &nan), "vertex 4");
    // measure --against: a 3D reference for a 2D mesh; a level set of the wrong size.
    assert_clean_error(
        &anisomesh(&["measure", s(&m2), "--against", s(&m3), "--sol", s(&u3p)]),
        "3D mesh",
    );
    assert_clean_error(
        &anisomesh(&[
            "measure",
            s(&m3),
            "--against",
            s(&m3),
            "--sol",
            s(&u3p),
            "--level-set",
            s(&u2),
        ]),
        "u2.sol",
    );
    // No zero level on either side.
    let pos = tmp("pos3.sol");
    io::write_sol(&pos, &Sol::scalar_dim(3, vec![1.0; k.points.len()])).unwrap();
    assert_clean_error(
        &anisomesh(&["measure", s(&m3), "--against", s(&m3), "--sol", s(&pos)]),
        "no zero level",
    );
}
