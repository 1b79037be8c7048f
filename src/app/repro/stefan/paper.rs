//! The pentagon seed of 001 §6 without surface tension (ε_C = ε_V = 0): (−1.5, 1.5)², a uniform
//! base mesh (128 × 128 cells, 129² vertices), Δt = 2.5e-4 to t = 0.4, initial temperature 0 in
//! the solid and −½ in the liquid (6.5)–(6.6), insulated walls (6.3). The seed's size is not
//! given in 001; here it is the regular pentagon of circumradius 0.1 centred at the origin with a
//! vertex on the positive y axis.

use crate::app::plot::{lines_png, LinesPlot, Series, SeriesStyle};
use anisomesh::backends::fitted::{fit, stefan_step, FitOptions, StefanState};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::io::atomic_write;
use anisomesh::levelset::redistance::redistance_geometric;
use anisomesh::mesh::{GridPattern, Mesh2};
use serde::Serialize;
use std::path::Path;
use std::time::Instant;

/// Circumradius of the pentagon seed.
pub const SEED_RADIUS: f64 = 0.1;

/// A snapshot of the run.
#[derive(Debug, Clone, Serialize)]
pub struct Snapshot {
    /// Time.
    pub time: f64,
    /// Steps done.
    pub step: usize,
    /// Solid area.
    pub area: f64,
    /// Vertices of the fitted mesh.
    pub fitted_vertices: usize,
    /// Largest `|v_n|` of the last step.
    pub max_vn: f64,
    /// CG iterations of the last step.
    pub cg_iterations: usize,
    /// Interface vertex positions.
    #[serde(skip)]
    pub interface: Vec<(f64, f64)>,
}

/// The report of [`run`].
#[derive(Debug, Clone, Serialize)]
pub struct PentagonReport {
    /// Cells per side.
    pub n: usize,
    /// Time step.
    pub dt: f64,
    /// End time.
    pub t_end: f64,
    /// Wall time, seconds.
    pub seconds: f64,
    /// Snapshots at t = 0 and at `snapshots` equal intervals.
    pub snapshots: Vec<Snapshot>,
}

fn snapshot(
    base: &Mesh2,
    st: &StefanState,
    step: usize,
    last: (usize, f64, usize),
) -> Result<Snapshot> {
    let fm = fit(base, &st.phi, &FitOptions::default())?;
    let mut interface = Vec::new();
    for [a, _] in fm.interface_edges() {
        let p = fm.mesh.points[a as usize];
        interface.push((p.x, p.y));
    }
    Ok(Snapshot {
        time: st.time,
        step,
        area: fm.area_inside(),
        fitted_vertices: last.0.max(fm.mesh.n_points()),
        max_vn: last.1,
        cg_iterations: last.2,
        interface,
    })
}

/// Runs the pentagon case on an n × n base mesh with time step `dt` to `t_end`.
pub fn run(n: usize, dt: f64, t_end: f64, snapshots: usize) -> Result<PentagonReport> {
    if n < 8 || !(dt.is_finite() && dt > 0.0) || !(t_end.is_finite() && t_end > 0.0) {
        return Err(Error::InvalidInput(format!(
            "pentagon: need n >= 8, dt > 0 and t_end > 0, finite (got {n}, {dt}, {t_end})"
        )));
    }
    let base = Mesh2::rectangle(
        DVec2::new(-1.5, -1.5),
        DVec2::new(1.5, 1.5),
        n,
        n,
        GridPattern::UnionJack,
    )?;
    let corners: Vec<DVec2> = (0..5)
        .map(|k| {
            let a = std::f64::consts::FRAC_PI_2 + 2.0 * std::f64::consts::PI * k as f64 / 5.0;
            SEED_RADIUS * DVec2::new(a.cos(), a.sin())
        })
        .collect();
    // Largest signed distance to the edge lines: negative exactly inside the convex pentagon.
    let phi0: Vec<f64> = base
        .points
        .iter()
        .map(|&p| {
            (0..5).fold(f64::NEG_INFINITY, |m, k| {
                let (a, b) = (corners[k], corners[(k + 1) % 5]);
                let e = (b - a).normalize();
                let outward = DVec2::new(e.y, -e.x);
                m.max((p - a).dot(outward))
            })
        })
        .collect();
    let phi = redistance_geometric(&base, &phi0)?;
    let temperature = phi
        .iter()
        .map(|&f| if f < 0.0 { 0.0 } else { -0.5 })
        .collect();
    let mut st = StefanState {
        phi,
        temperature,
        time: 0.0,
    };
    let h = 3.0 / n as f64;
    let steps = (t_end / dt).round().max(1.0) as usize;
    let every = (steps / snapshots.max(1)).max(1);
    let start = Instant::now();
    let mut snaps = vec![snapshot(&base, &st, 0, (0, 0.0, 0))?];
    for k in 1..=steps {
        let rep = stefan_step(&base, &mut st, dt, 3.0 * h, 3.0 * h, None)?;
        if k % every == 0 || k == steps {
            let last = (rep.fitted_vertices, rep.max_vn, rep.cg_iterations);
            snaps.push(snapshot(&base, &st, k, last)?);
        }
    }
    Ok(PentagonReport {
        n,
        dt,
        t_end,
        seconds: start.elapsed().as_secs_f64(),
        snapshots: snaps,
    })
}

/// Writes `stefan.json` and `figures/pentagon.png` (the interface at the snapshot times).
pub fn write(dir: &Path, rep: &PentagonReport) -> Result<()> {
    let figs = dir.join("figures");
    std::fs::create_dir_all(&figs).map_err(|e| Error::Io {
        path: figs.clone(),
        source: e,
    })?;
    atomic_write(&dir.join("stefan.json"), |w| {
        serde_json::to_writer_pretty(&mut *w, rep).map_err(std::io::Error::other)
    })?;
    let series = rep
        .snapshots
        .iter()
        .map(|s| Series {
            name: format!("t = {:.3}", s.time),
            points: s.interface.clone(),
            show_fit_slope: false,
            style: SeriesStyle::Markers,
        })
        .collect();
    lines_png(
        &figs.join("pentagon.png"),
        &LinesPlot {
            title: "Pentagon seed, no surface tension: interface at several times".into(),
            x_label: "x".into(),
            y_label: "y".into(),
            series,
            width: 800,
            height: 800,
        },
    )
}
