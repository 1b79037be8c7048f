//! Runs the redistancing experiments of 003 §8 (torus tables 8.1–8.3, the 2D circle analogue,
//! and the repeated-redistancing volume test of Fig. 8.4) and writes `reinit.json`.
//! `cargo run --release --example redistance_reinit -- [max_level_3d] [max_level_2d] [volume_level] [out_dir] [reps] [k]`
//! (a level of 0 or below 3 skips that part; `k` = 0 runs both degrees).

use anisomesh::bench::reinit::{run, ReinitOptions};

fn main() -> anisomesh::Result<()> {
    let arg = |i: usize, d: u32| {
        std::env::args()
            .nth(i)
            .and_then(|s| s.parse().ok())
            .unwrap_or(d)
    };
    // ANISOMESH_QUICK=1 (CI): small levels, no volume drift.
    let quick = std::env::var_os("ANISOMESH_QUICK").is_some();
    let (l3, l2, lv) = if quick {
        (arg(1, 3), arg(2, 5), arg(3, 0))
    } else {
        (arg(1, 5), arg(2, 8), arg(3, 4))
    };
    let opts = ReinitOptions {
        levels_3d: (3..=l3).collect(),
        levels_2d: (3..=l2).collect(),
        volume_levels: if lv > 0 { vec![lv] } else { vec![] },
        // Output directory: the 4th argument, else a temporary directory (never the source tree).
        out_dir: Some(
            std::env::args()
                .nth(4)
                .map(std::path::PathBuf::from)
                .unwrap_or_else(|| std::env::temp_dir().join("anisomesh-reinit")),
        ),
        volume_reps: arg(5, 100) as usize,
        degrees: match arg(6, 0) {
            0 => vec![1, 2],
            k => vec![k as usize],
        },
        ..ReinitOptions::default()
    };
    let t0 = std::time::Instant::now();
    run(&opts)?;
    println!("\ntotal {:.1} s", t0.elapsed().as_secs_f64());
    Ok(())
}
