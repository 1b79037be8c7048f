//! The files of `anisomesh advect`: `advect.json` (the report), `advect.csv` (the measures after
//! each period), the final mesh and level set (`advect_final.mesh` + `.sol`, `advect_final.vtu`)
//! and the frames (`advect_frames.png`: the zero level over the mesh at the kept times,
//! `advect_half.png`: the kept state nearest the middle of the run, full size, and
//! `advect_final.png`: the final zero level over the initial one).

use super::run::AdvectReport;
use crate::app::plot::{mesh_rgb, MeshPlot, RGBColor, RgbImage};
use anisomesh::advect::{RunResult, Snapshot};
use anisomesh::error::Result;
use anisomesh::geom::DVec2;
use anisomesh::io::{self, FieldRef, Sol};
use anisomesh::levelset::interface::extract_zero_level;
use std::path::Path;

const BLUE: RGBColor = RGBColor(31, 119, 180);
const RED: RGBColor = RGBColor(214, 39, 40);

/// Writes the report, the time series, the final mesh and level set and the figures into `dir`.
pub fn write_all(dir: &Path, report: &AdvectReport, r: &RunResult) -> Result<()> {
    crate::app::repro::zalesak::output::write_report_and_series(
        dir,
        "advect",
        report,
        &report.series,
    )?;
    let (mesh, u) = (&r.last.mesh, &r.last.u);
    io::write_mesh(&dir.join("advect_final.mesh"), mesh)?;
    io::write_sol(&dir.join("advect_final.sol"), &Sol::scalar(u.clone()))?;
    io::write_vtu(
        &dir.join("advect_final.vtu"),
        mesh,
        &[("levelset", FieldRef::Scalar(u))],
        &[],
    )?;
    write_frames(dir, report, r)
}

/// The zero level of `s` as drawable paths in `colour`.
fn lines(s: &Snapshot, colour: RGBColor, width: u32) -> Result<Vec<(Vec<DVec2>, RGBColor, u32)>> {
    Ok(extract_zero_level(&s.mesh, &s.u)?
        .iter()
        .map(|l| (l.path_points(), colour, width))
        .collect())
}

/// One panel: the mesh of `s` with its zero level.
pub fn frame(s: &Snapshot, view: (DVec2, DVec2), title: String, size: u32) -> Result<RgbImage> {
    let plot = MeshPlot {
        width: size,
        height: size,
        view: Some(view),
        polylines: lines(s, RED, 2)?,
        title,
        ..MeshPlot::default()
    };
    mesh_rgb(&s.mesh, &plot)
}

fn write_frames(dir: &Path, report: &AdvectReport, r: &RunResult) -> Result<()> {
    let view = (
        DVec2::new(report.domain[0], report.domain[1]),
        DVec2::new(report.domain[2], report.domain[3]),
    );
    let mut panels = vec![frame(&r.initial, view, "t = 0".into(), 700)?];
    for s in &r.snapshots {
        panels.push(frame(
            s,
            view,
            format!("t = {:.3}, {} vertices", s.time, s.mesh.n_points()),
            700,
        )?);
    }
    RgbImage::side_by_side(&panels)?.save_png(&dir.join("advect_frames.png"))?;
    // The state halfway (the most stretched interface of a time-reversed flow), full size.
    let half = 0.5 * (r.initial.time + r.last.time);
    if let Some(s) = r
        .snapshots
        .iter()
        .min_by(|a, b| (a.time - half).abs().total_cmp(&(b.time - half).abs()))
    {
        let title = format!(
            "t = {:.3}: {} vertices, interface length {:.4}",
            s.time,
            s.mesh.n_points(),
            anisomesh::levelset::interface::interface_length(&s.mesh, &s.u)?
        );
        frame(s, view, title, 1100)?.save_png(&dir.join("advect_half.png"))?;
    }
    let mut polylines = lines(&r.initial, BLUE, 2)?;
    polylines.extend(lines(&r.last, RED, 1)?);
    let plot = MeshPlot {
        width: 1000,
        height: 1000,
        view: Some(view),
        polylines,
        title: format!(
            "initial (blue) and t = {} (red): area {:+.2e}, symmetric difference {:.2} %",
            report.t_end,
            report.area_error(),
            100.0 * report.symmetric_difference_relative()
        ),
        ..MeshPlot::default()
    };
    mesh_rgb(&r.last.mesh, &plot)?.save_png(&dir.join("advect_final.png"))
}
