//! The figures of `anisomesh zalesak` (004 §5.1), written as PNG into the output directory:
//! - `zalesak_positions.png`: the adapted meshes and zero levels at the rotations `k π/2`,
//!   `k = 0..3`, in a 2 x 2 panel;
//! - `zalesak_initial_final.png`: the initial and final zero levels superposed on the final
//!   mesh, with zoomed insets at the four slot corners;
//! - `zalesak_period_mesh.png`: one adapted mesh of a period (the fixed point of 004 §3.5)
//!   with the zero levels at the period's start and end;
//! - `zalesak_compare.png` and `zalesak_compare_series.png` (with `--compare`): the final
//!   interfaces on the anisotropic, isotropic and uniform meshes, and the relative area and
//!   perimeter errors along the revolution.

use super::exact::{EXACT_AREA, EXACT_PERIMETER};
use super::types::{Snapshot, ZalesakReport, ZalesakSample};
use crate::app::plot::{
    lines_rgb, mesh_rgb, Corner, Inset, LinesPlot, MeshPlot, RGBColor, RgbImage, Series,
    SeriesStyle,
};
use anisomesh::error::Result;
use anisomesh::geom::DVec2;
use anisomesh::levelset::interface::extract_zero_level;
use anisomesh::mesh::Mesh2;
use std::f64::consts::FRAC_PI_2;
use std::path::Path;

const BLUE: RGBColor = RGBColor(31, 119, 180);
const RED: RGBColor = RGBColor(214, 39, 40);

/// The zero level of `u` as drawable paths.
fn paths(mesh: &Mesh2, u: &[f64]) -> Result<Vec<Vec<DVec2>>> {
    Ok(extract_zero_level(mesh, u)?
        .iter()
        .map(|l| l.path_points())
        .collect())
}

fn overlay(
    paths: Vec<Vec<DVec2>>,
    colour: RGBColor,
    width: u32,
) -> Vec<(Vec<DVec2>, RGBColor, u32)> {
    paths.into_iter().map(|p| (p, colour, width)).collect()
}

/// Copies `src` into `dst` with its top-left corner at `(x0, y0)` (clipped).
fn blit(dst: &mut RgbImage, src: &RgbImage, x0: u32, y0: u32) {
    for y in 0..src.height.min(dst.height.saturating_sub(y0)) {
        let w = src.width.min(dst.width.saturating_sub(x0)) as usize;
        let s = 3 * (y as usize * src.width as usize);
        let d = 3 * ((y0 + y) as usize * dst.width as usize + x0 as usize);
        dst.pixels[d..d + 3 * w].copy_from_slice(&src.pixels[s..s + 3 * w]);
    }
}

/// Panels laid out in rows of `cols`, all of the size of the first.
fn grid(panels: &[RgbImage], cols: usize) -> Result<RgbImage> {
    let (w, h) = (panels[0].width, panels[0].height);
    let rows = panels.len().div_ceil(cols);
    let mut img = RgbImage::new(w * cols as u32, h * rows as u32)?;
    for (i, p) in panels.iter().enumerate() {
        blit(&mut img, p, w * (i % cols) as u32, h * (i / cols) as u32);
    }
    Ok(img)
}

/// `p` rotated by the angle `t` about the origin.
fn rotate(p: DVec2, t: f64) -> DVec2 {
    let (s, c) = t.sin_cos();
    DVec2::new(c * p.x - s * p.y, s * p.x + c * p.y)
}

/// A square window of half-size `r` around `c`.
fn window(c: DVec2, r: f64) -> (DVec2, DVec2) {
    (c - DVec2::splat(r), c + DVec2::splat(r))
}

/// The four slot corners of the unrotated disk: bottom (on the circle) and top of both walls.
fn slot_corners() -> [DVec2; 4] {
    let s = anisomesh::levelset::shapes::Zalesak::default();
    let yb = s.centre.y - (s.radius * s.radius - s.half_width * s.half_width).sqrt();
    let (xl, xr, yt) = (
        s.centre.x - s.half_width,
        s.centre.x + s.half_width,
        s.slot_top,
    );
    [
        DVec2::new(xl, yt),
        DVec2::new(xr, yt),
        DVec2::new(xl, yb),
        DVec2::new(xr, yb),
    ]
}

fn positions(dir: &Path, r: &ZalesakReport) -> Result<()> {
    let snaps: Vec<&Snapshot> = (0..4)
        .filter_map(|k| {
            let t = k as f64 * FRAC_PI_2;
            r.frames
                .snapshots
                .iter()
                .find(|s| (s.time - t).abs() < 1e-9)
        })
        .collect();
    if snaps.is_empty() {
        return Ok(());
    }
    let mut panels = Vec::new();
    for (k, s) in snaps.iter().enumerate() {
        let plot = MeshPlot {
            width: 760,
            height: 700,
            view: Some(window(DVec2::ZERO, 1.4)),
            polylines: overlay(paths(&s.mesh, &s.u)?, RED, 2),
            title: format!(
                "rotation {k}π/2 (period {}): {} vertices",
                s.period,
                s.mesh.n_points()
            ),
            ..MeshPlot::default()
        };
        panels.push(mesh_rgb(&s.mesh, &plot)?);
    }
    grid(&panels, 2)?.save_png(&dir.join("zalesak_positions.png"))
}

fn initial_final(dir: &Path, r: &ZalesakReport) -> Result<()> {
    let (Some(first), Some(last)) = (r.frames.snapshots.first(), r.frames.snapshots.last()) else {
        return Ok(());
    };
    let corners = slot_corners();
    let places = [
        Corner::TopLeft,
        Corner::TopRight,
        Corner::BottomLeft,
        Corner::BottomRight,
    ];
    let (ea, ep) = r.relative_errors();
    let mut lines = overlay(paths(&first.mesh, &first.u)?, BLUE, 2);
    lines.extend(overlay(paths(&last.mesh, &last.u)?, RED, 1));
    let plot = MeshPlot {
        width: 1100,
        height: 1000,
        view: Some((DVec2::new(-2.0, -1.55), DVec2::new(2.0, 2.0))),
        polylines: lines,
        insets: corners
            .iter()
            .zip(places)
            .map(|(&c, placement)| Inset {
                view: window(c, 0.012),
                placement,
            })
            .collect(),
        title: format!(
            "initial (blue) and after one revolution (red): area {ea:+.1e}, perimeter {ep:+.1e}"
        ),
        ..MeshPlot::default()
    };
    mesh_rgb(&last.mesh, &plot)?.save_png(&dir.join("zalesak_initial_final.png"))
}

fn period_mesh(dir: &Path, r: &ZalesakReport) -> Result<()> {
    let Some((start, end)) = &r.frames.period else {
        return Ok(());
    };
    let mut lines = overlay(paths(&start.mesh, &start.u)?, BLUE, 2);
    lines.extend(overlay(paths(&end.mesh, &end.u)?, RED, 2));
    // Window around both positions of the disk.
    let c =
        0.5 * (rotate(DVec2::new(0.0, 0.75), start.time) + rotate(DVec2::new(0.0, 0.75), end.time));
    let corner = slot_corners()[1];
    let plot = MeshPlot {
        width: 1100,
        height: 1000,
        view: Some(window(c, 1.1)),
        polylines: lines,
        insets: vec![
            Inset {
                view: window(rotate(corner, start.time), 0.02),
                placement: Corner::TopRight,
            },
            Inset {
                view: window(rotate(corner, end.time), 0.02),
                placement: Corner::BottomLeft,
            },
        ],
        title: format!(
            "period {} of the fixed point: {} vertices, zero level at t = {:.4} (blue) and {:.4} (red)",
            end.period,
            end.mesh.n_points(),
            start.time,
            end.time
        ),
        ..MeshPlot::default()
    };
    mesh_rgb(&end.mesh, &plot)?.save_png(&dir.join("zalesak_period_mesh.png"))
}

fn compare(dir: &Path, r: &ZalesakReport) -> Result<()> {
    let runs: Vec<&ZalesakReport> = std::iter::once(r)
        .chain(
            [&r.compare_isotropic, &r.compare_uniform]
                .into_iter()
                .flatten()
                .map(|b| b.as_ref()),
        )
        .collect();
    if runs.len() < 2 {
        return Ok(());
    }
    let Some(first) = r.frames.snapshots.first() else {
        return Ok(());
    };
    let exact = paths(&first.mesh, &first.u)?;
    let mut panels = Vec::new();
    for run in &runs {
        let Some(last) = run.frames.snapshots.last() else {
            continue;
        };
        let (ea, ep) = run.relative_errors();
        let mut lines = overlay(exact.clone(), BLUE, 2);
        lines.extend(overlay(paths(&last.mesh, &last.u)?, RED, 2));
        let plot = MeshPlot {
            width: 700,
            height: 760,
            view: Some((DVec2::new(-0.6, 0.2), DVec2::new(0.6, 1.3))),
            polylines: lines,
            insets: vec![Inset {
                view: window(slot_corners()[1], 0.02),
                placement: Corner::BottomRight,
            }],
            title: format!(
                "{}: {:.0} verts, area {ea:+.1e}, perim {ep:+.1e}",
                run.label(),
                run.vertices_mean
            ),
            ..MeshPlot::default()
        };
        panels.push(mesh_rgb(&last.mesh, &plot)?);
    }
    grid(&panels, panels.len())?.save_png(&dir.join("zalesak_compare.png"))?;
    let chart = |what: &str, exact: f64, get: &dyn Fn(&ZalesakSample) -> f64| {
        lines_rgb(&LinesPlot {
            title: format!("relative {what} error along the revolution"),
            x_label: "t".into(),
            y_label: format!("({what} - exact) / exact"),
            series: runs
                .iter()
                .map(|run| Series {
                    name: format!("{} ({:.0} verts)", run.label(), run.vertices_mean),
                    points: run
                        .series
                        .iter()
                        .map(|s| (s.time, get(s) / exact - 1.0))
                        .collect(),
                    show_fit_slope: false,
                    style: SeriesStyle::LineMarkers,
                })
                .collect(),
            width: 800,
            height: 560,
        })
    };
    let a = chart("area", EXACT_AREA, &|s| s.area)?;
    let p = chart("perimeter", EXACT_PERIMETER, &|s| s.perimeter)?;
    grid(&[a, p], 2)?.save_png(&dir.join("zalesak_compare_series.png"))
}

/// Writes the figures listed in the module documentation into `dir` (those whose data the
/// report kept; the comparison figures only with `--compare`).
pub fn write_figures(dir: &Path, r: &ZalesakReport) -> Result<()> {
    std::fs::create_dir_all(dir).map_err(|e| anisomesh::Error::io(dir, e))?;
    positions(dir, r)?;
    initial_final(dir, r)?;
    period_mesh(dir, r)?;
    compare(dir, r)?;
    Ok(())
}
