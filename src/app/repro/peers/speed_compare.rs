//! The speed case with the peers: `mmg2d_O3 -in BG.mesh -sol M.sol` against our adaptation of
//! the same files ([`crate::app::repro::speed`]), each measured by [`super::measure`].

use super::{find_program, measure, parse_mmg_elapsed, run_with_timeout, write_csv};
use super::{PeerKind, PeerResult};
use crate::app::repro::speed::{read_mesh_and_metric, speed_case_metric, write_speed_case};
use anisomesh::adapt::{adapt, metric_file_options};
use anisomesh::error::Result;
use anisomesh::io;
use std::path::Path;
use std::process::Command;
use std::time::{Duration, Instant};

/// Runs mmg2d (when `with_mmg` and installed) and then ours on the speed case with `eps`, ours
/// on a worker thread with a time budget of `budget` (a run past it is reported as such).
/// Writes `<out>/peers_speed.csv` after each row; `each` sees every row as it comes.
pub fn speed_case(
    out: &Path,
    eps: f64,
    with_mmg: bool,
    budget: Duration,
    mut each: impl FnMut(&PeerResult),
) -> Result<Vec<PeerResult>> {
    let n = 100;
    let dir = out.join("speed");
    let (bg, sol) = write_speed_case(&dir, n, eps)?;
    let target = speed_case_metric(n, eps);
    let mut rows = Vec::new();
    match find_program("mmg2d_O3").filter(|_| with_mmg) {
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
                r.self_seconds_last = parse_mmg_elapsed(&run.stdout);
                r
            } else {
                PeerResult::failed(
                    PeerKind::Mmg2dMetric,
                    eps,
                    format!("timed out {} / {}", run.timed_out, run.stderr.trim()),
                )
            };
            each(&r);
            rows.push(r);
        }
    }
    // Written now too, so that the MMG row survives an interrupted run of ours.
    write_csv(&out.join("peers_speed.csv"), &rows)?;
    let (tx, rx) = std::sync::mpsc::channel();
    let (bg2, sol2, dir2) = (bg.clone(), sol.clone(), dir.clone());
    std::thread::spawn(move || {
        let go = || -> Result<PeerResult> {
            let t0 = Instant::now();
            let (mut mesh, mut metric) = read_mesh_and_metric(&bg2, &sol2)?;
            adapt(
                &mut mesh,
                &mut metric,
                &mut [],
                None,
                &metric_file_options(),
            )?;
            let s = t0.elapsed().as_secs_f64();
            io::write_mesh(&dir2.join("anisomesh_out.mesh"), &mesh)?;
            let mut r = measure(PeerKind::Anisomesh, &mesh, &target);
            (r.iterations, r.seconds, r.seconds_last) = (1, s, s);
            Ok(r)
        };
        let _ = tx.send(go());
    });
    let r = match rx.recv_timeout(budget) {
        Ok(Ok(r)) => r,
        Ok(Err(e)) => PeerResult::failed(PeerKind::Anisomesh, eps, e.to_string()),
        Err(_) => PeerResult::failed(
            PeerKind::Anisomesh,
            eps,
            format!("not finished within the budget of {} s", budget.as_secs()),
        ),
    };
    each(&r);
    rows.push(r);
    write_csv(&out.join("peers_speed.csv"), &rows)?;
    Ok(rows)
}
