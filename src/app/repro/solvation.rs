//! The solvation runs of 001 §7 on the interface-fitted mesh: relaxations of the three
//! systems from loose and tight wraps, and the two-rod sweep over the distance `d`
//! (001 Fig. 7.8), with their reports, CSV and figures.

use crate::app::plot::{lines_png, mesh_png, LinesPlot, MeshPlot, RGBColor, Series, SeriesStyle};
use anisomesh::backends::fitted::solvation::{
    relax, setup, Energy, RelaxOptions, StepRecord, SystemKind, Wrap,
};
use anisomesh::backends::fitted::{fit, FitOptions, REF_INSIDE};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::io::atomic_write;
use anisomesh::mesh::Mesh2;
use rayon::prelude::*;
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// One relaxation: its record and the surfaces it started from and ended at.
#[derive(Debug, Clone, Serialize)]
pub struct Run {
    /// "loose" or "tight".
    pub wrap: String,
    /// Steps done.
    pub steps: usize,
    /// Whether the mean |V_n| fell below the tolerance.
    pub converged: bool,
    /// The free energy of the final surface.
    pub final_energy: Energy,
    /// Components of the final solute region.
    pub components: usize,
    /// Whether the total free energy never increased from one step to the next.
    pub monotone: bool,
    /// The largest increase of the total from one step to the next (0 if monotone).
    pub largest_increase: f64,
    /// Wall time, seconds.
    pub seconds: f64,
    /// One record per step.
    pub records: Vec<StepRecord>,
    /// Interface edges at the start and at the end, for the pictures.
    #[serde(skip)]
    pub initial_edges: Vec<[DVec2; 2]>,
    #[serde(skip)]
    pub final_edges: Vec<[DVec2; 2]>,
    #[serde(skip)]
    pub final_mesh: Option<(Mesh2, Vec<f64>)>,
}

/// The report of a system's relaxations.
#[derive(Debug, Clone, Serialize)]
pub struct Report {
    /// "three", "ring" or "rods".
    pub system: String,
    /// Rod distance in units of sigma (rods only).
    pub d: Option<f64>,
    /// Cells per side of the base grid on the unit square.
    pub n: usize,
    /// Surface tension, solvent density, pressure, Tolman length.
    pub gamma: f64,
    pub rho_w: f64,
    pub pressure: f64,
    pub tolman: f64,
    /// Particles: x, y, sigma, epsilon.
    pub particles: Vec<[f64; 4]>,
    /// The relaxations.
    pub runs: Vec<Run>,
}

fn edges(mesh: &Mesh2, phi: &[f64]) -> Result<Vec<[DVec2; 2]>> {
    let fm = fit(mesh, phi, &FitOptions::default())?;
    Ok(fm
        .interface_edges()
        .into_iter()
        .map(|[a, b]| [fm.mesh.points[a as usize], fm.mesh.points[b as usize]])
        .collect())
}

/// Relaxes `kind` from `wrap` on an `n × n` grid.
pub fn run_one(kind: SystemKind, wrap: Wrap, n: usize, opts: &RelaxOptions) -> Result<Run> {
    let sys = kind.system()?;
    let start = Instant::now();
    let (base, phi0) = setup(&sys, wrap, kind == SystemKind::Ring, n)?;
    let h = 1.0 / n as f64;
    let rel = relax(&base, h, &sys, phi0, opts)?;
    let mut largest_increase = 0.0f64;
    for w in rel.records.windows(2) {
        largest_increase = largest_increase.max(w[1].energy.total - w[0].energy.total);
    }
    let fin = rel.final_energy();
    let fm = fit(&base, &rel.phi, &FitOptions::default())?;
    let inside: Vec<f64> = (0..fm.mesh.n_tris())
        .map(|t| {
            if fm.mesh.tri_ref[t] == REF_INSIDE {
                1.0
            } else {
                0.0
            }
        })
        .collect();
    Ok(Run {
        wrap: format!("{wrap:?}").to_lowercase(),
        steps: rel.records.len() - 1,
        converged: rel.converged,
        final_energy: fin,
        components: fin.components,
        monotone: largest_increase <= 0.0,
        largest_increase,
        seconds: start.elapsed().as_secs_f64(),
        initial_edges: edges(&base, &rel.phi_initial)?,
        final_edges: edges(&base, &rel.phi)?,
        records: rel.records,
        final_mesh: Some((fm.mesh, inside)),
    })
}

/// Relaxes `kind` from each of `wraps` (in parallel).
pub fn run(kind: SystemKind, wraps: &[Wrap], n: usize, opts: &RelaxOptions) -> Result<Report> {
    let sys = kind.system()?;
    let runs = wraps
        .par_iter()
        .map(|&w| run_one(kind, w, n, opts))
        .collect::<Result<Vec<Run>>>()?;
    let q = sys.params;
    Ok(Report {
        system: kind.name().into(),
        d: match kind {
            SystemKind::Rods { d, .. } => Some(d),
            _ => None,
        },
        n,
        gamma: q.gamma,
        rho_w: q.rho_w,
        pressure: q.pressure,
        tolman: q.tolman,
        particles: sys
            .particles
            .iter()
            .map(|p| [p.x.x, p.x.y, p.sigma, p.epsilon])
            .collect(),
        runs,
    })
}

fn circle(c: DVec2, r: f64) -> Vec<DVec2> {
    (0..=48)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / 48.0;
            c + DVec2::new(a.cos(), a.sin()) * r
        })
        .collect()
}

fn create_dir(d: &Path) -> Result<()> {
    std::fs::create_dir_all(d).map_err(|e| Error::io(d, e))
}

/// Writes `solvation.json`, `figures/solvation_<name>_<wrap>_energy.png` (the energies against
/// the step) and `figures/solvation_<name>_<wrap>.png` (the final solute region shaded, the
/// initial interface in orange, the final one in black, the circles `r = σ` in red).
pub fn write(dir: &Path, name: &str, rep: &Report) -> Result<()> {
    let figs = dir.join("figures");
    create_dir(&figs)?;
    atomic_write(&dir.join("solvation.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, rep).map_err(std::io::Error::other)
    })?;
    for r in &rep.runs {
        // A tight wrap starts with a van der Waals energy many orders above the final one: the
        // plot starts where the total is within five energy scales of its final value.
        let fin = r.final_energy;
        let scale = fin.surface + fin.vdw.abs();
        let k0 = r
            .records
            .iter()
            .position(|s| (s.energy.total - fin.total).abs() <= 5.0 * scale)
            .unwrap_or(0);
        let pick = |f: fn(&Energy) -> f64| -> Vec<(f64, f64)> {
            r.records[k0..]
                .iter()
                .map(|s| (s.step as f64, f(&s.energy)))
                .collect()
        };
        let series = [
            ("surface", (|e: &Energy| e.surface) as fn(&Energy) -> f64),
            ("van der Waals", |e: &Energy| e.vdw),
            ("total", |e: &Energy| e.total),
        ]
        .into_iter()
        .map(|(what, f)| Series {
            name: what.into(),
            points: pick(f),
            show_fit_slope: false,
            style: SeriesStyle::Line,
        })
        .collect();
        lines_png(
            &figs.join(format!("solvation_{name}_{}_energy.png", r.wrap)),
            &LinesPlot {
                title: format!(
                    "{name}, {} wrap: free energy (001 (7.1)) from step {k0}",
                    r.wrap
                ),
                x_label: "step".into(),
                y_label: "energy".into(),
                series,
                width: 640,
                height: 440,
            },
        )?;
    }
    for r in &rep.runs {
        let Some((mesh, inside)) = &r.final_mesh else {
            continue;
        };
        let mut polylines: Vec<(Vec<DVec2>, RGBColor, u32)> = Vec::new();
        for e in &r.initial_edges {
            polylines.push((e.to_vec(), RGBColor(255, 127, 14), 2));
        }
        for e in &r.final_edges {
            polylines.push((e.to_vec(), RGBColor(0, 0, 0), 2));
        }
        for p in &rep.particles {
            polylines.push((
                circle(DVec2::new(p[0], p[1]), p[2]),
                RGBColor(214, 39, 40),
                1,
            ));
            polylines.push((
                circle(DVec2::new(p[0], p[1]), 0.1 * p[2]),
                RGBColor(214, 39, 40),
                2,
            ));
        }
        mesh_png(
            &figs.join(format!("solvation_{name}_{}.png", r.wrap)),
            mesh,
            &MeshPlot {
                width: 520,
                height: 480,
                tri_colour: Some(inside.clone()),
                colour_range: Some((0.0, 1.0)),
                colour_label: "solute".into(),
                draw_edges: false,
                polylines,
                title: format!(
                    "{name}, {} wrap: G = {:.4e}, {} component(s)",
                    r.wrap, r.final_energy.total, r.components
                ),
                ..MeshPlot::default()
            },
        )?;
    }
    Ok(())
}

/// One row of the rod sweep: the final energies and components from both wraps at `d`.
#[derive(Debug, Clone, Serialize)]
pub struct SweepRow {
    /// Distance in units of sigma.
    pub d: f64,
    pub loose_energy: f64,
    pub loose_components: usize,
    pub loose_steps: usize,
    pub tight_energy: f64,
    pub tight_components: usize,
    pub tight_steps: usize,
    /// Whether every relaxation of the row converged.
    pub converged: bool,
    /// Whether both relaxations decreased the total monotonically.
    pub monotone: bool,
}

/// The rod sweep and the range of `d` in which the wraps end in different minima.
#[derive(Debug, Clone, Serialize)]
pub struct Sweep {
    pub n: usize,
    /// Spacing of the particles along a rod, in units of sigma.
    pub spacing: f64,
    pub rows: Vec<SweepRow>,
    /// Smallest and largest `d` of the sweep (units of sigma) at which the loose and tight
    /// relaxations end with different numbers of components.
    pub bistable: Option<(f64, f64)>,
}

/// Relaxes the rods at every `d` from both wraps (in parallel).
pub fn sweep(ds: &[f64], spacing: f64, n: usize, opts: &RelaxOptions) -> Result<Sweep> {
    let jobs: Vec<(f64, Wrap)> = ds
        .iter()
        .flat_map(|&d| [(d, Wrap::Loose), (d, Wrap::Tight)])
        .collect();
    let runs = jobs
        .par_iter()
        .map(|&(d, w)| run_one(SystemKind::Rods { d, spacing }, w, n, opts))
        .collect::<Result<Vec<Run>>>()?;
    let rows: Vec<SweepRow> = ds
        .iter()
        .zip(runs.chunks(2))
        .map(|(&d, r)| SweepRow {
            d,
            loose_energy: r[0].final_energy.total,
            loose_components: r[0].components,
            loose_steps: r[0].steps,
            tight_energy: r[1].final_energy.total,
            tight_components: r[1].components,
            tight_steps: r[1].steps,
            converged: r[0].converged && r[1].converged,
            monotone: r[0].monotone && r[1].monotone,
        })
        .collect();
    let differ: Vec<f64> = rows
        .iter()
        .filter(|r| r.loose_components != r.tight_components)
        .map(|r| r.d)
        .collect();
    let bistable = match (differ.first(), differ.last()) {
        (Some(&a), Some(&b)) => Some((a, b)),
        _ => None,
    };
    Ok(Sweep {
        n,
        spacing,
        rows,
        bistable,
    })
}

/// Writes `solvation_sweep.json`, `solvation_sweep.csv` and `figures/solvation_rods_sweep.png`
/// (001 Fig. 7.8: the final free energy against d from both wraps).
pub fn write_sweep(dir: &Path, s: &Sweep) -> Result<()> {
    let figs = dir.join("figures");
    create_dir(&figs)?;
    atomic_write(&dir.join("solvation_sweep.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, s).map_err(std::io::Error::other)
    })?;
    atomic_write(&dir.join("solvation_sweep.csv"), |w| {
        writeln!(
            w,
            "d_over_sigma,loose_energy,loose_components,tight_energy,tight_components,converged"
        )?;
        for r in &s.rows {
            writeln!(
                w,
                "{},{:.9e},{},{:.9e},{},{}",
                r.d,
                r.loose_energy,
                r.loose_components,
                r.tight_energy,
                r.tight_components,
                r.converged
            )?;
        }
        Ok(())
    })?;
    let series = vec![
        Series {
            name: "loose wrap".into(),
            points: s.rows.iter().map(|r| (r.d, r.loose_energy)).collect(),
            show_fit_slope: false,
            style: SeriesStyle::LineMarkers,
        },
        Series {
            name: "tight wrap".into(),
            points: s.rows.iter().map(|r| (r.d, r.tight_energy)).collect(),
            show_fit_slope: false,
            style: SeriesStyle::LineMarkers,
        },
    ];
    lines_png(
        &figs.join("solvation_rods_sweep.png"),
        &LinesPlot {
            title: "two rods: relaxed free energy against the distance d (001 Fig. 7.8)".into(),
            x_label: "d / sigma".into(),
            y_label: "G".into(),
            series,
            width: 800,
            height: 560,
        },
    )
}
