//! Figures: every plot function writes a PNG of the requested size with real content, a 1e5
//! triangle mesh renders quickly, and the log-log slope fit recovers exact power laws.

use crate::app::plot::{
    fit_loglog_slope, lines_png, lines_rgb, loglog_png, loglog_rgb, mesh_png, mesh_rgb, Corner,
    Inset, LinesPlot, LogLogPlot, MeshPlot, Series, SeriesStyle,
};
use anisomesh::levelset::{extract_zero_level, nodal_distance, Zalesak};
use anisomesh::{DVec2, GridPattern, Mesh2};
use plotters::style::RGBColor;
use std::path::PathBuf;
use std::time::Instant;

fn out_dir() -> PathBuf {
    let dir = std::env::temp_dir().join("anisomesh_plot_figures");
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Checks the PNG signature and the IHDR width and height.
fn assert_png(path: &std::path::Path, w: u32, h: u32) {
    let bytes = std::fs::read(path).unwrap();
    assert!(
        bytes.len() > 1000,
        "{} is only {} bytes",
        path.display(),
        bytes.len()
    );
    assert_eq!(&bytes[..8], b"\x89PNG\r\n\x1a\n");
    assert_eq!(&bytes[12..16], b"IHDR");
    let be = |i: usize| u32::from_be_bytes(bytes[i..i + 4].try_into().unwrap());
    assert_eq!((be(16), be(20)), (w, h));
    // No temporary file of this figure is left behind (other tests write beside it).
    let prefix = format!(".{}.", path.file_name().unwrap().to_string_lossy());
    let leftovers = std::fs::read_dir(path.parent().unwrap())
        .unwrap()
        .filter(|e| {
            let name = e
                .as_ref()
                .unwrap()
                .file_name()
                .to_string_lossy()
                .into_owned();
            name.starts_with(&prefix) && name.contains(".tmp")
        })
        .count();
    assert_eq!(leftovers, 0);
}

fn zalesak_plot(n: usize) -> (Mesh2, MeshPlot) {
    let mesh = Mesh2::rectangle(
        DVec2::new(-1.0, 0.0),
        DVec2::new(1.0, 1.5),
        n,
        n,
        GridPattern::UnionJack,
    )
    .unwrap();
    let u = nodal_distance(&mesh, &Zalesak::default());
    let lines = extract_zero_level(&mesh, &u).unwrap();
    let size: Vec<f64> = (0..mesh.n_tris())
        .map(|t| mesh.tri_area(t).sqrt() * (1.0 + 10.0 * u[mesh.tris[t][0] as usize].abs()))
        .collect();
    let plot = MeshPlot {
        width: 900,
        height: 700,
        tri_colour: Some(size),
        log_colour: true,
        colour_label: "element size h".into(),
        polylines: lines
            .iter()
            .map(|l| (l.path_points(), RGBColor(230, 30, 30), 2))
            .collect(),
        insets: vec![Inset {
            view: (DVec2::new(-0.12, 0.78), DVec2::new(0.12, 0.92)),
            placement: Corner::TopRight,
        }],
        title: "Zalesak disk: size field and zero level".into(),
        ..MeshPlot::default()
    };
    (mesh, plot)
}

#[test]
fn mesh_figure_with_colour_bar_overlay_and_inset() {
    let (mesh, plot) = zalesak_plot(40);
    let img = mesh_rgb(&mesh, &plot).unwrap();
    assert_eq!((img.width, img.height), (900, 700));
    assert!(img.distinct_colours() > 50, "{}", img.distinct_colours());
    // The overlay colour is present (interface drawn) and so is the inset frame colour.
    let has = |c: [u8; 3]| img.pixels.chunks_exact(3).any(|p| p == c);
    assert!(has([230, 30, 30]));
    assert!(has([214, 39, 40]));
    let path = out_dir().join("zalesak_mesh.png");
    mesh_png(&path, &mesh, &plot).unwrap();
    assert_png(&path, 900, 700);

    // Plain mesh, no colour: a light fill and edges.
    let plain = MeshPlot {
        width: 400,
        height: 300,
        ..MeshPlot::default()
    };
    let img = mesh_rgb(&mesh, &plain).unwrap();
    assert!(img.distinct_colours() > 2);
}

#[test]
fn hundred_thousand_triangles_render_fast() {
    let (mesh, mut plot) = zalesak_plot(224); // 4 x 224² ≈ 2e5 triangles (union jack: 2 per cell)
    assert!(mesh.n_tris() >= 100_000, "{}", mesh.n_tris());
    plot.width = 1200;
    plot.height = 1000;
    let t0 = Instant::now();
    let path = out_dir().join("big_mesh.png");
    mesh_png(&path, &mesh, &plot).unwrap();
    let secs = t0.elapsed().as_secs_f64();
    eprintln!("{} triangles rendered in {secs:.2} s", mesh.n_tris());
    assert!(secs < 3.0, "{secs} s");
    assert_png(&path, 1200, 1000);
}

#[test]
fn bad_mesh_plot_options_are_errors() {
    let (mesh, mut plot) = zalesak_plot(4);
    plot.tri_colour = Some(vec![1.0; 3]);
    assert!(mesh_rgb(&mesh, &plot).is_err());
    let (mesh, mut plot) = zalesak_plot(4);
    plot.view = Some((DVec2::ONE, DVec2::ZERO));
    assert!(mesh_rgb(&mesh, &plot).is_err());
    let (mesh, mut plot) = zalesak_plot(4);
    plot.colour_range = Some((-1.0, 1.0)); // log scale needs lo > 0
    assert!(mesh_rgb(&mesh, &plot).is_err());
    let (mesh, mut plot) = zalesak_plot(4);
    plot.width = 0;
    assert!(mesh_rgb(&mesh, &plot).is_err());
}

#[test]
fn loglog_figure_and_slope_fit() {
    let power = |c: f64, p: f64| -> Vec<(f64, f64)> {
        (0..6)
            .map(|i| {
                let n = 100.0 * 2f64.powi(i);
                (n, c * n.powf(p))
            })
            .collect()
    };
    let iso = power(3.0, -0.5);
    let ani = power(50.0, -1.0);
    assert!((fit_loglog_slope(&iso) + 0.5).abs() < 1e-12);
    assert!((fit_loglog_slope(&ani) + 1.0).abs() < 1e-12);
    assert!(fit_loglog_slope(&[(1.0, 1.0)]).is_nan());
    assert!(fit_loglog_slope(&[(1.0, 1.0), (1.0, 2.0)]).is_nan());
    // Non-positive points are ignored.
    let mut with_zero = ani.clone();
    with_zero.push((0.0, 1.0));
    assert!((fit_loglog_slope(&with_zero) + 1.0).abs() < 1e-12);

    let plot = LogLogPlot {
        title: "Interface error vs vertices".into(),
        x_label: "vertices".into(),
        y_label: "Hausdorff distance".into(),
        series: vec![
            Series {
                name: "isotropic".into(),
                points: iso,
                show_fit_slope: true,
                style: SeriesStyle::LineMarkers,
            },
            Series {
                name: "anisotropic".into(),
                points: ani,
                show_fit_slope: true,
                style: SeriesStyle::Markers,
            },
        ],
        width: 800,
        height: 600,
    };
    let img = loglog_rgb(&plot).unwrap();
    assert!(img.distinct_colours() > 10);
    let path = out_dir().join("loglog.png");
    loglog_png(&path, &plot).unwrap();
    assert_png(&path, 800, 600);
    assert!(loglog_rgb(&LogLogPlot::default()).is_err());
}

#[test]
fn line_chart() {
    let t: Vec<f64> = (0..200).map(|i| i as f64 * 0.05).collect();
    let plot = LinesPlot {
        title: "Area drift".into(),
        x_label: "time".into(),
        y_label: "relative area error".into(),
        series: vec![
            Series {
                name: "no correction".into(),
                points: t.iter().map(|&t| (t, 1e-3 * t)).collect(),
                style: SeriesStyle::Line,
                ..Series::default()
            },
            Series {
                name: "mass correction".into(),
                points: t.iter().map(|&t| (t, 1e-4 * t.sin())).collect(),
                style: SeriesStyle::Line,
                ..Series::default()
            },
        ],
        width: 700,
        height: 450,
    };
    let img = lines_rgb(&plot).unwrap();
    assert!(img.distinct_colours() > 10);
    let path = out_dir().join("lines.png");
    lines_png(&path, &plot).unwrap();
    assert_png(&path, 700, 450);
}

#[test]
fn colour_scale_and_viridis() {
    use crate::app::plot::colormap::{viridis, ColourScale, INVALID_COLOUR};
    assert_eq!(viridis(0.0), RGBColor(68, 1, 84));
    assert_eq!(viridis(1.0), RGBColor(253, 231, 37));
    assert_eq!(viridis(0.5), RGBColor(33, 145, 140));
    // Perceptual ordering: luminance increases monotonically along the map.
    let lum = |c: RGBColor| 0.2126 * c.0 as f64 + 0.7152 * c.1 as f64 + 0.0722 * c.2 as f64;
    let l: Vec<f64> = (0..=100).map(|i| lum(viridis(i as f64 / 100.0))).collect();
    assert!(l.windows(2).all(|w| w[1] > w[0]));
    let s = ColourScale::fit(&[1e-3, 1e-1, f64::NAN, -1.0], true).unwrap();
    assert_eq!((s.lo, s.hi), (1e-3, 1e-1));
    assert!((s.position(1e-2).unwrap() - 0.5).abs() < 1e-12);
    assert!((s.value_at(0.5) - 1e-2).abs() < 1e-15);
    assert_eq!(s.colour(-1.0), INVALID_COLOUR);
    assert!(ColourScale::fit(&[f64::NAN], false).is_none());
    let flat = ColourScale::fit(&[2.0, 2.0], false).unwrap();
    assert!(flat.lo < 2.0 && flat.hi > 2.0);
}

/// Panels side by side: each image is copied to its offset, the rest stays white; a buffer that
/// does not match its size, or no image, is a typed error and never a panic.
#[test]
fn side_by_side_places_each_image_at_its_offset() {
    use crate::app::plot::RgbImage;
    let mut a = RgbImage::new(20, 30).unwrap();
    a.pixels.iter_mut().for_each(|p| *p = 10);
    let mut b = RgbImage::new(40, 16).unwrap();
    b.pixels.iter_mut().for_each(|p| *p = 200);
    let img = RgbImage::side_by_side(&[a.clone(), b.clone()]).unwrap();
    assert_eq!((img.width, img.height), (60, 30));
    assert_eq!(img.pixel(19, 29), [10; 3]);
    assert_eq!(img.pixel(20, 0), [200; 3]);
    assert_eq!(img.pixel(59, 15), [200; 3]);
    assert_eq!(img.pixel(59, 16), [255; 3]);
    assert!(RgbImage::side_by_side(&[]).is_err());
    let mut broken = b;
    broken.pixels.pop();
    assert!(RgbImage::side_by_side(&[a, broken]).is_err());
}
