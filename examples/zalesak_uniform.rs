//! Zalesak slotted-disk rotation (004 §5.1) on fixed uniform meshes: the baseline of the
//! characteristics-Galerkin advection (004 eq. (2)) without adaptation.
//!
//! One revolution of `u = (-y, x)` in 16 periods of π/8; prints the initial and final area and
//! perimeter of the P1 zero level beside the exact values and the paper's, for the nodal and
//! L2-projected forms and P1 / quadratic evaluation at the feet.
//!
//! Usage: `cargo run --release --example zalesak_uniform -- [n ...]` (default: 100).

use anisomesh::advect::{AdvectOptions, Form, Interpolation};
use anisomesh::bench::zalesak::{run, ZalesakMesh, ZalesakOptions};

fn main() -> anisomesh::Result<()> {
    let ns: Vec<usize> = std::env::args()
        .skip(1)
        .filter_map(|a| a.parse().ok())
        .collect();
    // ANISOMESH_QUICK=1 (CI): a 50 x 50 grid.
    let ns = if !ns.is_empty() {
        ns
    } else if std::env::var_os("ANISOMESH_QUICK").is_some() {
        vec![50]
    } else {
        vec![100]
    };
    let steps: usize = std::env::var("ZALESAK_PERIODS")
        .ok()
        .and_then(|s| s.parse().ok())
        .unwrap_or(16);
    for n in ns {
        for (form, interp) in [
            (Form::Nodal, Interpolation::P1),
            (Form::Nodal, Interpolation::QUADRATIC),
            (Form::L2Projection { subdivisions: 0 }, Interpolation::P1),
            (
                Form::L2Projection { subdivisions: 0 },
                Interpolation::QUADRATIC,
            ),
        ] {
            let opts = ZalesakOptions {
                mesh: ZalesakMesh::Uniform { n },
                periods: steps,
                advect: AdvectOptions {
                    form,
                    interp,
                    ..AdvectOptions::default()
                },
                ..ZalesakOptions::default()
            };
            let r = run(&opts)?;
            let (ea, ep) = r.relative_errors();
            println!(
                "n={n:4} {form:?} {interp:?}: area {:.6} -> {:.6} ({:+.3e}), perimeter {:.5} -> {:.5} ({:+.3e}), iface max {:.2e} back {:.2e}, {:.2} s",
                r.area_initial, r.area_final, ea, r.perimeter_initial, r.perimeter_final, ep,
                r.interface_to_exact_max, r.exact_to_interface_max, r.seconds
            );
        }
    }
    Ok(())
}
