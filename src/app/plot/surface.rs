//! Shaded pictures of 3D surfaces and of plane cuts through tetrahedral meshes, drawn by a small
//! software rasteriser ([`raster`]): z-buffer, 3 × 3 supersampling, smooth (area-weighted
//! vertex normal) shading with ambient, Lambert and a weak highlight, optional per-vertex
//! scalars coloured with viridis (one scale shared by all panels, with a colour bar), optional
//! wireframe of the visible edges, orthographic or perspective camera.
//!
//! [`render_surfaces`] draws several surfaces side by side (frames of a flow), all framed by
//! the same camera so that sizes compare; [`render_tet_cut`] draws the intersection polygons of
//! the tetrahedra cut by a plane, each coloured by a per-tetrahedron value.

mod raster;

use self::raster::{Camera, Canvas, Tri, SS};
use super::colormap::{viridis, ColourScale};
use super::{ensure_font, render_error, tick, RgbImage, FONT};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec3;
use anisomesh::levelset::TriangleSurface;
use anisomesh::mesh3::Mesh3;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// Camera and style of a surface picture.
#[derive(Debug, Clone, PartialEq)]
pub struct View {
    /// Direction from the scene's centre towards the eye.
    pub direction: DVec3,
    /// The direction that appears upwards.
    pub up: DVec3,
    /// Perspective projection (30° field of view) instead of orthographic.
    pub perspective: bool,
    /// Side of each (square) panel in pixels.
    pub size: u32,
    /// Draw the visible triangle edges.
    pub wireframe: bool,
    /// Label of the colour bar (when scalars are drawn).
    pub colour_label: String,
}

impl Default for View {
    /// Orthographic, from the front right and above, `z` up, 800 pixels, no wireframe.
    fn default() -> View {
        View {
            direction: DVec3::new(1.0, -1.3, 0.9),
            up: DVec3::Z,
            perspective: false,
            size: 800,
            wireframe: false,
            colour_label: String::new(),
        }
    }
}

impl View {
    /// A head-on view along `normal` (for plane cuts), with `z` (or `y` when `normal` is
    /// vertical) up.
    pub fn facing(normal: DVec3) -> View {
        let n = normal.normalize_or(DVec3::Z);
        let up = if n.z.abs() > 0.9 { DVec3::Y } else { DVec3::Z };
        View {
            direction: n,
            up,
            ..View::default()
        }
    }
}

/// One panel: a surface, optional per-vertex scalars and a title.
#[derive(Debug, Clone)]
pub struct SurfacePanel<'a> {
    /// The surface (outward-oriented triangles give outward normals; both sides are lit).
    pub surface: &'a TriangleSurface,
    /// One value per vertex, coloured with viridis; `None`: a plain colour.
    pub scalars: Option<&'a [f64]>,
    /// Title above the panel (may be empty).
    pub title: String,
}

/// A plane `{x : (x − point) · normal = 0}`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct CutPlane {
    /// A point of the plane.
    pub point: DVec3,
    /// Its normal (any length but zero).
    pub normal: DVec3,
}

/// The plain surface colour (a light steel blue).
const PLAIN: [f32; 3] = [0.62, 0.73, 0.88];
/// Height reserved for a panel title.
const TITLE_H: u32 = 40;
/// Width of the colour bar.
const BAR_W: u32 = 130;

/// Smooth normals: the sum of the (area-weighted) normals of the incident triangles.
fn vertex_normals(s: &TriangleSurface) -> Vec<DVec3> {
    let mut n = vec![DVec3::ZERO; s.points.len()];
    for t in &s.triangles {
        let [a, b, c] = t.map(|v| s.points[v as usize]);
        let f = (b - a).cross(c - a);
        for &v in t {
            n[v as usize] += f;
        }
    }
    n.iter().map(|v| v.normalize_or_zero()).collect()
}

fn rgb(c: RGBColor) -> [f32; 3] {
    [c.0, c.1, c.2].map(|v| v as f32 / 255.0)
}

/// Checks the panels and returns a bounding sphere of all their vertices (centred at the
/// centre of their bounding box).
fn check_panels(panels: &[SurfacePanel]) -> Result<(DVec3, f64)> {
    if panels.is_empty() {
        return Err(Error::InvalidInput("no surface to draw".into()));
    }
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for (i, p) in panels.iter().enumerate() {
        let s = p.surface;
        if let Some(t) = s
            .triangles
            .iter()
            .position(|t| t.iter().any(|&v| v as usize >= s.points.len()))
        {
            return Err(Error::InvalidInput(format!(
                "surface {i}: triangle {t} refers to a missing vertex"
            )));
        }
        if let Some(v) = p.scalars {
            if v.len() != s.points.len() {
                return Err(Error::InvalidInput(format!(
                    "surface {i}: {} scalars for {} vertices",
                    v.len(),
                    s.points.len()
                )));
            }
        }
        for &q in &s.points {
            if q.is_finite() {
                lo = lo.min(q);
                hi = hi.max(q);
            }
        }
    }
    if lo.x > hi.x {
        return Err(Error::InvalidInput(
            "the surfaces have no finite vertex".into(),
        ));
    }
    let centre = 0.5 * (lo + hi);
    let radius = panels
        .iter()
        .flat_map(|p| p.surface.points.iter())
        .filter(|q| q.is_finite())
        .map(|&q| (q - centre).length())
        .fold(0.0, f64::max);
    Ok((centre, radius))
}

/// Rasterises the triangles into a `size × size` panel with `title`.
fn draw_panel(tris: &[Tri], cam: &Camera, view: &View, title: &str) -> Result<RgbImage> {
    let side = view.size as usize * SS;
    let mut canvas = Canvas::new(side, side);
    let line = 0.6 * SS as f64 * (view.size as f64 / 800.0).max(1.0);
    for t in tris {
        canvas.draw(cam, t, line);
    }
    let (w, h, pixels) = canvas.downsample();
    let mut img = RgbImage::new(w as u32, h as u32)?;
    img.pixels = pixels;
    if !title.is_empty() {
        let root =
            BitMapBackend::with_buffer(&mut img.pixels, (w as u32, h as u32)).into_drawing_area();
        let style = TextStyle::from((FONT, 24).into_font()).pos(Pos::new(HPos::Center, VPos::Top));
        root.draw(&Text::new(title.to_string(), (w as i32 / 2, 10), style))
            .map_err(render_error)?;
        root.present().map_err(render_error)?;
    }
    Ok(img)
}

/// A vertical colour bar for `scale`, `height` pixels high, labelled `label`.
fn colour_bar(scale: ColourScale, height: u32, label: &str) -> Result<RgbImage> {
    let mut img = RgbImage::new(BAR_W, height)?;
    let (y0, y1) = (TITLE_H as i32 + 30, height as i32 - 60);
    let (x0, x1) = (14, 40);
    {
        let root = BitMapBackend::with_buffer(&mut img.pixels, (BAR_W, height)).into_drawing_area();
        let h = (y1 - y0).max(1);
        for j in 0..h {
            let t = 1.0 - (j as f64 + 0.5) / h as f64;
            root.draw(&PathElement::new(
                vec![(x0, y0 + j), (x1, y0 + j)],
                viridis(t).stroke_width(1),
            ))
            .map_err(render_error)?;
        }
        root.draw(&Rectangle::new([(x0, y0), (x1, y1)], BLACK.stroke_width(1)))
            .map_err(render_error)?;
        let style = TextStyle::from((FONT, 15).into_font()).pos(Pos::new(HPos::Left, VPos::Center));
        for k in 0..=4 {
            let t = k as f64 / 4.0;
            let v = scale.lo + t * (scale.hi - scale.lo);
            let y = y1 - (t * h as f64).round() as i32;
            root.draw(&PathElement::new(
                vec![(x1, y), (x1 + 5, y)],
                BLACK.stroke_width(1),
            ))
            .map_err(render_error)?;
            root.draw(&Text::new(tick(v), (x1 + 8, y), style.clone()))
                .map_err(render_error)?;
        }
        if !label.is_empty() {
            let style =
                TextStyle::from((FONT, 16).into_font()).pos(Pos::new(HPos::Left, VPos::Top));
            root.draw(&Text::new(label.to_string(), (6, TITLE_H as i32), style))
                .map_err(render_error)?;
        }
        root.present().map_err(render_error)?;
    }
    Ok(img)
}

/// Renders the panels side by side into memory (see [`render_surfaces`]).
pub fn render_surfaces_rgb(panels: &[SurfacePanel], view: &View) -> Result<RgbImage> {
    ensure_font()?;
    let (centre, radius) = check_panels(panels)?;
    let all: Vec<f64> = panels
        .iter()
        .filter_map(|p| p.scalars)
        .flatten()
        .copied()
        .collect();
    let scale = ColourScale::fit(&all, false);
    let side = view.size as usize * SS;
    let cam = Camera::new(
        centre,
        radius,
        view.direction,
        view.up,
        view.perspective,
        (side, side),
        0.9 * (1.0 - TITLE_H as f64 / view.size as f64),
        0.5 * (TITLE_H as usize * SS) as f64,
    );
    let edges = if view.wireframe { 0b111 } else { 0 };
    let mut images = Vec::with_capacity(panels.len() + 1);
    for p in panels {
        let s = p.surface;
        let normals = vertex_normals(s);
        let colour = |v: usize| match (p.scalars, scale) {
            (Some(x), Some(sc)) => rgb(sc.colour(x[v])),
            _ => PLAIN,
        };
        let tris: Vec<Tri> = s
            .triangles
            .iter()
            .map(|t| {
                let i = t.map(|v| v as usize);
                Tri {
                    p: i.map(|v| s.points[v]),
                    n: i.map(|v| normals[v]),
                    c: i.map(colour),
                    edges,
                }
            })
            .collect();
        images.push(draw_panel(&tris, &cam, view, &p.title)?);
    }
    if let (Some(sc), true) = (scale, panels.iter().any(|p| p.scalars.is_some())) {
        images.push(colour_bar(sc, view.size, &view.colour_label)?);
    }
    RgbImage::side_by_side(&images)
}

/// Renders surfaces side by side, all seen by the same camera (framing the bounding sphere of
/// all of them), and writes a PNG atomically. Errors: no panel, scalars not one per vertex, a
/// triangle referring to a missing vertex, no finite vertex, an image size out of range, I/O.
pub fn render_surfaces(path: &Path, panels: &[SurfacePanel], view: &View) -> Result<()> {
    render_surfaces_rgb(panels, view)?.save_png(path)
}

/// The polygon where `plane` cuts the tetrahedron (3 or 4 points in order), if it does.
fn cut_polygon(p: [DVec3; 4], plane: &CutPlane) -> Option<Vec<DVec3>> {
    let s = p.map(|q| (q - plane.point).dot(plane.normal));
    let neg: Vec<usize> = (0..4).filter(|&i| s[i] < 0.0).collect();
    let pos: Vec<usize> = (0..4).filter(|&i| s[i] >= 0.0).collect();
    let cut = |a: usize, b: usize| p[a] + s[a] / (s[a] - s[b]) * (p[b] - p[a]);
    match (neg.len(), pos.len()) {
        (1, 3) => Some(pos.iter().map(|&o| cut(neg[0], o)).collect()),
        (3, 1) => Some(neg.iter().map(|&i| cut(i, pos[0])).collect()),
        (2, 2) => Some(vec![
            cut(neg[0], pos[0]),
            cut(neg[0], pos[1]),
            cut(neg[1], pos[1]),
            cut(neg[1], pos[0]),
        ]),
        _ => None,
    }
}

/// Renders the cut of `mesh` by `plane` into memory (see [`render_tet_cut`]).
pub fn render_tet_cut_rgb(
    mesh: &Mesh3,
    plane: &CutPlane,
    values: &[f64],
    title: &str,
    view: &View,
) -> Result<RgbImage> {
    ensure_font()?;
    if values.len() != mesh.tets.len() {
        return Err(Error::InvalidInput(format!(
            "{} values for {} tetrahedra",
            values.len(),
            mesh.tets.len()
        )));
    }
    let len = plane.normal.length();
    if !len.is_finite() || len == 0.0 || !plane.point.is_finite() {
        return Err(Error::InvalidInput(
            "the cut plane needs a non-zero normal".into(),
        ));
    }
    let scale = ColourScale::fit(values, false)
        .ok_or_else(|| Error::InvalidInput("no finite value to colour the cut".into()))?;
    let n = plane.normal.normalize();
    let mut tris = Vec::new();
    for (t, &value) in values.iter().enumerate() {
        let Some(poly) = cut_polygon(mesh.tet_points(t), plane) else {
            continue;
        };
        let c = rgb(scale.colour(value));
        // A quadrilateral is split along (0, 2), whose edge gets no line.
        let (first, second) = if poly.len() == 4 {
            (0b011, 0b110)
        } else {
            (0b111, 0)
        };
        tris.push(Tri {
            p: [poly[0], poly[1], poly[2]],
            n: [n; 3],
            c: [c; 3],
            edges: if view.wireframe { first } else { 0 },
        });
        if poly.len() == 4 {
            tris.push(Tri {
                p: [poly[0], poly[2], poly[3]],
                n: [n; 3],
                c: [c; 3],
                edges: if view.wireframe { second } else { 0 },
            });
        }
    }
    if tris.is_empty() {
        return Err(Error::InvalidInput(
            "the plane does not cut the mesh".into(),
        ));
    }
    let (mut lo, mut hi) = (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY));
    for q in tris.iter().flat_map(|t| t.p) {
        lo = lo.min(q);
        hi = hi.max(q);
    }
    let side = view.size as usize * SS;
    let cam = Camera::new(
        0.5 * (lo + hi),
        0.5 * (hi - lo).length(),
        view.direction,
        view.up,
        view.perspective,
        (side, side),
        0.9 * (1.0 - TITLE_H as f64 / view.size as f64),
        0.5 * (TITLE_H as usize * SS) as f64,
    );
    let panel = draw_panel(&tris, &cam, view, title)?;
    let bar = colour_bar(scale, view.size, &view.colour_label)?;
    RgbImage::side_by_side(&[panel, bar])
}

/// Renders the intersection polygons of the tetrahedra of `mesh` cut by `plane`, each coloured
/// by its tetrahedron's entry of `values` (e.g. the quality of an adapted mesh) with a colour
/// bar, wireframe edges when `view.wireframe` ([`View::facing`] gives a head-on view), and
/// writes a PNG atomically. Errors: `values` not one per tetrahedron, a zero normal, a plane
/// missing the mesh, no finite value, an image size out of range, I/O.
pub fn render_tet_cut(
    path: &Path,
    mesh: &Mesh3,
    plane: &CutPlane,
    values: &[f64],
    title: &str,
    view: &View,
) -> Result<()> {
    render_tet_cut_rgb(mesh, plane, values, title, view)?.save_png(path)
}
