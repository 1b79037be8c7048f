//! The fitted mesh beside `mmg2d_O3 -ls -noinsert -noswap -nomove` (when installed): on the same
//! grid and level set both cut the mesh along the zero level with the same labels, and the
//! insides have the same area.

use crate::app::repro::peers::{find_program, run_with_timeout};
use anisomesh::backends::fitted::{fit, FitOptions, REF_INSIDE, REF_INTERFACE};
use anisomesh::io::{self, Sol};
use anisomesh::levelset::enclosed_area;
use anisomesh::{DVec2, GridPattern, Mesh2};
use std::process::Command;
use std::time::Duration;

fn area_label(m: &Mesh2, label: i32) -> f64 {
    m.live_tris()
        .filter(|&t| m.tri_ref[t] == label)
        .map(|t| m.tri_area(t))
        .sum()
}

#[test]
fn fitted_mesh_matches_mmg2d_ls() {
    let base = Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, 50, 50, GridPattern::Right).unwrap();
    // Two disks, one of them cut by the boundary x = 1.
    let u: Vec<f64> = base
        .points
        .iter()
        .map(|&p| {
            let a = (p - DVec2::new(0.353, 0.41)).length() - 0.21;
            let b = (p - DVec2::new(0.97, 0.72)).length() - 0.17;
            a.min(b)
        })
        .collect();
    let ours = fit(&base, &u, &FitOptions::default()).unwrap();
    ours.mesh.check().unwrap();
    let p1 = enclosed_area(&base, &u).unwrap();
    assert!((ours.area_inside() - p1).abs() <= 1e-12 * p1);
    let Some(mmg) = find_program("mmg2d_O3") else {
        eprintln!("mmg2d_O3 not on PATH: comparison with mmg2d -ls skipped");
        return;
    };
    let dir = std::env::temp_dir().join(format!("anisomesh-fit-peers-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    let (mesh_in, sol_in, mesh_out) = (
        dir.join("in.mesh"),
        dir.join("in.sol"),
        dir.join("out.mesh"),
    );
    io::write_mesh(&mesh_in, &base).unwrap();
    io::write_sol(&sol_in, &Sol::scalar(u.clone())).unwrap();
    let mut cmd = Command::new(mmg);
    cmd.args(["-ls", "-noinsert", "-noswap", "-nomove", "-v", "-1", "-in"])
        .arg(&mesh_in)
        .arg("-sol")
        .arg(&sol_in)
        .arg("-out")
        .arg(&mesh_out);
    let run = run_with_timeout(&mut cmd, Duration::from_secs(60), &dir, "mmg2d").unwrap();
    assert!(run.success, "mmg2d failed: {}", run.stderr);
    let theirs = io::read_mesh(&mesh_out).unwrap();
    let (a_ours, a_mmg) = (ours.area_inside(), area_label(&theirs, REF_INSIDE));
    assert!(
        (a_ours - a_mmg).abs() <= 1e-9 * a_ours,
        "inside area: ours {a_ours}, mmg2d {a_mmg}"
    );
    assert_eq!(ours.mesh.n_points(), theirs.n_points());
    let interface = |m: &Mesh2| {
        m.live_tris()
            .flat_map(|t| m.edge_ref[t])
            .filter(|&r| r == REF_INTERFACE)
            .count()
    };
    assert_eq!(interface(&ours.mesh), interface(&theirs));
    std::fs::remove_dir_all(&dir).ok();
}
