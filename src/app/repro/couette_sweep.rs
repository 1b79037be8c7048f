//! Mesh-convergence sweeps of the Couette benchmark (004 §5.1): how `ω` converges with the
//! mesh on adapted (non-fitted) and body-fitted meshes, and how much `ω` moves when the
//! interface is shifted across a fixed adapted mesh (the robustness of the cut-element
//! viscosity rule).
//!
//! Adapted family: one scale `s` for all sizes of the eq. (6) metric, `ε = 1e-4 s²`,
//! `hmin = band = 1e-3 s`, `hmax = 0.06 s`, and the growth rate of the sizes away from the
//! interface `grade = 0.3 s` (sizes `h ≈ 0.3 s d` at distance `d`: with a fixed grade the flow
//! near the disk is not refined and ω stalls near 1e-4). The default run is `s = 1`; the mesh sizes scale
//! like `s`, so the vertex count roughly like `1/s²`. Fitted family: edge length `h` on the circle,
//! `hmax = 8 h` (at most 0.1).

use super::couette::{build_mesh, run, CouetteOptions, CouetteReport, PAPER};
use crate::app::plot::{loglog_png, LogLogPlot, Series, SeriesStyle};
use anisomesh::adapt::LevelSetMetric;
use anisomesh::error::Result;
use anisomesh::flows::{CouetteCase, InterfaceViscosity, StokesSolver};
use serde::Serialize;

/// One line of [`sweep`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct SweepRow {
    /// "adapted, harmonic", "adapted, quadrature" or "fitted".
    pub family: String,
    /// The scale `s` (adapted) or the interface edge length `h` (fitted).
    pub param: f64,
    pub report: CouetteReport,
}

/// The options of the adapted mesh of scale `s`.
pub fn adapted_options(s: f64, interface: InterfaceViscosity) -> CouetteOptions {
    CouetteOptions {
        metric: LevelSetMetric {
            eps: 1e-4 * s * s,
            hmin: 1e-3 * s,
            band: 1e-3 * s,
            hmax: 0.06 * s,
            grade: 0.3 * s,
            ..LevelSetMetric::default()
        },
        interface,
        figures: false,
        ..CouetteOptions::default()
    }
}

/// The options of the body-fitted mesh with edge length `h` on the circle.
pub fn fitted_options(h: f64) -> CouetteOptions {
    CouetteOptions {
        fitted: true,
        h_interface: h,
        metric: LevelSetMetric {
            hmax: (8.0 * h).min(0.1),
            ..CouetteOptions::default().metric
        },
        figures: false,
        ..CouetteOptions::default()
    }
}

/// Runs the adapted families (harmonic and quadrature cut-element rules) over the scales
/// `scales` and the fitted family over the interface sizes `hs`.
pub fn sweep(scales: &[f64], hs: &[f64]) -> Result<Vec<SweepRow>> {
    let mut rows = Vec::new();
    for (name, rule) in [
        ("adapted, harmonic", InterfaceViscosity::Harmonic),
        ("adapted, quadrature", InterfaceViscosity::Quadrature),
    ] {
        for &s in scales {
            rows.push(SweepRow {
                family: name.into(),
                param: s,
                report: run(&adapted_options(s, rule))?,
            });
        }
    }
    for &h in hs {
        rows.push(SweepRow {
            family: "fitted".into(),
            param: h,
            report: run(&fitted_options(h))?,
        });
    }
    Ok(rows)
}

/// The sweep as a markdown table.
pub fn sweep_table(rows: &[SweepRow]) -> String {
    let mut t = String::from(
        "| mesh | s or h | vertices | ω | abs(ω+1) | rigidity | Uzawa its | seconds |\n\
         |---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        let p = &r.report;
        t += &format!(
            "| {} | {} | {} | {:.7} | {:.1e} | {:.1e} | {} | {:.2} |\n",
            r.family,
            r.param,
            p.vertices,
            p.omega,
            p.omega_error,
            p.rigidity,
            p.uzawa_iterations,
            p.seconds
        );
    }
    t
}

/// `ω + 1` with the harmonic and with the quadrature cut-element rule on the default adapted
/// mesh when the disk radius is changed by each of `shifts` (the mesh is kept: the interface
/// moves across its elements; the exact `ω` stays -1). Returns `(shift, harmonic, quadrature)`.
pub fn interface_shift(shifts: &[f64]) -> Result<Vec<(f64, f64, f64)>> {
    let (mesh, _) = build_mesh(&CouetteOptions::default())?;
    let solver = StokesSolver::default();
    let mut out = Vec::new();
    for &d in shifts {
        let mut w = [0.0; 2];
        for (k, rule) in [InterfaceViscosity::Harmonic, InterfaceViscosity::Quadrature]
            .into_iter()
            .enumerate()
        {
            let case = CouetteCase {
                radius: CouetteCase::default().radius + d,
                interface: rule,
                ..CouetteCase::default()
            };
            w[k] = case.solve(&mesh, solver)?.fit.omega + 1.0;
        }
        out.push((d, w[0], w[1]));
    }
    Ok(out)
}

/// Writes `|ω + 1|` against the vertex count of each family of `rows` as a log-log PNG (with
/// the paper's FreeFem++ adapted-mesh results, 004 §5.1, as a fourth series).
pub fn sweep_png(path: &std::path::Path, rows: &[SweepRow]) -> Result<()> {
    let mut families: Vec<&str> = Vec::new();
    for r in rows {
        if !families.contains(&r.family.as_str()) {
            families.push(&r.family);
        }
    }
    let mut series: Vec<Series> = families
        .iter()
        .map(|f| Series {
            name: (*f).to_string(),
            points: rows
                .iter()
                .filter(|r| r.family == *f && r.report.omega_error > 0.0)
                .map(|r| (r.report.vertices as f64, r.report.omega_error))
                .collect(),
            show_fit_slope: true,
            style: SeriesStyle::LineMarkers,
        })
        .collect();
    series.push(Series {
        name: "FreeFem++ adapted (004)".into(),
        points: PAPER
            .iter()
            .map(|&(n, w)| (n as f64, (w + 1.0).abs()))
            .collect(),
        show_fit_slope: false,
        style: SeriesStyle::Markers,
    });
    loglog_png(
        path,
        &LogLogPlot {
            title: "Couette disk (004 §5.1): |omega + 1| against vertices".into(),
            x_label: "vertices".into(),
            y_label: "|omega + 1|".into(),
            series,
            ..LogLogPlot::default()
        },
    )
}
