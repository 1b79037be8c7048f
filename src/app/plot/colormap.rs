//! A perceptually uniform colormap (viridis) and the value → colour scale of mesh plots.

use plotters::style::RGBColor;

/// matplotlib's viridis sampled at 11 equally spaced points (`#440154` ... `#fde725`); linear
/// interpolation between them stays within a couple of units of the full 256-entry table.
const VIRIDIS: [[u8; 3]; 11] = [
    [68, 1, 84],
    [72, 36, 117],
    [65, 68, 135],
    [53, 95, 141],
    [42, 120, 142],
    [33, 145, 140],
    [34, 168, 132],
    [68, 191, 112],
    [122, 209, 81],
    [189, 223, 38],
    [253, 231, 37],
];

/// The viridis colour at `t` in `[0, 1]` (clamped; NaN gives the low end).
pub fn viridis(t: f64) -> RGBColor {
    let t = if t.is_nan() { 0.0 } else { t.clamp(0.0, 1.0) };
    let s = t * (VIRIDIS.len() - 1) as f64;
    let i = (s.floor() as usize).min(VIRIDIS.len() - 2);
    let f = s - i as f64;
    let mix = |k: usize| {
        let (a, b) = (VIRIDIS[i][k] as f64, VIRIDIS[i + 1][k] as f64);
        (a + f * (b - a)).round() as u8
    };
    RGBColor(mix(0), mix(1), mix(2))
}

/// Maps values to `[0, 1]` linearly or logarithmically between `lo` and `hi`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ColourScale {
    pub lo: f64,
    pub hi: f64,
    pub log: bool,
}

/// Colour of values the scale cannot place (NaN, or non-positive on a log scale).
pub const INVALID_COLOUR: RGBColor = RGBColor(190, 190, 190);

impl ColourScale {
    /// The scale spanning the finite (and, for `log`, positive) values, widened when degenerate.
    /// `None` when no value qualifies.
    pub fn fit(values: &[f64], log: bool) -> Option<ColourScale> {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for &v in values {
            if v.is_finite() && (!log || v > 0.0) {
                lo = lo.min(v);
                hi = hi.max(v);
            }
        }
        if lo > hi {
            return None;
        }
        Some(ColourScale { lo, hi, log }.widened())
    }

    /// Widens an empty range (`lo == hi`) so that it can be drawn.
    pub fn widened(mut self) -> ColourScale {
        if self.hi <= self.lo {
            if self.log {
                self.lo /= 2.0;
                self.hi = self.lo * 4.0;
            } else {
                let d = self.lo.abs().max(1.0) * 0.5;
                self.hi = self.lo + d;
                self.lo -= d;
            }
        }
        self
    }

    /// Position of `v` in `[0, 1]` (clamped), or `None` if `v` cannot be placed.
    pub fn position(&self, v: f64) -> Option<f64> {
        if !v.is_finite() || (self.log && v <= 0.0) {
            return None;
        }
        let t = if self.log {
            (v.ln() - self.lo.ln()) / (self.hi.ln() - self.lo.ln())
        } else {
            (v - self.lo) / (self.hi - self.lo)
        };
        Some(t.clamp(0.0, 1.0))
    }

    #[cfg(test)]
    /// The value at position `t` in `[0, 1]`.
    pub fn value_at(&self, t: f64) -> f64 {
        if self.log {
            (self.lo.ln() + t * (self.hi.ln() - self.lo.ln())).exp()
        } else {
            self.lo + t * (self.hi - self.lo)
        }
    }

    /// The colour of `v`.
    pub fn colour(&self, v: f64) -> RGBColor {
        self.position(v).map_or(INVALID_COLOUR, viridis)
    }
}
