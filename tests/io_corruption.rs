//! Corrupt inputs: every reader returns an error naming the file, the line and the problem, and
//! never panics (a proptest mutates valid files by truncation, byte flips and token deletion).

use anisomesh::io;
use anisomesh::{DVec2, GridPattern, Mesh2};
use proptest::prelude::*;
use std::path::{Path, PathBuf};

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("anisomesh-io-bad-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d.join(name)
}

const HEAD: &str = "MeshVersionFormatted 2\nDimension 2\n";
const VERTS: &str = "Vertices\n4\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n";

/// Writes `text` to `name`, reads it with `read`, and checks the message names the file, the
/// line and contains `problem`.
fn expect_err<T: std::fmt::Debug>(
    name: &str,
    text: &str,
    read: impl Fn(&Path) -> anisomesh::Result<T>,
    line: Option<usize>,
    problem: &str,
) {
    let p = scratch(name);
    std::fs::write(&p, text).unwrap();
    let e = read(&p).expect_err(name).to_string();
    assert!(
        e.contains(name),
        "{name}: message does not name the file: {e}"
    );
    if let Some(l) = line {
        assert!(
            e.contains(&format!("{name}:{l}:")),
            "{name}: expected line {l}: {e}"
        );
    }
    assert!(e.contains(problem), "{name}: expected '{problem}': {e}");
}

#[test]
fn medit_corruptions_name_file_line_and_problem() {
    let tri = "Triangles\n2\n1 2 3 0\n1 3 4 0\n";
    // 1. Count larger than data: the next keyword is met where a number is expected.
    let t = format!("{HEAD}Vertices\n5\n0 0 1\n1 0 1\n1 1 1\n0 1 1\n{tri}End\n");
    expect_err(
        "count.mesh",
        &t,
        io::read_mesh,
        Some(9),
        "expected a number, found 'Triangles'",
    );
    // 2. Out-of-range vertex index.
    let t = format!("{HEAD}{VERTS}Triangles\n2\n1 2 3 0\n1 3 7 0\nEnd\n");
    expect_err(
        "range.mesh",
        &t,
        io::read_mesh,
        Some(12),
        "refers to vertex 7",
    );
    // 2b. Index 0 (files are 1-based).
    let t = format!("{HEAD}{VERTS}Triangles\n2\n1 2 3 0\n0 3 4 0\nEnd\n");
    expect_err("zero.mesh", &t, io::read_mesh, Some(12), "out of range");
    // 3. NaN coordinate.
    let t = format!("{HEAD}Vertices\n4\n0 0 1\nnan 0 1\n1 1 1\n0 1 1\n{tri}");
    expect_err("nan.mesh", &t, io::read_mesh, Some(6), "non-finite");
    // 4. Missing Vertices section.
    let t = format!("{HEAD}{tri}End\n");
    expect_err(
        "novert.mesh",
        &t,
        io::read_mesh,
        None,
        "no Vertices section",
    );
    // 5. Wrong dimension.
    let t = format!("MeshVersionFormatted 2\nDimension 4\n{VERTS}");
    expect_err(
        "dim.mesh",
        &t,
        io::read_mesh,
        Some(2),
        "unsupported Dimension 4",
    );
    // 6. Truncated mid-line.
    let t = format!("{HEAD}{VERTS}Triangles\n2\n1 2 3 0\n1 3");
    expect_err(
        "trunc.mesh",
        &t,
        io::read_mesh,
        Some(12),
        "unexpected end of file",
    );
    // 7. Duplicate triangles.
    let t = format!("{HEAD}{VERTS}Triangles\n3\n1 2 3 0\n1 3 4 0\n2 3 1 0\nEnd\n");
    expect_err("dup.mesh", &t, io::read_mesh, Some(13), "same vertices");
    // 8. One inverted triangle among counter-clockwise ones.
    let t = format!("{HEAD}{VERTS}Triangles\n2\n1 2 3 0\n1 4 3 0\nEnd\n");
    expect_err("inv.mesh", &t, io::read_mesh, Some(12), "mixed orientation");
    // 9. Non-numeric token.
    let t = format!("{HEAD}Vertices\n4\n0 0 1\n1 abc 1\n1 1 1\n0 1 1\n{tri}");
    expect_err(
        "token.mesh",
        &t,
        io::read_mesh,
        Some(6),
        "expected a number, found 'abc'",
    );
    // 10. Negative count.
    let t = format!("{HEAD}{VERTS}Triangles\n-2\n1 2 3 0\n");
    expect_err("neg.mesh", &t, io::read_mesh, Some(10), "negative count -2");
    // 11. Edges entry that is not an edge of the mesh (the diagonal 2-4 is not one).
    let t = format!("{HEAD}{VERTS}{tri}Edges\n2\n1 2 1\n2 4 3\nEnd\n");
    expect_err(
        "edge.mesh",
        &t,
        io::read_mesh,
        Some(16),
        "(2, 4) is not an edge",
    );
    // 12. Count smaller than data.
    let t = format!("{HEAD}{VERTS}Triangles\n1\n1 2 3 0\n1 3 4 0\nEnd\n");
    expect_err(
        "small.mesh",
        &t,
        io::read_mesh,
        Some(12),
        "where a keyword was expected",
    );
    // 13. Degenerate (zero-area) triangle.
    let t = format!("{HEAD}Vertices\n3\n0 0 0\n1 1 0\n2 2 0\nTriangles\n1\n1 2 3 0\n");
    expect_err("flat.mesh", &t, io::read_mesh, Some(10), "degenerate");
    // 14. Non-manifold edge (three triangles on edge 1-3).
    let t = format!(
        "{HEAD}Vertices\n5\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n2 0.5 0\n\
         Triangles\n3\n1 2 3 0\n1 3 4 0\n1 5 3 0\n"
    );
    let p = scratch("manifold.mesh");
    std::fs::write(&p, t).unwrap();
    let e = io::read_mesh(&p).unwrap_err().to_string();
    assert!(
        e.contains("manifold.mesh:") && (e.contains("more than two") || e.contains("overlap")),
        "{e}"
    );
    // 15. Unsupported element type.
    let t = format!("{HEAD}{VERTS}Quadrilaterals\n1\n1 2 3 4 0\n");
    expect_err("quad.mesh", &t, io::read_mesh, Some(9), "not supported");
    // 16. Not a mesh extension.
    let e = io::read_mesh(Path::new("x.stl")).unwrap_err().to_string();
    assert!(e.contains("x.stl") && e.contains(".stl"), "{e}");
    // 17. Missing file.
    let e = io::read_mesh(Path::new("/nonexistent/none.mesh"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("none.mesh"), "{e}");
}

#[test]
fn sol_corruptions() {
    let mesh = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 1, 1, GridPattern::Right).unwrap();
    let sol = "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n3\n1 1\n0\n1\n2\nEnd\n";
    // Vertex count differs from the mesh.
    let n = mesh.n_points();
    expect_err(
        "count.sol",
        sol,
        |p| io::read_sol_for(p, n),
        Some(4),
        "has 3 vertices but the mesh has 4",
    );
    // Unsupported type.
    let t = sol.replace("1 1\n", "1 4\n");
    expect_err(
        "type.sol",
        &t,
        io::read_sol,
        Some(5),
        "unsupported solution type 4",
    );
    // Truncated tensor.
    let t = "MeshVersionFormatted 2\nDimension 2\nSolAtVertices\n2\n1 3\n1 0 1\n1 0\n";
    expect_err(
        "tensor.sol",
        t,
        io::read_sol,
        Some(7),
        "unexpected end of file",
    );
    // No SolAtVertices.
    expect_err(
        "empty.sol",
        "MeshVersionFormatted 2\nDimension 2\nEnd\n",
        io::read_sol,
        None,
        "no SolAtVertices",
    );
    // Infinite value.
    let t = sol.replace("\n1\n2\n", "\ninf\n2\n");
    expect_err("inf.sol", &t, io::read_sol, Some(7), "non-finite");
}

const MSH: &str = "$MeshFormat\n4.1 0 8\n$EndMeshFormat\n\
$Nodes\n1 4 1 4\n2 1 0 4\n1\n2\n3\n4\n0 0 0\n1 0 0\n1 1 0\n0 1 0\n$EndNodes\n\
$Elements\n1 2 1 2\n2 1 2 2\n1 1 2 3\n2 1 3 4\n$EndElements\n";

#[test]
fn gmsh_corruptions() {
    let p = scratch("good.msh");
    std::fs::write(&p, MSH).unwrap();
    assert!((io::read_mesh(&p).unwrap().area() - 1.0).abs() < 1e-15);
    let t = MSH.replace("4.1 0 8", "2.2 0 8");
    expect_err(
        "v22.msh",
        &t,
        io::read_mesh,
        Some(2),
        "unsupported Gmsh format version 2.2",
    );
    let t = MSH.replace("4.1 0 8", "4.1 1 8");
    expect_err("bin.msh", &t, io::read_mesh, Some(2), "binary");
    let t = MSH.replace("2 1 3 4\n", "2 1 3 9\n");
    expect_err(
        "node.msh",
        &t,
        io::read_mesh,
        Some(20),
        "unknown node tag 9",
    );
    let t = MSH.replace("2 1 2 2\n", "2 1 3 2\n");
    expect_err(
        "quad.msh",
        &t,
        io::read_mesh,
        Some(18),
        "element type 3 is not supported",
    );
    let t = MSH.replace("1 1 0\n0 1 0", "1 1 0.5\n0 1 0");
    expect_err("z.msh", &t, io::read_mesh, Some(13), "z = 0.5");
    let t = MSH.replace("$EndNodes", "$EndNode");
    expect_err("end.msh", &t, io::read_mesh, Some(15), "expected $EndNodes");
    let t = MSH.replace("1 4 1 4\n", "1 5 1 5\n");
    expect_err("total.msh", &t, io::read_mesh, None, "announces 5 nodes");
    let t = MSH.replace("3\n4\n0 0 0", "3\n3\n0 0 0");
    expect_err(
        "duptag.msh",
        &t,
        io::read_mesh,
        None,
        "node tag 3 appears twice",
    );
}

#[test]
fn obj_errors_name_the_file() {
    let e = io::read_obj(Path::new("/nonexistent/missing.obj"))
        .unwrap_err()
        .to_string();
    assert!(e.contains("missing.obj"), "{e}");
    let p = scratch("nofaces.obj");
    std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 0 1 0\n").unwrap();
    let e = io::read_obj(&p).unwrap_err().to_string();
    assert!(
        e.contains("nofaces.obj") && e.contains("no triangles"),
        "{e}"
    );
    let p = scratch("badface.obj");
    std::fs::write(&p, "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 9\n").unwrap();
    let e = io::read_obj(&p).unwrap_err().to_string();
    assert!(e.contains("badface.obj"), "{e}");
}

/// Valid inputs the mutation proptest starts from (built once).
fn seeds() -> &'static [(&'static str, String)] {
    static SEEDS: std::sync::OnceLock<Vec<(&'static str, String)>> = std::sync::OnceLock::new();
    SEEDS.get_or_init(make_seeds)
}

fn make_seeds() -> Vec<(&'static str, String)> {
    let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 3, 2, GridPattern::UnionJack).unwrap();
    let mesh_path = scratch("seed.mesh");
    let msh_path = scratch("seed.msh");
    let sol_path = scratch("seed.sol");
    io::write_mesh(&mesh_path, &m).unwrap();
    io::write_mesh(&msh_path, &m).unwrap();
    let sol = io::Sol {
        dim: 2,
        fields: vec![
            io::SolField::Scalar(vec![0.5; m.n_points()]),
            io::SolField::Tensor2(vec![anisomesh::Sym2::IDENTITY; m.n_points()]),
        ],
    };
    io::write_sol(&sol_path, &sol).unwrap();
    let obj = "v 1 0 0\nv -1 0 0\nv 0 1 0\nv 0 -1 0\nv 0 0 1\nf 1 3 5\nf 3 2 5\nf 2 4 5 1\n";
    let cube = "MeshVersionFormatted 2\nDimension 3\nVertices\n4\n0 0 0 0\n1 0 0 0\n0 1 0 0\n\
0 0 1 0\nTetrahedra\n1\n1 2 3 4 1\nTriangles\n1\n1 2 3 2\nEnd\n";
    vec![
        ("mesh", std::fs::read_to_string(&mesh_path).unwrap()),
        ("msh", std::fs::read_to_string(&msh_path).unwrap()),
        ("sol", std::fs::read_to_string(&sol_path).unwrap()),
        ("obj", obj.to_string()),
        ("mesh3", cube.to_string()),
    ]
}

#[derive(Debug, Clone)]
enum Mutation {
    Truncate(usize),
    Flip(usize, u8),
    DeleteToken(usize),
    DuplicateToken(usize),
}

fn mutate(text: &str, muts: &[Mutation]) -> Vec<u8> {
    let mut b = text.as_bytes().to_vec();
    for m in muts {
        if b.is_empty() {
            break;
        }
        match *m {
            Mutation::Truncate(k) => b.truncate(k % b.len()),
            Mutation::Flip(k, x) => {
                let i = k % b.len();
                b[i] ^= x;
            }
            Mutation::DeleteToken(k) | Mutation::DuplicateToken(k) => {
                let s = String::from_utf8_lossy(&b).into_owned();
                let toks: Vec<(usize, &str)> = s
                    .split_ascii_whitespace()
                    .map(|t| (t.as_ptr() as usize - s.as_ptr() as usize, t))
                    .collect();
                if toks.is_empty() {
                    continue;
                }
                let (at, t) = toks[k % toks.len()];
                let mut out = s[..at].to_string();
                if matches!(m, Mutation::DuplicateToken(_)) {
                    out.push_str(t);
                    out.push(' ');
                    out.push_str(t);
                }
                out.push_str(&s[at + t.len()..]);
                b = out.into_bytes();
            }
        }
    }
    b
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), 1u8..=255).prop_map(|(k, x)| Mutation::Flip(k, x)),
        any::<usize>().prop_map(Mutation::DeleteToken),
        any::<usize>().prop_map(Mutation::DuplicateToken),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(3000))]
    #[test]
    fn mutated_files_never_panic(which in 0usize..5, muts in prop::collection::vec(mutation(), 1..4)) {
        let seeds = seeds();
        let (kind, text) = &seeds[which];
        let bytes = mutate(text, &muts);
        let p = Path::new("fuzz");
        let r = std::panic::catch_unwind(|| {
            let s = String::from_utf8_lossy(&bytes);
            match *kind {
                "mesh" => { let _ = io::parse_mesh2(p, &s); let _ = io::parse_medit3(p, &s); }
                "msh" => { let _ = io::parse_msh(p, &s); }
                "sol" => { let _ = io::parse_sol(p, &s, None); let _ = io::parse_sol(p, &s, Some(12)); }
                "obj" => { let _ = io::parse_obj(p, &bytes); }
                _ => { let _ = io::parse_medit3(p, &s); let _ = io::parse_mesh2(p, &s); }
            }
        });
        prop_assert!(r.is_ok(), "panic on mutated {} input: {:?}", kind, String::from_utf8_lossy(&bytes));
    }
}
