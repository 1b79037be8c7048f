//! `anisomesh ugawg cube-linear|cube-polar-1 [--n N] -o DIR`: the starting mesh of a UGAWG
//! benchmark (the Kuhn mesh of `[0,1]³` with `N` cubes per side), its metric at the vertices as a
//! Medit `.sol` (what `mmg3d_O3 -in DIR/CASE.mesh -sol DIR/CASE.sol` reads), and the
//! statistics of that mesh in the analytic metric: edge lengths integrated along the edges, and
//! the UGAWG measures (end-point rule) that the UGAWG study's published shares use.

use super::measure::{print_conformity, print_ugawg_line};
use anisomesh::io::{self, Medit3, Sol};
use anisomesh::mesh3::Mesh3;
use anisomesh::metric::ugawg::UgawgCase;
use anisomesh::metric::{conformity_analytic, conformity_ugawg};
use anisomesh::{DVec3, Error, Result};
use clap::Args;
use std::path::PathBuf;

/// Options of `anisomesh ugawg`.
#[derive(Debug, Args)]
pub struct UgawgArgs {
    /// cube-linear or cube-polar-1.
    pub case: String,
    /// Cubes per side of the Kuhn mesh (6 tetrahedra each).
    #[arg(long, default_value_t = 10)]
    pub n: usize,
    /// Output directory (written: CASE.mesh, CASE.sol).
    #[arg(short, long, default_value = "out")]
    pub output: PathBuf,
    /// Also adapt the starting mesh to the analytic metric (evaluated exactly at every new or
    /// moved vertex) and write CASE_adapted.mesh with its statistics.
    #[arg(long)]
    pub adapt: bool,
}

/// The Medit form of a tetrahedral mesh: its tetrahedra and labelled boundary triangles.
pub fn to_medit3(m: &Mesh3) -> Medit3 {
    let (tris, tri_ref): (Vec<[u32; 3]>, Vec<i32>) = m
        .boundary_faces()
        .map(|(t, i)| (m.face_vertices(t, i), m.face_ref[t][i]))
        .unzip();
    Medit3 {
        points: m.points.clone(),
        point_ref: vec![0; m.points.len()],
        tets: m.tets.clone(),
        tet_ref: m.tet_ref.clone(),
        tris,
        tri_ref,
    }
}

/// Runs `anisomesh ugawg`.
pub fn run(a: UgawgArgs) -> Result<()> {
    let case = UgawgCase::parse(&a.case)?;
    if !(1..=200).contains(&a.n) {
        return Err(Error::InvalidInput(format!(
            "--n {}: expected 1 to 200 cubes per side",
            a.n
        )));
    }
    let mesh = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [a.n; 3])?;
    std::fs::create_dir_all(&a.output).map_err(|e| Error::Io {
        path: a.output.clone(),
        source: e,
    })?;
    let mesh_path = a.output.join(format!("{}.mesh", case.name()));
    let sol_path = a.output.join(format!("{}.sol", case.name()));
    io::write_medit3(&mesh_path, &to_medit3(&mesh))?;
    let field = case.field(&mesh.points);
    io::write_sol(&sol_path, &Sol::metric3(&field))?;
    let metric = move |p| case.metric(p);
    let c = conformity_analytic(&mesh.points, &mesh.tets, &metric)?;
    print_conformity(
        &format!(
            "{}: Kuhn mesh {n}x{n}x{n}, {} vertices, {} tetrahedra, in the metric {}",
            case.name(),
            mesh.n_points(),
            mesh.n_tets(),
            case.name(),
            n = a.n
        ),
        &c,
    );
    print_ugawg_line(&conformity_ugawg(&mesh.points, &mesh.tets, &field)?);
    println!("wrote {}", mesh_path.display());
    println!("wrote {}", sol_path.display());
    if a.adapt {
        adapt(case, &mesh, &a.output)?;
    }
    Ok(())
}

/// Prints, per operator kind, the passes, changes and seconds of an adaptation.
fn print_passes(rep: &anisomesh::adapt::AdaptReport) {
    use anisomesh::adapt::PassKind;
    for kind in [
        PassKind::Split,
        PassKind::Collapse,
        PassKind::Flip,
        PassKind::Smooth,
    ] {
        let (mut n, mut count, mut s) = (0, 0, 0.0);
        for p in rep.passes.iter().filter(|p| p.kind == kind) {
            n += 1;
            count += p.count;
            s += p.seconds;
        }
        println!("  {kind:?}: {n} passes, {count} changes, {s:.2} s");
    }
}

/// Adapts `start` to the analytic metric of `case` and prints the statistics of the result
/// (the same conformity measure as for the starting mesh and as `anisomesh measure --ugawg`).
fn adapt(case: UgawgCase, start: &Mesh3, dir: &std::path::Path) -> Result<()> {
    use anisomesh::adapt::{run3, Run3Options, Target3};
    let metric = move |p: DVec3| case.metric(p);
    let a = run3(
        Target3::Metric(&metric),
        Some(start),
        &Run3Options::default(),
    )?;
    let r = &a.report;
    let c = conformity_analytic(&a.mesh.points, &a.mesh.tets, &metric)?;
    print_conformity(
        &format!(
            "{} adapted: {} vertices, {} tetrahedra, {:.2} s ({} cycles)",
            case.name(),
            r.vertices,
            r.tetrahedra,
            r.seconds,
            r.adapt.cycles
        ),
        &c,
    );
    let at_vertices = case.field(&a.mesh.points);
    print_ugawg_line(&conformity_ugawg(
        &a.mesh.points,
        &a.mesh.tets,
        &at_vertices,
    )?);
    print_passes(&r.adapt);
    let path = dir.join(format!("{}_adapted.mesh", case.name()));
    io::write_medit3(&path, &to_medit3(&a.mesh))?;
    println!("wrote {}", path.display());
    Ok(())
}
