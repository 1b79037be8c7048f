//! `anisomesh adapt --input M.mesh --sol S.sol` on tetrahedral meshes (a metric, sizes or a level
//! set at the vertices), `anisomesh measure M.mesh --shape sphere` against brute-force answers,
//! and the one-line errors for bad 3D input (no panic, no output file).

use anisomesh::io::{self, Medit3, Sol};
use anisomesh::levelset::compare_radial::{interface_triangles, zero_level_triangles};
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::{conformity, Sym3};
use anisomesh::DVec3;
use std::path::{Path, PathBuf};

mod common;
use common::{anisomesh, anisomesh_ok, assert_clean_error, s, scratch};

fn dir(tag: &str) -> PathBuf {
    scratch(&format!("adapt3-{tag}"))
}

/// The Kuhn mesh `n³` of the box `[lo, hi]³` with its boundary triangles, as a Medit file.
fn kuhn_file(path: &Path, n: usize, lo: f64, hi: f64) -> Mesh3 {
    let mesh = Mesh3::kuhn_box(DVec3::splat(lo), DVec3::splat(hi), [n; 3]).unwrap();
    let mut m = Medit3 {
        points: mesh.points.clone(),
        point_ref: vec![0; mesh.points.len()],
        tets: mesh.tets.clone(),
        tet_ref: mesh.tet_ref.clone(),
        ..Medit3::default()
    };
    for (t, i) in mesh.boundary_faces() {
        m.tris.push(mesh.face_vertices(t, i));
        m.tri_ref.push(1);
    }
    io::write_medit3(path, &m).unwrap();
    mesh
}

/// A `.sol` text with 3D tensors in file order (written by hand so that bad values can be).
fn tensor_sol(path: &Path, t: &[[f64; 6]]) {
    let mut s = format!(
        "MeshVersionFormatted 2\nDimension 3\nSolAtVertices\n{}\n1 3\n",
        t.len()
    );
    for a in t {
        s += &format!("{} {} {} {} {} {}\n", a[0], a[1], a[2], a[3], a[4], a[5]);
    }
    s += "End\n";
    std::fs::write(path, s).unwrap();
}

fn read3(path: &Path) -> Medit3 {
    io::read_medit3(path).unwrap()
}

#[test]
fn a_metric_file_is_conformed_to_and_the_box_kept() {
    let d = dir("metric");
    let (mp, sp, out) = (d.join("box.mesh"), d.join("box.sol"), d.join("out"));
    let mesh = kuhn_file(&mp, 4, 0.0, 1.0);
    // Anisotropic and constant: sizes 0.25, 0.25, 0.08 along x, y, z (file order xx xy yy xz
    // yz zz).
    let m = Sym3::new(16.0, 0.0, 0.0, 16.0, 0.0, 1.0 / 0.0064);
    tensor_sol(&sp, &vec![io::sym3_to_file(&m); mesh.n_points()]);
    let text = anisomesh_ok(&["adapt", "--input", s(&mp), "--sol", s(&sp), "-o", s(&out)]);
    assert!(text.contains("metric read from file"), "{text}");
    let r = read3(&out.join("box_adapted.mesh"));
    let vol: f64 = r
        .tets
        .iter()
        .map(|t| {
            let p = t.map(|v| r.points[v as usize]);
            (p[1] - p[0]).dot((p[2] - p[0]).cross(p[3] - p[0])) / 6.0
        })
        .sum();
    assert!((vol - 1.0).abs() < 1e-12, "volume {vol}");
    let c = conformity(&r.points, &r.tets, &vec![m; r.points.len()]).unwrap();
    assert!(c.edge_length_in_range > 0.85, "{c:?}");
    assert!(c.mean_ratio_min > 0.2, "{c:?}");
    assert_eq!(c.inverted, 0);
    for f in ["box_adapted.vtu", "box_adapted.png", "report.json"] {
        assert!(out.join(f).exists(), "{f}");
    }
}

#[test]
fn sizes_and_gradation_from_a_scalar_file() {
    let d = dir("sizes");
    let (mp, sp) = (d.join("box.mesh"), d.join("h.sol"));
    let mesh = kuhn_file(&mp, 4, 0.0, 1.0);
    let h: Vec<f64> = mesh.points.iter().map(|p| 0.1 + 0.25 * p.x).collect();
    io::write_sol(&sp, &Sol::scalar_dim(3, h)).unwrap();
    let out = d.join("out");
    let text = anisomesh_ok(&[
        "adapt",
        "--input",
        s(&mp),
        "--sol",
        s(&sp),
        "--sizes",
        "-o",
        s(&out),
    ]);
    assert!(text.contains("sizes read from file"), "{text}");
    let r = read3(&out.join("box_adapted.mesh"));
    // The sizes are interpolated geometrically between the input's vertices; measured in the
    // linear size field the lengths stay near 1.
    let m: Vec<Sym3> = r
        .points
        .iter()
        .map(|p| Sym3::iso(0.1 + 0.25 * p.x))
        .collect();
    let c = conformity(&r.points, &r.tets, &m).unwrap();
    assert!(c.edge_length_in_range > 0.8, "{c:?}");
    // Graded with a slow growth, the elements near x = 1 are smaller: more vertices.
    let graded = d.join("graded");
    anisomesh_ok(&[
        "adapt",
        "--input",
        s(&mp),
        "--sol",
        s(&sp),
        "--sizes",
        "--hgrad",
        "1.05",
        "-o",
        s(&graded),
    ]);
    let g = read3(&graded.join("box_adapted.mesh"));
    assert!(
        g.points.len() as f64 > 1.2 * r.points.len() as f64,
        "{} vs {}",
        g.points.len(),
        r.points.len()
    );
}

#[test]
fn a_level_set_file_is_adapted_to_and_measured_against_the_sphere() {
    let d = dir("ls");
    let (mp, sp, out) = (d.join("cube.mesh"), d.join("u.sol"), d.join("out"));
    let mesh = kuhn_file(&mp, 10, -1.0, 1.0);
    let u: Vec<f64> = mesh.points.iter().map(|p| p.length() - 0.5).collect();
    io::write_sol(&sp, &Sol::scalar_dim(3, u)).unwrap();
    let text = anisomesh_ok(&[
        "adapt",
        "--input",
        s(&mp),
        "--sol",
        s(&sp),
        "--eps",
        "1e-2",
        "--hmin",
        "0.04",
        "--hmax",
        "0.4",
        "-o",
        s(&out),
    ]);
    assert!(text.contains("input volume"), "{text}");
    let stats = |args: &[&str]| -> serde_json::Value {
        let json = anisomesh_ok(args);
        let v: serde_json::Value = serde_json::from_str(&json).unwrap();
        v["comparison"].clone()
    };
    let a = out.join("cube_adapted.mesh");
    let c = stats(&[
        "measure",
        s(&a),
        "--shape",
        "sphere",
        "--level-set",
        s(&out.join("cube_adapted.sol")),
        "--json",
        "--sampling-level",
        "5",
    ]);
    // The input's own P1 zero level (chords of the 10³ mesh) against the sphere.
    let i = stats(&[
        "measure",
        s(&mp),
        "--shape",
        "sphere",
        "--json",
        "--sampling-level",
        "5",
    ]);
    // The adapted zero level follows the input's within eps = 1e-2 (004 eq. (6)): its distances
    // to the sphere and its volume are the input's, up to that.
    let get = |v: &serde_json::Value, a: &str, b: &str| v[a][b].as_f64().unwrap();
    for dir in ["discrete_to_exact", "exact_to_discrete"] {
        assert!(get(&c, dir, "max") < get(&i, dir, "max") + 1e-2, "{c}\n{i}");
    }
    // (The median from the discrete side depends on how the triangles sample the surface.)
    let e = "exact_to_discrete";
    assert!(
        (get(&c, e, "median") - get(&i, e, "median")).abs() < 5e-3,
        "{c}\n{i}"
    );
    let (va, vi) = (c["volume"].as_f64().unwrap(), i["volume"].as_f64().unwrap());
    assert!((va / vi - 1.0).abs() < 0.02, "{va} vs {vi}");
    // Graded (rounds of the exact metric intersected with the graded field), at a coarser
    // setting: sizes only shrink, so more vertices, the same zero level.
    let coarse = |hgrad: Option<&str>, out: &Path| {
        let mut args = vec![
            "adapt",
            "--input",
            s(&mp),
            "--sol",
            s(&sp),
            "--eps",
            "2e-2",
            "--hmin",
            "0.1",
            "--hmax",
            "0.5",
            "-o",
            s(out),
        ];
        if let Some(g) = hgrad {
            args.extend_from_slice(&["--hgrad", g]);
        }
        anisomesh_ok(&args);
        read3(&out.join("cube_adapted.mesh")).points.len()
    };
    let (g0, g) = (d.join("ungraded"), d.join("graded"));
    let (na, ng) = (coarse(None, &g0), coarse(Some("1.2"), &g));
    assert!(ng as f64 > 1.1 * na as f64, "{ng} vs {na}");
    let cg = stats(&[
        "measure",
        s(&g.join("cube_adapted.mesh")),
        "--shape",
        "sphere",
        "--level-set",
        s(&g.join("cube_adapted.sol")),
        "--json",
        "--sampling-level",
        "5",
    ]);
    for dir in ["discrete_to_exact", "exact_to_discrete"] {
        assert!(
            get(&cg, dir, "max") < get(&i, dir, "max") + 2e-2,
            "{cg}\n{i}"
        );
    }
}

/// The sphere of radius 0.5 on a Kuhn mesh: `measure --shape sphere` against the distances
/// computed here by brute force, in both directions, and the volume.
#[test]
fn measure_shape_matches_brute_force_on_the_sphere() {
    let d = dir("measure");
    let mp = d.join("cube.mesh");
    let mesh = kuhn_file(&mp, 9, -1.0, 1.0);
    let u: Vec<f64> = mesh.points.iter().map(|p| p.length() - 0.5).collect();
    let json = anisomesh_ok(&[
        "measure",
        s(&mp),
        "--shape",
        "sphere",
        "--json",
        "--sampling-level",
        "3",
    ]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    let c = &v["comparison"];
    let (tris, vol) = zero_level_triangles(&mesh.points, &mesh.tets, &u).unwrap();
    // Discrete → exact: the 15 grid points of each triangle, at distance ||q| − 0.5|.
    let mut dd = Vec::new();
    for [a, b, cc] in &tris {
        for i in 0..=4 {
            for j in 0..=4 - i {
                let q = *a + (*b - *a) * (i as f64 / 4.0) + (*cc - *a) * (j as f64 / 4.0);
                dd.push((q.length() - 0.5).abs());
            }
        }
    }
    dd.sort_by(f64::total_cmp);
    let max = c["discrete_to_exact"]["max"].as_f64().unwrap();
    let med = c["discrete_to_exact"]["median"].as_f64().unwrap();
    assert!(
        (max - dd[dd.len() - 1]).abs() < 1e-9,
        "{max} vs {}",
        dd[dd.len() - 1]
    );
    assert!((med - dd[dd.len().div_ceil(2) - 1]).abs() < 1e-9);
    // Exact → discrete: points of the sphere to the nearest triangle by brute force, over the
    // icosphere samples (vertices and projected centroids).
    let ico = anisomesh::levelset::icosphere(3);
    let mut samples: Vec<DVec3> = ico.points.iter().map(|p| 0.5 * *p).collect();
    samples.extend(ico.triangles.iter().map(|t| {
        let c = t.iter().map(|&v| ico.points[v as usize]).sum::<DVec3>();
        0.5 * c.normalize()
    }));
    let brute = samples
        .iter()
        .map(|&q| {
            tris.iter()
                .map(|[a, b, cc]| {
                    let p =
                        anisomesh::levelset::triangulated::closest::closest_point(q, *a, *b, *cc);
                    (q - p.0).length()
                })
                .fold(f64::INFINITY, f64::min)
        })
        .fold(0.0, f64::max);
    let back = c["exact_to_discrete"]["max"].as_f64().unwrap();
    assert!((back - brute).abs() < 1e-12, "{back} vs {brute}");
    let exact = 4.0 / 3.0 * std::f64::consts::PI * 0.125;
    let err = c["volume_error"].as_f64().unwrap();
    assert!((err - (vol - exact)).abs() < 1e-12, "{err}");
    // Chords lie inside the sphere: the volume is too small, by less than the crude bound of
    // the area times the largest distance.
    assert!(err < 0.0 && -err < 3.2 * max, "{err} {max}");

    // The same zero level as labelled regions (inside 3, outside 2, as mmg3d -ls labels them):
    // the faces between them, the volume of region 3.
    let mut labelled = read3(&mp);
    labelled.tet_ref = mesh
        .tets
        .iter()
        .map(|t| {
            let c = t.iter().map(|&v| mesh.points[v as usize]).sum::<DVec3>() / 4.0;
            if c.length() < 0.5 {
                3
            } else {
                2
            }
        })
        .collect();
    let lp = d.join("labelled.mesh");
    io::write_medit3(&lp, &labelled).unwrap();
    let json = anisomesh_ok(&[
        "measure",
        s(&lp),
        "--shape",
        "sphere",
        "--json",
        "--sampling-level",
        "3",
    ]);
    let v: serde_json::Value = serde_json::from_str(&json).unwrap();
    assert!(v["discrete_surface"]
        .as_str()
        .unwrap()
        .contains("regions 3 and 2"));
    let (faces, vol3) =
        interface_triangles(&mesh.points, &mesh.tets, &labelled.tet_ref, 3, 2).unwrap();
    let c = &v["comparison"];
    assert_eq!(c["triangles"].as_u64().unwrap() as usize, faces.len());
    assert!((c["volume"].as_f64().unwrap() - vol3).abs() < 1e-12);
    let worst = faces
        .iter()
        .flat_map(|f| f.iter())
        .map(|p| (p.length() - 0.5).abs())
        .fold(0.0, f64::max);
    assert!(c["discrete_to_exact"]["max"].as_f64().unwrap() >= worst - 1e-12);
}

#[test]
fn bad_three_dimensional_input_is_one_typed_line() {
    let d = dir("bad");
    let mp = d.join("box.mesh");
    let mesh = kuhn_file(&mp, 2, 0.0, 1.0);
    let n = mesh.n_points();
    let out = d.join("out");
    let run = |args: &[&str]| {
        let mut a = vec!["adapt"];
        a.extend_from_slice(args);
        a.extend_from_slice(&["-o", s(&out)]);
        anisomesh(&a)
    };
    let good = io::sym3_to_file(&Sym3::iso(0.3));
    // A NaN tensor and an indefinite one: the vertex is named (1-based).
    let sp = d.join("nan.sol");
    let mut t = vec![good; n];
    t[6][2] = f64::NAN;
    tensor_sol(&sp, &t);
    assert_clean_error(&run(&["--input", s(&mp), "--sol", s(&sp)]), "vertex 7");
    let sp = d.join("indefinite.sol");
    let mut t = vec![good; n];
    t[3] = [1.0, 2.0, 1.0, 0.0, 0.0, 1.0];
    tensor_sol(&sp, &t);
    assert_clean_error(
        &run(&["--input", s(&mp), "--sol", s(&sp)]),
        "vertex 4 is not a metric",
    );
    // Size mismatch.
    let sp = d.join("short.sol");
    tensor_sol(&sp, &vec![good; n - 1]);
    assert_clean_error(&run(&["--input", s(&mp), "--sol", s(&sp)]), "vertices");
    // A 2D .sol with the 3D mesh, and a 3D .sol with a 2D mesh.
    let sp2 = d.join("two.sol");
    io::write_sol(&sp2, &Sol::scalar(vec![1.0; n])).unwrap();
    assert_clean_error(
        &run(&["--input", s(&mp), "--sol", s(&sp2)]),
        "a 2D solution for a 3D mesh",
    );
    let m2 = d.join("square.mesh");
    let sq = anisomesh::Mesh2::rectangle(
        anisomesh::DVec2::ZERO,
        anisomesh::DVec2::ONE,
        3,
        3,
        Default::default(),
    )
    .unwrap();
    io::write_mesh(&m2, &sq).unwrap();
    let sp3 = d.join("three.sol");
    tensor_sol(&sp3, &vec![good; sq.n_points()]);
    assert_clean_error(
        &run(&["--input", s(&m2), "--sol", s(&sp3)]),
        "a 3D solution for a 2D mesh",
    );
    // Sizes that are not positive.
    let sp = d.join("h.sol");
    let mut h = vec![0.2; n];
    h[2] = -0.1;
    io::write_sol(&sp, &Sol::scalar_dim(3, h)).unwrap();
    assert_clean_error(
        &run(&["--input", s(&mp), "--sol", s(&sp), "--sizes"]),
        "size at vertex 3",
    );
    // An inverted tetrahedron.
    let mut m = read3(&mp);
    m.tets[4].swap(0, 1);
    let inv = d.join("inverted.mesh");
    io::write_medit3(&inv, &m).unwrap();
    let sp = d.join("ok.sol");
    tensor_sol(&sp, &vec![good; n]);
    assert_clean_error(
        &run(&["--input", s(&inv), "--sol", s(&sp)]),
        "tetrahedron 5",
    );
    // A surface mesh without volume.
    let mut surf = read3(&mp);
    surf.tets.clear();
    surf.tet_ref.clear();
    let sm = d.join("surface.mesh");
    io::write_medit3(&sm, &surf).unwrap();
    assert_clean_error(&run(&["--input", s(&sm), "--sol", s(&sp)]), "surface mesh");
    // A level set without a zero level.
    let sp = d.join("positive.sol");
    io::write_sol(&sp, &Sol::scalar_dim(3, vec![1.0; n])).unwrap();
    assert_clean_error(&run(&["--input", s(&mp), "--sol", s(&sp)]), "no zero level");
    // --dim 3 with a 2D mesh.
    let sp = d.join("u2.sol");
    io::write_sol(&sp, &Sol::scalar(vec![1.0; sq.n_points()])).unwrap();
    assert_clean_error(
        &run(&["--input", s(&m2), "--sol", s(&sp), "--dim", "3"]),
        "is a 2D mesh",
    );
    // Nothing was written.
    assert!(!out.exists() || std::fs::read_dir(&out).unwrap().next().is_none());
    // measure --shape: an unknown shape, bad regions.
    assert_clean_error(
        &anisomesh(&["measure", s(&mp), "--shape", "cube"]),
        "expected star",
    );
    assert_clean_error(
        &anisomesh(&["measure", s(&mp), "--shape", "sphere", "--regions", "3"]),
        "IN,OUT",
    );
}

/// `metric` on a tetrahedral mesh writes the metric `adapt --input --sol` adapts to: 004 eq. (6)
/// of the input's zero level with adapt's 3D defaults and flags, graded as `--hgrad` grades it.
#[test]
fn the_metric_command_writes_the_metric_adapt_uses() {
    use anisomesh::adapt::{shape_metric3, DiscreteLevelSet3, Run3Options};
    let d = dir("metric-cmd");
    let (mp, sp) = (d.join("cube.mesh"), d.join("u.sol"));
    let mesh = kuhn_file(&mp, 6, -1.0, 1.0);
    let u: Vec<f64> = mesh.points.iter().map(|p| p.length() - 0.5).collect();
    io::write_sol(&sp, &Sol::scalar_dim(3, u.clone())).unwrap();
    let shape = DiscreteLevelSet3::new(&mesh.points, &mesh.tets, &u).unwrap();
    for (hgrad, eps) in [(None, "2e-2"), (Some("1.5"), "1e-2")] {
        let out = d.join(format!("m{}.sol", hgrad.unwrap_or("")));
        let mut args = vec![
            "metric",
            "--input",
            s(&mp),
            "--sol",
            s(&sp),
            "--eps",
            eps,
            "-o",
            s(&out),
        ];
        if let Some(g) = hgrad {
            args.extend_from_slice(&["--hgrad", g]);
        }
        anisomesh_ok(&args);
        let sol = io::read_sol(&out).unwrap();
        let io::SolField::Tensor3(t) = &sol.fields[0] else {
            panic!("no 3D tensor field")
        };
        let lm = anisomesh::adapt::LevelSetMetric {
            eps: eps.parse().unwrap(),
            // In 3D the band keeps its ratio to hmin (a length), not to eps.
            ..Run3Options::default().metric
        };
        let beta = hgrad.map(|g| g.parse().unwrap());
        let want = shape_metric3(&shape, &lm, &mesh.points, &mesh.tets, beta).unwrap();
        for (a, b) in t.iter().zip(&want) {
            let b = io::sym3_to_file(b);
            for k in 0..6 {
                assert!(
                    (a[k] - b[k]).abs() <= 1e-15 * b[k].abs().max(1.0),
                    "{a:?} {b:?}"
                );
            }
        }
    }
}
