//! Round trips write -> read for every format, and reading of peer-style variants (keywords in
//! any case, numbers split across lines, comments, unknown sections, clockwise meshes).

use anisomesh::io::{self, FieldRef, Medit3, PhysicalName, Sol, SolField};
use anisomesh::mesh::{from_polygon, PolygonDomain};
use anisomesh::{DVec2, DVec3, GridPattern, Mesh2, Sym2, NONE};
use std::path::PathBuf;

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("anisomesh-io-rt-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

/// A unit square with two sub-domains (x > 0.5 is label 2), the interface labelled 9, corners,
/// vertex labels and a required interior vertex.
fn labelled_square() -> Mesh2 {
    let mut m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 4, 4, GridPattern::UnionJack).unwrap();
    for t in 0..m.n_tris() {
        let c = m.tri_points(t).iter().sum::<DVec2>() / 3.0;
        m.tri_ref[t] = if c.x > 0.5 { 2 } else { 1 };
    }
    for t in 0..m.n_tris() {
        for i in 0..3 {
            let nb = m.neighbours[t][i];
            m.edge_ref[t][i] = if nb == NONE {
                m.edge_ref[t][i]
            } else if m.tri_ref[nb as usize] != m.tri_ref[t] {
                9
            } else {
                0
            };
        }
    }
    for v in 0..m.n_points() {
        m.vert_ref[v] = (v % 3) as i32;
    }
    m.required[12] = true;
    m.check().unwrap();
    m
}

#[test]
fn medit_2d_round_trip_is_exact() {
    let m = labelled_square();
    let p = scratch("square.mesh");
    io::write_mesh(&p, &m).unwrap();
    let r = io::read_mesh(&p).unwrap();
    assert_eq!(r, m);
    // A CDT mesh with Steiner points (arbitrary floats) reads back bit-exactly.
    let hole: Vec<DVec2> = (0..7)
        .map(|k| {
            let a = -(k as f64) * std::f64::consts::TAU / 7.0;
            DVec2::new(0.5 + 0.2 * a.cos(), 0.5 + 0.2 * a.sin())
        })
        .collect();
    let sq = vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y];
    let c = from_polygon(&sq, &[hole], Some(0.01), Some(28.0)).unwrap();
    let p = scratch("cdt.mesh");
    io::write_mesh(&p, &c).unwrap();
    assert_eq!(io::read_mesh(&p).unwrap(), c);
}

#[test]
fn gmsh_round_trip_keeps_labels_and_physical_groups() {
    let m = labelled_square();
    let p = scratch("square.msh");
    let names = vec![
        PhysicalName {
            dim: 2,
            tag: 1,
            name: "left part".into(),
        },
        PhysicalName {
            dim: 1,
            tag: 9,
            name: "interface".into(),
        },
    ];
    io::write_msh_named(&p, &m, &names).unwrap();
    let g = io::read_msh_full(&p).unwrap();
    assert_eq!(g.physical_names, names);
    let r = g.mesh;
    assert_eq!(r.points, m.points);
    assert_eq!(r.tris, m.tris);
    assert_eq!(r.tri_ref, m.tri_ref);
    assert_eq!(r.edge_ref, m.edge_ref);
    assert_eq!(r.corner, m.corner);
    // Gmsh point elements carry the corners; they are read as corner and required vertices.
    assert_eq!(r.required, m.corner);
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.starts_with("$MeshFormat\n4.1 0 8\n"));
    // Physical tags of the curves: labels 1..4 and 9; of the surfaces 1 and 2.
    let mut labels: Vec<i32> = r
        .edge_ref
        .iter()
        .flatten()
        .copied()
        .filter(|&l| l != 0)
        .collect();
    labels.sort_unstable();
    labels.dedup();
    assert_eq!(labels, vec![1, 2, 3, 4, 9]);
    // Writing through write_mesh (no names) and reading again gives the same mesh.
    io::write_mesh(&p, &r).unwrap();
    assert_eq!(io::read_mesh(&p).unwrap(), r);
}

#[test]
fn gmsh_reads_sparse_tags_parametric_nodes_and_cw_surfaces() {
    // Node tags 10, 20, 30, 40 in two blocks (one parametric on a curve); triangles clockwise
    // (a surface with normal -z): reoriented on reading.
    let text = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n\
$Entities\n0 1 1 0\n7 0 0 0 1 0 0 1 3 0\n5 0 0 0 1 1 0 1 11 0\n$EndEntities\n\
$Nodes\n2 4 10 40\n1 7 1 1\n20\n1 0 0 0.5\n2 5 0 3\n10\n30\n40\n0 0 0\n1 1 0\n0 1 0\n$EndNodes\n\
$Elements\n2 3 1 3\n1 7 1 1\n1 10 20\n2 5 2 2\n2 10 30 20\n3 10 40 30\n$EndElements\n\
$Comments\nanything \"at all\" 1 2\n$EndComments\n";
    let p = scratch("sparse.msh");
    std::fs::write(&p, text).unwrap();
    let m = io::read_mesh(&p).unwrap();
    m.check().unwrap();
    assert_eq!(m.n_points(), 4);
    assert_eq!(m.points[1], DVec2::new(1.0, 0.0)); // tag 20 is the second smallest
    assert!((m.area() - 1.0).abs() < 1e-15);
    assert!(m.tri_ref.iter().all(|&r| r == 11));
    let bottom: Vec<i32> = m
        .boundary_edges()
        .iter()
        .filter(|e| m.points[e.0 as usize].y == 0.0 && m.points[e.1 as usize].y == 0.0)
        .map(|e| e.2)
        .collect();
    assert_eq!(bottom, vec![3]);
}

#[test]
fn medit_3d_round_trip() {
    // The unit cube cut into 6 Kuhn tetrahedra, with its 12 boundary triangles.
    let points: Vec<DVec3> = (0..8)
        .map(|k| DVec3::new((k & 1) as f64, ((k >> 1) & 1) as f64, ((k >> 2) & 1) as f64))
        .collect();
    let tets = vec![
        [0, 1, 3, 7],
        [0, 1, 5, 7],
        [0, 2, 3, 7],
        [0, 2, 6, 7],
        [0, 4, 5, 7],
        [0, 4, 6, 7],
    ];
    let m = Medit3 {
        point_ref: (0..8).collect(),
        tet_ref: vec![1, 1, 2, 2, 3, 3],
        tris: vec![[0, 1, 3], [0, 3, 2]],
        tri_ref: vec![5, 6],
        points,
        tets,
    };
    let p = scratch("cube.mesh");
    io::write_medit3(&p, &m).unwrap();
    assert_eq!(io::read_medit3(&p).unwrap(), m);
    match io::read_any(&p).unwrap() {
        io::AnyFile::Medit3(r) => assert_eq!(r, m),
        other => panic!("read_any gave {other:?}"),
    }
    let e = io::read_mesh(&p).unwrap_err().to_string();
    assert!(e.contains("volume mesh"), "{e}");
}

#[test]
fn sol_round_trip_all_types() {
    let n = 5;
    let s2 = Sol {
        dim: 2,
        fields: vec![
            SolField::Scalar((0..n).map(|v| v as f64 / 3.0 - 0.7).collect()),
            SolField::Vector((0..n).map(|v| [v as f64, -1e-20 * v as f64, 0.0]).collect()),
            SolField::Tensor2(
                (0..n)
                    .map(|v| Sym2::new(1e4 + v as f64, 0.1, 3.0))
                    .collect(),
            ),
        ],
    };
    let p = scratch("all.sol");
    io::write_sol(&p, &s2).unwrap();
    assert_eq!(io::read_sol(&p).unwrap(), s2);
    assert_eq!(io::read_sol_for(&p, n).unwrap(), s2);
    // The 2D tensor is written in the Medit/MMG order xx xy yy.
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.contains("SolAtVertices\n5\n3 1 2 3\n"), "{text}");
    assert!(text.contains("-0.7 0 -0 10000 0.1 3\n"), "{text}");
    let s3 = Sol {
        dim: 3,
        fields: vec![
            SolField::Tensor3(
                (0..n)
                    .map(|v| [1.0, 2.0, 3.0, 4.0, 5.0, v as f64])
                    .collect(),
            ),
            SolField::Vector((0..n).map(|v| [1.0, 2.0, v as f64]).collect()),
        ],
    };
    let p = scratch("all3.sol");
    io::write_sol(&p, &s3).unwrap();
    assert_eq!(io::read_sol(&p).unwrap(), s3);
}

#[test]
fn vtu_is_well_formed_and_complete() {
    let m = labelled_square();
    let n = m.n_points();
    let phi: Vec<f64> = m.points.iter().map(|p| p.x - 0.5).collect();
    let grad: Vec<DVec2> = vec![DVec2::X; n];
    let met: Vec<Sym2> = (0..n)
        .map(|v| Sym2::new(1.0 + v as f64, 0.5, 2.0))
        .collect();
    let area: Vec<f64> = (0..m.n_tris()).map(|t| m.tri_area(t)).collect();
    let p = scratch("fields.vtu");
    io::write_vtu(
        &p,
        &m,
        &[
            ("phi", FieldRef::Scalar(&phi)),
            ("grad", FieldRef::Vector(&grad)),
            ("metric", FieldRef::Tensor(&met)),
            ("metric3", FieldRef::TensorComponents(&met)),
        ],
        &[("area", &area)],
    )
    .unwrap();
    let text = std::fs::read_to_string(&p).unwrap();
    assert!(text.starts_with("<?xml") && text.trim_end().ends_with("</VTKFile>"));
    let piece = format!(
        "<Piece NumberOfPoints=\"{n}\" NumberOfCells=\"{}\">",
        m.n_tris()
    );
    assert!(text.contains(&piece));
    // Every DataArray holds (count x components) finite numbers.
    let mut arrays = 0;
    for chunk in text.split("<DataArray").skip(1) {
        let (head, rest) = chunk.split_once('>').unwrap();
        let body = rest.split("</DataArray>").next().unwrap();
        let name = head
            .split("Name=\"")
            .nth(1)
            .unwrap()
            .split('"')
            .next()
            .unwrap();
        let comps: usize = head
            .split("NumberOfComponents=\"")
            .nth(1)
            .map_or(1, |s| s.split('"').next().unwrap().parse().unwrap());
        let vals: Vec<f64> = body
            .split_whitespace()
            .map(|t| t.parse().unwrap())
            .collect();
        assert!(vals.iter().all(|v| v.is_finite()), "{name}");
        let count = match name {
            "Points" | "phi" | "grad" | "metric" | "metric3" => n,
            "connectivity" => 3 * m.n_tris(),
            _ => m.n_tris(),
        };
        assert_eq!(vals.len(), count * comps, "{name}");
        arrays += 1;
    }
    assert_eq!(arrays, 1 + 3 + 4 + 2);
    assert_eq!(
        text.matches("<DataArray").count(),
        text.matches("</DataArray>").count()
    );
    // NaN fields are refused.
    let bad = vec![f64::NAN; n];
    let e = io::write_vtu(&p, &m, &[("bad", FieldRef::Scalar(&bad))], &[]).unwrap_err();
    assert!(e.to_string().contains("bad") && e.to_string().contains("non-finite"));
}

#[test]
fn obj_octahedron_and_quads() {
    let p = scratch("octa.obj");
    let text = "# octahedron\nv 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nv 0 0 -1\n\
f 1 3 5\nf 3 2 5\nf 2 4 5\nf 4 1 5\nf 3 1 6\nf 2 3 6\nf 4 2 6\nf 1 4 6\n";
    std::fs::write(&p, text).unwrap();
    let s = io::read_obj(&p).unwrap();
    assert_eq!((s.points.len(), s.tris.len()), (6, 8));
    // Closed surface: every edge used twice.
    let mut e: Vec<(u32, u32)> = s
        .tris
        .iter()
        .flat_map(|t| (0..3).map(move |i| (t[i].min(t[(i + 1) % 3]), t[i].max(t[(i + 1) % 3]))))
        .collect();
    e.sort_unstable();
    assert!(e.chunks(2).all(|c| c[0] == c[1]) && e.len() == 24);
    let q = scratch("quad.obj");
    std::fs::write(&q, "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nf 1 2 3 4\n").unwrap();
    assert_eq!(io::read_obj(&q).unwrap().tris.len(), 2);
}

#[test]
fn medit_peer_variants_are_read() {
    // Lower-case keywords, numbers split across lines, comments, unknown sections with data,
    // clockwise triangles (repaired), Dimension 3 with z = 0, no End.
    let text = "meshversionformatted\n1\n# comment line\ndimension 3\nvertices 4\n\
0 0 0 1\n1 0 0 1 0 1\n0 1 1 1\n0 1\nNormals 1\n0 0 1\nNormalAtVertices 1\n1 1\n\
triangles 2\n1 3 2 7\n2 3 4 7\nEDGES 1\n1 2 5 # labelled\nRidges 1\n1\n";
    let p = scratch("peer.mesh");
    std::fs::write(&p, text).unwrap();
    let m = io::read_mesh(&p).unwrap();
    m.check().unwrap();
    assert!((m.area() - 1.0).abs() < 1e-15);
    assert_eq!(m.tris[0], [0, 1, 2]);
    let labels: Vec<i32> = m.boundary_edges().iter().map(|e| e.2).collect();
    assert_eq!(labels.iter().filter(|&&l| l == 5).count(), 1);
    assert_eq!(labels.iter().filter(|&&l| l == 1).count(), 3);
}

#[test]
fn cdt_sample_domain_round_trips_through_gmsh() {
    let c = DVec2::splat(0.5);
    let m = PolygonDomain::new(vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y], 1)
        .interface(anisomesh::mesh::circle_points(c, 0.3, 48), 3, 2)
        .with_size(0.03)
        .with_min_angle(25.0)
        .mesh()
        .unwrap();
    let p = scratch("circle.msh");
    io::write_mesh(&p, &m).unwrap();
    let r = io::read_mesh(&p).unwrap();
    assert_eq!(r.points, m.points);
    assert_eq!(r.tris, m.tris);
    assert_eq!(r.tri_ref, m.tri_ref);
    assert_eq!(r.edge_ref, m.edge_ref);
}

#[test]
fn freefem_style_header_is_read() {
    // FreeFem++/BAMG: version 0, quoted Identifier and Geometry strings (which may contain
    // keyword-like words), geometric sections after the elements.
    let text = "MeshVersionFormatted 0\n\nDimension\n2\n\nIdentifier\n\"Vertices Triangles 3\"\n\n\
Geometry\n\"x.gmsh\"\n\nVertices\n4\n0 0 1\n1 0 2\n1 1 3\n0 1 4\n\nEdges\n1\n1 2 1\n\n\
Triangles\n2\n1 2 3 0\n1 3 4 0\n\nSubDomainFromMesh\n1\n3 1 1 0\n\nVertexOnGeometricVertex\n1\n1 1\n\nEnd\n";
    let p = scratch("ff.mesh");
    std::fs::write(&p, text).unwrap();
    let m = io::read_mesh(&p).unwrap();
    assert_eq!((m.n_points(), m.n_tris()), (4, 2));
    assert_eq!(m.vert_ref, vec![1, 2, 3, 4]);
    assert!((m.area() - 1.0).abs() < 1e-15);
}
