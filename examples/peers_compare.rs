//! anisomesh against the peer mesh adapters (MMG 5.8 `mmg2d_O3`, FreeFem++ BAMG), same problem,
//! same run, same measures.
//!
//! The problem is the Zalesak slotted disk in `[-2, 2]²` with the geometric metric of 004 eq. (6),
//! `M = ∇u∇uᵀ/hmin² + |D²u|/ε` (hmin = 0.001, hmax = 0.2), `u` the exact signed distance. Each
//! peer runs the fixed point a user would run (evaluate the metric at the current vertices →
//! adapt → repeat) from a uniform grid; each result is measured by
//! `anisomesh::bench::peers::measure`: vertex count, share of edges of unit metric length,
//! `Q_ani` (004 §3.4), relative area and perimeter errors of the zero level of the exact distance
//! interpolated on the mesh, and the two-sided Hausdorff distance to the exact boundary.
//!
//! Part 1, the accuracy sweep over ε → `peers_sweep.csv` (error versus vertex count).
//! Part 2, the speed case of issue 3 (skipped with `ANISOMESH_QUICK=1` or `--sweep-only`): a
//! 100x100-vertex grid `BG.mesh` and the eq. (6) metric `M.sol` with ε = hmin = 1e-5 at its
//! vertices; `mmg2d_O3 -in BG.mesh -sol M.sol` against our `adapt` on the same files →
//! `peers_speed.csv`.
//!
//! Usage: `cargo run --release --example peers_compare -- [OUT_DIR] [--sweep-only|--speed-only]
//! [--speed-eps=E]`
//! (default `OUT_DIR` = `target/peers`). Peers missing on `PATH` are reported and skipped;
//! `ANISOMESH_PEERS_KINDS=mmg2d-metric,bamg-metric,...` restricts the sweep to those adapters.

use anisomesh::adapt::adapt;
use anisomesh::bench::peers::{
    self, find_program, measure, run_with_timeout, speed_case_metric, sweep, write_csv, PeerKind,
    PeerOptions, PeerResult,
};
use anisomesh::io;
use std::path::PathBuf;
use std::process::Command;
use std::time::{Duration, Instant};

fn print(r: &PeerResult) {
    if r.is_ok() {
        println!(
            "{:<13} eps {:>7.1e}  nv {:>8}  in-range {:>5.1}%  Qmean {:>6.3}  Qmax {:>9.2}  \
             area {:>+9.2e}  perim {:>+9.2e}  haus {:>8.2e}  t {:>7.2} s (last {:.2} s, self {})",
            r.peer.slug(),
            r.eps,
            r.vertices,
            100.0 * r.edge_length_in_range,
            r.q_ani_mean,
            r.q_ani_max,
            r.area_rel_error,
            r.perimeter_rel_error,
            r.hausdorff,
            r.seconds,
            r.seconds_last,
            r.self_seconds_last
                .map(|s| format!("{s:.2} s"))
                .unwrap_or_else(|| "-".into())
        );
    } else {
        println!("{:<13} eps {:>7.1e}  {:?}", r.peer.slug(), r.eps, r.status);
    }
}

fn speed_case(out: &std::path::Path, n: usize, eps: f64) -> anisomesh::Result<Vec<PeerResult>> {
    let dir = out.join("speed");
    let (bg, sol) = peers::write_speed_case(&dir, n, eps)?;
    println!("speed case: {} and {}", bg.display(), sol.display());
    let target = speed_case_metric(n, eps);
    let mut rows = Vec::new();

    // MMG on the same files (skipped when `ANISOMESH_PEERS_KINDS` leaves out mmg2d-metric).
    let mmg_wanted = std::env::var("ANISOMESH_PEERS_KINDS")
        .map_or(true, |l| l.split(',').any(|s| s.trim() == "mmg2d-metric"));
    match find_program("mmg2d_O3").filter(|_| mmg_wanted) {
        None => rows.push(PeerResult::unavailable(
            PeerKind::Mmg2dMetric,
            eps,
            "mmg2d_O3 not found on PATH (or not selected)",
        )),
        Some(exe) => {
            let out_mesh = dir.join("mmg_out.mesh");
            let mut cmd = Command::new(exe);
            cmd.args(["-v", "1", "-in"]).arg(&bg).arg("-sol").arg(&sol);
            cmd.arg("-out").arg(&out_mesh);
            let run = run_with_timeout(&mut cmd, Duration::from_secs(3600), &dir, "mmg")?;
            let r = if run.success {
                let m = io::read_mesh(&out_mesh)?;
                let mut r = measure(PeerKind::Mmg2dMetric, &m, &target);
                (r.iterations, r.seconds, r.seconds_last) = (1, run.seconds, run.seconds);
                r.self_seconds_last = peers::parse_mmg_elapsed(&run.stdout);
                r
            } else {
                PeerResult::failed(
                    PeerKind::Mmg2dMetric,
                    eps,
                    format!("timed out {} / {}", run.timed_out, run.stderr.trim()),
                )
            };
            print(&r);
            rows.push(r);
        }
    }
    // Written now too, so that the MMG row survives an interrupted run of ours.
    write_csv(&out.join("peers_speed.csv"), &rows)?;
    // Ours: the equivalent of `anisomesh adapt --input BG.mesh --sol M.sol`, on a worker thread
    // with a time budget (`ANISOMESH_PEERS_BUDGET` seconds, default 1800): a run past it is
    // reported as such and the process ends after writing the CSV.
    let budget: u64 = std::env::var("ANISOMESH_PEERS_BUDGET")
        .ok()
        .and_then(|v| v.parse().ok())
        .unwrap_or(1800);
    let (tx, rx) = std::sync::mpsc::channel();
    let (bg2, sol2, dir2) = (bg.clone(), sol.clone(), dir.clone());
    std::thread::spawn(move || {
        let go = || -> anisomesh::Result<PeerResult> {
            let t0 = Instant::now();
            let (mut mesh, mut metric) = peers::read_mesh_and_metric(&bg2, &sol2)?;
            let opts = anisomesh::bench::adapt_run::metric_file_options();
            let rep = adapt(&mut mesh, &mut metric, &mut [], None, &opts)?;
            let s = t0.elapsed().as_secs_f64();
            println!(
                "anisomesh adapt: converged {} after {} cycles",
                rep.converged, rep.cycles
            );
            io::write_mesh(&dir2.join("anisomesh_out.mesh"), &mesh)?;
            let mut r = measure(PeerKind::Anisomesh, &mesh, &target);
            (r.iterations, r.seconds, r.seconds_last) = (1, s, s);
            Ok(r)
        };
        let _ = tx.send(go());
    });
    let r = match rx.recv_timeout(Duration::from_secs(budget)) {
        Ok(Ok(r)) => r,
        Ok(Err(e)) => PeerResult::failed(PeerKind::Anisomesh, eps, e.to_string()),
        Err(_) => PeerResult::failed(
            PeerKind::Anisomesh,
            eps,
            format!("not finished within the budget of {budget} s"),
        ),
    };
    print(&r);
    rows.push(r);
    write_csv(&out.join("peers_speed.csv"), &rows)?;
    Ok(rows)
}

fn main() -> anisomesh::Result<()> {
    let quick = std::env::var("ANISOMESH_QUICK").is_ok_and(|v| v == "1");
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .iter()
        .find(|a| !a.starts_with("--"))
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from("target/peers"));
    let speed_only = args.iter().any(|a| a == "--speed-only");
    let sweep_only = args.iter().any(|a| a == "--sweep-only");

    if !speed_only {
        let (eps, opts): (&[f64], PeerOptions) = if quick {
            let o = PeerOptions {
                background: 30,
                iterations: 2,
                timeout: Duration::from_secs(120),
                work_dir: out.join("work"),
                ..PeerOptions::default()
            };
            (&[1e-2, 4e-3], o)
        } else {
            let o = PeerOptions {
                work_dir: out.join("work"),
                ..PeerOptions::default()
            };
            (&[1e-2, 3e-3, 1e-3, 3e-4, 1e-4], o)
        };
        println!(
            "sweep: background {0}x{0}, {1} fixed-point iterations per peer",
            opts.background, opts.iterations
        );
        // `ANISOMESH_PEERS_KINDS=mmg2d-metric,bamg-metric` restricts the sweep (default: all).
        let kinds: Vec<PeerKind> = match std::env::var("ANISOMESH_PEERS_KINDS") {
            Ok(list) => PeerKind::ALL
                .into_iter()
                .filter(|k| list.split(',').any(|s| s.trim() == k.slug()))
                .collect(),
            Err(_) => PeerKind::ALL.to_vec(),
        };
        let results = sweep(&kinds, eps, &opts, &out)?;
        for r in &results {
            print(r);
        }
        println!("wrote {}", out.join("peers_sweep.csv").display());
    }
    if !quick && !sweep_only {
        // `--speed-eps=E` picks the accuracy (default 1e-5, the case).
        let speed_eps = args
            .iter()
            .find_map(|a| a.strip_prefix("--speed-eps=")?.parse().ok())
            .unwrap_or(1e-5);
        speed_case(&out, 100, speed_eps)?;
        println!("wrote {}", out.join("peers_speed.csv").display());
    }
    Ok(())
}
