//! Interoperability with the peers: MMG (`mmg2d_O3`) and Gmsh (Python module `gmsh`).
//!
//! Each check runs only when the peer is available (on `PATH` / importable) and prints clearly
//! that it was skipped otherwise; CI installs them with `pip install mmgpy gmsh`.

use anisomesh::io::{self, Sol, SolField};
use anisomesh::mesh::{circle_points, PolygonDomain};
use anisomesh::{DVec2, GridPattern, Mesh2, Sym2};
use std::path::{Path, PathBuf};
use std::process::Command;

fn scratch() -> PathBuf {
    let d = std::env::temp_dir().join(format!("anisomesh-interop-{}", std::process::id()));
    std::fs::create_dir_all(&d).unwrap();
    d
}

fn on_path(cmd: &str) -> bool {
    std::env::var_os("PATH")
        .is_some_and(|p| std::env::split_paths(&p).any(|d| d.join(cmd).is_file()))
}

fn python_has_gmsh() -> bool {
    Command::new("python3")
        .args(["-c", "import gmsh"])
        .output()
        .is_ok_and(|o| o.status.success())
}

fn run(cmd: &mut Command) -> String {
    let out = cmd.output().expect("spawn");
    let text = format!(
        "{}{}",
        String::from_utf8_lossy(&out.stdout),
        String::from_utf8_lossy(&out.stderr)
    );
    assert!(out.status.success(), "{cmd:?} failed:\n{text}");
    text
}

fn labels(m: &Mesh2) -> Vec<i32> {
    let mut l: Vec<i32> = m.boundary_edges().iter().map(|e| e.2).collect();
    l.sort_unstable();
    l.dedup();
    l
}

/// A metric with size 0.02 across the circle |x - (0.5, 0.5)| = 0.3 and 0.1 along it.
fn metric(m: &Mesh2) -> Vec<Sym2> {
    m.points
        .iter()
        .map(|p| {
            let d = *p - DVec2::splat(0.5);
            let n = if d.length() > 1e-12 {
                d.normalize()
            } else {
                DVec2::X
            };
            let h = 0.02 + 0.08 * ((d.length() - 0.3).abs() / 0.2).min(1.0);
            let (a, b) = (1.0 / (h * h), 100.0);
            Sym2::new(
                a * n.x * n.x + b * n.y * n.y,
                (a - b) * n.x * n.y,
                a * n.y * n.y + b * n.x * n.x,
            )
        })
        .collect()
}

#[test]
fn mmg2d_reads_our_files_and_we_read_its_output() {
    if !on_path("mmg2d_O3") {
        println!("SKIPPED: mmg2d_O3 is not on PATH (pip install mmgpy)");
        return;
    }
    let d = scratch();
    let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 10, 10, GridPattern::UnionJack).unwrap();
    let (a, s, b) = (d.join("a.mesh"), d.join("a.sol"), d.join("b.mesh"));
    io::write_mesh(&a, &m).unwrap();
    io::write_sol(&s, &Sol::metric(metric(&m))).unwrap();
    let log = run(Command::new("mmg2d_O3")
        .arg("-in")
        .arg(&a)
        .arg("-sol")
        .arg(&s)
        .arg("-out")
        .arg(&b)
        .args(["-v", "1"]));
    assert!(
        log.contains("ANISOTROPIC"),
        "MMG did not see a tensor metric:\n{log}"
    );
    let r = io::read_mesh(&b).unwrap();
    r.check().unwrap();
    assert!((r.area() - 1.0).abs() < 1e-12, "area {}", r.area());
    assert_eq!(labels(&r), vec![1, 2, 3, 4]);
    assert_eq!(r.corner.iter().filter(|&&c| c).count(), 4);
    assert!(r.n_points() > 2 * m.n_points(), "{} vertices", r.n_points());
    // MMG writes the interpolated metric beside the mesh.
    let sol = io::read_sol_for(&b.with_extension("sol"), r.n_points()).unwrap();
    assert!(matches!(&sol.fields[0], SolField::Tensor2(t) if t.iter().all(|t| t.det() > 0.0)));
    println!(
        "mmg2d_O3: read our {} vertices + metric, wrote {} vertices / {} triangles that we read",
        m.n_points(),
        r.n_points(),
        r.n_tris()
    );

    // Component order: a constant metric with h = 0.02 along x and 0.2 along y, written as
    // `xx xy yy` = `2500 0 25`; MMG's edges must have unit length in that metric (swapped
    // components would make them 10 times too long or too short).
    let aniso = Sym2::new(2500.0, 0.0, 25.0);
    let (s2, b2) = (d.join("aniso.sol"), d.join("aniso_out.mesh"));
    io::write_sol(&s2, &Sol::metric(vec![aniso; m.n_points()])).unwrap();
    run(Command::new("mmg2d_O3")
        .arg("-in")
        .arg(&a)
        .arg("-sol")
        .arg(&s2)
        .arg("-out")
        .arg(&b2)
        .args(["-v", "-1"]));
    let r = io::read_mesh(&b2).unwrap();
    let lens: Vec<f64> = r
        .edges()
        .iter()
        .map(|&([p, q], _, _)| {
            aniso
                .quad(r.points[p as usize] - r.points[q as usize])
                .sqrt()
        })
        .collect();
    let mean = lens.iter().sum::<f64>() / lens.len() as f64;
    let unit = lens.iter().filter(|&&l| (0.6..1.5).contains(&l)).count() as f64 / lens.len() as f64;
    assert!(
        (0.7..1.4).contains(&mean) && unit > 0.8,
        "mean metric length {mean}, unit fraction {unit}"
    );
    println!(
        "mmg2d_O3 with diag(2500, 25): mean metric edge length {mean:.3}, {:.0}% in [0.6, 1.5]",
        100.0 * unit
    );

    // Level-set discretisation (-ls): MMG splits the mesh along the zero level of our scalar
    // field; we read back two sub-domains (MMG refs 2 inside, 3 outside) and interface edges.
    let phi: Vec<f64> = m
        .points
        .iter()
        .map(|p| (*p - DVec2::splat(0.5)).length() - 0.3)
        .collect();
    let (ls, c) = (d.join("phi.sol"), d.join("c.mesh"));
    io::write_sol(&ls, &Sol::scalar(phi)).unwrap();
    run(Command::new("mmg2d_O3")
        .arg("-in")
        .arg(&a)
        .arg("-ls")
        .arg("-sol")
        .arg(&ls)
        .arg("-out")
        .arg(&c)
        .args(["-v", "-1"]));
    let r = io::read_mesh(&c).unwrap();
    r.check().unwrap();
    let inside: f64 = r
        .live_tris()
        .filter(|&t| r.tri_ref[t] == 3)
        .map(|t| r.tri_area(t))
        .sum();
    let outside: f64 = r
        .live_tris()
        .filter(|&t| r.tri_ref[t] == 2)
        .map(|t| r.tri_area(t))
        .sum();
    let disk = std::f64::consts::PI * 0.09;
    assert!((inside + outside - 1.0).abs() < 1e-12);
    assert!(
        (inside - disk).abs() < 0.02 && (outside - (1.0 - disk)).abs() < 0.02,
        "{inside} {outside}"
    );
    println!("mmg2d_O3 -ls: inside area {inside:.5} (disk {disk:.5}), read back with both refs");

    // A CDT mesh with a hole and labelled boundaries survives MMG remeshing.
    let hole: Vec<DVec2> = circle_points(DVec2::splat(0.5), 0.2, 40)
        .into_iter()
        .rev()
        .collect();
    let h = PolygonDomain::new(vec![DVec2::ZERO, DVec2::X, DVec2::ONE, DVec2::Y], 1)
        .hole(hole, 5)
        .with_max_area(0.005)
        .with_min_angle(25.0)
        .mesh()
        .unwrap();
    let (e, f) = (d.join("hole.mesh"), d.join("hole_out.mesh"));
    io::write_mesh(&e, &h).unwrap();
    run(Command::new("mmg2d_O3")
        .arg("-in")
        .arg(&e)
        .arg("-out")
        .arg(&f)
        .args(["-hmax", "0.05", "-v", "-1"]));
    let r = io::read_mesh(&f).unwrap();
    assert_eq!(labels(&r), vec![1, 5]);
    assert_eq!(r.boundary_loops().len(), 2);
    assert!(
        (r.area() - h.area()).abs() < 1e-3,
        "{} vs {}",
        r.area(),
        h.area()
    );
}

fn python(script: &str, args: &[&Path]) -> String {
    let mut c = Command::new("python3");
    c.arg("-c").arg(script);
    for a in args {
        c.arg(a);
    }
    run(&mut c)
}

#[test]
fn gmsh_reads_our_msh_and_we_read_gmsh_output() {
    if !python_has_gmsh() {
        println!("SKIPPED: the python module gmsh is not importable (pip install gmsh)");
        return;
    }
    let d = scratch();
    let mut m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 6, 5, GridPattern::Right).unwrap();
    for t in 0..m.n_tris() {
        m.tri_ref[t] = if m.tri_points(t)[0].y < 0.5 { 1 } else { 2 };
    }
    let p = d.join("ours.msh");
    io::write_mesh(&p, &m).unwrap();
    let out = python(
        "import gmsh, sys\n\
gmsh.initialize()\n\
gmsh.option.setNumber('General.Terminal', 0)\n\
gmsh.open(sys.argv[1])\n\
ty, tags, _ = gmsh.model.mesh.getElements(2)\n\
ntri = sum(len(x) for x, t in zip(tags, ty) if t == 2)\n\
ty, tags, _ = gmsh.model.mesh.getElements(1)\n\
nlin = sum(len(x) for x, t in zip(tags, ty) if t == 1)\n\
nn = len(gmsh.model.mesh.getNodes()[0])\n\
print(nn, ntri, nlin, ' '.join('%d:%d' % g for g in sorted(gmsh.model.getPhysicalGroups())))\n\
gmsh.finalize()\n",
        &[&p],
    );
    let nb = m.boundary_edges().len();
    let expect = format!(
        "{} {} {} 1:1 1:2 1:3 1:4 2:1 2:2",
        m.n_points(),
        m.n_tris(),
        nb
    );
    assert_eq!(out.trim(), expect);
    println!("gmsh read our .msh: {}", out.trim());

    // Gmsh meshes a rectangle minus a disk with physical groups; we read its 4.1 output.
    let g = d.join("gmsh.msh");
    python(
        "import gmsh, sys, math\n\
gmsh.initialize()\n\
gmsh.option.setNumber('General.Terminal', 0)\n\
occ = gmsh.model.occ\n\
r = occ.addRectangle(0, 0, 0, 2, 1)\n\
d = occ.addDisk(1, 0.5, 0, 0.25, 0.25)\n\
occ.cut([(2, r)], [(2, d)])\n\
occ.synchronize()\n\
gmsh.model.addPhysicalGroup(2, [e[1] for e in gmsh.model.getEntities(2)], 7, 'fluid')\n\
cs = [e[1] for e in gmsh.model.getEntities(1)]\n\
circ = [c for c in cs if abs(occ.getMass(1, c) - 2 * math.pi * 0.25) < 1e-6]\n\
gmsh.model.addPhysicalGroup(1, [c for c in cs if c not in circ], 3, 'walls')\n\
gmsh.model.addPhysicalGroup(1, circ, 4, 'cylinder')\n\
gmsh.option.setNumber('Mesh.MeshSizeMax', 0.05)\n\
gmsh.model.mesh.generate(2)\n\
gmsh.option.setNumber('Mesh.MshFileVersion', 4.1)\n\
gmsh.write(sys.argv[1])\n\
gmsh.finalize()\n",
        &[&g],
    );
    let r = io::read_msh_full(&g).unwrap();
    let m = &r.mesh;
    m.check().unwrap();
    assert!(m.tri_ref.iter().all(|&t| t == 7));
    assert_eq!(labels(m), vec![3, 4]);
    let exact = 2.0 - std::f64::consts::PI * 0.0625;
    assert!(
        (m.area() - exact).abs() < 5e-3,
        "area {} vs {exact}",
        m.area()
    );
    let names: Vec<&str> = r.physical_names.iter().map(|n| n.name.as_str()).collect();
    assert_eq!(names, ["walls", "cylinder", "fluid"]);
    println!(
        "read gmsh's .msh: {} vertices, {} triangles, area {:.5} (exact domain {exact:.5})",
        m.n_points(),
        m.n_tris(),
        m.area()
    );
}

#[test]
fn freefem_reads_our_mesh_and_we_read_its_output() {
    if !on_path("FreeFem++") {
        println!("SKIPPED: FreeFem++ is not on PATH");
        return;
    }
    let d = scratch();
    let m = io::read_mesh(&Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/square_hole.mesh"))
        .unwrap();
    io::write_mesh(&d.join("ours.mesh"), &m).unwrap();
    let script = "cout.precision(17);\nmesh Th = readmesh(\"ours.mesh\");\n\
cout << \"OURS \" << Th.nv << \" \" << Th.nt << \" \" << Th.nbe << \" \" << Th.measure << endl;\n\
int[int] lab = labels(Th);\n\
cout << \"LABELS \" << lab.n << \" \" << lab.min << \" \" << lab.max << endl;\n\
mesh Th2 = square(5, 4, [2*x, y]);\n\
Th2 = adaptmesh(Th2, 1./(0.05*0.05), 0, 1./(0.2*0.2), IsMetric=1, nbvx=100000);\n\
savemesh(Th2, \"theirs.mesh\");\n";
    std::fs::write(d.join("t.edp"), script).unwrap();
    let out = run(Command::new("FreeFem++")
        .current_dir(&d)
        .args(["-nw", "-v", "0", "t.edp"]));
    let ours = out.lines().find(|l| l.starts_with("OURS ")).expect(&out);
    let v: Vec<f64> = ours[5..]
        .split_whitespace()
        .map(|t| t.parse().unwrap())
        .collect();
    assert_eq!(v[0] as usize, m.n_points(), "{out}");
    assert_eq!(v[1] as usize, m.n_tris(), "{out}");
    assert_eq!(v[2] as usize, m.boundary_edges().len(), "{out}");
    assert!((v[3] - m.area()).abs() < 1e-9, "{out}");
    assert!(out.contains("LABELS 2 1 5"), "{out}");
    let r = io::read_mesh(&d.join("theirs.mesh")).unwrap();
    r.check().unwrap();
    assert!((r.area() - 2.0).abs() < 1e-12);
    assert_eq!(labels(&r), vec![1, 2, 3, 4]);
    println!(
        "FreeFem++ read our {} vertices / {} triangles; we read its adapted mesh ({} vertices)",
        m.n_points(),
        m.n_tris(),
        r.n_points()
    );
}

#[test]
fn mmg3d_reads_our_cube_and_3d_tensor_order() {
    if !on_path("mmg3d_O3") {
        println!("SKIPPED: mmg3d_O3 is not on PATH (pip install mmgpy)");
        return;
    }
    let d = scratch();
    let cube =
        io::read_medit3(&Path::new(env!("CARGO_MANIFEST_DIR")).join("meshes/cube.mesh")).unwrap();
    let (a, s, b) = (
        d.join("cube.mesh"),
        d.join("cube.sol"),
        d.join("cube_out.mesh"),
    );
    io::write_medit3(&a, &cube).unwrap();
    // h = 0.2, 0.1, 0.4 along x, y, z; file order xx xy yy xz yz zz (MMG's internal order
    // xx xy xz yy yz zz would make this tensor indefinite).
    let m = [25.0, 0.0, 100.0, 0.0, 0.0, 6.25];
    io::write_sol(
        &s,
        &Sol {
            dim: 3,
            fields: vec![SolField::Tensor3(vec![m; cube.points.len()])],
        },
    )
    .unwrap();
    run(Command::new("mmg3d_O3")
        .arg("-in")
        .arg(&a)
        .arg("-sol")
        .arg(&s)
        .arg("-out")
        .arg(&b)
        .args(["-v", "-1"]));
    let r = io::read_medit3(&b).unwrap();
    let mut lens = Vec::new();
    for t in &r.tets {
        for i in 0..4 {
            for j in i + 1..4 {
                let e = r.points[t[i] as usize] - r.points[t[j] as usize];
                lens.push((25.0 * e.x * e.x + 100.0 * e.y * e.y + 6.25 * e.z * e.z).sqrt());
            }
        }
    }
    let mean = lens.iter().sum::<f64>() / lens.len() as f64;
    assert!((0.7..1.4).contains(&mean), "mean metric edge length {mean}");
    let vol: f64 = r
        .tets
        .iter()
        .map(|t| {
            let p = t.map(|v| r.points[v as usize]);
            (p[1] - p[0]).cross(p[2] - p[0]).dot(p[3] - p[0]).abs() / 6.0
        })
        .sum();
    assert!((vol - 1.0).abs() < 1e-9, "volume {vol}");
    println!(
        "mmg3d_O3 read our cube + 3D tensor: {} tets, mean metric edge length {mean:.3}",
        r.tets.len()
    );
}

#[test]
fn vtk_reads_our_vtu() {
    let has_vtk = Command::new("python3")
        .args(["-c", "import vtkmodules.vtkIOXML"])
        .output()
        .is_ok_and(|o| o.status.success());
    if !has_vtk {
        println!("SKIPPED: the python module vtk (ParaView's reader) is not importable (pip install vtk)");
        return;
    }
    let d = scratch();
    let m = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 4, 3, GridPattern::CrissCross).unwrap();
    let phi: Vec<f64> = m.points.iter().map(|p| p.x - 0.25).collect();
    let grad = vec![DVec2::new(1.0, 0.0); m.n_points()];
    let met = metric(&m);
    let area: Vec<f64> = (0..m.n_tris()).map(|t| m.tri_area(t)).collect();
    let p = d.join("fields.vtu");
    io::write_vtu(
        &p,
        &m,
        &[
            ("phi", io::FieldRef::Scalar(&phi)),
            ("grad", io::FieldRef::Vector(&grad)),
            ("metric", io::FieldRef::Tensor(&met)),
        ],
        &[("area", &area)],
    )
    .unwrap();
    let out = python(VTK_SCRIPT, &[&p]);
    let expect = format!(
        "{} {} 5 1 3 9 {} 1.000000000000 -0.250000",
        m.n_points(),
        m.n_tris(),
        m.n_tris()
    );
    assert_eq!(out.trim(), expect);
    println!("VTK XML reader read our .vtu: {}", out.trim());
}

const VTK_SCRIPT: &str = r#"import sys
from vtkmodules.vtkIOXML import vtkXMLUnstructuredGridReader
r = vtkXMLUnstructuredGridReader()
r.SetFileName(sys.argv[1])
r.Update()
g = r.GetOutput()
pd, cd = g.GetPointData(), g.GetCellData()
tot = 0.0
for c in range(g.GetNumberOfCells()):
    ids = g.GetCell(c).GetPointIds()
    (ax, ay, _), (bx, by, _), (cx, cy, _) = [g.GetPoint(ids.GetId(k)) for k in range(3)]
    tot += 0.5 * ((bx - ax) * (cy - ay) - (by - ay) * (cx - ax))
print(g.GetNumberOfPoints(), g.GetNumberOfCells(), g.GetCellType(0),
      pd.GetArray('phi').GetNumberOfComponents(), pd.GetArray('grad').GetNumberOfComponents(),
      pd.GetArray('metric').GetNumberOfComponents(), cd.GetArray('tri_ref').GetNumberOfTuples(),
      '%.12f' % tot, '%.6f' % pd.GetArray('phi').GetRange()[0])
"#;
