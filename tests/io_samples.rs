//! The sample files in `meshes/` are exactly what the generators below produce, and every one of
//! them is accepted by `io::read_any` (CI runs `anisomesh info` on each).
//!
//! Regenerate them with `ANISOMESH_WRITE_SAMPLES=1 cargo test --release --test io_samples`.

use anisomesh::io::{self, AnyFile, Medit3, Sol, SolField};
use anisomesh::levelset::{radial_surface, StarSurface};
use anisomesh::mesh::{circle_points, PolygonDomain};
use anisomesh::{DVec2, DVec3, GridPattern, Mesh2, Sym2};
use std::path::{Path, PathBuf};

fn dir() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes")
}

fn square() -> Mesh2 {
    Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 8, 8, GridPattern::UnionJack).unwrap()
}

fn square_hole() -> Mesh2 {
    let hole: Vec<DVec2> = circle_points(DVec2::splat(0.5), 0.2, 32)
        .into_iter()
        .rev()
        .collect();
    PolygonDomain::new(vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y], 1)
        .hole(hole, 5)
        .with_max_area(0.004)
        .with_min_angle(25.0)
        .mesh()
        .unwrap()
}

/// The unit cube split into 2x2x2 cells of 6 Kuhn tetrahedra each (positively oriented), with
/// its boundary triangles oriented outwards and labelled by face (1..6).
fn cube() -> Medit3 {
    let n = 2usize;
    let id = |i: usize, j: usize, k: usize| (i + (n + 1) * (j + (n + 1) * k)) as u32;
    let mut points = Vec::new();
    for k in 0..=n {
        for j in 0..=n {
            for i in 0..=n {
                points.push(DVec3::new(i as f64, j as f64, k as f64) / n as f64);
            }
        }
    }
    let vol = |t: &[u32; 4]| {
        let p = t.map(|v| points[v as usize]);
        (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0])
    };
    let mut tets = Vec::new();
    for k in 0..n {
        for j in 0..n {
            for i in 0..n {
                let c = |b: usize| id(i + (b & 1), j + ((b >> 1) & 1), k + ((b >> 2) & 1));
                for path in [[1, 3], [1, 5], [2, 3], [2, 6], [4, 5], [4, 6]] {
                    let mut t = [c(0), c(path[0]), c(path[1]), c(7)];
                    if vol(&t) < 0.0 {
                        t.swap(2, 3);
                    }
                    tets.push(t);
                }
            }
        }
    }
    let mut faces = std::collections::HashMap::new();
    for t in &tets {
        for skip in 0..4 {
            let f: Vec<u32> = (0..4).filter(|&q| q != skip).map(|q| t[q]).collect();
            let mut key = [f[0], f[1], f[2]];
            key.sort_unstable();
            faces
                .entry(key)
                .or_insert_with(Vec::new)
                .push(([f[0], f[1], f[2]], t[skip]));
        }
    }
    let mut tris = Vec::new();
    let mut tri_ref = Vec::new();
    let mut keys: Vec<_> = faces.iter().filter(|(_, v)| v.len() == 1).collect();
    keys.sort_by_key(|(k, _)| **k);
    for (_, v) in keys {
        let (mut f, opp) = v[0];
        let p = f.map(|q| points[q as usize]);
        let nrm = (p[1] - p[0]).cross(p[2] - p[0]);
        if nrm.dot(points[opp as usize] - p[0]) > 0.0 {
            f.swap(1, 2);
        }
        let c = (p[0] + p[1] + p[2]) / 3.0;
        let label = if c.x == 0.0 {
            1
        } else if c.x == 1.0 {
            2
        } else if c.y == 0.0 {
            3
        } else if c.y == 1.0 {
            4
        } else if c.z == 0.0 {
            5
        } else {
            6
        };
        tris.push(f);
        tri_ref.push(label);
    }
    Medit3 {
        point_ref: vec![0; points.len()],
        tet_ref: vec![1; tets.len()],
        points,
        tets,
        tris,
        tri_ref,
    }
}

fn level_set(m: &Mesh2) -> Sol {
    Sol::scalar(
        m.points
            .iter()
            .map(|p| (*p - DVec2::splat(0.5)).length() - 0.3)
            .collect(),
    )
}

/// A metric refining across the circle of radius 0.3: size 0.01 normal to it near it, 0.1
/// elsewhere (004 §3.3: eigenvalues 1/h^2 along the normal and tangent).
fn metric(m: &Mesh2) -> Sol {
    Sol::metric(
        m.points
            .iter()
            .map(|p| {
                let d = *p - DVec2::splat(0.5);
                let r = d.length();
                let nrm = if r > 1e-12 { d / r } else { DVec2::X };
                let h_n = 0.01 + 0.09 * ((r - 0.3).abs() / 0.2).min(1.0);
                let (a, b) = (1.0 / (h_n * h_n), 1.0 / (0.1 * 0.1));
                let n = Sym2::outer(nrm);
                let t = Sym2::outer(nrm.perp());
                Sym2::new(
                    a * n.xx + b * t.xx,
                    a * n.xy + b * t.xy,
                    a * n.yy + b * t.yy,
                )
            })
            .collect(),
    )
}

const OCTAHEDRON: &str = "# regular octahedron, outward-oriented faces\n\
v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";

/// Writes every sample into `d`.
fn generate(d: &Path) {
    let sq = square();
    io::write_mesh(&d.join("square.mesh"), &sq).unwrap();
    io::write_mesh(&d.join("square.msh"), &sq).unwrap();
    io::write_mesh(&d.join("square_hole.mesh"), &square_hole()).unwrap();
    io::write_medit3(&d.join("cube.mesh"), &cube()).unwrap();
    io::write_sol(&d.join("square_levelset.sol"), &level_set(&sq)).unwrap();
    io::write_sol(&d.join("square_metric.sol"), &metric(&sq)).unwrap();
    io::atomic_write(&d.join("octahedron.obj"), |w| {
        w.write_all(OCTAHEDRON.as_bytes())
    })
    .unwrap();
    // The 004 star surface, as `anisomesh triangulate --shape star [--level 4]` writes it.
    let star = StarSurface::PAPER;
    for (name, level) in [("star.obj", 6), ("star_coarse.obj", 4)] {
        let s = radial_surface(star.centre, |p| star.radius_towards(p), level);
        io::write_obj(&d.join(name), &s.points, &s.triangles, 7).unwrap();
    }
}

#[test]
fn samples_are_current_and_readable() {
    if std::env::var_os("ANISOMESH_WRITE_SAMPLES").is_some() {
        std::fs::create_dir_all(dir()).unwrap();
        generate(&dir());
    }
    let tmp = std::env::temp_dir().join(format!("anisomesh-samples-{}", std::process::id()));
    std::fs::create_dir_all(&tmp).unwrap();
    generate(&tmp);
    let mut total = 0u64;
    let mut names: Vec<String> = std::fs::read_dir(dir())
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    names.sort();
    assert_eq!(
        names,
        [
            "cube.mesh",
            "octahedron.obj",
            "square.mesh",
            "square.msh",
            "square_hole.mesh",
            "square_levelset.sol",
            "square_metric.sol",
            "star.obj",
            "star_coarse.obj"
        ]
    );
    for name in &names {
        let committed = dir().join(name);
        if !name.starts_with("star") {
            total += std::fs::metadata(&committed).unwrap().len();
        }
        let a = io::read_any(&committed).unwrap_or_else(|e| panic!("{e}"));
        let b = io::read_any(&tmp.join(name)).unwrap();
        match (&a, &b) {
            (AnyFile::Mesh2(x), AnyFile::Mesh2(y)) => {
                x.check().unwrap();
                if name == "square_hole.mesh" {
                    // spade's refinement may change between patch releases: compare geometry.
                    assert!((x.area() - y.area()).abs() < 1e-12);
                    assert!(
                        (x.area() - (1.0 - 16.0 * 0.04 * (std::f64::consts::PI / 16.0).sin()))
                            .abs()
                            < 1e-12
                    );
                } else {
                    assert_eq!(x, y, "{name}");
                }
            }
            (AnyFile::Medit3(x), AnyFile::Medit3(y)) => assert_eq!(x, y),
            (AnyFile::Sol(x), AnyFile::Sol(y)) => {
                assert_eq!(x, y);
                assert_eq!(x.n_vertices(), 81);
            }
            (AnyFile::Surface(x), AnyFile::Surface(y)) => assert_eq!(x, y),
            _ => panic!("{name}: different kinds"),
        }
    }
    // The small samples stay small; the star surfaces are the fine triangulations the 3D
    // commands use (about 3 MB and 0.2 MB).
    assert!(total < 200_000, "samples take {total} bytes");
    // The metric sample is SPD everywhere and the sols fit the square.
    let sq = io::read_mesh(&dir().join("square.mesh")).unwrap();
    assert_eq!(sq.n_points(), 81);
    let s = io::read_sol_for(&dir().join("square_metric.sol"), sq.n_points()).unwrap();
    match &s.fields[0] {
        SolField::Tensor2(m) => assert!(m.iter().all(|t| t.xx > 0.0 && t.det() > 0.0)),
        f => panic!("unexpected field {f:?}"),
    }
    // The cube: 48 tetrahedra of total volume 1, 48 boundary triangles.
    let c = io::read_medit3(&dir().join("cube.mesh")).unwrap();
    let vol: f64 = c
        .tets
        .iter()
        .map(|t| {
            let p = t.map(|v| c.points[v as usize]);
            (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]) / 6.0
        })
        .sum();
    assert_eq!((c.tets.len(), c.tris.len()), (48, 48));
    assert!((vol - 1.0).abs() < 1e-14);
}
