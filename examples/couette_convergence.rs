//! Couette benchmark (004 §5.1): how ω converges with the mesh, on adapted (non-fitted) meshes
//! with the two cut-element viscosity rules and on body-fitted meshes; how much ω moves when
//! the interface is shifted across the default adapted mesh; and (without `ANISOMESH_QUICK=1`)
//! the timing of a 100,000-vertex fitted two-phase solve split into meshing, assembly,
//! factorisation and Uzawa. Prints markdown tables.
//!
//! Usage: `cargo run --release --example couette_convergence [-- out=DIR]` (`out` writes
//! `couette_convergence.png`, the figure of the README: `out=figures`).

use anisomesh::bench::couette::run;
use anisomesh::bench::couette_sweep::{
    fitted_options, interface_shift, sweep, sweep_png, sweep_table,
};

fn main() -> anisomesh::Result<()> {
    let quick = std::env::var("ANISOMESH_QUICK").is_ok_and(|v| v == "1");
    let (scales, hs, shifts): (Vec<f64>, Vec<f64>, Vec<f64>) = if quick {
        (vec![2.0, 1.0], vec![0.01, 0.005], vec![-1e-4, 0.0, 1e-4])
    } else {
        (
            vec![2.0, 1.4, 1.0, 0.7, 0.5, 0.35],
            vec![0.01, 0.005, 0.0025, 0.00125],
            (-4..=4).map(|k| k as f64 * 1e-4).collect(),
        )
    };
    let out = std::env::args()
        .skip(1)
        .find_map(|a| a.strip_prefix("out=").map(std::path::PathBuf::from));
    let rows = sweep(&scales, &hs)?;
    println!("{}", sweep_table(&rows));
    if let Some(dir) = &out {
        std::fs::create_dir_all(dir).map_err(|e| anisomesh::Error::io(dir, e))?;
        sweep_png(&dir.join("couette_convergence.png"), &rows)?;
    }
    println!("Default adapted mesh, disk radius 0.1 + shift (mesh unchanged), omega + 1:\n");
    println!("| shift | harmonic | quadrature |\n|---|---|---|");
    let sh = interface_shift(&shifts)?;
    for (d, h, q) in &sh {
        println!("| {d:+.0e} | {h:+.1e} | {q:+.1e} |");
    }
    let spread = |k: usize| {
        let v: Vec<f64> = sh.iter().map(|r| if k == 0 { r.1 } else { r.2 }).collect();
        v.iter().cloned().fold(f64::MIN, f64::max) - v.iter().cloned().fold(f64::MAX, f64::min)
    };
    println!(
        "\nspread of omega: harmonic {:.1e}, quadrature {:.1e}\n",
        spread(0),
        spread(1)
    );
    if !quick {
        let r = run(&fitted_options(0.0005))?;
        println!(
            "fitted h = 0.0005: {} vertices, omega {:.7}, {} Uzawa its; meshing {:.2} s, \
             assembly {:.2} s, factorisation {:.2} s (L: {} entries), Uzawa {:.2} s, solve \
             total {:.2} s",
            r.vertices,
            r.omega,
            r.uzawa_iterations,
            r.mesh_seconds,
            r.assembly_seconds,
            r.factor_seconds,
            r.factor_nnz,
            r.uzawa_seconds,
            r.solve_seconds
        );
    }
    Ok(())
}
