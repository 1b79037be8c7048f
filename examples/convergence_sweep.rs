//! Error versus vertex count on Zalesak's slotted disk (issue 3 item 7): anisotropic meshes
//! adapted to the geometric metric of 004 eq. (6) for decreasing `ε` (with `h_min = 0.1 √ε`,
//! `h_max = 0.2`), the isotropic version of the same metric at the same `ε`, and uniform
//! union-jack grids up to 800 x 800 cells (641,601 vertices). For every mesh, the zero level of
//! the nodal interpolant of the exact signed distance is compared with the exact shape: two-sided
//! Hausdorff distance, relative area and perimeter errors. Prints the table, the fitted log-log
//! slopes and the isotropic/anisotropic vertex ratio at equal error ("anisotropy pays"), and
//! writes `figures/convergence_zalesak.{csv,png}`.
//!
//! Usage: `cargo run --release --example convergence_sweep -- [shape] [points]`
//! (`shape` = zalesak | circle | flower, default zalesak; `points` per family, default 5).
//! With `ANISOMESH_QUICK=1`: a tiny sweep (3 points per family, seconds) written to a temporary
//! directory instead of `figures/`.

use anisomesh::bench::convergence::{run, ConvergenceOptions};

fn main() -> anisomesh::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = std::env::var("ANISOMESH_QUICK").is_ok_and(|v| v == "1");
    let shape = args.first().cloned().unwrap_or_else(|| "zalesak".into());
    let points = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(5);
    let out_dir = if quick {
        std::env::temp_dir().join(format!("anisomesh-convergence-{}", std::process::id()))
    } else {
        std::path::PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("figures")
    };
    let report = run(&ConvergenceOptions {
        shape,
        out_dir: Some(out_dir),
        points,
        quick,
    })?;
    print!("{}", report.table());
    for f in &report.files {
        println!("wrote {}", f.display());
    }
    Ok(())
}
