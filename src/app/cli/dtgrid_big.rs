//! `anisomesh dtgrid mcf --matrix-free`: a sphere on a band too large for assembled matrices
//! (`f32` values on a DT-Grid, matrix-free products, windowed rebuild), built by block pruning
//! and moved by mean curvature for a few steps; prints the band's size, bytes per node (index and
//! values), peak resident memory and the seconds of each phase, and writes
//! `dtgrid_mcf_matrix_free.json`.

use crate::app::repro::reinit::run::peak_rss_mib;
use anisomesh::backends::dtgrid::lattice::Lattice;
use anisomesh::backends::dtgrid::lean::{LeanOptions, LeanState};
use anisomesh::backends::dtgrid::mcf::{cpu_seconds, McfOptions};
use anisomesh::backends::dtgrid::Band;
use anisomesh::error::{Error, Result};
use std::path::Path;
use std::time::Instant;

/// The options of a matrix-free run.
pub struct BigRun<'a> {
    /// Grid nodes per side.
    pub n: usize,
    /// The sphere's radius (centre 0).
    pub radius: f64,
    /// Time steps (None: to `t_end`).
    pub steps: Option<usize>,
    /// The time step (None: `h²`).
    pub tau: Option<f64>,
    /// The final time when `steps` is not given.
    pub t_end: f64,
    /// The step options.
    pub mcf: McfOptions,
    /// Output directory.
    pub output: &'a Path,
}

/// Runs the matrix-free sphere.
pub fn run(r: &BigRun) -> Result<()> {
    let lat = Lattice::unit(r.n)?;
    let h = lat.h;
    let tau = r.tau.unwrap_or(h * h);
    let steps = match r.steps {
        Some(s) => s,
        None => (r.t_end / tau - 1e-9).ceil().max(1.0) as usize,
    };
    if steps == 0 || !(tau > 0.0 && tau.is_finite()) {
        return Err(Error::InvalidInput(format!(
            "matrix-free run: {steps} steps of tau = {tau} (both positive)"
        )));
    }
    let o = LeanOptions {
        mcf: r.mcf,
        ..LeanOptions::default()
    };
    let (t, c) = (Instant::now(), cpu_seconds());
    let r0 = r.radius;
    let mut s = LeanState::new(lat, r.mcf.j, &|p| p.length() - r0, 1.0, o.chunk_nodes)?;
    let (build, build_cpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - c);
    let nodes = s.nb.band.len();
    let index = s.nb.band.index_bytes();
    println!(
        "sphere r = {r0:.6} on {n}³ nodes (h = {h:.3e}), band j = {j}: {nodes} nodes, {runs} runs",
        n = r.n,
        j = r.mcf.j,
        runs = s.nb.band.runs()
    );
    println!(
        "bytes per node: index {:.3} ({index} B), values 4 (f32), interior flags 1",
        index as f64 / nodes as f64
    );
    println!(
        "build (pruned band, values, signed distance): {build:.2} s wall, {build_cpu:.2} s cpu"
    );
    println!("step  solves  cg   assembly s  solve s  rebuild s  (wall; cpu)  nodes");
    let mut rows = Vec::new();
    for k in 1..=steps {
        let rep = s.step(tau, &o)?;
        let t = rep.times;
        println!(
            "{k:4} {:7} {:4} {:10.2} {:8.2} {:10.2}   ({:.2}; {:.2}; {:.2})  {}",
            rep.solves,
            rep.cg_iterations,
            t.assembly,
            t.solve,
            t.rebuild,
            t.assembly_cpu,
            t.solve_cpu,
            t.rebuild_cpu,
            s.nb.band.len()
        );
        rows.push(serde_json::json!({
            "step": k, "solves": rep.solves, "cg_iterations": rep.cg_iterations,
            "assembly_s": t.assembly, "solve_s": t.solve, "rebuild_s": t.rebuild,
            "assembly_cpu_s": t.assembly_cpu, "solve_cpu_s": t.solve_cpu,
            "rebuild_cpu_s": t.rebuild_cpu, "nodes": s.nb.band.len(),
        }));
    }
    let t_end = tau * steps as f64;
    let exact = (r0 * r0 - 4.0 * t_end).max(0.0).sqrt();
    let (t, c) = (Instant::now(), cpu_seconds());
    let mean = s.surface_mean(|x| x.length(), 64)?;
    let (meas, meas_cpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - c);
    println!(
        "t = {t_end:.4e}: mean radius of the zero level {mean:.9}, exact {exact:.9} \
         ({meas:.2} s wall, {meas_cpu:.2} s cpu)"
    );
    let peak = peak_rss_mib();
    if let Some(p) = peak {
        println!(
            "peak resident memory {:.0} MiB ({:.1} B per band node)",
            p,
            p * 1048576.0 / nodes as f64
        );
    }
    std::fs::create_dir_all(r.output).map_err(|e| Error::io(r.output, e))?;
    let report = serde_json::json!({
        "n": r.n, "h": h, "band": r.mcf.j, "bc": r.mcf.bc.name(), "inner": r.mcf.inner,
        "tau": tau, "steps": steps, "radius": r0, "nodes": nodes, "runs": s.nb.band.runs(),
        "index_bytes": index, "index_bytes_per_node": index as f64 / nodes as f64,
        "value_bytes_per_node": 4, "build_s": build, "build_cpu_s": build_cpu,
        "step_rows": rows, "radius_final": mean, "radius_exact": exact,
        "peak_rss_mib": peak,
    });
    let path = r.output.join("dtgrid_mcf_matrix_free.json");
    anisomesh::io::atomic_write(&path, |w| {
        serde_json::to_writer_pretty(&mut *w, &report).map_err(std::io::Error::other)?;
        writeln!(w)
    })?;
    println!("wrote {}", path.display());
    Ok(())
}
