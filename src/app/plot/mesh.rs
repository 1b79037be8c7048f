//! Mesh figures: triangles filled by a per-triangle value through viridis with a colour bar,
//! thin edges, overlay curves (interfaces) and zoomed insets.
//!
//! Triangles are scan-converted directly into the image (pixel-centre sampling), so every pixel
//! inside the mesh is painted exactly by the triangle containing its centre — no cracks, and
//! 1e5–1e6 triangles cost little more than the pixel count. Axes, labels and lines go through
//! plotters.

use super::colormap::{viridis, ColourScale};
use super::{ensure_font, render_error, RgbImage, FONT};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::mesh::{Mesh2, NONE};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// A corner of the plotting area.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Corner {
    TopLeft,
    #[default]
    TopRight,
    BottomLeft,
    BottomRight,
}

/// A zoomed view of the window `view = (lo, hi)` drawn in a corner of the plot; the window is
/// outlined in the main view. The inset's longer side is 40 % of the plot's shorter side.
#[derive(Debug, Clone, PartialEq)]
pub struct Inset {
    pub view: (DVec2, DVec2),
    pub placement: Corner,
}

/// Options of [`mesh_png`].
#[derive(Debug, Clone, PartialEq)]
pub struct MeshPlot {
    /// Image size in pixels.
    pub width: u32,
    pub height: u32,
    /// The window `(lo, hi)` to show; `None` for the mesh's bounding box. The window is widened
    /// in one direction so that x and y have the same scale.
    pub view: Option<(DVec2, DVec2)>,
    /// One value per triangle slot (`mesh.n_tris()`), mapped through viridis; `None` fills the
    /// mesh in a light neutral colour and draws no colour bar.
    pub tri_colour: Option<Vec<f64>>,
    /// Colour range; `None` for the range of the (finite, for `log_colour` positive) values.
    pub colour_range: Option<(f64, f64)>,
    /// Logarithmic colour scale (values <= 0 are drawn grey).
    pub log_colour: bool,
    /// Label of the colour bar.
    pub colour_label: String,
    /// Draw the triangle edges (thin, semi-transparent black).
    pub draw_edges: bool,
    /// Overlay curves: points, colour, line width in pixels.
    pub polylines: Vec<(Vec<DVec2>, RGBColor, u32)>,
    pub insets: Vec<Inset>,
    pub title: String,
}

impl Default for MeshPlot {
    fn default() -> Self {
        MeshPlot {
            width: 1000,
            height: 850,
            view: None,
            tri_colour: None,
            colour_range: None,
            log_colour: false,
            colour_label: String::new(),
            draw_edges: true,
            polylines: Vec::new(),
            insets: Vec::new(),
            title: String::new(),
        }
    }
}

/// Colour of the mesh when no per-triangle value is given.
const PLAIN: RGBColor = RGBColor(222, 232, 244);
/// Colour of inset frames and the outlines of their source windows.
const INSET_FRAME: RGBColor = RGBColor(214, 39, 40);

/// A pixel rectangle of the image and the world window it shows.
#[derive(Debug, Clone, Copy)]
struct Frame {
    x0: i32,
    y0: i32,
    w: i32,
    h: i32,
    lo: DVec2,
    hi: DVec2,
}

impl Frame {
    /// World point → pixel coordinates relative to the frame's top-left corner.
    fn pixel_of(&self, p: DVec2) -> (f64, f64) {
        (
            (p.x - self.lo.x) / (self.hi.x - self.lo.x) * self.w as f64,
            (self.hi.y - p.y) / (self.hi.y - self.lo.y) * self.h as f64,
        )
    }
}

fn check_window(what: &str, (lo, hi): (DVec2, DVec2)) -> Result<()> {
    if !(lo.is_finite() && hi.is_finite() && hi.x > lo.x && hi.y > lo.y) {
        return Err(Error::InvalidInput(format!(
            "{what} [{lo}, {hi}]: need finite corners with hi > lo"
        )));
    }
    Ok(())
}

/// Widens `(lo, hi)` symmetrically so that its aspect ratio is `w / h`.
fn fit_aspect((lo, hi): (DVec2, DVec2), w: f64, h: f64) -> (DVec2, DVec2) {
    let size = hi - lo;
    let scale = (size.x / w).max(size.y / h);
    let half = 0.5 * DVec2::new(scale * w, scale * h);
    let c = 0.5 * (lo + hi);
    (c - half, c + half)
}

/// Renders a mesh figure into memory. See [`MeshPlot`].
pub fn mesh_rgb(mesh: &Mesh2, opts: &MeshPlot) -> Result<RgbImage> {
    ensure_font()?;
    let mut img = RgbImage::new(opts.width, opts.height)?;
    let (w, h) = (opts.width, opts.height);
    let bbox = mesh
        .bounding_box()
        .ok_or_else(|| Error::InvalidInput("cannot plot an empty mesh".into()))?;
    let view = match opts.view {
        Some(v) => v,
        None => {
            let pad = 0.02 * (bbox.1 - bbox.0).max_element().max(f64::MIN_POSITIVE);
            (bbox.0 - DVec2::splat(pad), bbox.1 + DVec2::splat(pad))
        }
    };
    check_window("view", view)?;
    for inset in &opts.insets {
        check_window("inset window", inset.view)?;
    }
    let scale = colour_scale(mesh, opts)?;
    let tri_colour = |t: usize| match (&opts.tri_colour, &scale) {
        (Some(v), Some(s)) => s.colour(v[t]),
        _ => PLAIN,
    };

    // Pass 1: title, axes and colour bar through plotters; find the plotting rectangle.
    let frame = {
        let root = BitMapBackend::with_buffer(&mut img.pixels, (w, h)).into_drawing_area();
        root.fill(&WHITE).map_err(render_error)?;
        let area = if opts.title.is_empty() {
            root.clone()
        } else {
            root.titled(&opts.title, (FONT, 22)).map_err(render_error)?
        };
        let (aw, _) = area.dim_in_pixel();
        let (main, bar) = match &scale {
            Some(_) if aw > 300 => {
                let (m, b) = area.split_horizontally(aw as i32 - 125);
                (m, Some(b))
            }
            _ => (area, None),
        };
        let frame = draw_axes(&main, view)?;
        if let (Some(bar), Some(s)) = (bar, scale) {
            draw_colour_bar(&bar, s, &opts.colour_label, frame.y0, frame.y0 + frame.h)?;
        }
        root.present().map_err(render_error)?;
        frame
    };

    // Main view: triangles, then overlays.
    raster(&mut img, &frame, mesh, &tri_colour);
    overlays(&mut img, &frame, mesh, opts, true)?;

    // Insets: white background, triangles, overlays and a frame.
    for inset in &opts.insets {
        let f = inset_frame(&frame, inset);
        fill_rect(&mut img, &f, [255, 255, 255]);
        raster(&mut img, &f, mesh, &tri_colour);
        let sub = MeshPlot {
            insets: Vec::new(),
            ..opts.clone()
        };
        overlays(&mut img, &f, mesh, &sub, false)?;
    }
    Ok(img)
}

/// Renders a mesh figure (see [`MeshPlot`]) and writes it as a PNG file (atomically).
pub fn mesh_png(path: &Path, mesh: &Mesh2, opts: &MeshPlot) -> Result<()> {
    mesh_rgb(mesh, opts)?.save_png(path)
}

fn colour_scale(mesh: &Mesh2, opts: &MeshPlot) -> Result<Option<ColourScale>> {
    let Some(values) = &opts.tri_colour else {
        return Ok(None);
    };
    if values.len() != mesh.n_tris() {
        return Err(Error::InvalidField {
            name: "tri_colour".into(),
            msg: format!("{} values for {} triangles", values.len(), mesh.n_tris()),
        });
    }
    let scale = match opts.colour_range {
        Some((lo, hi)) => {
            if !(lo.is_finite() && hi.is_finite() && hi > lo && (!opts.log_colour || lo > 0.0)) {
                return Err(Error::InvalidInput(format!(
                    "colour range ({lo}, {hi}): need finite lo < hi (and lo > 0 on a log scale)"
                )));
            }
            ColourScale {
                lo,
                hi,
                log: opts.log_colour,
            }
        }
        // No usable value: an arbitrary range, everything is drawn grey.
        None => ColourScale::fit(values, opts.log_colour).unwrap_or(ColourScale {
            lo: 1.0,
            hi: 10.0,
            log: opts.log_colour,
        }),
    };
    Ok(Some(scale))
}

/// Axes with an equal-scale window; returns the plotting rectangle.
fn draw_axes<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    view: (DVec2, DVec2),
) -> Result<Frame> {
    let (margin, xl, yl) = (12u32, 32u32, 58u32);
    let (aw, ah) = area.dim_in_pixel();
    let pw = aw.saturating_sub(2 * margin + yl).max(8) as f64;
    let ph = ah.saturating_sub(2 * margin + xl).max(8) as f64;
    let (lo, hi) = fit_aspect(view, pw, ph);
    let mut chart = ChartBuilder::on(area)
        .margin(margin)
        .x_label_area_size(xl)
        .y_label_area_size(yl)
        .build_cartesian_2d(lo.x..hi.x, lo.y..hi.y)
        .map_err(render_error)?;
    chart
        .configure_mesh()
        .disable_mesh()
        .x_labels(7)
        .y_labels(7)
        .label_style((FONT, 14))
        .draw()
        .map_err(render_error)?;
    let (xr, yr) = chart.plotting_area().get_pixel_range();
    let (w, h) = (xr.end - xr.start, yr.end - yr.start);
    // Re-fit to the exact pixel rectangle plotters chose (equal to the prediction up to rounding).
    let (lo, hi) = fit_aspect(view, w as f64, h as f64);
    Ok(Frame {
        x0: xr.start,
        y0: yr.start,
        w,
        h,
        lo,
        hi,
    })
}

/// Tick values of a colour scale: "nice" steps on a linear scale; 1-2-5 (or 1..9 on narrow
/// ranges, every decade on wide ones) on a log scale.
fn colour_ticks(scale: &ColourScale) -> Vec<f64> {
    let (lo, hi) = (scale.lo, scale.hi);
    let eps = 1e-9 * (hi - lo).abs();
    if scale.log {
        let (k0, k1) = (lo.log10().floor() as i32, hi.log10().ceil() as i32);
        let pick = |ms: &[f64], every: i32| -> Vec<f64> {
            (k0..=k1)
                .filter(|k| (k - k0) % every == 0)
                .flat_map(|k| ms.iter().map(move |m| m * 10f64.powi(k)))
                .filter(|v| *v >= lo * (1.0 - 1e-9) && *v <= hi * (1.0 + 1e-9))
                .collect()
        };
        let mut t = pick(&[1.0, 2.0, 5.0], 1);
        if t.len() < 3 {
            t = pick(&[1.0, 2.0, 3.0, 4.0, 5.0, 6.0, 7.0, 8.0, 9.0], 1);
        }
        if t.len() > 12 {
            let every = ((k1 - k0) / 8).max(1);
            t = pick(&[1.0], every);
        }
        t
    } else {
        let raw = (hi - lo) / 6.0;
        let mag = 10f64.powf(raw.log10().floor());
        let step = [1.0, 2.0, 5.0, 10.0]
            .iter()
            .map(|m| m * mag)
            .find(|s| *s >= raw)
            .unwrap_or(10.0 * mag);
        let first = (lo / step).ceil() as i64;
        let last = (hi / step).floor() as i64;
        (first..=last)
            .map(|i| i as f64 * step)
            .filter(|v| *v >= lo - eps && *v <= hi + eps)
            .collect()
    }
}

/// A vertical viridis bar beside the plot (rows `top..bottom` of the image), ticks and labels on
/// its right, and the rotated colour label.
fn draw_colour_bar<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    scale: ColourScale,
    label: &str,
    top: i32,
    bottom: i32,
) -> Result<()> {
    let base = area.get_base_pixel();
    let (aw, _) = area.dim_in_pixel();
    let (y0, y1) = (top - base.1, bottom - base.1);
    let (x0, x1) = (8, 32);
    let h = (y1 - y0).max(1);
    for j in 0..h {
        let t = 1.0 - (j as f64 + 0.5) / h as f64;
        area.draw(&PathElement::new(
            vec![(x0, y0 + j), (x1, y0 + j)],
            viridis(t).stroke_width(1),
        ))
        .map_err(render_error)?;
    }
    area.draw(&Rectangle::new([(x0, y0), (x1, y1)], BLACK.stroke_width(1)))
        .map_err(render_error)?;
    let style = TextStyle::from((FONT, 13).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
    for v in colour_ticks(&scale) {
        let Some(t) = scale.position(v) else { continue };
        let y = y1 - (t * h as f64).round() as i32;
        area.draw(&PathElement::new(
            vec![(x1, y), (x1 + 5, y)],
            BLACK.stroke_width(1),
        ))
        .map_err(render_error)?;
        area.draw(&Text::new(super::tick(v), (x1 + 8, y), style.clone()))
            .map_err(render_error)?;
    }
    if !label.is_empty() {
        let style = TextStyle::from((FONT, 15).into_font())
            .transform(FontTransform::Rotate90)
            .pos(Pos::new(HPos::Center, VPos::Center));
        area.draw(&Text::new(
            label.to_string(),
            (aw as i32 - 16, (y0 + y1) / 2),
            style,
        ))
        .map_err(render_error)?;
    }
    Ok(())
}

/// Paints every pixel of `f` whose centre lies in a live triangle with that triangle's colour.
fn raster(img: &mut RgbImage, f: &Frame, mesh: &Mesh2, colour: &dyn Fn(usize) -> RGBColor) {
    let width = img.width as i32;
    let height = img.height as i32;
    // Clip to the image as well as the frame.
    let (cx0, cy0) = (f.x0.max(0), f.y0.max(0));
    let (cx1, cy1) = ((f.x0 + f.w).min(width), (f.y0 + f.h).min(height));
    for t in mesh.live_tris() {
        let p = mesh.tri_points(t).map(|q| {
            let (x, y) = f.pixel_of(q);
            (x + f.x0 as f64, y + f.y0 as f64)
        });
        let min_x = p.iter().map(|q| q.0).fold(f64::INFINITY, f64::min);
        let max_x = p.iter().map(|q| q.0).fold(f64::NEG_INFINITY, f64::max);
        let min_y = p.iter().map(|q| q.1).fold(f64::INFINITY, f64::min);
        let max_y = p.iter().map(|q| q.1).fold(f64::NEG_INFINITY, f64::max);
        // Pixel (i, j) has its centre at (i + 0.5, j + 0.5).
        let i0 = ((min_x - 0.5).ceil() as i64).max(cx0 as i64);
        let i1 = ((max_x - 0.5).floor() as i64).min(cx1 as i64 - 1);
        let j0 = ((min_y - 0.5).ceil() as i64).max(cy0 as i64);
        let j1 = ((max_y - 0.5).floor() as i64).min(cy1 as i64 - 1);
        if i0 > i1 || j0 > j1 {
            continue;
        }
        let cross = |a: (f64, f64), b: (f64, f64), c: (f64, f64)| {
            (b.0 - a.0) * (c.1 - a.1) - (b.1 - a.1) * (c.0 - a.0)
        };
        let area = cross(p[0], p[1], p[2]);
        if area == 0.0 {
            continue;
        }
        let s = area.signum();
        let RGBColor(r, g, b) = colour(t);
        for j in j0..=j1 {
            let cy = j as f64 + 0.5;
            for i in i0..=i1 {
                let c = (i as f64 + 0.5, cy);
                if s * cross(p[1], p[2], c) >= 0.0
                    && s * cross(p[2], p[0], c) >= 0.0
                    && s * cross(p[0], p[1], c) >= 0.0
                {
                    let k = 3 * (j as usize * img.width as usize + i as usize);
                    img.pixels[k..k + 3].copy_from_slice(&[r, g, b]);
                }
            }
        }
    }
}

fn fill_rect(img: &mut RgbImage, f: &Frame, rgb: [u8; 3]) {
    for j in f.y0.max(0)..(f.y0 + f.h).min(img.height as i32) {
        for i in f.x0.max(0)..(f.x0 + f.w).min(img.width as i32) {
            let k = 3 * (j as usize * img.width as usize + i as usize);
            img.pixels[k..k + 3].copy_from_slice(&rgb);
        }
    }
}

/// The inset's pixel rectangle in a corner of `main`, with the inset window's aspect ratio.
fn inset_frame(main: &Frame, inset: &Inset) -> Frame {
    let (lo, hi) = inset.view;
    let aspect = (hi.x - lo.x) / (hi.y - lo.y);
    let side = 0.4 * main.w.min(main.h) as f64;
    let (w, h) = if aspect >= 1.0 {
        (side, side / aspect)
    } else {
        (side * aspect, side)
    };
    let (w, h) = (w.round().max(8.0) as i32, h.round().max(8.0) as i32);
    let pad = 10;
    let x0 = match inset.placement {
        Corner::TopLeft | Corner::BottomLeft => main.x0 + pad,
        Corner::TopRight | Corner::BottomRight => main.x0 + main.w - pad - w,
    };
    let y0 = match inset.placement {
        Corner::TopLeft | Corner::TopRight => main.y0 + pad,
        Corner::BottomLeft | Corner::BottomRight => main.y0 + main.h - pad - h,
    };
    Frame {
        x0,
        y0,
        w,
        h,
        lo,
        hi,
    }
}

/// Liang–Barsky clipping of the segment `a b` to `[0, w] x [0, h]`.
fn clip(a: (f64, f64), b: (f64, f64), w: f64, h: f64) -> Option<((f64, f64), (f64, f64))> {
    let (dx, dy) = (b.0 - a.0, b.1 - a.1);
    let (mut t0, mut t1) = (0.0f64, 1.0f64);
    for (p, q) in [(-dx, a.0), (dx, w - a.0), (-dy, a.1), (dy, h - a.1)] {
        if p == 0.0 {
            if q < 0.0 {
                return None;
            }
        } else {
            let r = q / p;
            if p < 0.0 {
                t0 = t0.max(r);
            } else {
                t1 = t1.min(r);
            }
        }
    }
    if t0 > t1 || !t0.is_finite() || !t1.is_finite() {
        return None;
    }
    Some((
        (a.0 + t0 * dx, a.1 + t0 * dy),
        (a.0 + t1 * dx, a.1 + t1 * dy),
    ))
}

/// Draws a world-space polyline clipped to the frame, as maximal unclipped runs.
fn draw_polyline<DB: DrawingBackend>(
    area: &DrawingArea<DB, Shift>,
    f: &Frame,
    pts: &[DVec2],
    style: ShapeStyle,
) -> Result<()> {
    let (w, h) = (f.w as f64, f.h as f64);
    let mut run: Vec<(i32, i32)> = Vec::new();
    let px = |q: (f64, f64)| (q.0.round() as i32, q.1.round() as i32);
    let flush = |run: &mut Vec<(i32, i32)>| -> Result<()> {
        if run.len() > 1 {
            area.draw(&PathElement::new(std::mem::take(run), style))
                .map_err(render_error)?;
        }
        run.clear();
        Ok(())
    };
    for s in pts.windows(2) {
        let (a, b) = (f.pixel_of(s[0]), f.pixel_of(s[1]));
        match clip(a, b, w, h) {
            Some((ca, cb)) => {
                if ca != a || run.is_empty() {
                    flush(&mut run)?;
                    run.push(px(ca));
                }
                run.push(px(cb));
                if cb != b {
                    flush(&mut run)?;
                }
            }
            None => flush(&mut run)?,
        }
    }
    flush(&mut run)
}

/// Edges, overlay curves and (for the main view) the inset windows' outlines, or (for an inset)
/// its frame.
fn overlays(
    img: &mut RgbImage,
    f: &Frame,
    mesh: &Mesh2,
    opts: &MeshPlot,
    main: bool,
) -> Result<()> {
    let (w, h) = (img.width, img.height);
    let root = BitMapBackend::with_buffer(&mut img.pixels, (w, h)).into_drawing_area();
    let area = root.clone().shrink((f.x0, f.y0), (f.w as u32, f.h as u32));
    if opts.draw_edges {
        let style = BLACK.mix(0.45).stroke_width(1);
        let (fw, fh) = (f.w as f64, f.h as f64);
        for t in mesh.live_tris() {
            for i in 0..3 {
                let nb = mesh.neighbours[t][i];
                if nb != NONE && (nb as usize) < t {
                    continue;
                }
                let [a, b] = mesh.edge_vertices(t, i);
                let (pa, pb) = (
                    f.pixel_of(mesh.points[a as usize]),
                    f.pixel_of(mesh.points[b as usize]),
                );
                if let Some((ca, cb)) = clip(pa, pb, fw, fh) {
                    let (ia, ib) = (
                        (ca.0.round() as i32, ca.1.round() as i32),
                        (cb.0.round() as i32, cb.1.round() as i32),
                    );
                    if ia != ib {
                        area.draw(&PathElement::new(vec![ia, ib], style))
                            .map_err(render_error)?;
                    }
                }
            }
        }
    }
    for (pts, colour, width) in &opts.polylines {
        draw_polyline(&area, f, pts, colour.stroke_width((*width).max(1)))?;
    }
    let frame_style = INSET_FRAME.stroke_width(2);
    if main {
        for inset in &opts.insets {
            let (lo, hi) = inset.view;
            let corners = [lo, DVec2::new(hi.x, lo.y), hi, DVec2::new(lo.x, hi.y), lo];
            draw_polyline(&area, f, &corners, frame_style)?;
        }
        area.draw(&Rectangle::new(
            [(0, 0), (f.w - 1, f.h - 1)],
            BLACK.stroke_width(1),
        ))
        .map_err(render_error)?;
    } else {
        area.draw(&Rectangle::new([(0, 0), (f.w - 1, f.h - 1)], frame_style))
            .map_err(render_error)?;
    }
    root.present().map_err(render_error)?;
    Ok(())
}
