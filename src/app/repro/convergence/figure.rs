//! The figure and CSV of the error-versus-vertex-count sweep ([`super::sweep`]): anisomesh's
//! three families, the peers measured in the same run, and the reported peer points
//! ([`REPORTED`]); a third panel shows "anisotropy pays", the ratio of isotropic to
//! anisotropic vertex counts at equal Hausdorff error, beside the paper's claim of about 10
//! (004 §5.1).

use std::path::Path;

use super::types::{ConvergenceReport, ConvergenceRow, Family};
use crate::app::plot::{loglog_rgb, LogLogPlot, RgbImage, Series, SeriesStyle};
use crate::app::repro::peers::PeerResult;
use anisomesh::error::Result;

/// A reported Zalesak point of a peer or reference mesh: vertices, Hausdorff, relative area and perimeter errors
/// (NaN where not reported).
#[derive(Debug, Clone, Copy)]
pub struct ReportedPoint {
    /// `BAMG`, `mmg2d`, `isotropic` or `uniform`.
    pub peer: &'static str,
    pub vertices: f64,
    pub hausdorff: f64,
    pub area_rel_error: f64,
    pub perimeter_rel_error: f64,
    /// The errors are the target level the report refers to ("errors of this size"), not
    /// measured values.
    pub at_target: bool,
}

const fn reported(
    peer: &'static str,
    vertices: f64,
    hausdorff: f64,
    area_rel_error: f64,
    perimeter_rel_error: f64,
    at_target: bool,
) -> ReportedPoint {
    ReportedPoint {
        peer,
        vertices,
        hausdorff,
        area_rel_error,
        perimeter_rel_error,
        at_target,
    }
}

/// The reported Zalesak points: BAMG (FreeFem++ `adaptmesh`), mmg2d after six
/// fixed-point passes, and "isotropic adaptation needs 26,000–54,000 vertices and a uniform mesh
/// 641,601 vertices for errors of this size" — these three carry no measured error and are
/// placed at the target errors (Hausdorff 5e-4, area 5e-5). The full sweep measures that very
/// uniform grid (800 x 800 cells).
pub const REPORTED: [ReportedPoint; 7] = [
    reported("BAMG", 5720.0, 4.5e-4, 5.5e-5, f64::NAN, false),
    reported("BAMG", 4988.0, 1.1e-3, 2.6e-4, f64::NAN, false),
    reported("BAMG", 9426.0, 5.5e-4, 8.7e-5, f64::NAN, false),
    reported("mmg2d", 4465.0, f64::NAN, 3.7e-4, 3.4e-4, false),
    reported("isotropic", 26000.0, 5e-4, 5e-5, f64::NAN, true),
    reported("isotropic", 54000.0, 5e-4, 5e-5, f64::NAN, true),
    reported("uniform", 641601.0, 5e-4, 5e-5, f64::NAN, true),
];

fn csv_num(x: f64) -> String {
    if x.is_finite() {
        format!("{x:e}")
    } else {
        String::new()
    }
}

/// The legend name of a measured peer series.
fn peer_label(slug: &str) -> String {
    match slug {
        "mmg2d-metric" => "mmg2d, same metric (measured)".into(),
        "bamg-metric" => "BAMG, same metric (measured)".into(),
        "bamg-ls" => "BAMG, own metric err=eps (measured)".into(),
        "mmg2d-ls" => "mmg2d -ls (measured)".into(),
        s => format!("{s} (measured)"),
    }
}

/// Writes the rows, the measured peers and (Zalesak) the reported points as CSV, atomically.
/// The `family` column says which; `converged` is empty for the reported points.
pub fn write_csv(path: &Path, report: &ConvergenceReport) -> Result<()> {
    let mut lines = vec![
        "family,parameter,hmin,vertices,triangles,hausdorff,hausdorff_corners,hausdorff_rest,area_rel_error,perimeter_rel_error,seconds,converged".to_string(),
    ];
    for r in &report.rows {
        lines.push(format!(
            "{},{},{},{},{},{},{},{},{},{},{:.3},{}",
            r.family.name(),
            csv_num(r.parameter),
            csv_num(r.hmin),
            r.vertices,
            r.triangles,
            csv_num(r.hausdorff),
            csv_num(r.hausdorff_corners),
            csv_num(r.hausdorff_rest),
            csv_num(r.area_rel_error),
            csv_num(r.perimeter_rel_error),
            r.seconds,
            r.converged
        ));
    }
    for p in report.peers.iter().filter(|p| p.is_ok()) {
        lines.push(format!(
            "{} (measured),{},,{},{},{},,,{},{},{:.3},",
            p.peer.slug(),
            csv_num(p.eps),
            p.vertices,
            p.triangles,
            csv_num(p.hausdorff),
            csv_num(p.area_rel_error.abs()),
            csv_num(p.perimeter_rel_error.abs()),
            p.seconds
        ));
    }
    if report.shape == "zalesak" {
        for p in REPORTED {
            let what = if p.at_target {
                "quoted, at the target errors"
            } else {
                "quoted"
            };
            lines.push(format!(
                "{} ({what}),,,{},,{},,,{},{},,",
                p.peer,
                p.vertices,
                csv_num(p.hausdorff),
                csv_num(p.area_rel_error),
                csv_num(p.perimeter_rel_error)
            ));
        }
    }
    let text = lines.join("\n") + "\n";
    anisomesh::io::atomic_write(path, |w| w.write_all(text.as_bytes()))
}

/// The measured peers of one kind as `(vertices, error)` points.
fn peer_points(peers: &[PeerResult], slug: &str, area: bool) -> Vec<(f64, f64)> {
    let mut pts: Vec<(f64, f64)> = peers
        .iter()
        .filter(|p| p.is_ok() && p.peer.slug() == slug)
        .map(|p| {
            let e = if area {
                p.area_rel_error.abs()
            } else {
                p.hausdorff
            };
            (p.vertices as f64, e)
        })
        .collect();
    pts.sort_by(|a, b| a.0.total_cmp(&b.0));
    pts
}

/// One log-log panel: the three families (fitted slopes in the legend), the measured peers and
/// the reported points.
fn panel(report: &ConvergenceReport, area: bool) -> LogLogPlot {
    let value = |r: &ConvergenceRow| if area { r.area_rel_error } else { r.hausdorff };
    let mut series: Vec<Series> = [Family::Anisotropic, Family::Isotropic, Family::Uniform]
        .into_iter()
        .map(|f| Series {
            name: format!("anisomesh {}", f.name()),
            points: report
                .family(f)
                .iter()
                .map(|r| (r.vertices as f64, value(r)))
                .collect(),
            show_fit_slope: true,
            style: SeriesStyle::LineMarkers,
        })
        .collect();
    let mut slugs: Vec<&str> = report.peers.iter().map(|p| p.peer.slug()).collect();
    slugs.dedup();
    for slug in slugs {
        let points = peer_points(&report.peers, slug, area);
        if !points.is_empty() {
            series.push(Series {
                name: peer_label(slug),
                points,
                show_fit_slope: false,
                style: SeriesStyle::LineMarkers,
            });
        }
    }
    if report.shape == "zalesak" {
        for peer in ["BAMG", "mmg2d", "isotropic", "uniform"] {
            let chosen: Vec<&ReportedPoint> = REPORTED.iter().filter(|p| p.peer == peer).collect();
            let points: Vec<(f64, f64)> = chosen
                .iter()
                .map(|p| {
                    (
                        p.vertices,
                        if area { p.area_rel_error } else { p.hausdorff },
                    )
                })
                .filter(|p| p.1.is_finite())
                .collect();
            // An empty series still takes its palette colour: the same series has the same
            // colour in both panels.
            let name = if chosen.iter().any(|p| p.at_target) {
                format!("{peer} (reported, at target error)")
            } else {
                format!("{peer} (reported)")
            };
            series.push(Series {
                name,
                points,
                show_fit_slope: false,
                style: SeriesStyle::Markers,
            });
        }
    }
    let (what, label) = if area {
        ("relative area error", "|A_h - A| / A")
    } else {
        ("interface Hausdorff distance", "Hausdorff distance")
    };
    LogLogPlot {
        title: format!("{}: {what} vs vertices", report.shape),
        x_label: "vertices".into(),
        y_label: label.into(),
        series,
        width: 900,
        height: 700,
    }
}

/// Horizontal lines `(name, ratio)` across the range of the positive finite `xs` (a ratio panel's
/// reference values, such as the paper's 10); none when that range is empty or a single value.
pub(super) fn ratio_lines(xs: impl IntoIterator<Item = f64>, lines: &[(&str, f64)]) -> Vec<Series> {
    let (lo, hi) = xs
        .into_iter()
        .filter(|x| *x > 0.0 && x.is_finite())
        .fold((f64::INFINITY, 0.0f64), |(l, h), x| (l.min(x), h.max(x)));
    if lo >= hi {
        return Vec::new();
    }
    lines
        .iter()
        .map(|&(name, y)| Series {
            name: name.into(),
            points: vec![(lo, y), (hi, y)],
            show_fit_slope: false,
            style: SeriesStyle::Line,
        })
        .collect()
}

/// The "anisotropy pays" panel: isotropic / anisotropic vertex counts against the Hausdorff
/// error — interpolated between sweep points, from the fitted power laws, and at equal `ε`
/// (plotted at the anisotropic mesh's error) — with the paper's claim of 10 as a line.
fn gain_panel(report: &ConvergenceReport) -> LogLogPlot {
    let g = &report.gain;
    let interp: Vec<(f64, f64)> = g
        .at_equal_error
        .iter()
        .map(|p| (p.error, p.ratio))
        .collect();
    let mut fitted = g.fitted.clone();
    fitted.sort_by(|a, b| a.0.total_cmp(&b.0));
    let ani = report.family(Family::Anisotropic);
    let mut equal_eps: Vec<(f64, f64)> = g
        .at_equal_eps
        .iter()
        .filter_map(|(eps, r)| {
            ani.iter()
                .find(|a| a.parameter == *eps)
                .map(|a| (a.hausdorff, *r))
        })
        .collect();
    equal_eps.sort_by(|a, b| a.0.total_cmp(&b.0));
    let lines = ratio_lines(
        interp.iter().chain(&fitted).chain(&equal_eps).map(|p| p.0),
        &[("paper: about 10 (004 5.1)", 10.0)],
    );
    let mut series = vec![
        Series {
            name: "equal Hausdorff, interpolated".into(),
            points: interp,
            show_fit_slope: false,
            style: SeriesStyle::Markers,
        },
        Series {
            name: "equal Hausdorff, fitted power laws".into(),
            points: fitted,
            show_fit_slope: false,
            style: SeriesStyle::LineMarkers,
        },
        Series {
            name: "equal eps (same hmin, band)".into(),
            points: equal_eps,
            show_fit_slope: false,
            style: SeriesStyle::LineMarkers,
        },
    ];
    series.extend(lines);
    LogLogPlot {
        title: format!("{}: anisotropy pays?", report.shape),
        x_label: "Hausdorff distance".into(),
        y_label: "isotropic / anisotropic vertices".into(),
        series,
        width: 700,
        height: 700,
    }
}

/// The panels side by side: Hausdorff, area error, and (when the families' errors overlap) the
/// anisotropy gain.
pub fn figure(report: &ConvergenceReport) -> Result<RgbImage> {
    let mut panels = vec![
        loglog_rgb(&panel(report, false))?,
        loglog_rgb(&panel(report, true))?,
    ];
    let gp = gain_panel(report);
    if gp.series.iter().any(|s| !s.points.is_empty()) {
        panels.push(loglog_rgb(&gp)?);
    }
    RgbImage::side_by_side(&panels)
}
