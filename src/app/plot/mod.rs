//! Figures drawn with plotters into PNG files: meshes coloured per triangle with overlays and
//! zoomed insets ([`mesh_png`]), log-log convergence plots with fitted slopes ([`loglog_png`]) and
//! plain line charts ([`lines_png`]).
//!
//! Every figure is first rendered into an in-memory [`RgbImage`] (`*_rgb` functions, useful for
//! tests and embedding) and then encoded as PNG in memory and written atomically
//! ([`anisomesh::io::atomic_write`]). Text uses DejaVu Sans, shipped in `assets/` and registered
//! with plotters once, so no system font is needed.

mod charts;
pub mod colormap;
mod mesh;
pub mod surface;

pub use charts::{
    fit_loglog_slope, lines_png, lines_rgb, loglog_png, loglog_rgb, LinesPlot, LogLogPlot, Series,
    SeriesStyle,
};
pub use mesh::{mesh_png, mesh_rgb, Corner, Inset, MeshPlot};
/// The colour type of overlay curves (plotters' 8-bit RGB).
pub use plotters::style::RGBColor;

use anisomesh::error::{Error, Result};
use anisomesh::io::atomic_write;
use image::codecs::png::PngEncoder;
use image::{ColorType, ImageEncoder};
use plotters::prelude::*;
use std::path::Path;
use std::sync::OnceLock;

/// The font family name under which the shipped font is registered.
pub(crate) const FONT: &str = "sans-serif";

static FONT_BYTES: &[u8] = include_bytes!("../../../assets/DejaVuSans.ttf");

/// Registers the shipped font with plotters (once per process).
pub(crate) fn ensure_font() -> Result<()> {
    static REGISTERED: OnceLock<std::result::Result<(), String>> = OnceLock::new();
    REGISTERED
        .get_or_init(|| {
            plotters::style::register_font(FONT, FontStyle::Normal, FONT_BYTES)
                .map_err(|_| "the shipped font assets/DejaVuSans.ttf is invalid".to_string())
        })
        .clone()
        .map_err(Error::InvalidInput)
}

/// An 8-bit RGB image, rows top to bottom.
#[derive(Debug, Clone, PartialEq)]
pub struct RgbImage {
    pub width: u32,
    pub height: u32,
    /// `3 * width * height` bytes.
    pub pixels: Vec<u8>,
}

impl RgbImage {
    /// A white image.
    pub fn new(width: u32, height: u32) -> Result<RgbImage> {
        if width < 16 || height < 16 || width > 16384 || height > 16384 {
            return Err(Error::InvalidInput(format!(
                "image size {width} x {height}: each side must be in 16..=16384 pixels"
            )));
        }
        Ok(RgbImage {
            width,
            height,
            pixels: vec![255; 3 * width as usize * height as usize],
        })
    }

    #[cfg(test)]
    /// The pixel at `(x, y)` (`(0, 0)` is the top-left corner).
    pub fn pixel(&self, x: u32, y: u32) -> [u8; 3] {
        let i = 3 * (y as usize * self.width as usize + x as usize);
        [self.pixels[i], self.pixels[i + 1], self.pixels[i + 2]]
    }

    #[cfg(test)]
    /// Number of distinct colours.
    pub fn distinct_colours(&self) -> usize {
        let mut set: Vec<u32> = self
            .pixels
            .chunks_exact(3)
            .map(|c| (c[0] as u32) << 16 | (c[1] as u32) << 8 | c[2] as u32)
            .collect();
        set.sort_unstable();
        set.dedup();
        set.len()
    }

    /// Checks that the pixel buffer holds `3 width height` bytes.
    fn check_buffer(&self) -> Result<()> {
        let expected = 3 * self.width as usize * self.height as usize;
        if self.pixels.len() == expected {
            return Ok(());
        }
        Err(Error::InvalidInput(format!(
            "image of {} x {} pixels holds {} bytes, not {expected}",
            self.width,
            self.height,
            self.pixels.len()
        )))
    }

    /// The images side by side, top-aligned, on a white background as high as the highest.
    /// Errors: no image, an image whose pixel buffer does not hold `3 width height` bytes, or a
    /// result outside the size limits of [`RgbImage::new`].
    pub fn side_by_side(images: &[RgbImage]) -> Result<RgbImage> {
        for p in images {
            p.check_buffer()?;
        }
        let width = images
            .iter()
            .try_fold(0u32, |w, p| w.checked_add(p.width))
            .unwrap_or(u32::MAX);
        let height = images.iter().map(|p| p.height).max().unwrap_or(0);
        let mut img = RgbImage::new(width, height)?;
        let w = img.width as usize;
        let mut x0 = 0usize;
        for src in images {
            let sw = src.width as usize;
            for y in 0..src.height as usize {
                let s = &src.pixels[3 * y * sw..3 * (y + 1) * sw];
                img.pixels[3 * (y * w + x0)..3 * (y * w + x0 + sw)].copy_from_slice(s);
            }
            x0 += sw;
        }
        Ok(img)
    }

    /// Encodes the image as PNG in memory and writes it to `path` atomically
    /// ([`anisomesh::io::atomic_write`]: readers never see a partial file). Errors: a pixel
    /// buffer that does not hold `3 width height` bytes, an encoder or an I/O failure.
    pub fn save_png(&self, path: &Path) -> Result<()> {
        self.check_buffer()?;
        let mut png = Vec::new();
        PngEncoder::new(&mut png)
            .write_image(&self.pixels, self.width, self.height, ColorType::Rgb8)
            .map_err(|e| drawing_error(path, e))?;
        atomic_write(path, |w| w.write_all(&png))
    }
}

fn drawing_error(path: &Path, e: impl std::fmt::Display) -> Error {
    Error::io(path, std::io::Error::other(e.to_string()))
}

/// A rendering error (in memory): a font or layout problem.
pub(crate) fn render_error(e: impl std::fmt::Display) -> Error {
    Error::InvalidInput(format!("plot rendering failed: {e}"))
}

/// Tick label: plain numbers in `[1e-3, 1e4)` with at most 4 decimals, otherwise `1e-5` style.
pub(crate) fn tick(v: f64) -> String {
    let a = v.abs();
    if a == 0.0 {
        "0".into()
    } else if (1e-3..1e4).contains(&a) {
        let s = format!("{v:.4}");
        s.trim_end_matches('0').trim_end_matches('.').to_string()
    } else {
        format!("{v:.1e}").replace(".0e", "e")
    }
}
