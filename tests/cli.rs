//! The command line: every sample mesh is readable by `info`; every error is one line on stderr
//! with a non-zero exit status and never a panic.

use std::path::Path;
use std::process::{Command, Output};

fn anisomesh(args: &[&str]) -> Output {
    Command::new(env!("CARGO_BIN_EXE_anisomesh"))
        .args(args)
        .current_dir(env!("CARGO_MANIFEST_DIR"))
        .output()
        .expect("the binary runs")
}

fn assert_clean_error(out: &Output, needle: &str) {
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(!out.status.success(), "expected failure, got success");
    assert!(!stderr.contains("panicked"), "panic: {stderr}");
    assert_eq!(stderr.trim_end().lines().count(), 1, "one line: {stderr}");
    assert!(stderr.contains(needle), "'{needle}' not in: {stderr}");
}

#[test]
fn info_reads_every_sample_file() {
    let mut n = 0;
    for entry in std::fs::read_dir(Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes")).unwrap() {
        let path = entry.unwrap().path();
        let out = anisomesh(&["info", path.to_str().unwrap()]);
        assert!(
            out.status.success(),
            "{}: {}",
            path.display(),
            String::from_utf8_lossy(&out.stderr)
        );
        let stdout = String::from_utf8_lossy(&out.stdout);
        assert!(
            stdout.contains("vertices") || stdout.contains("field"),
            "{stdout}"
        );
        n += 1;
    }
    assert!(n >= 5, "only {n} sample files");
}

#[test]
fn info_with_metric_reports_edge_lengths() {
    let out = anisomesh(&[
        "info",
        "meshes/square.mesh",
        "--sol",
        "meshes/square_metric.sol",
    ]);
    assert!(out.status.success());
    let stdout = String::from_utf8_lossy(&out.stdout);
    assert!(
        stdout.contains("edge lengths in [1/sqrt2, sqrt2]"),
        "{stdout}"
    );
}

#[test]
fn errors_are_one_line_and_name_the_problem() {
    assert_clean_error(
        &anisomesh(&["info", "no/such/file.mesh"]),
        "no/such/file.mesh",
    );
    assert_clean_error(&anisomesh(&["info", "Cargo.toml"]), "extension");
    assert_clean_error(
        &anisomesh(&[
            "info",
            "meshes/square_hole.mesh",
            "--sol",
            "meshes/square_metric.sol",
        ]),
        "vertices",
    );
    assert_clean_error(
        &anisomesh(&[
            "shape",
            "--expr",
            "x^2+(y",
            "--mesh",
            "meshes/square.mesh",
            "-o",
            "x.sol",
        ]),
        "column",
    );
    assert_clean_error(
        &anisomesh(&[
            "shape",
            "--name",
            "teapot",
            "--mesh",
            "meshes/square.mesh",
            "-o",
            "x.sol",
        ]),
        "zalesak",
    );
    assert!(!Path::new(env!("CARGO_MANIFEST_DIR")).join("x.sol").exists());
}

#[test]
fn convert_and_shape_round_trip() {
    let dir = std::env::temp_dir().join(format!("anisomesh-cli-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let msh = dir.join("square.msh");
    let out = anisomesh(&["convert", "meshes/square_hole.mesh", msh.to_str().unwrap()]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let out = anisomesh(&["info", msh.to_str().unwrap()]);
    assert!(String::from_utf8_lossy(&out.stdout).contains("vertices      231"));
    let sol = dir.join("ls.sol");
    let out = anisomesh(&[
        "shape",
        "--name",
        "circle",
        "--mesh",
        msh.to_str().unwrap(),
        "-o",
        sol.to_str().unwrap(),
    ]);
    assert!(
        out.status.success(),
        "{}",
        String::from_utf8_lossy(&out.stderr)
    );
    let text = std::fs::read_to_string(&sol).unwrap();
    assert!(text.contains("SolAtVertices"));
    std::fs::remove_dir_all(&dir).ok();
}
