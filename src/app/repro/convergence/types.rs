//! The shared types of the convergence sweep: its options, one measured mesh ([`ConvergenceRow`]),
//! the fitted slopes, the anisotropy gain and the report with its plain-text table. Nothing here
//! imports from the sibling modules.

use std::path::PathBuf;

use serde::Serialize;

use crate::app::repro::peers::PeerResult;

/// Options of [`super::run`] (the CLI `anisomesh convergence --shape ...` maps onto these).
#[derive(Debug, Clone, Serialize)]
pub struct ConvergenceOptions {
    /// `zalesak`, `circle` or `flower` ([`anisomesh::levelset::shape_by_name`]).
    pub shape: String,
    /// Where `convergence_<shape>.csv` and `convergence_<shape>.png` are written; nothing is
    /// written when `None`.
    pub out_dir: Option<PathBuf>,
    /// Sweep points per family (at least 2).
    pub points: usize,
    /// A tiny sweep (coarse `ε` and grids, seconds): for tests and smoke runs.
    pub quick: bool,
    /// Resolve the kinks of the distance at the scale `k hmin` in the metric of the adapted
    /// families ([`anisomesh::adapt::ShapeAdaptOptions::kink_scale`]); default `None` (the
    /// pointwise Hessian, as `anisomesh adapt`: on the Zalesak disk `Some(1.0)` changed the
    /// corner errors only within their scatter).
    pub kink_scale: Option<f64>,
    /// Half-width of the band where eq. (6) applies, in units of `h_min`; `None` (default): the
    /// `anisomesh adapt` band `5 ε` (`0.5 h_min` at `ε = 1e-4`).
    pub band_hmin: Option<f64>,
    /// Growth rate of the sizes outside the band; `None` (default): the `anisomesh adapt` rate 1.
    pub grade: Option<f64>,
    /// On the Zalesak disk, also run the installed peers ([`super::sweep::PEER_KINDS`]) on the
    /// anisotropic family's metric at every `ε` of the sweep (skipped with a printed note when a
    /// peer is not on `PATH`).
    pub peers: bool,
}

impl Default for ConvergenceOptions {
    fn default() -> Self {
        ConvergenceOptions {
            shape: "zalesak".into(),
            out_dir: None,
            points: 5,
            quick: false,
            kink_scale: None,
            band_hmin: None,
            grade: None,
            peers: true,
        }
    }
}

/// A mesh family of the sweep.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Family {
    Anisotropic,
    Isotropic,
    Uniform,
}

impl Family {
    /// Lower-case name (CSV column, legend).
    pub fn name(self) -> &'static str {
        match self {
            Family::Anisotropic => "anisotropic",
            Family::Isotropic => "isotropic",
            Family::Uniform => "uniform",
        }
    }
}

/// One measured mesh.
#[derive(Debug, Clone, Serialize)]
pub struct ConvergenceRow {
    pub family: Family,
    /// `ε` of eq. (6) for the adapted families, cells per side for the uniform one.
    pub parameter: f64,
    /// Smallest prescribed size (`0.1 √ε`), or the grid step for the uniform family.
    pub hmin: f64,
    pub vertices: usize,
    pub triangles: usize,
    /// Two-sided sampled Hausdorff distance between `Γ_h` and `Γ`.
    pub hausdorff: f64,
    /// The part of it attained within [`super::measure::CORNER_RADIUS`] of a corner of the shape
    /// ([`super::measure::hausdorff_split`]; 0 for shapes without corners).
    pub hausdorff_corners: f64,
    /// The part attained elsewhere (on the straight and curved parts).
    pub hausdorff_rest: f64,
    /// `|A_h - A| / A`.
    pub area_rel_error: f64,
    /// `|L_h - L| / L`.
    pub perimeter_rel_error: f64,
    /// Mesh generation time (adaptation rounds, or grid construction).
    pub seconds: f64,
    /// Whether the adaptation settled (always true for grids).
    pub converged: bool,
}

/// Least-squares log-log slopes of one family.
#[derive(Debug, Clone, Serialize)]
pub struct FamilyFit {
    pub family: Family,
    /// Slope of `log hausdorff` against `log vertices`.
    pub hausdorff_slope: f64,
    /// Slope of `log area error` against `log vertices`.
    pub area_slope: f64,
}

/// Vertex counts of the two families at one common error (Hausdorff distance or relative area
/// error, as the list holding it says).
#[derive(Debug, Clone, Serialize)]
pub struct GainPoint {
    pub error: f64,
    pub anisotropic_vertices: f64,
    pub isotropic_vertices: f64,
    pub ratio: f64,
}

/// "Anisotropy pays": isotropic over anisotropic vertex counts.
#[derive(Debug, Clone, Serialize)]
pub struct AnisotropyGain {
    /// At the errors of the anisotropic points that lie inside the isotropic error range (the
    /// isotropic count interpolated log-log between its sweep points).
    pub at_equal_error: Vec<GainPoint>,
    /// Median of `at_equal_error` ratios (`None` when the error ranges do not overlap).
    pub median_at_equal_error: Option<f64>,
    /// `(ε, isotropic / anisotropic vertices)` at the same `ε`, i.e. the same `hmin` and band
    /// (the paper's comparison, 004 §5.1: "the corresponding isotropic graded mesh").
    pub at_equal_eps: Vec<(f64, f64)>,
    /// `(Hausdorff error, ratio)` from the least-squares power laws `log N = a + b log e` of the
    /// two families, at errors log-spaced over the overlap of their ranges (less sensitive to
    /// one noisy sweep point than the interpolation).
    pub fitted: Vec<(f64, f64)>,
    /// `(relative area error, isotropic / anisotropic vertices)` at equal area error, as
    /// `at_equal_error` (each family's count interpolated log-log at the other's errors).
    pub at_equal_area_error: Vec<(f64, f64)>,
}

/// What [`super::run`] measured.
#[derive(Debug, Clone, Serialize)]
pub struct ConvergenceReport {
    pub shape: String,
    /// `[xmin, ymin, xmax, ymax]`.
    pub domain: [f64; 4],
    pub rows: Vec<ConvergenceRow>,
    pub fits: Vec<FamilyFit>,
    pub gain: AnisotropyGain,
    /// The peers run on the anisotropic family's metric (Zalesak only; unavailable ones are
    /// listed with their status).
    pub peers: Vec<PeerResult>,
    /// Files written (CSV, PNG).
    pub files: Vec<PathBuf>,
}

impl ConvergenceReport {
    /// The rows of one family, in sweep order.
    pub fn family(&self, f: Family) -> Vec<&ConvergenceRow> {
        self.rows.iter().filter(|r| r.family == f).collect()
    }

    #[cfg(test)]
    /// The fit of one family.
    pub fn fit(&self, f: Family) -> Option<&FamilyFit> {
        self.fits.iter().find(|x| x.family == f)
    }

    /// A plain-text table of the sweep, the slopes and the gain.
    pub fn table(&self) -> String {
        let mut s = format!(
            "convergence on {} (domain [{}, {}] x [{}, {}])\n{:<12} {:>10} {:>10} {:>9} {:>11} {:>11} {:>11} {:>11} {:>11} {:>8}\n",
            self.shape,
            self.domain[0],
            self.domain[2],
            self.domain[1],
            self.domain[3],
            "family",
            "eps|cells",
            "hmin",
            "vertices",
            "hausdorff",
            "d_H corners",
            "d_H rest",
            "area err",
            "perim err",
            "seconds"
        );
        for r in &self.rows {
            s += &format!(
                "{:<12} {:>10.3e} {:>10.3e} {:>9} {:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e} {:>11.3e} {:>8.2}\n",
                r.family.name(),
                r.parameter,
                r.hmin,
                r.vertices,
                r.hausdorff,
                r.hausdorff_corners,
                r.hausdorff_rest,
                r.area_rel_error,
                r.perimeter_rel_error,
                r.seconds
            );
        }
        for f in &self.fits {
            s += &format!(
                "slope {:<12} hausdorff {:+.3}  area {:+.3}\n",
                f.family.name(),
                f.hausdorff_slope,
                f.area_slope
            );
        }
        for g in &self.gain.at_equal_error {
            s += &format!(
                "equal error {:.3e}: isotropic {:.0} / anisotropic {:.0} vertices = {:.2}\n",
                g.error, g.isotropic_vertices, g.anisotropic_vertices, g.ratio
            );
        }
        match self.gain.median_at_equal_error {
            Some(m) => s += &format!("anisotropy pays (median ratio at equal error): {m:.2}\n"),
            None => s += "anisotropy pays: the error ranges do not overlap\n",
        }
        for (e, r) in &self.gain.fitted {
            s += &format!("fitted power laws, error {e:.3e}: isotropic / anisotropic = {r:.2}\n");
        }
        for (e, r) in &self.gain.at_equal_area_error {
            s += &format!("equal area error {e:.3e}: isotropic / anisotropic vertices = {r:.2}\n");
        }
        for (eps, r) in &self.gain.at_equal_eps {
            s += &format!("equal eps {eps:.1e}: isotropic / anisotropic vertices = {r:.2}\n");
        }
        for p in &self.peers {
            if p.is_ok() {
                s += &format!(
                    "peer {:<13} eps {:.1e}: {} vertices, hausdorff {:.3e}, area {:.3e}, perimeter {:.3e}, {:.1} s\n",
                    p.peer.slug(),
                    p.eps,
                    p.vertices,
                    p.hausdorff,
                    p.area_rel_error.abs(),
                    p.perimeter_rel_error.abs(),
                    p.seconds
                );
            } else {
                s += &format!(
                    "peer {:<13} eps {:.1e}: {:?}\n",
                    p.peer.slug(),
                    p.eps,
                    p.status
                );
            }
        }
        s
    }
}
