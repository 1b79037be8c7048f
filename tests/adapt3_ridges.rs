//! Ridges and corners of a user's tetrahedral mesh kept by the adaptation: an L-shaped block
//! (a polyhedral, non-convex domain with a re-entrant edge), ridges found from the angle between
//! boundary normals and from labels, plus an edge polyline and a corner declared in its Medit
//! file. After adapting to a metric refined at the re-entrant edge, the output's ridges and the
//! input's coincide (Hausdorff distance ~ 0 both ways), every corner is still a vertex, the
//! volume is kept to 1e-10 and the mesh passes its check.

use anisomesh::adapt::{run3, Run3Options, Target3};
use anisomesh::io::{parse_medit3_features, write_medit3_features, Medit3};
use anisomesh::mesh3::{edge_key, DeclaredFeatures3, Mesh3, DEFAULT_RIDGE_ANGLE};
use anisomesh::metric::Sym3;
use anisomesh::DVec3;
use std::collections::HashMap;

/// The unit cube minus the quarter `x > 1/2, y > 1/2`, as Kuhn tetrahedra with `4 n` cells per
/// side; every boundary face labelled 1, except the face `y = 0` where `x > 1/2` (label 2).
fn l_block(n: usize) -> Mesh3 {
    let cube = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [4 * n; 3]).unwrap();
    let keep: Vec<[u32; 4]> = cube
        .tets
        .iter()
        .copied()
        .filter(|t| {
            let c = t.iter().map(|&v| cube.points[v as usize]).sum::<DVec3>() / 4.0;
            !(c.x > 0.5 && c.y > 0.5)
        })
        .collect();
    let mut map: HashMap<u32, u32> = HashMap::new();
    let mut points = Vec::new();
    let tets: Vec<[u32; 4]> = keep
        .iter()
        .map(|t| {
            t.map(|v| {
                *map.entry(v).or_insert_with(|| {
                    points.push(cube.points[v as usize]);
                    (points.len() - 1) as u32
                })
            })
        })
        .collect();
    let nt = tets.len();
    let mut m = Mesh3::from_parts(points, tets, vec![1; nt]);
    m.label_boundary(|m, f| {
        let p = f.map(|v| m.points[v as usize]);
        let c = (p[0] + p[1] + p[2]) / 3.0;
        if p.iter().all(|q| q.y == 0.0) && c.x > 0.5 {
            2
        } else {
            1
        }
    });
    m.check().unwrap();
    m
}

/// Distance from `p` to the segment `s`.
fn seg_dist(p: DVec3, s: [DVec3; 2]) -> f64 {
    let d = s[1] - s[0];
    let t = ((p - s[0]).dot(d) / d.length_squared()).clamp(0.0, 1.0);
    (p - (s[0] + t * d)).length()
}

/// The largest distance from points sampled on the segments `a` to the segments `b`.
fn one_way(a: &[[DVec3; 2]], b: &[[DVec3; 2]]) -> f64 {
    let mut worst = 0.0f64;
    for s in a {
        for k in 0..=8 {
            let p = s[0].lerp(s[1], k as f64 / 8.0);
            let d = b
                .iter()
                .map(|&t| seg_dist(p, t))
                .fold(f64::INFINITY, f64::min);
            worst = worst.max(d);
        }
    }
    worst
}

#[test]
fn ridges_and_corners_of_an_l_block_survive_adaptation() {
    let mesh = l_block(1);
    // Declared in the Medit file: the line y = 1/4 on the top face z = 1 and a required vertex
    // at its middle.
    let on_line = |p: DVec3| p.z == 1.0 && p.y == 0.25;
    let mut declared = DeclaredFeatures3::default();
    let line: Vec<u32> = {
        let mut v: Vec<u32> = (0..mesh.n_points() as u32)
            .filter(|&v| on_line(mesh.points[v as usize]))
            .collect();
        v.sort_by(|a, b| {
            mesh.points[*a as usize]
                .x
                .total_cmp(&mesh.points[*b as usize].x)
        });
        v
    };
    assert_eq!(line.len(), 5);
    declared.edges = line.windows(2).map(|w| [w[0], w[1]]).collect();
    declared.required = vec![line[2]];
    // Through the file format: written, read back, detected.
    let (tris, tri_ref): (Vec<[u32; 3]>, Vec<i32>) = mesh
        .boundary_faces()
        .map(|(t, i)| (mesh.face_vertices(t, i), mesh.face_ref[t][i]))
        .unzip();
    let medit = Medit3 {
        points: mesh.points.clone(),
        point_ref: vec![0; mesh.n_points()],
        tets: mesh.tets.clone(),
        tet_ref: mesh.tet_ref.clone(),
        tris,
        tri_ref,
    };
    let dir = std::env::temp_dir().join(format!("anisomesh_ridges_{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let path = dir.join("l.mesh");
    let file_features = anisomesh::mesh3::Features3 {
        ridges: declared
            .edges
            .iter()
            .map(|e| edge_key(e[0], e[1]))
            .collect(),
        corners: declared.required.clone(),
    };
    write_medit3_features(&path, &medit, &file_features).unwrap();
    let text = std::fs::read_to_string(&path).unwrap();
    let (_, read) = parse_medit3_features(&path, &text).unwrap();
    assert_eq!(read.edges, file_features.ridges);
    assert_eq!(read.corners, file_features.corners);
    let _ = std::fs::remove_dir_all(&dir);

    let mut start = mesh.clone();
    let declared = DeclaredFeatures3 {
        edges: read.edges,
        corners: read.corners,
        required: Vec::new(),
    };
    start.features = start
        .detect_features(DEFAULT_RIDGE_ANGLE, &declared)
        .unwrap();
    // The L-prism's 18 edges (perimeter 4 top and bottom, 6 vertical edges of length 1) in
    // segments of 1/4, the label change along x = 1/2 on y = 0 (4 segments) and the declared
    // line (4 segments); corners: the prism's 12, the ends of the label line and of the
    // declared line (each on a prism edge, so on 3 ridges) and the declared middle vertex.
    assert_eq!(start.features.ridges.len(), 16 + 16 + 24 + 4 + 4);
    assert_eq!(start.features.corners.len(), 12 + 2 + 2 + 1);
    start.check().unwrap();

    // A metric fine across the re-entrant edge x = y = 1/2, coarse along it.
    let metric = |p: DVec3| {
        let d = ((p.x - 0.5).powi(2) + (p.y - 0.5).powi(2)).sqrt();
        let h = 0.03 + 0.4 * d;
        Sym3::new(
            1.0 / (h * h),
            0.0,
            0.0,
            1.0 / (h * h),
            0.0,
            1.0 / 0.15f64.powi(2),
        )
    };
    let mut opts = Run3Options::default();
    opts.adapt.check_each_pass = true;
    let a = run3(Target3::Metric(&metric), Some(&start), &opts).unwrap();
    let out = &a.mesh;
    out.check().unwrap();
    eprintln!(
        "L-block: {} -> {} vertices, {} -> {} ridge edges, {} corners",
        start.n_points(),
        out.n_points(),
        start.features.ridges.len(),
        out.features.ridges.len(),
        out.features.corners.len()
    );
    assert!(out.n_points() > 4 * start.n_points(), "{}", out.n_points());
    assert!(
        out.features.ridges.len() > start.features.ridges.len(),
        "ridges {} -> {}",
        start.features.ridges.len(),
        out.features.ridges.len()
    );
    let (vin, vout) = (start.volume(), out.volume());
    assert!((vout - vin).abs() <= 1e-10 * vin, "volume {vin} -> {vout}");
    let (rin, rout) = (
        start.features.segments(&start.points),
        out.features.segments(&out.points),
    );
    let (d1, d2) = (one_way(&rin, &rout), one_way(&rout, &rin));
    assert!(
        d1 < 1e-12 && d2 < 1e-12,
        "ridge Hausdorff {d1:.2e} / {d2:.2e}"
    );
    let corners_out: Vec<DVec3> = out
        .features
        .corners
        .iter()
        .map(|&v| out.points[v as usize])
        .collect();
    assert_eq!(corners_out.len(), start.features.corners.len());
    for &c in &start.features.corners {
        let p = start.points[c as usize];
        assert!(corners_out.contains(&p), "corner {p} lost");
    }
    // Every boundary vertex of the output lies on the input's boundary planes.
    for (t, i) in out.boundary_faces() {
        for v in out.face_vertices(t, i) {
            let p = out.points[v as usize];
            let at = |x: f64, c: f64| (x - c).abs() <= 1e-12;
            let on = [p.x, p.y, p.z].iter().any(|&x| at(x, 0.0) || at(x, 1.0))
                || (at(p.x, 0.5) && p.y >= 0.5)
                || (at(p.y, 0.5) && p.x >= 0.5);
            assert!(on, "boundary vertex {p} off the block's faces");
        }
    }
}

#[test]
fn feature_detection_errors_and_angle() {
    let m = l_block(1);
    let none = DeclaredFeatures3::default();
    // At 100 degrees the right-angled prism edges are not ridges; the boundary of the label-2
    // rectangle still is (4 + 4 + 2 + 2 edges), and its right-angled turns are not corners.
    let f = m.detect_features(100.0, &none).unwrap();
    assert_eq!(f.ridges.len(), 12);
    assert_eq!(f.corners.len(), 0);
    assert!(m.detect_features(200.0, &none).is_err());
    // A declared edge through the interior, a vertex out of range.
    let centre = (0..m.n_points() as u32)
        .find(|&v| m.points[v as usize] == DVec3::new(0.25, 0.25, 0.5))
        .unwrap();
    let top = (0..m.n_points() as u32)
        .find(|&v| m.points[v as usize] == DVec3::new(0.25, 0.25, 0.75))
        .unwrap();
    let bad = DeclaredFeatures3 {
        edges: vec![[centre, top]],
        ..Default::default()
    };
    let e = m.detect_features(45.0, &bad).unwrap_err().to_string();
    assert!(e.contains("not an edge of a boundary triangle"), "{e}");
    let bad = DeclaredFeatures3 {
        corners: vec![m.n_points() as u32],
        ..Default::default()
    };
    assert!(m.detect_features(45.0, &bad).is_err());
}
