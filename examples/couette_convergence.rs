//! Couette benchmark (004 §5.1): ω and rigidity on body-fitted CDT meshes of decreasing size,
//! then the default adapted run, then (without `ANISOMESH_QUICK=1`) a large fitted solve for
//! timing. Prints a table.
//!
//! Usage: `cargo run --release --example couette_convergence`

use anisomesh::bench::couette::{run, CouetteOptions};

fn main() -> anisomesh::Result<()> {
    let quick = std::env::var("ANISOMESH_QUICK").is_ok_and(|v| v == "1");
    println!(
        "{:>8} {:>8} {:>8} {:>14} {:>10} {:>10} {:>6} {:>8}",
        "mesh", "h_int", "verts", "omega", "|om+1|", "rigidity", "its", "seconds"
    );
    let mut hs = vec![0.02, 0.01, 0.005, 0.0025];
    if !quick {
        hs.extend([0.00125, 0.0005]);
    }
    let mut cases: Vec<CouetteOptions> = hs
        .iter()
        .map(|&h| CouetteOptions {
            fitted: true,
            h_interface: h,
            hmax: (8.0 * h).min(0.1),
            ..CouetteOptions::default()
        })
        .collect();
    cases.push(CouetteOptions::default());
    for o in &cases {
        let r = run(o)?;
        println!(
            "{:>8} {:>8} {:>8} {:>14.8} {:>10.2e} {:>10.2e} {:>6} {:>8.3}",
            r.mesh,
            if o.fitted { o.h_interface } else { o.hmin },
            r.vertices,
            r.omega,
            r.omega_error,
            r.rigidity,
            r.uzawa_iterations,
            r.seconds
        );
    }
    Ok(())
}
