//! Runs the redistancing experiments of 003 §8 (torus tables 8.1–8.3, the 2D circle and Zalesak
//! analogues, and the repeated-redistancing volume test of Fig. 8.4), prints the tables beside
//! the paper's values and writes `reinit.json` and the PNG plots.
//!
//! ```text
//! cargo run --release --example redistance_reinit -- [--levels3 3-6] [--levels2 3-8]
//!     [--alphas 1,10,50] [--k 1,2] [--drift 5] [--reps 100] [--out DIR]
//! ```
//! Lists are comma-separated or `a-b` ranges; an empty list (`--levels3 none`) skips that part.
//! Output goes to `DIR` (default: a temporary directory, never the source tree).
//! With `ANISOMESH_QUICK=1` (CI) the defaults shrink to seconds: torus level 3, 2D levels 3–5,
//! a 10-repetition drift on level 3.

use anisomesh::bench::reinit::{run, ReinitOptions};

fn list(s: &str) -> Vec<u32> {
    if s == "none" {
        return vec![];
    }
    s.split(',')
        .flat_map(|p| match p.split_once('-') {
            Some((a, b)) => {
                let (a, b) = (a.parse().unwrap_or(0), b.parse().unwrap_or(0));
                (a..=b).collect::<Vec<u32>>()
            }
            None => p.parse().ok().into_iter().collect(),
        })
        .collect()
}

fn main() -> anisomesh::Result<()> {
    let quick = std::env::var("ANISOMESH_QUICK").is_ok_and(|v| v == "1");
    let mut opts = ReinitOptions {
        out_dir: Some(std::env::temp_dir().join("anisomesh-reinit")),
        ..ReinitOptions::default()
    };
    if quick {
        opts.levels_3d = vec![3];
        opts.levels_2d = (3..=5).collect();
        opts.alphas = vec![1, 10];
        opts.volume_levels = vec![3];
        opts.volume_reps = 10;
    }
    let args: Vec<String> = std::env::args().skip(1).collect();
    for pair in args.chunks(2) {
        let (flag, val) = (pair[0].as_str(), pair.get(1).map_or("", String::as_str));
        match flag {
            "--levels3" => opts.levels_3d = list(val),
            "--levels2" => opts.levels_2d = list(val),
            "--alphas" => opts.alphas = list(val),
            "--k" => opts.degrees = list(val).into_iter().map(|k| k as usize).collect(),
            "--drift" => opts.volume_levels = list(val),
            "--reps" => opts.volume_reps = val.parse().unwrap_or(opts.volume_reps),
            "--out" => opts.out_dir = Some(val.into()),
            _ => {
                eprintln!("unknown option {flag} (see the example's documentation)");
                std::process::exit(2);
            }
        }
    }
    let t0 = std::time::Instant::now();
    run(&opts)?;
    if let Some(d) = &opts.out_dir {
        println!("\nwrote {}", d.join("reinit.json").display());
    }
    println!("total {:.1} s", t0.elapsed().as_secs_f64());
    Ok(())
}
