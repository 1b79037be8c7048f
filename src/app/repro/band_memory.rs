//! The DT-Grid memory and speed benchmark (000 §3–§4): the band `|f| ≤ j·h` of the sphere
//! `|x| = 1/3` in `(−½, ½)³` on an `n³` grid — nodes, runs, index bytes per node, build time,
//! a streaming pass over the cells — and OpenVDB holding the same active voxels in the same run
//! (Debian's `python3-openvdb` under `/usr/bin/python3`).

use anisomesh::backends::dtgrid::{Band, DtGrid, Implicit};
use anisomesh::error::{Error, Result};
use std::process::Command;
use std::time::Instant;

/// The sphere radius.
const RADIUS: f64 = 1.0 / 3.0;

/// Our side of one benchmark row.
#[derive(Debug, Clone)]
pub struct BandRow {
    /// Band nodes.
    pub nodes: usize,
    /// Runs along the last axis.
    pub runs: usize,
    /// Bytes of the index (everything but the values).
    pub index_bytes: usize,
    /// Wall time of [`DtGrid::from_implicit`] (all threads).
    pub build_seconds: f64,
    /// Cells (all corners in the band) and the time of one pass summing their corner values
    /// (one thread).
    pub cells: usize,
    /// Seconds of the cell pass.
    pub cell_pass_seconds: f64,
    /// The sum of the pass (printed so the pass cannot be optimised away).
    pub cell_sum: f64,
}

/// OpenVDB's side: a `FloatGrid` with the same active voxels.
#[derive(Debug, Clone)]
pub struct VdbRow {
    /// `activeVoxelCount()`.
    pub active: u64,
    /// `memUsage()` in bytes.
    pub mem_bytes: u64,
    /// Seconds to fill the grid in Python.
    pub seconds: f64,
}

fn geometry(n: usize, j: u32) -> Implicit {
    Implicit {
        n,
        origin: [-0.5; 3],
        h: 1.0 / n as f64,
        half_width: j,
    }
}

fn sphere(p: &[f64]) -> f64 {
    (p[0] * p[0] + p[1] * p[1] + p[2] * p[2]).sqrt() - RADIUS
}

/// Builds the sphere band and streams once over its cells.
pub fn ours(n: usize, j: u32) -> Result<BandRow> {
    let g = geometry(n, j);
    let t = Instant::now();
    let band = DtGrid::<[i32; 3]>::from_implicit(&g, sphere)?;
    let build_seconds = t.elapsed().as_secs_f64();
    let u: Vec<f64> = band
        .coords()
        .map(|c| {
            let p = [
                g.origin[0] + g.h * c[0] as f64,
                g.origin[1] + g.h * c[1] as f64,
                g.origin[2] + g.h * c[2] as f64,
            ];
            sphere(&p)
        })
        .collect();
    let t = Instant::now();
    let mut cells = 0;
    let mut sum = 0.0;
    for (_, cell) in band.cells() {
        cells += 1;
        sum += cell.iter().map(|&i| u[i as usize]).sum::<f64>();
    }
    let cell_pass_seconds = t.elapsed().as_secs_f64();
    Ok(BandRow {
        nodes: band.len(),
        runs: band.runs(),
        index_bytes: band.index_bytes(),
        build_seconds,
        cells,
        cell_pass_seconds,
        cell_sum: sum,
    })
}

/// The Python program filling an OpenVDB `FloatGrid` slab by slab with the voxels where
/// `|f| ≤ j·h`, evaluated in the same floating-point operations as [`ours`].
const VDB_SCRIPT: &str = r#"
import sys, time
import numpy as np
import pyopenvdb as vdb
n, j = int(sys.argv[1]), int(sys.argv[2])
h = 1.0 / n
w = j * h
r = 1.0 / 3.0
bg = np.float32(1e30)
g = vdb.FloatGrid(float(bg))
t = time.time()
y = -0.5 + h * np.arange(n + 1, dtype=np.float64)
Y, Z = np.meshgrid(y, y, indexing="ij")
YZ = None
for i in range(n + 1):
    x = -0.5 + h * i
    f = np.sqrt(x * x + Y * Y + Z * Z) - r
    m = np.abs(f) <= w
    if not m.any():
        continue
    a = np.where(m, f, bg).astype(np.float32)
    g.copyFromArray(a.reshape(1, n + 1, n + 1), (i, 0, 0), 0.0)
print(g.activeVoxelCount(), g.memUsage(), time.time() - t)
"#;

/// The interpreter with Debian's `pyopenvdb`.
const VDB_PYTHON: &str = "/usr/bin/python3";

/// Fills OpenVDB with the same band; `Err` says why not (module absent, failure).
pub fn openvdb(n: usize, j: u32) -> std::result::Result<VdbRow, String> {
    let out = Command::new(VDB_PYTHON)
        .arg("-c")
        .arg(VDB_SCRIPT)
        .arg(n.to_string())
        .arg(j.to_string())
        .output()
        .map_err(|e| format!("{VDB_PYTHON}: {e}"))?;
    if !out.status.success() {
        let err = String::from_utf8_lossy(&out.stderr);
        return Err(err.lines().last().unwrap_or("failed").to_string());
    }
    let s = String::from_utf8_lossy(&out.stdout);
    let v: Vec<&str> = s.split_whitespace().collect();
    let parse = || -> Option<VdbRow> {
        Some(VdbRow {
            active: v.first()?.parse().ok()?,
            mem_bytes: v.get(1)?.parse().ok()?,
            seconds: v.get(2)?.parse().ok()?,
        })
    };
    parse().ok_or_else(|| format!("unexpected OpenVDB output: {s}"))
}

/// Checks the benchmark's options.
pub fn check(n: usize, bands: &[u32]) -> Result<()> {
    if n < 8 || bands.is_empty() || bands.iter().any(|&j| j == 0 || 2 * j as usize > n) {
        return Err(Error::InvalidInput(format!(
            "bench band: need n ≥ 8 and band half-widths 1 ≤ j ≤ n/2 (n {n}, bands {bands:?})"
        )));
    }
    Ok(())
}

/// Options of `anisomesh bench band`.
#[derive(Debug, clap::Args)]
pub struct BandArgs {
    /// Cells per side of the grid.
    #[arg(long, default_value_t = 1024)]
    n: usize,
    /// Band half-widths in cells, comma-separated.
    #[arg(long, value_delimiter = ',', default_values_t = vec![1, 2, 4, 8])]
    band: Vec<u32>,
    /// A small case (n = 256, half-width 2).
    #[arg(long)]
    quick: bool,
    /// Without OpenVDB (it is skipped anyway beyond n = 2048, where filling it from Python
    /// slab by slab takes too long).
    #[arg(long)]
    no_openvdb: bool,
}

/// The grid size beyond which OpenVDB is not filled.
const VDB_MAX_N: usize = 2048;

/// Runs `anisomesh bench band`, printing one table.
pub fn run(a: BandArgs) -> Result<()> {
    let (n, bands) = if a.quick {
        (256, vec![2])
    } else {
        (a.n, a.band)
    };
    check(n, &bands)?;
    let threads = rayon::current_num_threads();
    println!(
        "sphere r = 1/3 in (-1/2, 1/2)^3, {n}^3 cells, band |f| <= j h; build on {threads} threads, \
         cell pass on 1"
    );
    println!(
        "{:>3} {:>12} {:>10} {:>10} {:>8} {:>9} {:>12} {:>14} {:>12} {:>10} {:>9} {:>7}",
        "j",
        "nodes",
        "runs",
        "index MB",
        "B/node",
        "build s",
        "cells",
        "pass nodes/s",
        "vdb active",
        "vdb MB",
        "vdb B/vox",
        "ratio"
    );
    for &j in &bands {
        let r = ours(n, j)?;
        let per_node = r.index_bytes as f64 / r.nodes as f64;
        let ours_f32 = per_node + 4.0;
        let vdb = if a.no_openvdb {
            Err("not asked for".to_string())
        } else if n > VDB_MAX_N {
            Err(format!("skipped beyond n = {VDB_MAX_N}"))
        } else {
            openvdb(n, j)
        };
        let (va, vm, vb, ratio) = match &vdb {
            Ok(v) => {
                let b = v.mem_bytes as f64 / v.active as f64;
                (
                    v.active.to_string(),
                    format!("{:.1}", v.mem_bytes as f64 / 1e6),
                    format!("{b:.2}"),
                    format!("{:.2}", ours_f32 / b),
                )
            }
            Err(_) => ("-".into(), "-".into(), "-".into(), "-".into()),
        };
        println!(
            "{:>3} {:>12} {:>10} {:>10.1} {:>8.3} {:>9.2} {:>12} {:>14.3e} {:>12} {:>10} {:>9} {:>7}",
            j,
            r.nodes,
            r.runs,
            r.index_bytes as f64 / 1e6,
            per_node,
            r.build_seconds,
            r.cells,
            r.nodes as f64 / r.cell_pass_seconds,
            va,
            vm,
            vb,
            ratio
        );
        match vdb {
            Ok(v) if v.active as usize != r.nodes => println!(
                "    OpenVDB holds {} active voxels, we hold {} nodes: the bands differ",
                v.active, r.nodes
            ),
            Ok(v) => println!(
                "    same voxels; ours with f32 values {ours_f32:.2} B/node; OpenVDB fill {:.1} s; \
                 cell sum {:.6e}",
                v.seconds, r.cell_sum
            ),
            Err(why) => println!(
                "    OpenVDB: {why}; ours with f32 values {ours_f32:.2} B/node; cell sum {:.6e}",
                r.cell_sum
            ),
        }
    }
    Ok(())
}
