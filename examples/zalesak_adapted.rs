//! Zalesak slotted-disk rotation (004 §5.1) with anisotropic adaptation and the transient fixed
//! point (004 §3.5): one revolution in 16 periods of π/8, metric 004 eq. (6) with hmin = 0.001
//! and stretching 200, metrics of u^n and u^{n+1} intersected each period.
//!
//! Usage: `cargo run --release --example zalesak_adapted -- [eps] [fixed-point iterations] [grade] [l2|nodal] [iso] [compare]
//! (`ZALESAK_OUT=dir` writes `zalesak.json` and `zalesak.csv` there).`

use anisomesh::advect::{AdvectOptions, Form, Interpolation};
use anisomesh::bench::zalesak::{run, ZalesakMesh, ZalesakOptions};

fn main() -> anisomesh::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let eps: f64 = args.first().and_then(|s| s.parse().ok()).unwrap_or(1.2e-3);
    let fp: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(5);
    let nodal = args.iter().any(|a| a == "nodal");
    let iso = args.iter().any(|a| a == "iso");
    let grade: f64 = args.get(2).and_then(|s| s.parse().ok()).unwrap_or(1.0);
    let periods: usize = std::env::var("ZALESAK_PERIODS")
        .ok()
        .and_then(|s| s.parse().ok())
        // ANISOMESH_QUICK=1 (CI): 4 periods of pi/2.
        .unwrap_or(if std::env::var_os("ANISOMESH_QUICK").is_some() {
            4
        } else {
            16
        });
    let opts = ZalesakOptions {
        mesh: ZalesakMesh::Adapted {
            hmin: 0.001,
            stretching: 200.0,
            isotropic: iso,
        },
        metric: anisomesh::adapt::LevelSetMetric {
            eps,
            grade,
            ..ZalesakOptions::default().metric
        },
        periods,
        fixed_point_iterations: fp,
        out_dir: std::env::var("ZALESAK_OUT")
            .ok()
            .map(std::path::PathBuf::from),
        compare: args.iter().any(|a| a == "compare"),
        advect: AdvectOptions {
            form: if nodal {
                Form::Nodal
            } else {
                Form::L2Projection { subdivisions: 0 }
            },
            interp: if nodal {
                Interpolation::QUADRATIC
            } else {
                Interpolation::P1
            },
            ..AdvectOptions::default()
        },
        ..ZalesakOptions::default()
    };
    let r = run(&opts)?;
    print!("{}", r.summary());
    println!(
        "fixed-point iterations per period: {:?}",
        r.fixed_point_iterations
    );
    for s in &r.series {
        println!(
            "{:3} {:.4} area {:.6} perim {:.5} verts {}",
            s.period, s.time, s.area, s.perimeter, s.vertices
        );
    }
    Ok(())
}
