//! The user-file tools `redistance`, `measure`, `ugawg` (and `metric` where built) run as a user
//! would: files in, files out, against independent computations; bad input gives one-line typed
//! errors, never a panic.

use anisomesh::io::{self, Medit3, Sol, SolField};
use anisomesh::mesh3::Mesh3;
use anisomesh::{DVec2, DVec3, GridPattern, Mesh2};
use std::path::{Path, PathBuf};
use std::process::Command;

mod common;
use common::{anisomesh, assert_clean_error, ok, s, scratch};

fn tmp(name: &str) -> PathBuf {
    scratch("cli-tools").join(name)
}

fn grid(n: usize, lo: f64, hi: f64) -> Mesh2 {
    Mesh2::rectangle(DVec2::splat(lo), DVec2::splat(hi), n, n, GridPattern::Right).unwrap()
}

fn write_case(name: &str, mesh: &Mesh2, u: &[f64]) -> (PathBuf, PathBuf) {
    let (m, f) = (tmp(&format!("{name}.mesh")), tmp(&format!("{name}.sol")));
    io::write_medit2(&m, mesh).unwrap();
    io::write_sol(&f, &Sol::scalar(u.to_vec())).unwrap();
    (m, f)
}

fn read_scalar(p: &Path) -> Vec<f64> {
    match io::read_sol(p).unwrap().fields.remove(0) {
        SolField::Scalar(v) => v,
        f => panic!("not scalar: {f:?}"),
    }
}

/// The zero level of the P1 field `u` on the triangles, as segments (marching triangles, written
/// here independently of the library; no vertex value is exactly zero in these tests).
fn zero_segments(mesh: &Mesh2, u: &[f64]) -> Vec<(DVec2, DVec2)> {
    let mut segs = Vec::new();
    for t in mesh.live_tris() {
        let v = mesh.tris[t].map(|i| i as usize);
        let mut pts = Vec::new();
        for (a, b) in [(v[0], v[1]), (v[1], v[2]), (v[2], v[0])] {
            if (u[a] < 0.0) != (u[b] < 0.0) {
                let s = u[a] / (u[a] - u[b]);
                pts.push(mesh.points[a] + (mesh.points[b] - mesh.points[a]) * s);
            }
        }
        if pts.len() == 2 {
            segs.push((pts[0], pts[1]));
        }
    }
    segs
}

fn segment_distance(p: DVec2, (a, b): (DVec2, DVec2)) -> f64 {
    let e = b - a;
    let t = ((p - a).dot(e) / e.length_squared()).clamp(0.0, 1.0);
    (p - (a + e * t)).length()
}

/// A scaled, non-distance polynomial level set: a tilted ellipse with a cubic term.
fn poly(p: DVec2) -> f64 {
    3.0 * (p.x * p.x + 2.0 * p.y * p.y + 0.6 * p.x * p.y - 0.3) + 0.8 * p.x * p.x * p.x
}

#[test]
fn geometric_redistance_is_the_exact_distance_to_the_p1_zero_level() {
    let mesh = grid(200, -1.0, 1.0);
    let u: Vec<f64> = mesh.points.iter().map(|&p| poly(p)).collect();
    let (m, f) = write_case("poly", &mesh, &u);
    let d_path = tmp("poly_d.sol");
    let out = ok(&anisomesh(&[
        "redistance",
        "--input",
        s(&m),
        "--sol",
        s(&f),
        "-o",
        s(&d_path),
    ]));
    eprintln!("{out}");
    let d = read_scalar(&d_path);
    let segs = zero_segments(&mesh, &u);
    let mut worst: f64 = 0.0;
    for (i, &p) in mesh.points.iter().enumerate() {
        let e = segs
            .iter()
            .map(|&sg| segment_distance(p, sg))
            .fold(f64::INFINITY, f64::min);
        let exact = if u[i] < 0.0 { -e } else { e };
        worst = worst.max((d[i] - exact).abs());
    }
    eprintln!("max |d - exact distance to the P1 zero level| = {worst:.2e}");
    assert!(worst <= 1e-12, "{worst}");
    // The printed relative area change (the line "relative change X").
    let change: f64 = out
        .split("relative change ")
        .nth(1)
        .and_then(|r| r.split(')').next())
        .and_then(|x| x.parse().ok())
        .expect("area change printed");
    assert!(change <= 1e-4, "{change}");
}

#[test]
fn ppr_redistance_is_second_order_for_p1() {
    // Errors on the vertices of the cut cells against the distance to the true circle.
    let mut errs = Vec::new();
    for n in [40, 80, 160] {
        let mesh = grid(n, -1.0, 1.0);
        let u: Vec<f64> = mesh
            .points
            .iter()
            .map(|p| 2.0 * (p.length_squared() - 0.36))
            .collect();
        let (m, f) = write_case(&format!("circle{n}"), &mesh, &u);
        let d_path = tmp(&format!("circle{n}_d.sol"));
        ok(&anisomesh(&[
            "redistance",
            "--input",
            s(&m),
            "--sol",
            s(&f),
            "--method",
            "ppr",
            "-o",
            s(&d_path),
        ]));
        let d = read_scalar(&d_path);
        let mut e: f64 = 0.0;
        for t in mesh.live_tris() {
            let v = mesh.tris[t].map(|i| i as usize);
            if v.iter().any(|&i| u[i] < 0.0) && v.iter().any(|&i| u[i] > 0.0) {
                for i in v {
                    e = e.max((d[i] - (mesh.points[i].length() - 0.6)).abs());
                }
            }
        }
        errs.push(e);
    }
    let eoc: Vec<f64> = errs.windows(2).map(|w| (w[0] / w[1]).log2()).collect();
    eprintln!("PPR P1 band errors {errs:?}, orders {eoc:.2?}");
    assert!(eoc.iter().all(|&o| o > 1.7), "{eoc:?}");
}

fn kuhn_medit(n: usize) -> (Mesh3, Medit3) {
    let mesh = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [n; 3]).unwrap();
    let m = Medit3 {
        points: mesh.points.clone(),
        point_ref: vec![0; mesh.points.len()],
        tets: mesh.tets.clone(),
        tet_ref: mesh.tet_ref.clone(),
        ..Medit3::default()
    };
    (mesh, m)
}

#[test]
fn redistance_on_tetrahedra_approximates_the_sphere_distance() {
    let (mesh, m) = kuhn_medit(16);
    let mp = tmp("ball.mesh");
    io::write_medit3(&mp, &m).unwrap();
    let c = DVec3::splat(0.5);
    let u: Vec<f64> = mesh
        .points
        .iter()
        .map(|p| 4.0 * ((*p - c).length_squared() - 0.09))
        .collect();
    let up = tmp("ball.sol");
    io::write_sol(&up, &Sol::scalar_dim(3, u.clone())).unwrap();
    for method in ["geometric", "fmm"] {
        let dp = tmp(&format!("ball_{method}.sol"));
        let out = ok(&anisomesh(&[
            "redistance",
            "--input",
            s(&mp),
            "--sol",
            s(&up),
            "--method",
            method,
            "-o",
            s(&dp),
        ]));
        assert!(out.contains("volume"), "{out}");
        let sol = io::read_sol(&dp).unwrap();
        assert_eq!(sol.dim, 3);
        let d = read_scalar(&dp);
        let h = 1.0 / 16.0;
        let worst = mesh
            .points
            .iter()
            .zip(&d)
            .map(|(p, d)| (d - ((*p - c).length() - 0.3)).abs())
            .fold(0.0, f64::max);
        eprintln!("{method}: max error to the sphere distance {worst:.3e} (h = {h})");
        assert!(worst < h, "{method}: {worst}");
        assert!(u.iter().zip(&d).all(|(u, d)| u * d >= 0.0));
    }
}

#[test]
fn measure_and_ugawg_agree_and_write_json() {
    let dir = tmp("ugawg");
    let out = ok(&anisomesh(&[
        "ugawg",
        "cube-linear",
        "--n",
        "8",
        "-o",
        s(&dir),
    ]));
    assert!(out.contains("in [1/sqrt2, sqrt2]"), "{out}");
    let mesh = dir.join("cube-linear.mesh");
    let sol = dir.join("cube-linear.sol");
    let m3 = io::read_medit3(&mesh).unwrap();
    assert_eq!(m3.tets.len(), 6 * 512);
    let from_file = ok(&anisomesh(&[
        "measure",
        s(&mesh),
        "--metric",
        s(&sol),
        "--json",
    ]));
    let analytic = ok(&anisomesh(&[
        "measure",
        s(&mesh),
        "--ugawg",
        "cube-linear",
        "--json",
    ]));
    let share = |j: &str| -> (f64, usize) {
        let v: serde_json::Value = serde_json::from_str(j).unwrap();
        (
            v["conformity"]["edge_length_in_range"].as_f64().unwrap(),
            v["conformity"]["edges"].as_u64().unwrap() as usize,
        )
    };
    let (a, ea) = share(&from_file);
    let (b, eb) = share(&analytic);
    eprintln!("cube-linear 8^3: share {a:.4} (file metric) {b:.4} (analytic)");
    assert_eq!(ea, eb);
    assert!(a > 0.0 && b > 0.0 && (a - b).abs() < 0.05);
    // The file's metric is the case's metric at the vertices.
    let sol = io::read_sol(&sol).unwrap();
    match &sol.fields[0] {
        SolField::Tensor3(t) => {
            let m = io::sym3_from_file(&t[0]);
            let want = anisomesh::metric::ugawg::UgawgCase::CubeLinear.metric(m3.points[0]);
            assert_eq!(m, want);
        }
        f => panic!("{f:?}"),
    }
}

#[test]
fn bad_inputs_are_one_line_errors() {
    let mesh = grid(4, 0.0, 1.0);
    let u: Vec<f64> = mesh.points.iter().map(|p| p.x - 0.45).collect();
    let (m, f) = write_case("bad", &mesh, &u);
    let o = tmp("bad_out.sol");
    let red =
        |sol: &Path| anisomesh(&["redistance", "--input", s(&m), "--sol", s(sol), "-o", s(&o)]);
    // Size mismatch.
    let short = tmp("short.sol");
    io::write_sol(&short, &Sol::scalar(vec![1.0; 7])).unwrap();
    assert_clean_error(&red(&short), "short.sol");
    // A metric where a scalar is needed, and a scalar where a metric is needed.
    let met = tmp("met.sol");
    io::write_sol(
        &met,
        &Sol::metric(vec![anisomesh::Sym2::IDENTITY; mesh.n_points()]),
    )
    .unwrap();
    assert_clean_error(&red(&met), "scalar level set is needed");
    assert_clean_error(
        &anisomesh(&["measure", s(&m), "--metric", s(&f)]),
        "holds no metric",
    );
    // NaN.
    let nan = tmp("nan.sol");
    let text = std::fs::read_to_string(&f).unwrap();
    let first_value = text
        .lines()
        .position(|l| l.trim() == "1 1")
        .expect("sol header")
        + 1;
    let lines: Vec<String> = text
        .lines()
        .enumerate()
        .map(|(i, l)| {
            if i == first_value {
                "NaN".into()
            } else {
                l.into()
            }
        })
        .collect();
    std::fs::write(&nan, lines.join("\n")).unwrap();
    let out = red(&nan);
    let stderr = String::from_utf8_lossy(&out.stderr);
    assert!(stderr.contains("nan.sol"), "{stderr}");
    assert_clean_error(&out, "nan.sol");
    // No zero level.
    let pos = tmp("pos.sol");
    io::write_sol(&pos, &Sol::scalar(vec![1.0; mesh.n_points()])).unwrap();
    assert_clean_error(&red(&pos), "no zero");
    // A 3D solution for a 2D mesh.
    let s3 = tmp("s3.sol");
    io::write_sol(&s3, &Sol::scalar_dim(3, u.clone())).unwrap();
    assert_clean_error(&red(&s3), "3D solution for a 2D mesh");
    // Unknown method, UGAWG metric on a 2D mesh.
    let out = anisomesh(&[
        "redistance",
        "--input",
        s(&m),
        "--sol",
        s(&f),
        "--method",
        "magic",
        "-o",
        s(&o),
    ]);
    assert_clean_error(&out, "--method");
    assert_clean_error(
        &anisomesh(&["measure", s(&m), "--ugawg", "cube-linear"]),
        "3D",
    );
    // A metric of a level set without zero level; a metric that is not SPD.
    assert_clean_error(
        &anisomesh(&["metric", "--input", s(&m), "--expr", "1 + x^2", "-o", s(&o)]),
        "no zero level",
    );
    let neg = tmp("neg.sol");
    io::write_sol(
        &neg,
        &Sol::metric(vec![anisomesh::Sym2::new(1.0, 0.0, -1.0); mesh.n_points()]),
    )
    .unwrap();
    assert_clean_error(
        &anisomesh(&["measure", s(&m), "--metric", s(&neg)]),
        "not a metric",
    );
    assert_clean_error(
        &anisomesh(&["ugawg", "cube-linear", "--n", "0", "-o", s(&tmp("ug0"))]),
        "--n 0",
    );
}

fn on_path(tool: &str) -> bool {
    Command::new(tool)
        .arg("-h")
        .output()
        .map(|o| o.status.success() || !o.stdout.is_empty())
        .unwrap_or(false)
}

/// The share of edges in range printed by `measure --json`.
fn json_share(out: &str) -> f64 {
    let v: serde_json::Value = serde_json::from_str(out).unwrap();
    v["conformity"]["edge_length_in_range"].as_f64().unwrap()
}

#[test]
fn metric_files_drive_our_adapt_and_mmg2d_and_measure_rates_both() {
    let mesh = grid(40, -1.0, 1.0);
    let m = tmp("circle40.mesh");
    io::write_medit2(&m, &mesh).unwrap();
    let met = tmp("circle40_metric.sol");
    let flags = ["--eps", "1e-3", "--hmin", "0.005", "--hmax", "0.2"];
    let mut args = vec![
        "metric",
        "--input",
        s(&m),
        "--expr",
        "x^2 + y^2 - 0.25",
        "-o",
        s(&met),
    ];
    args.extend(flags);
    ok(&anisomesh(&args));
    // The metric at a vertex on the circle: size hmin across (the normal is radial).
    let sol = io::read_sol(&met).unwrap();
    let SolField::Tensor2(metric) = &sol.fields[0] else {
        panic!("no tensor field")
    };
    let i = mesh
        .points
        .iter()
        .position(|p| (p.length() - 0.5).abs() < 1e-12 && p.y.abs() < 1e-12)
        .expect("vertex (0.5, 0)");
    let h_normal = 1.0 / metric[i].xx.sqrt();
    assert!((h_normal - 0.005).abs() < 0.001, "{h_normal}");
    let dir = tmp("ours_adapt");
    ok(&anisomesh(&[
        "adapt",
        "--input",
        s(&m),
        "--sol",
        s(&met),
        "-o",
        s(&dir),
    ]));
    let ours = dir.join("circle40_adapted.mesh");
    let rate = |mesh: &Path| {
        json_share(&ok(&anisomesh(&[
            "measure",
            s(mesh),
            "--metric",
            s(&met),
            "--metric-mesh",
            s(&m),
            "--json",
        ])))
    };
    let share_ours = rate(&ours);
    eprintln!("ours: {share_ours:.4} of the edges in [1/sqrt2, sqrt2] of the input metric");
    assert!(share_ours > 0.7, "{share_ours}");
    // The zero level of the input level set interpolated on the adapted mesh, against the
    // input's own (a 40² grid: its polygon is the reference).
    let u: Vec<f64> = mesh
        .points
        .iter()
        .map(|p| p.length_squared() - 0.25)
        .collect();
    let up = tmp("circle40_u.sol");
    io::write_sol(&up, &Sol::scalar(u)).unwrap();
    let cmp = |mesh: &Path| {
        let out = ok(&anisomesh(&[
            "measure",
            s(mesh),
            "--against",
            s(&m),
            "--sol",
            s(&up),
            "--json",
        ]));
        let v: serde_json::Value = serde_json::from_str(&out).unwrap();
        (
            v["against"]["hausdorff"].as_f64().unwrap(),
            v["against"]["relative_area_error"].as_f64().unwrap(),
        )
    };
    let (h_ours, a_ours) = cmp(&ours);
    eprintln!("ours against the input zero level: Hausdorff {h_ours:.3e}, area {a_ours:.2e}");
    assert!(h_ours < 0.01 && a_ours < 0.01, "{h_ours} {a_ours}");
    if !on_path("mmg2d_O3") {
        eprintln!("mmg2d_O3 not on PATH: the mmg half of this test is skipped");
        return;
    }
    let theirs = tmp("circle40_mmg.mesh");
    let out = Command::new("mmg2d_O3")
        .args([
            "-in",
            s(&m),
            "-sol",
            s(&met),
            "-hgrad",
            "-1",
            "-out",
            s(&theirs),
        ])
        .output()
        .unwrap();
    assert!(out.status.success(), "mmg2d_O3 refused our metric");
    let share_mmg = rate(&theirs);
    let (h_mmg, a_mmg) = cmp(&theirs);
    eprintln!(
        "mmg2d_O3 (-hgrad -1): {share_mmg:.4} of the edges in range of the same metric; \
         Hausdorff {h_mmg:.3e}, area {a_mmg:.2e}"
    );
    assert!(share_mmg > 0.5, "{share_mmg}");
    assert!(h_mmg < 0.01 && a_mmg < 0.01, "{h_mmg} {a_mmg}");
}

#[test]
fn metric_on_tetrahedra_is_a_3d_tensor_field() {
    let (mesh, m3) = kuhn_medit(12);
    let mp = tmp("ball_metric.mesh");
    io::write_medit3(&mp, &m3).unwrap();
    let out_path = tmp("ball_metric.sol");
    ok(&anisomesh(&[
        "metric",
        "--input",
        s(&mp),
        "--expr",
        "(x-0.5)^2 + (y-0.5)^2 + (z-0.5)^2 - 0.09",
        "--hmin",
        "0.01",
        "--eps",
        "1e-3",
        "-o",
        s(&out_path),
    ]));
    let sol = io::read_sol(&out_path).unwrap();
    assert_eq!(sol.dim, 3);
    let SolField::Tensor3(t) = &sol.fields[0] else {
        panic!("no 3D tensor field")
    };
    assert_eq!(t.len(), mesh.n_points());
    // Far from the sphere (a corner, distance 0.566) the sizes reach hmax.
    let m0 = io::sym3_from_file(&t[0]);
    assert!((1.0 / m0.xx.sqrt() - 0.2).abs() < 1e-9, "{m0:?}");
    // The 3D metric cannot be targeted (2D only): one-line error.
    assert_clean_error(
        &anisomesh(&[
            "metric",
            "--input",
            s(&mp),
            "--expr",
            "x - 0.5",
            "--target-vertices",
            "1000",
            "-o",
            s(&out_path),
        ]),
        "2D only",
    );
    if on_path("mmg3d_O3") {
        let out = Command::new("mmg3d_O3")
            .args([
                "-in",
                s(&mp),
                "-sol",
                s(&out_path),
                "-out",
                s(&tmp("ball_mmg.mesh")),
            ])
            .output()
            .unwrap();
        assert!(out.status.success(), "mmg3d_O3 refused our 3D metric");
        let rated = ok(&anisomesh(&["measure", s(&tmp("ball_mmg.mesh")), "--json"]));
        assert!(json_share(&rated) >= 0.0);
    }
}
