//! Log-log convergence plots with least-squares slopes, and plain x-y line charts.

use super::{ensure_font, render_error, tick, RgbImage, FONT};
use anisomesh::error::{Error, Result};
use plotters::prelude::*;
use std::path::Path;

/// How a series is drawn.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum SeriesStyle {
    Line,
    Markers,
    #[default]
    LineMarkers,
}

/// One data series.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Series {
    pub name: String,
    pub points: Vec<(f64, f64)>,
    /// Append the least-squares log-log slope to the legend entry ("name (slope -1.02)").
    pub show_fit_slope: bool,
    pub style: SeriesStyle,
}

/// A log-log chart (axes in decades, legend with fitted slopes).
#[derive(Debug, Clone, PartialEq)]
pub struct LogLogPlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub width: u32,
    pub height: u32,
}

impl Default for LogLogPlot {
    fn default() -> Self {
        LogLogPlot {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            series: Vec::new(),
            width: 900,
            height: 650,
        }
    }
}

/// A linear x-y chart with a legend (time series).
#[derive(Debug, Clone, PartialEq)]
pub struct LinesPlot {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub series: Vec<Series>,
    pub width: u32,
    pub height: u32,
}

impl Default for LinesPlot {
    fn default() -> Self {
        LinesPlot {
            title: String::new(),
            x_label: String::new(),
            y_label: String::new(),
            series: Vec::new(),
            width: 900,
            height: 600,
        }
    }
}

/// The tab10 palette.
const PALETTE: [RGBColor; 10] = [
    RGBColor(31, 119, 180),
    RGBColor(255, 127, 14),
    RGBColor(44, 160, 44),
    RGBColor(214, 39, 40),
    RGBColor(148, 103, 189),
    RGBColor(140, 86, 75),
    RGBColor(227, 119, 194),
    RGBColor(127, 127, 127),
    RGBColor(188, 189, 34),
    RGBColor(23, 190, 207),
];

/// Least-squares slope of `log y` against `log x` over the points with finite positive
/// coordinates: the measured convergence order of a power law `y = C x^p` (exactly `p` for exact
/// data). NaN with fewer than two such points or when all their `x` are equal.
pub fn fit_loglog_slope(points: &[(f64, f64)]) -> f64 {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(x, y)| x.is_finite() && y.is_finite() && *x > 0.0 && *y > 0.0)
        .map(|(x, y)| (x.ln(), y.ln()))
        .collect();
    if logs.len() < 2 {
        return f64::NAN;
    }
    let n = logs.len() as f64;
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / n;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / n;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx) * (p.0 - mx)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    if sxx == 0.0 {
        f64::NAN
    } else {
        sxy / sxx
    }
}

fn legend_name(s: &Series) -> String {
    if s.show_fit_slope {
        let p = fit_loglog_slope(&s.points);
        if p.is_finite() {
            return format!("{} (slope {p:.2})", s.name);
        }
    }
    s.name.clone()
}

/// The legend corner with the fewest data points nearby (in normalised axis coordinates).
fn legend_corner(norm: &[(f64, f64)]) -> SeriesLabelPosition {
    let corners = [
        (SeriesLabelPosition::UpperRight, 1.0, 1.0),
        (SeriesLabelPosition::UpperLeft, 0.0, 1.0),
        (SeriesLabelPosition::LowerLeft, 0.0, 0.0),
        (SeriesLabelPosition::LowerRight, 1.0, 0.0),
    ];
    let count = |cx: f64, cy: f64| {
        norm.iter()
            .filter(|(x, y)| (x - cx).abs() < 0.45 && (y - cy).abs() < 0.4)
            .count()
    };
    let mut best = 0;
    for i in 1..corners.len() {
        if count(corners[i].1, corners[i].2) < count(corners[best].1, corners[best].2) {
            best = i;
        }
    }
    corners[best].0.clone()
}

/// Draws the series, legend and axes on an already built chart. A macro because log and linear
/// charts have different coordinate types.
macro_rules! draw_chart {
    ($root:expr, $plot:expr, $xr:expr, $yr:expr, $corner:expr, $valid:expr, $grid:expr) => {{
        let plot = $plot;
        let mut chart = ChartBuilder::on(&$root)
            .caption(&plot.title, (FONT, 22))
            .margin(16)
            .x_label_area_size(48)
            .y_label_area_size(78)
            .build_cartesian_2d($xr, $yr)
            .map_err(render_error)?;
        let mut mesh = chart.configure_mesh();
        mesh.x_desc(plot.x_label.as_str())
            .y_desc(plot.y_label.as_str())
            .label_style((FONT, 14))
            .axis_desc_style((FONT, 16))
            .x_label_formatter(&|v| tick(*v))
            .y_label_formatter(&|v| tick(*v))
            .x_labels(12)
            .y_labels(12)
            .max_light_lines(4)
            .light_line_style(RGBColor(235, 235, 235))
            .bold_line_style(RGBColor(205, 205, 205));
        if !$grid {
            mesh.disable_mesh();
        }
        mesh.draw().map_err(render_error)?;
        for (k, s) in plot.series.iter().enumerate() {
            let colour = PALETTE[k % PALETTE.len()];
            let pts: Vec<(f64, f64)> = s.points.iter().copied().filter($valid).collect();
            if pts.is_empty() {
                continue;
            }
            let line = colour.stroke_width(2);
            let name = legend_name(s);
            let with_line = s.style != SeriesStyle::Markers;
            let with_markers = s.style != SeriesStyle::Line;
            if with_line {
                let ann = chart
                    .draw_series(LineSeries::new(pts.clone(), line))
                    .map_err(render_error)?;
                ann.label(name.clone())
                    .legend(move |(x, y)| PathElement::new(vec![(x, y), (x + 22, y)], line));
            }
            if with_markers {
                let ann = chart
                    .draw_series(pts.iter().map(|&p| Circle::new(p, 4, colour.filled())))
                    .map_err(render_error)?;
                if !with_line {
                    ann.label(name.clone())
                        .legend(move |(x, y)| Circle::new((x + 11, y), 4, colour.filled()));
                }
            }
        }
        chart
            .configure_series_labels()
            .position($corner)
            .margin(12)
            .label_font((FONT, 15))
            .background_style(WHITE.mix(0.9))
            .border_style(BLACK)
            .draw()
            .map_err(render_error)?;
    }};
}

/// Renders a log-log chart into memory. Non-positive or non-finite points are skipped.
pub fn loglog_rgb(plot: &LogLogPlot) -> Result<RgbImage> {
    ensure_font()?;
    let valid = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite() && p.0 > 0.0 && p.1 > 0.0;
    let all: Vec<(f64, f64)> = plot
        .series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(valid)
        .collect();
    if all.is_empty() {
        return Err(Error::InvalidInput(format!(
            "log-log plot '{}': no point with positive finite coordinates",
            plot.title
        )));
    }
    // Whole decades around the data.
    let decades = |lo: f64, hi: f64| {
        let (a, mut b) = (lo.log10().floor(), hi.log10().ceil());
        if b <= a {
            b = a + 1.0;
        }
        // Slightly widened so that the end decades are inside the range despite round-off.
        (
            10f64.powi(a as i32) * (1.0 - 1e-9),
            10f64.powi(b as i32) * (1.0 + 1e-9),
        )
    };
    let (x0, x1) = decades(
        all.iter().map(|p| p.0).fold(f64::INFINITY, f64::min),
        all.iter().map(|p| p.0).fold(0.0, f64::max),
    );
    let (y0, y1) = decades(
        all.iter().map(|p| p.1).fold(f64::INFINITY, f64::min),
        all.iter().map(|p| p.1).fold(0.0, f64::max),
    );
    let norm: Vec<(f64, f64)> = all
        .iter()
        .map(|p| {
            (
                (p.0 / x0).ln() / (x1 / x0).ln(),
                (p.1 / y0).ln() / (y1 / y0).ln(),
            )
        })
        .collect();
    let mut img = RgbImage::new(plot.width, plot.height)?;
    {
        let root = BitMapBackend::with_buffer(&mut img.pixels, (plot.width, plot.height))
            .into_drawing_area();
        root.fill(&WHITE).map_err(render_error)?;
        draw_chart!(
            root,
            plot,
            (x0..x1).log_scale(),
            (y0..y1).log_scale(),
            legend_corner(&norm),
            valid,
            true
        );
        root.present().map_err(render_error)?;
    }
    Ok(img)
}

/// Renders a log-log chart (see [`LogLogPlot`]) into a PNG file (atomically).
pub fn loglog_png(path: &Path, plot: &LogLogPlot) -> Result<()> {
    loglog_rgb(plot)?.save_png(path)
}

/// Renders a linear x-y chart into memory. Non-finite points are skipped.
pub fn lines_rgb(plot: &LinesPlot) -> Result<RgbImage> {
    ensure_font()?;
    let valid = |p: &(f64, f64)| p.0.is_finite() && p.1.is_finite();
    let all: Vec<(f64, f64)> = plot
        .series
        .iter()
        .flat_map(|s| s.points.iter().copied())
        .filter(valid)
        .collect();
    if all.is_empty() {
        return Err(Error::InvalidInput(format!(
            "line chart '{}': no point with finite coordinates",
            plot.title
        )));
    }
    let padded = |lo: f64, hi: f64| {
        let d = if hi > lo {
            0.05 * (hi - lo)
        } else {
            0.5 * lo.abs().max(1.0)
        };
        (lo - d, hi + d)
    };
    let (x0, x1) = padded(
        all.iter().map(|p| p.0).fold(f64::INFINITY, f64::min),
        all.iter().map(|p| p.0).fold(f64::NEG_INFINITY, f64::max),
    );
    let (y0, y1) = padded(
        all.iter().map(|p| p.1).fold(f64::INFINITY, f64::min),
        all.iter().map(|p| p.1).fold(f64::NEG_INFINITY, f64::max),
    );
    let norm: Vec<(f64, f64)> = all
        .iter()
        .map(|p| ((p.0 - x0) / (x1 - x0), (p.1 - y0) / (y1 - y0)))
        .collect();
    let mut img = RgbImage::new(plot.width, plot.height)?;
    {
        let root = BitMapBackend::with_buffer(&mut img.pixels, (plot.width, plot.height))
            .into_drawing_area();
        root.fill(&WHITE).map_err(render_error)?;
        draw_chart!(
            root,
            plot,
            x0..x1,
            y0..y1,
            legend_corner(&norm),
            valid,
            true
        );
        root.present().map_err(render_error)?;
    }
    Ok(img)
}

/// Renders a linear x-y chart (see [`LinesPlot`]) into a PNG file (atomically).
pub fn lines_png(path: &Path, plot: &LinesPlot) -> Result<()> {
    lines_rgb(plot)?.save_png(path)
}
