//! Error versus vertex count on Zalesak's slotted disk (issue 3 item 7): anisotropic meshes
//! adapted to the geometric metric of 004 eq. (6) for decreasing `ε` (with `h_min = 0.1 √ε`,
//! `h_max = 0.2`, the default `anisomesh adapt` band and gradation), the isotropic version of the same metric at the
//! same `ε`, and uniform union-jack grids up to 800 x 800 cells (641,601 vertices). For every
//! mesh, the zero level of the nodal interpolant of the exact signed distance is compared with
//! the exact shape: two-sided Hausdorff distance (and where it is attained: near the four slot
//! corners or elsewhere), relative area and perimeter errors. The installed peers (mmg2d_O3,
//! FreeFem++ BAMG) are run on the same metric in the same run. Prints the table, the fitted
//! log-log slopes and the isotropic/anisotropic vertex ratio at equal error ("anisotropy
//! pays"), and writes `convergence_<shape>.{csv,png}`.
//!
//! Usage: `cargo run --release --example convergence_sweep -- [shape] [points] [--out DIR]
//! [--no-peers] [--kink K] [--band K] [--grade G]` (`shape` = zalesak | circle | flower, default
//! zalesak; `points` per family, default 5; `DIR` default `target/convergence`; `--out figures`
//! regenerates the committed figures; `--band K` applies eq. (6) within `K h_min` of the
//! interface instead of `5 ε`, `--grade G` grows sizes at rate `G` outside it instead of 1;
//! `--kink K` sees the kinks of the distance at the scale `K h_min`). With `ANISOMESH_QUICK=1`: a
//! tiny sweep (3 points per family, seconds) written to a temporary directory.
//!
//! `--paper-claim` (Zalesak) runs instead the comparison of 004 §5.1 as stated: at `ε = 1e-4`
//! (`h_min = 0.001`, `h_max = 0.2`, the default `anisomesh adapt` run) the anisotropic mesh
//! against the isotropic graded mesh with the same smallest size and gradation, for a few band
//! widths and growth rates ([`anisomesh::bench::convergence_claim`]); quick: `ε = 1e-2`, two
//! settings.
//!
//! `--best-vs-best` runs instead both families over their free parameters (`ε`, normal size and
//! band of eq. (6); isotropic size and band) and compares the Pareto fronts at equal error
//! ([`anisomesh::bench::convergence_fronts`]), writing `fronts_<shape>.{csv,png}`; quick: 8
//! meshes.

use anisomesh::bench::convergence::{run, ConvergenceOptions};
use anisomesh::bench::convergence_claim::{claim_table, paper_claim, CLAIM_SETTINGS};
use anisomesh::bench::convergence_fronts::{self, FrontGrid};
use std::path::PathBuf;

fn main() -> anisomesh::Result<()> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let quick = std::env::var("ANISOMESH_QUICK").is_ok_and(|v| v == "1");
    let mut positional = Vec::new();
    let mut out: Option<PathBuf> = None;
    let mut peers = true;
    let mut claim = false;
    let mut fronts = false;
    let d = ConvergenceOptions::default();
    let (mut kink_scale, mut band_hmin, mut grade) = (d.kink_scale, d.band_hmin, d.grade);
    let num = |v: Option<&String>| v.and_then(|s| s.parse::<f64>().ok());
    let mut it = args.iter();
    while let Some(a) = it.next() {
        match a.as_str() {
            "--out" => out = it.next().map(PathBuf::from),
            "--no-peers" => peers = false,
            "--paper-claim" => claim = true,
            "--best-vs-best" => fronts = true,
            "--kink" => kink_scale = num(it.next()),
            "--band" => band_hmin = num(it.next()),
            "--grade" => grade = num(it.next()),
            _ => positional.push(a.clone()),
        }
    }
    let shape = positional
        .first()
        .cloned()
        .unwrap_or_else(|| "zalesak".into());
    if claim {
        let (eps, settings) = if quick {
            (1e-2, &CLAIM_SETTINGS[..2])
        } else {
            (1e-4, &CLAIM_SETTINGS[..])
        };
        print!("{}", claim_table(&paper_claim(&shape, eps, settings)?));
        return Ok(());
    }
    let out_dir = match (quick, out) {
        (true, _) => {
            std::env::temp_dir().join(format!("anisomesh-convergence-{}", std::process::id()))
        }
        (false, Some(d)) => d,
        (false, None) => PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("target/convergence"),
    };
    if fronts {
        let grid = if quick {
            FrontGrid::quick()
        } else {
            FrontGrid::full()
        };
        let report = convergence_fronts::run(&shape, &grid, Some(&out_dir))?;
        print!("{}", report.table());
        for f in &report.files {
            println!("wrote {}", f.display());
        }
        return Ok(());
    }
    let points = positional.get(1).and_then(|s| s.parse().ok()).unwrap_or(5);
    let report = run(&ConvergenceOptions {
        shape,
        out_dir: Some(out_dir),
        points,
        quick,
        peers,
        kink_scale,
        band_hmin,
        grade,
    })?;
    print!("{}", report.table());
    for f in &report.files {
        println!("wrote {}", f.display());
    }
    Ok(())
}
