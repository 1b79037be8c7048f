//! `anisomesh dtgrid heat|mcf --shape/--expr` run as a user would: the report's fields, the
//! radius of a shrinking sphere against √(R0² − 4t), the surface and pictures written; bad input
//! (a shape that does not fit, a band wider than the grid, a NaN in the function, a zero level
//! that vanishes during the motion) gives one line and a non-zero exit, never a panic.

use std::path::{Path, PathBuf};

mod common;
use common::{anisomesh, assert_clean_error, ok, s, scratch};

fn tmp(name: &str) -> PathBuf {
    scratch("cli-dtgrid").join(name)
}

fn json(path: &Path) -> serde_json::Value {
    serde_json::from_str(&std::fs::read_to_string(path).unwrap()).unwrap()
}

fn assert_pictures(dir: &Path, name: &str) {
    for f in ["surface.vtu", "surface.png", "band.png"] {
        let p = dir.join(format!("{name}_{f}"));
        let len = std::fs::metadata(&p).map(|m| m.len()).unwrap_or(0);
        assert!(len > 1000, "{} missing or small ({len} bytes)", p.display());
    }
}

#[test]
fn sphere_mcf_reports_radius_and_writes_pictures() {
    let dir = tmp("sphere");
    let out = anisomesh(&[
        "dtgrid",
        "mcf",
        "--shape",
        "sphere",
        "--n",
        "17",
        "--band",
        "2",
        "-o",
        s(&dir),
    ]);
    let stdout = ok(&out);
    assert!(stdout.contains("radius_final"), "{stdout}");
    let v = json(&dir.join("dtgrid_mcf.json"));
    let row = &v["rows"][0];
    for key in [
        "n",
        "h",
        "band",
        "bc",
        "inner",
        "tau",
        "error",
        "paper_error",
        "nodes",
        "seconds",
    ] {
        assert!(row.get(key).is_some(), "{key} missing in {row}");
    }
    let exact = row["radius_exact"].as_f64().unwrap();
    let fin = row["radius_final"].as_f64().unwrap();
    assert!((exact - (0.0625f64 - 4.0 * 0.0059).sqrt()).abs() < 1e-12);
    // Within two grid cells (h = 1/16) of the exact radius, and the error is the mean distance.
    assert!((fin - exact).abs() < 2.0 / 16.0, "{fin} vs {exact}");
    assert!(row["error"].as_f64().unwrap() >= (fin - exact).abs() - 1e-9);
    assert_eq!(row["n"], 17);
    assert_eq!(row["bc"], "dirichlet");
    assert_pictures(&dir, "dtgrid_mcf");
    let vtu = std::fs::read_to_string(dir.join("dtgrid_mcf_surface.vtu")).unwrap();
    assert!(vtu.contains("<UnstructuredGrid>") && vtu.contains("NumberOfCells"));
}

#[test]
fn expression_and_heat_runs() {
    let dir = tmp("expr");
    let out = anisomesh(&[
        "dtgrid",
        "mcf",
        "--expr",
        "sqrt(x^2/0.09 + y^2/0.04 + z^2/0.04) - 1",
        "--n",
        "17",
        "--t-end",
        "0.002",
        "-o",
        s(&dir),
    ]);
    ok(&out);
    let row = &json(&dir.join("dtgrid_mcf.json"))["rows"][0];
    assert!(
        row["radius_final"].is_null() && row["error"].is_null(),
        "{row}"
    );
    assert_pictures(&dir, "dtgrid_mcf");

    // The heat equation on the sphere r = 1/3: the error against e^{−6t/r²} Y is that of
    // 000 Table 2.1 on 17³ (0.006–0.009).
    let dir = tmp("heat");
    let out = anisomesh(&[
        "dtgrid",
        "heat",
        "--shape",
        "sphere",
        "--n",
        "17",
        "--band",
        "2",
        "-o",
        s(&dir),
    ]);
    ok(&out);
    let row = &json(&dir.join("dtgrid_heat.json"))["rows"][0];
    let e = row["error"].as_f64().unwrap();
    assert!(e > 0.0 && e < 0.012, "heat error {e}");
    assert_pictures(&dir, "dtgrid_heat");

    // The same with the boundary rows completed by ghost values outside the band.
    let dir = tmp("heat-extrapolated");
    let out = anisomesh(&[
        "dtgrid",
        "heat",
        "--shape",
        "sphere",
        "--n",
        "17",
        "--band",
        "2",
        "--bc",
        "extrapolated",
        "-o",
        s(&dir),
    ]);
    ok(&out);
    let row = &json(&dir.join("dtgrid_heat.json"))["rows"][0];
    let e = row["error"].as_f64().unwrap();
    assert!(e > 0.0 && e < 0.012, "extrapolated heat error {e}");
}

#[test]
fn bad_input_gives_one_line() {
    let dir = tmp("bad");
    let o = s(&dir);
    let big = "sqrt(x^2+y^2+z^2) - 0.48";
    assert_clean_error(
        &anisomesh(&["dtgrid", "mcf", "--expr", big, "--n", "17", "-o", o]),
        "does not fit",
    );
    assert_clean_error(
        &anisomesh(&[
            "dtgrid", "mcf", "--shape", "sphere", "--n", "9", "--band", "4", "-o", o,
        ]),
        "wider than the grid",
    );
    assert_clean_error(
        &anisomesh(&[
            "dtgrid",
            "heat",
            "--expr",
            "sqrt(x) + y",
            "--n",
            "9",
            "-o",
            o,
        ]),
        "NaN",
    );
    assert_clean_error(
        &anisomesh(&[
            "dtgrid", "mcf", "--shape", "sphere", "--n", "17", "--t-end", "0.02", "-o", o,
        ]),
        "vanished",
    );
    assert_clean_error(
        &anisomesh(&["dtgrid", "mcf", "--expr", "1 + x^2", "--n", "9", "-o", o]),
        "empty level set",
    );
    assert_clean_error(
        &anisomesh(&[
            "dtgrid",
            "mcf",
            "--shape",
            "sphere",
            "--n",
            "17",
            "--bc",
            "extrapolated",
            "-o",
            o,
        ]),
        "conditions extrapolated",
    );
    assert_clean_error(
        &anisomesh(&["dtgrid", "mcf", "--expr", "x +* y", "--n", "9", "-o", o]),
        "column",
    );
    assert!(!dir.join("dtgrid_mcf.json").exists());
}
