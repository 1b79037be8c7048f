//! `anisomesh fit` and `anisomesh adapt --input --sol --fit` from the command line: valid output
//! that passes check(), and bad input (no zero crossing, NaN, a .sol of the wrong size, a zero
//! level through a domain corner) answered by one typed line on stderr, nothing written.

use anisomesh::io::{self, Sol};
use anisomesh::{DVec2, GridPattern, Mesh2};
use std::path::{Path, PathBuf};

mod common;
use common::{anisomesh, assert_clean_error, s};

fn tmp(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("anisomesh-cli-fit-{}-{name}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

/// Writes the unit-square grid with `n` cells per side and the level set `f` at its vertices.
fn write_case(dir: &Path, n: usize, f: impl Fn(DVec2) -> f64) -> (PathBuf, PathBuf, Mesh2) {
    let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::Right).unwrap();
    let u: Vec<f64> = m.points.iter().map(|&p| f(p)).collect();
    let (mp, sp) = (dir.join("m.mesh"), dir.join("u.sol"));
    io::write_mesh(&mp, &m).unwrap();
    io::write_sol(&sp, &Sol::scalar(u)).unwrap();
    (mp, sp, m)
}

#[test]
fn fit_writes_a_checked_mesh_and_refuses_bad_input() {
    let d = tmp("bad");
    let out = d.join("out.mesh");
    // A valid run, with its JSON report.
    let (mp, sp, _) = write_case(&d, 20, |p| (p - DVec2::new(0.52, 0.47)).length() - 0.3);
    let report = d.join("r.json");
    let o = anisomesh(&[
        "fit",
        "--input",
        s(&mp),
        "--sol",
        s(&sp),
        "-o",
        s(&out),
        "--report",
        s(&report),
    ]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let fitted = io::read_mesh(&out).unwrap();
    fitted.check().unwrap();
    let r: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(&report).unwrap()).unwrap();
    for key in [
        "vertices",
        "triangles",
        "area_inside",
        "interface_length",
        "seconds",
    ] {
        assert!(r.get(key).is_some(), "{key}");
    }
    std::fs::remove_file(&out).unwrap();

    // No zero crossing: one line, nothing written.
    let (mp, sp, _) = write_case(&d, 10, |p| p.x + 1.0);
    let o = anisomesh(&["fit", "--input", s(&mp), "--sol", s(&sp), "-o", s(&out)]);
    assert_clean_error(
        &o,
        "does not cross the mesh: every vertex value is above it",
    );
    assert!(!out.exists());

    // A zero level that touches the domain only at its corner (0, 0): no region to fit.
    let (mp, sp, _) = write_case(&d, 10, |p| p.x + p.y);
    let o = anisomesh(&["fit", "--input", s(&mp), "--sol", s(&sp), "-o", s(&out)]);
    assert_clean_error(&o, "on it at 1 vertices only (e.g. vertex 0 at [0, 0])");
    assert!(!out.exists());

    // NaN at a vertex.
    let (mp, sp, _) = write_case(&d, 10, |p| p.x - 0.5);
    let text = std::fs::read_to_string(&sp).unwrap();
    let lines: Vec<&str> = text.lines().collect();
    let header = lines
        .iter()
        .position(|l| l.trim() == "SolAtVertices")
        .unwrap();
    let mut bad: Vec<String> = lines.iter().map(|l| l.to_string()).collect();
    bad[header + 5] = "NaN".into();
    std::fs::write(&sp, bad.join("\n")).unwrap();
    let o = anisomesh(&["fit", "--input", s(&mp), "--sol", s(&sp), "-o", s(&out)]);
    assert_clean_error(&o, "vertex");
    assert!(!out.exists());

    // A .sol of another mesh (the wrong size).
    let (mp, _, _) = write_case(&d, 10, |p| p.x - 0.5);
    let small = d.join("small.sol");
    io::write_sol(&small, &Sol::scalar(vec![-1.0, 1.0, 1.0, 1.0])).unwrap();
    let o = anisomesh(&["fit", "--input", s(&mp), "--sol", s(&small), "-o", s(&out)]);
    assert_clean_error(&o, "small.sol");
    assert!(!out.exists());
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn fit_through_domain_corners_keeps_the_boundary() {
    // The circle through the corners (0, 0) and (1, 0): the inside meets the boundary at two
    // corners; the fitted mesh is valid and its boundary edges keep the side labels 1..4.
    let d = tmp("corner");
    let c = DVec2::new(0.5, -0.5);
    let (mp, sp, base) = write_case(&d, 16, |p| (p - c).length() - 0.5f64.sqrt());
    let out = d.join("out.mesh");
    let o = anisomesh(&["fit", "--input", s(&mp), "--sol", s(&sp), "-o", s(&out)]);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let f = io::read_mesh(&out).unwrap();
    f.check().unwrap();
    assert!((f.area() - base.area()).abs() < 1e-12);
    for t in f.live_tris() {
        for i in 0..3 {
            if f.neighbours[t][i] == anisomesh::NONE {
                assert!((1..=4).contains(&f.edge_ref[t][i]), "{}", f.edge_ref[t][i]);
            }
        }
    }
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn adapt_to_a_discrete_level_set_then_fit_it() {
    let d = tmp("adapt");
    let (mp, sp, base) = write_case(&d, 24, |p| (p - DVec2::new(0.48, 0.53)).length() - 0.27);
    let o = anisomesh(&[
        "adapt",
        "--input",
        s(&mp),
        "--sol",
        s(&sp),
        "--fit",
        "--hmin",
        "0.01",
        "--eps",
        "1e-3",
        "-o",
        s(&d),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{}{}",
        stdout,
        String::from_utf8_lossy(&o.stderr)
    );
    let f = io::read_mesh(&d.join("m_adapted_fitted.mesh")).unwrap();
    f.check().unwrap();
    let inside: f64 = f
        .live_tris()
        .filter(|&t| f.tri_ref[t] == 3)
        .map(|t| f.tri_area(t))
        .sum();
    let u: Vec<f64> = base
        .points
        .iter()
        .map(|&p| (p - DVec2::new(0.48, 0.53)).length() - 0.27)
        .collect();
    let p1 = anisomesh::levelset::enclosed_area(&base, &u).unwrap();
    // The adapted mesh resolves the input's zero level: the fitted inside is the input's
    // inside up to the interpolation onto the adapted vertices.
    assert!((inside - p1).abs() < 2e-3 * p1, "{inside} vs {p1}");
    assert!(f.live_tris().flat_map(|t| f.edge_ref[t]).any(|r| r == 10));
    assert!(stdout.contains("input inside area"));
    std::fs::remove_dir_all(&d).ok();
}

#[test]
fn compare_with_mmg2d_checks_every_output() {
    // The comparison at a small speed case: every output (ours, and mmg2d's when installed)
    // passes check(), and ours has the P1 area of every input to 1e-12.
    let d = tmp("compare");
    let o = anisomesh(&[
        "fit",
        "--compare-mmg",
        "--speed-n",
        "40",
        "--repeats",
        "1",
        "--dir",
        s(&d),
    ]);
    let stdout = String::from_utf8_lossy(&o.stdout);
    assert!(
        o.status.success(),
        "{stdout}{}",
        String::from_utf8_lossy(&o.stderr)
    );
    let json: serde_json::Value =
        serde_json::from_str(&std::fs::read_to_string(d.join("fit_compare.json")).unwrap())
            .unwrap();
    let rows = json["rows"].as_array().unwrap();
    let ours: Vec<_> = rows.iter().filter(|r| r["tool"] == "anisomesh").collect();
    assert_eq!(ours.len(), 6);
    for r in rows {
        assert_eq!(r["check"], "ok", "{r}");
    }
    for r in ours {
        assert!(r["area_rel_error"].as_f64().unwrap() <= 1e-12, "{r}");
    }
    std::fs::remove_dir_all(&d).ok();
}

/// The input is read without its own `check()`, the fitted mesh is checked instead: an input
/// defect that only `check()` finds (two vertices at one point) still gets the input's message
/// with its line, and nothing is written.
#[test]
fn an_input_defect_found_by_check_is_reported_on_the_input() {
    let d = tmp("defect");
    let (mp, sp, out) = (d.join("dup.mesh"), d.join("dup.sol"), d.join("out.mesh"));
    std::fs::write(
        &mp,
        "MeshVersionFormatted 2\nDimension 2\nVertices\n6\n0 0 0\n1 0 0\n0 1 0\n\
         0 0 0\n-1 0 0\n0 -1 0\nTriangles\n2\n1 2 3 0\n4 5 6 0\nEnd\n",
    )
    .unwrap();
    io::write_sol(&sp, &Sol::scalar(vec![-0.5, 0.5, -0.5, -0.5, -1.5, -0.5])).unwrap();
    let expected = io::read_mesh(&mp).unwrap_err().to_string();
    assert!(expected.contains("dup.mesh:"), "{expected}");
    let o = anisomesh(&["fit", "--input", s(&mp), "--sol", s(&sp), "-o", s(&out)]);
    assert_clean_error(&o, &expected);
    assert!(!out.exists());
    std::fs::remove_dir_all(&d).ok();
}
