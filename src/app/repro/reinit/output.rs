//! The files of the redistancing experiments: `reinit.json` and the figures.

use std::path::Path;

use super::types::ReinitReport;
use crate::app::plot::{lines_png, loglog_png, LinesPlot, LogLogPlot, Series};
use anisomesh::error::{Error, Result};
use anisomesh::io::atomic_write;

/// `reinit_<name>_einf.png`, `reinit_<name>_egrad.png` (log-log against `h`, fitted slopes) and
/// `reinit_volume.png` (relative volume error against the number of redistancings).
pub(super) fn write_plots(dir: &Path, report: &ReinitReport) -> Result<()> {
    let mut names: Vec<&str> = report.tables.iter().map(|t| t.name.as_str()).collect();
    names.dedup();
    for name in names {
        for (what, label) in [("einf", "e_inf"), ("egrad", "e_grad")] {
            let series = report
                .tables
                .iter()
                .filter(|t| t.name == name && t.rows.len() > 1)
                .map(|t| Series {
                    name: format!("k={} alpha={}", t.k, t.alpha),
                    points: t
                        .rows
                        .iter()
                        .map(|r| (r.h, if what == "einf" { r.e_inf } else { r.e_grad }))
                        .collect(),
                    show_fit_slope: true,
                    ..Series::default()
                })
                .collect::<Vec<_>>();
            if series.is_empty() {
                continue;
            }
            let plot = LogLogPlot {
                title: format!("{name}: {label} (003 §8)"),
                x_label: "h".into(),
                y_label: label.into(),
                series,
                ..LogLogPlot::default()
            };
            loglog_png(&dir.join(format!("reinit_{name}_{what}.png")), &plot)?;
        }
    }
    let mut ks: Vec<usize> = report.volume_drift.iter().map(|d| d.k).collect();
    ks.sort_unstable();
    ks.dedup();
    for k in ks {
        let geo = report.volume_drift_geometric.iter().filter(|_| k == 1);
        let series = report
            .volume_drift
            .iter()
            .filter(|d| d.k == k)
            .map(|d| (format!("PPR, level {}", d.level), d))
            .chain(geo.map(|d| (format!("geometric, level {}", d.level), d)))
            .map(|(name, d)| Series {
                name,
                points: d
                    .rel_error
                    .iter()
                    .enumerate()
                    .map(|(n, &e)| (n as f64, e))
                    .collect(),
                ..Series::default()
            })
            .collect();
        let plot = LinesPlot {
            title: format!("sphere r = 0.25, k = {k}: relative volume error (003 Fig. 8.4)"),
            x_label: "redistancings n".into(),
            y_label: "e_Vol^n".into(),
            series,
            ..LinesPlot::default()
        };
        lines_png(&dir.join(format!("reinit_volume_k{k}.png")), &plot)?;
    }
    Ok(())
}

/// Writes `dir/reinit.json` atomically ([`atomic_write`]).
pub(super) fn write_json(dir: &Path, report: &ReinitReport) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
    let text = serde_json::to_string_pretty(report)
        .map_err(|e| Error::InvalidInput(format!("reinit.json: {e}")))?;
    atomic_write(&dir.join("reinit.json"), |w| w.write_all(text.as_bytes()))
}
