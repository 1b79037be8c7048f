//! All the redistancing experiments in one run: the tables (2D and 3D) with their orders, the
//! volume drift, the printed tables and the files.

use std::collections::hash_map::Entry;
use std::collections::HashMap;
use std::io::IsTerminal;
use std::time::Instant;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use super::cases::{circle_case, zalesak_case};
use super::drift::{sphere_drift, sphere_drift_geometric_signed};
use super::output::{write_json, write_plots};
use super::print::{drift_line, print_table};
use super::torus::{refined_box, torus_case_on, torus_distance};
use super::types::{Drift, ReinitOptions, ReinitReport, Row, Table};
use anisomesh::error::Result;
use anisomesh::mesh3::Mesh3;

/// Peak resident set size of this process in MiB (`VmHWM` of `/proc/self/status`).
pub fn peak_rss_mib() -> Option<f64> {
    let s = std::fs::read_to_string("/proc/self/status").ok()?;
    let line = s.lines().find(|l| l.starts_with("VmHWM:"))?;
    let kb: f64 = line.split_whitespace().nth(1)?.parse().ok()?;
    Some(kb / 1024.0)
}

/// A progress bar of `len` steps on standard error when it is a terminal, hidden otherwise.
fn progress(len: u64, msg: &str) -> ProgressBar {
    let b = ProgressBar::new(len);
    if std::io::stderr().is_terminal() {
        b.set_draw_target(ProgressDrawTarget::stderr());
        if let Ok(s) = ProgressStyle::with_template("{msg} [{bar:30}] {pos}/{len} {elapsed}") {
            b.set_style(s);
        }
    } else {
        b.set_draw_target(ProgressDrawTarget::hidden());
    }
    b.set_message(msg.to_string());
    b
}

/// The rows with their orders `log(e_{i-1} / e_i) / log(h_{i-1} / h_i)` filled in.
fn with_orders(mut rows: Vec<Row>) -> Vec<Row> {
    for i in 1..rows.len() {
        let rh = (rows[i - 1].h / rows[i].h).ln();
        rows[i].order_inf = Some((rows[i - 1].e_inf / rows[i].e_inf).ln() / rh);
        rows[i].order_grad = Some((rows[i - 1].e_grad / rows[i].e_grad).ln() / rh);
    }
    rows
}

/// Runs the experiments of 003 §8 ([`super`]), prints the tables beside the paper's values, and
/// writes `reinit.json` and the figures when `out_dir` is set.
pub fn run(opts: &ReinitOptions) -> Result<ReinitReport> {
    let tables = run_tables(opts)?;
    let (volume_drift, volume_drift_geometric) = run_drift(opts)?;
    let report = ReinitReport {
        tables,
        volume_drift,
        volume_drift_geometric,
    };
    if let Some(dir) = &opts.out_dir {
        write_json(dir, &report)?;
        write_plots(dir, &report)?;
    }
    Ok(report)
}

/// The convergence tables: every shape with levels, every `α` and degree, one row per level
/// (printed as each table completes when `opts.print`).
fn run_tables(opts: &ReinitOptions) -> Result<Vec<Table>> {
    let mut tables = Vec::new();
    let sets = [
        ("circle", 2usize, &opts.levels_2d),
        ("zalesak", 2, &opts.levels_2d),
        ("torus", 3, &opts.levels_3d),
    ];
    let cases: Vec<(&str, usize, u32, usize)> = sets
        .iter()
        .filter(|(_, _, l)| !l.is_empty())
        .flat_map(|&(name, dim, _)| {
            opts.alphas
                .iter()
                .flat_map(move |&a| opts.degrees.iter().map(move |&k| (name, dim, a, k)))
        })
        .collect();
    let levels_of = |dim: usize| {
        if dim == 2 {
            &opts.levels_2d
        } else {
            &opts.levels_3d
        }
    };
    let total: usize = cases.iter().map(|c| levels_of(c.1).len()).sum();
    let bar = progress(total as u64, "tables");
    // Torus meshes by level, built once (the deepest levels take seconds and hundreds of MiB).
    let mut meshes: HashMap<u32, Mesh3> = HashMap::new();
    for (name, dim, alpha, k) in cases {
        let mut rows = Vec::new();
        for &l in levels_of(dim) {
            let a = f64::from(alpha);
            let t0 = Instant::now();
            let (h, e_inf, e_grad, report) = match name {
                "circle" => circle_case(l, k, a)?,
                "zalesak" => zalesak_case(l, k, a)?,
                _ => {
                    let m = match meshes.entry(l) {
                        Entry::Occupied(e) => e.into_mut(),
                        Entry::Vacant(e) => e.insert(refined_box(l, torus_distance)?),
                    };
                    torus_case_on(m, l, k, a)?
                }
            };
            rows.push(Row {
                level: l,
                h,
                e_inf,
                order_inf: None,
                e_grad,
                order_grad: None,
                report,
                secs: t0.elapsed().as_secs_f64(),
                peak_mib: peak_rss_mib(),
            });
            bar.inc(1);
        }
        let t = Table {
            name: name.into(),
            dim,
            k,
            alpha,
            rows: with_orders(rows),
        };
        if opts.print {
            bar.suspend(|| print_table(&t));
        }
        tables.push(t);
    }
    bar.finish_and_clear();
    Ok(tables)
}

/// The volume drift at every level of `opts.volume_levels`: PPR for every degree, and geometric
/// redistancing when degree 1 is asked for; `(PPR, geometric)`.
fn run_drift(opts: &ReinitOptions) -> Result<(Vec<Drift>, Vec<Drift>)> {
    let mut volume_drift = Vec::new();
    let mut volume_drift_geometric = Vec::new();
    for &l in &opts.volume_levels {
        for &k in &opts.degrees {
            let bar = progress(opts.volume_reps as u64, &format!("sphere k={k} l={l}"));
            let e = sphere_drift(l, k, opts.volume_reps, Some(&bar))?;
            bar.finish_and_clear();
            if opts.print {
                println!("\n{}", drift_line(k, l, &e));
            }
            volume_drift.push(Drift {
                k,
                level: l,
                rel_error: e,
            });
        }
        if opts.degrees.contains(&1) {
            let bar = progress(opts.volume_reps as u64, &format!("sphere geometric l={l}"));
            let e: Vec<f64> = sphere_drift_geometric_signed(l, opts.volume_reps, Some(&bar))?
                .into_iter()
                .map(f64::abs)
                .collect();
            bar.finish_and_clear();
            if opts.print {
                println!("geometric redistancing, {}", drift_line(1, l, &e));
            }
            volume_drift_geometric.push(Drift {
                k: 1,
                level: l,
                rel_error: e,
            });
        }
    }
    Ok((volume_drift, volume_drift_geometric))
}
