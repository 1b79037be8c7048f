//! "Anisotropy pays" at equal interface error, best mesh against best mesh: both families swept
//! over their free parameters, the Pareto front of each (fewest vertices for a given error), and
//! the isotropic / anisotropic vertex ratio of the fronts at equal error.
//!
//! The convergence sweep ([`super::sweep`]) ties the normal size of eq. (6) to the
//! accuracy (`h_min = 0.1 √ε`, so that `ε = 1e-4` is the paper's `h_min = 0.001`) and compares it
//! with the isotropic mesh of size `h_min`. Neither is the cheapest mesh of its kind for a given
//! interface error. Here each family is given the parameters that matter, and only its best
//! meshes count:
//! - **anisotropic**: eq. (6), `M = ∇u∇uᵀ/h_min² + |D²u|/ε`, for every `ε` of the grid, every
//!   normal size `h_min = k √ε` (`k` from [`FrontGrid::normal`]) and every band half-width
//!   (`b h_min`, `b` from [`FrontGrid::bands`]);
//! - **isotropic**: the isotropic variant (`λ_max I`) with size `h` in the band, for every `h` of
//!   [`FrontGrid::sizes`] and every band half-width `b h`. Its `ε` is [`ISOTROPIC_EPS`], so the
//!   curvature term never asks for less than `h` and the size in the band is exactly `h`.
//!
//! Everything else is the `anisomesh adapt` default for both: growth rate 1 outside the band,
//! metric gradation 2, `h_max = 0.2`, exact corner features, adaptation rounds until the vertex
//! count settles with at least 95% of the edges in range. Only runs whose rounds settled enter
//! the fronts. Every mesh is measured as in the sweep ([`super::measure::measure`]: the zero
//! level of the nodal interpolant of the exact distance against the exact shape).
//!
//! Why the ratio is small (what this benchmark measures): the signed distance is linear across
//! its zero level, so the interface error of its interpolant is set by the element size *along*
//! the interface (004 Corollary 1: `l² κ`, with the normal size `h` only in `1 − hκ − h²κ²`). On a
//! curved interface the best anisotropic element is then about as long as it is wide, and the
//! two fronts meet. The paper's ten-fold gain (004 §5.1) compares the two meshes at the same
//! smallest size instead ([`super::claim`]).

use std::path::PathBuf;

use serde::Serialize;

use super::figure::ratio_lines;
use super::gain::{equal_error_ratios, median_ratio};
use super::measure::{adapted_row, corners_of, domain_of};
use super::types::{ConvergenceRow, Family, GainPoint};
use crate::app::plot::{loglog_rgb, LogLogPlot, RgbImage, Series, SeriesStyle};
use anisomesh::adapt::LevelSetMetric;
use anisomesh::error::{Error, Result};
use anisomesh::levelset::shape_by_name;

/// `ε` of the isotropic runs: large enough that the curvature term `κ/ε` of eq. (6) stays below
/// `1/h²` for every size of the grid (`κ h² < 1`), so the size in the band is `h`.
pub const ISOTROPIC_EPS: f64 = 1.0;

/// The parameter grid of [`run`].
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct FrontGrid {
    /// `ε` of eq. (6) for the anisotropic runs.
    pub eps: Vec<f64>,
    /// Normal sizes of the anisotropic runs as multiples `k` of `√ε` (`h_min = k √ε`; the
    /// convergence sweep uses 0.1, which is `anisomesh adapt`'s `h_min = 0.001` at `ε = 1e-4`).
    pub normal: Vec<f64>,
    /// Sizes `h` of the isotropic runs.
    pub sizes: Vec<f64>,
    /// Band half-widths in units of the run's smallest size (`h_min` or `h`; `anisomesh adapt`'s
    /// default band `5 ε` is 0.5 `h_min` at its `ε = 1e-4`).
    pub bands: Vec<f64>,
}

impl FrontGrid {
    /// The full grid: `ε` from 1e-3 to 3e-5, `k` in {0.1, 0.3, 0.6, 1} (at `k = 1` the normal
    /// size exceeds the tangential size `√(ε/κ)` wherever `κ > 1`), sizes from 0.03 to 0.0025,
    /// bands of 0.5 and 2 (48 meshes; about 10 s on the Zalesak disk).
    pub fn full() -> FrontGrid {
        FrontGrid {
            eps: vec![1e-3, 3e-4, 1e-4, 3e-5],
            normal: vec![0.1, 0.3, 0.6, 1.0],
            sizes: vec![0.03, 0.02, 0.014, 0.01, 0.007, 0.005, 0.0035, 0.0025],
            bands: vec![0.5, 2.0],
        }
    }

    /// A small grid for tests and CI: two `ε`, two normal sizes, four isotropic sizes, band 0.5
    /// (8 meshes, seconds).
    pub fn quick() -> FrontGrid {
        FrontGrid {
            eps: vec![1e-3, 1e-4],
            normal: vec![0.1, 0.6],
            sizes: vec![0.03, 0.014, 0.007, 0.005],
            bands: vec![0.5],
        }
    }

    /// An error unless every value is finite and positive and no list is empty.
    pub fn validate(&self) -> Result<()> {
        for (what, v) in [
            ("eps", &self.eps),
            ("normal", &self.normal),
            ("sizes", &self.sizes),
            ("bands", &self.bands),
        ] {
            if v.is_empty() || v.iter().any(|x| !(x.is_finite() && *x > 0.0)) {
                return Err(Error::InvalidInput(format!(
                    "anisotropy fronts: grid '{what}' needs finite positive values (got {v:?})"
                )));
            }
        }
        Ok(())
    }
}

/// One adapted mesh of the grid: its measures and the band half-width it was adapted with.
#[derive(Debug, Clone, Serialize)]
pub struct FrontRun {
    /// `parameter` is `ε` (anisotropic) or [`ISOTROPIC_EPS`] (isotropic); `hmin` is the normal
    /// size `k √ε` or the isotropic size `h`.
    pub row: ConvergenceRow,
    /// Band half-width in units of `row.hmin`.
    pub band: f64,
}

impl FrontRun {
    /// The anisotropic runs' `k` of `h_min = k √ε` (NaN for an isotropic run).
    pub fn normal_factor(&self) -> f64 {
        match self.row.family {
            Family::Anisotropic => self.row.hmin / self.row.parameter.sqrt(),
            _ => f64::NAN,
        }
    }
}

/// The two fronts of one error measure and their ratio at equal error.
#[derive(Debug, Clone, Serialize)]
pub struct FrontComparison {
    /// `(vertices, error)` of the anisotropic front, vertices increasing, error decreasing.
    pub anisotropic: Vec<(f64, f64)>,
    /// The same for the isotropic front.
    pub isotropic: Vec<(f64, f64)>,
    /// Isotropic / anisotropic vertices of the fronts at equal error ([`equal_error_ratios`]).
    pub at_equal_error: Vec<GainPoint>,
}

impl FrontComparison {
    fn of(runs: &[FrontRun], error: fn(&ConvergenceRow) -> f64) -> FrontComparison {
        let front = |f: Family| {
            pareto_front(
                &runs
                    .iter()
                    .filter(|r| r.row.family == f && r.row.converged)
                    .map(|r| (r.row.vertices as f64, error(&r.row)))
                    .collect::<Vec<_>>(),
            )
        };
        let (anisotropic, isotropic) = (front(Family::Anisotropic), front(Family::Isotropic));
        FrontComparison {
            at_equal_error: equal_error_ratios(&anisotropic, &isotropic),
            anisotropic,
            isotropic,
        }
    }

    /// Whether `run` is a point of its own family's front, `error` being its error in this
    /// comparison's measure (a run whose rounds did not settle never is).
    pub fn holds(&self, run: &FrontRun, error: f64) -> bool {
        let front = match run.row.family {
            Family::Anisotropic => &self.anisotropic,
            Family::Isotropic => &self.isotropic,
            Family::Uniform => return false,
        };
        run.row.converged
            && front
                .iter()
                .any(|&(n, e)| n == run.row.vertices as f64 && e == error)
    }

    /// Median ratio at equal error (the geometric mean of the middle two for an even count;
    /// `None` when the fronts' errors do not overlap). Less sensitive than the range to the
    /// steps of a front sampled by a few meshes.
    pub fn median_ratio(&self) -> Option<f64> {
        median_ratio(&self.at_equal_error)
    }

    /// Smallest and largest ratio at equal error (`None` when the fronts' errors do not
    /// overlap).
    pub fn ratio_range(&self) -> Option<(f64, f64)> {
        self.at_equal_error
            .iter()
            .map(|g| g.ratio)
            .fold(None, |acc, r| match acc {
                None => Some((r, r)),
                Some((lo, hi)) => Some((lo.min(r), hi.max(r))),
            })
    }
}

/// What [`run`] measured.
#[derive(Debug, Clone, Serialize)]
pub struct FrontsReport {
    pub shape: String,
    pub grid: FrontGrid,
    pub runs: Vec<FrontRun>,
    /// Fronts of the two-sided interface distance.
    pub hausdorff: FrontComparison,
    /// Fronts of the relative area error.
    pub area: FrontComparison,
    /// Files written (CSV, PNG).
    pub files: Vec<PathBuf>,
}

/// The Pareto front of `(vertices, error)` points: the points that no other point beats on
/// both (no fewer vertices with an error at most as large), sorted by vertices, so the errors
/// strictly decrease along it. Points with a non-positive or non-finite coordinate are dropped.
pub fn pareto_front(points: &[(f64, f64)]) -> Vec<(f64, f64)> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(n, e)| n.is_finite() && e.is_finite() && *n > 0.0 && *e > 0.0)
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0).then(a.1.total_cmp(&b.1)));
    let mut front: Vec<(f64, f64)> = Vec::new();
    for q in p {
        if front.last().map_or(true, |last| q.1 < last.1) {
            front.push(q);
        }
    }
    front
}

/// Adapts every mesh of `grid` around `shape` (see the module doc), measures them and compares
/// the fronts; with `out_dir`, writes `fronts_<shape>.csv` and `fronts_<shape>.png`.
///
/// Errors: an unknown shape, an invalid grid, adaptation or I/O failures.
pub fn run(
    shape: &str,
    grid: &FrontGrid,
    out_dir: Option<&std::path::Path>,
) -> Result<FrontsReport> {
    grid.validate()?;
    let s = shape_by_name(shape)?;
    let name = shape.trim().to_ascii_lowercase();
    let domain = domain_of(&name)?;
    let corners = corners_of(&name);
    let d = LevelSetMetric::default();
    let mut settings: Vec<(Family, f64, f64, f64)> = Vec::new();
    for &eps in &grid.eps {
        for &k in &grid.normal {
            for &b in &grid.bands {
                settings.push((Family::Anisotropic, eps, k * eps.sqrt(), b));
            }
        }
    }
    for &h in &grid.sizes {
        for &b in &grid.bands {
            settings.push((Family::Isotropic, ISOTROPIC_EPS, h, b));
        }
    }
    let mut runs = Vec::with_capacity(settings.len());
    for (family, eps, hmin, band) in settings {
        let lm = LevelSetMetric {
            eps,
            hmin,
            band: band * hmin,
            isotropic: family == Family::Isotropic,
            ..d
        };
        let row = adapted_row(family, eps, lm, s.as_ref(), domain, &corners, None, None)?;
        runs.push(FrontRun { row, band });
    }
    let mut report = FrontsReport {
        shape: name.clone(),
        grid: grid.clone(),
        hausdorff: FrontComparison::of(&runs, |r| r.hausdorff),
        area: FrontComparison::of(&runs, |r| r.area_rel_error),
        runs,
        files: Vec::new(),
    };
    if let Some(dir) = out_dir {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let csv = dir.join(format!("fronts_{name}.csv"));
        let text = report.csv();
        anisomesh::io::atomic_write(&csv, |w| w.write_all(text.as_bytes()))?;
        let png = dir.join(format!("fronts_{name}.png"));
        figure(&report)?.save_png(&png)?;
        report.files = vec![csv, png];
    }
    Ok(report)
}

impl FrontsReport {
    /// Every run (with `*` on the Hausdorff front and `+` on the area front), then the ratios of
    /// the fronts at equal error and their range beside the paper's claim.
    pub fn table(&self) -> String {
        let mut s = format!(
            "anisotropy at equal interface error, best against best ({}; * on the Hausdorff front, + on the area front; the fronts hold settled runs only)\n{:<12} {:>9} {:>10} {:>6} {:>6} {:>9} {:>11} {:>11} {:>9}\n",
            self.shape, "family", "eps", "hmin", "k", "band", "vertices", "hausdorff", "area err", "front"
        );
        for r in &self.runs {
            let mark = format!(
                "{}{}{}",
                if self.hausdorff.holds(r, r.row.hausdorff) {
                    "*"
                } else {
                    ""
                },
                if self.area.holds(r, r.row.area_rel_error) {
                    "+"
                } else {
                    ""
                },
                if r.row.converged { "" } else { "unsettled" }
            );
            let k = r.normal_factor();
            s += &format!(
                "{:<12} {:>9.1e} {:>10.3e} {:>6} {:>6.1} {:>9} {:>11.3e} {:>11.3e} {:>9}\n",
                r.row.family.name(),
                r.row.parameter,
                r.row.hmin,
                if k.is_finite() {
                    format!("{k:.1}")
                } else {
                    "-".into()
                },
                r.band,
                r.row.vertices,
                r.row.hausdorff,
                r.row.area_rel_error,
                mark
            );
        }
        for (what, c) in [("Hausdorff", &self.hausdorff), ("area error", &self.area)] {
            for g in &c.at_equal_error {
                s += &format!(
                    "fronts at equal {what} {:.3e}: isotropic {:.0} / anisotropic {:.0} vertices = {:.2}\n",
                    g.error, g.isotropic_vertices, g.anisotropic_vertices, g.ratio
                );
            }
            match (c.median_ratio(), c.ratio_range()) {
                (Some(m), Some((lo, hi))) => {
                    s += &format!(
                        "best against best at equal {what}: isotropic / anisotropic = {m:.2} (median; {lo:.2} .. {hi:.2}) (004 §5.1: about 10 at equal hmin, see --paper-claim)\n"
                    )
                }
                _ => s += &format!("best against best at equal {what}: the fronts do not overlap\n"),
            }
        }
        s
    }

    /// The runs as CSV (`on_hausdorff_front`, `on_area_front` mark the fronts).
    pub fn csv(&self) -> String {
        let mut s = String::from(
            "family,eps,hmin,normal_factor,band_hmin,vertices,triangles,hausdorff,area_rel_error,perimeter_rel_error,seconds,converged,on_hausdorff_front,on_area_front\n",
        );
        for r in &self.runs {
            let row = &r.row;
            let k = r.normal_factor();
            s += &format!(
                "{},{:e},{:e},{},{},{},{},{:e},{:e},{:e},{:.3},{},{},{}\n",
                row.family.name(),
                row.parameter,
                row.hmin,
                if k.is_finite() {
                    format!("{k}")
                } else {
                    String::new()
                },
                r.band,
                row.vertices,
                row.triangles,
                row.hausdorff,
                row.area_rel_error,
                row.perimeter_rel_error,
                row.seconds,
                row.converged,
                self.hausdorff.holds(r, row.hausdorff),
                self.area.holds(r, row.area_rel_error)
            );
        }
        s
    }
}

/// One error-versus-vertices panel: every run of each family as markers, the two fronts as
/// lines, and the anisotropic runs with `h_min = 0.1 √ε` and band 0.5 `h_min` as a line (the
/// paper's proportions: at `ε = 1e-4` this is the default `anisomesh adapt` run).
fn front_panel(report: &FrontsReport, area: bool) -> LogLogPlot {
    let value = |r: &ConvergenceRow| if area { r.area_rel_error } else { r.hausdorff };
    let c = if area {
        &report.area
    } else {
        &report.hausdorff
    };
    let runs = |f: Family| -> Vec<(f64, f64)> {
        report
            .runs
            .iter()
            .filter(|r| r.row.family == f)
            .map(|r| (r.row.vertices as f64, value(&r.row)))
            .collect()
    };
    let mut sweep: Vec<(f64, f64)> = report
        .runs
        .iter()
        .filter(|r| {
            r.row.family == Family::Anisotropic
                && (r.normal_factor() - 0.1).abs() < 1e-9
                && r.band == 0.5
        })
        .map(|r| (r.row.vertices as f64, value(&r.row)))
        .collect();
    sweep.sort_by(|a, b| a.0.total_cmp(&b.0));
    let series = vec![
        Series {
            name: "anisotropic front (best of all runs)".into(),
            points: c.anisotropic.clone(),
            show_fit_slope: false,
            style: SeriesStyle::Line,
        },
        Series {
            name: "isotropic front (best of all runs)".into(),
            points: c.isotropic.clone(),
            show_fit_slope: false,
            style: SeriesStyle::Line,
        },
        Series {
            name: "eq. (6), hmin = 0.1 sqrt(eps), band 0.5 hmin (default adapt at eps 1e-4)".into(),
            points: sweep,
            show_fit_slope: false,
            style: SeriesStyle::LineMarkers,
        },
        Series {
            name: "anisotropic runs (eps, hmin = k sqrt(eps), band)".into(),
            points: runs(Family::Anisotropic),
            show_fit_slope: false,
            style: SeriesStyle::Markers,
        },
        Series {
            name: "isotropic runs (size h, band)".into(),
            points: runs(Family::Isotropic),
            show_fit_slope: false,
            style: SeriesStyle::Markers,
        },
    ];
    let (what, label) = if area {
        ("relative area error", "|A_h - A| / A")
    } else {
        ("Hausdorff distance", "Hausdorff distance")
    };
    LogLogPlot {
        title: format!("{}: {what}, every run and the fronts", report.shape),
        x_label: "vertices".into(),
        y_label: label.into(),
        series,
        width: 900,
        height: 700,
    }
}

/// The ratio of the fronts at equal Hausdorff and at equal area error, with the paper's 10.
fn ratio_panel(report: &FrontsReport) -> LogLogPlot {
    let pts = |c: &FrontComparison| -> Vec<(f64, f64)> {
        let mut p: Vec<(f64, f64)> = c
            .at_equal_error
            .iter()
            .map(|g| (g.error, g.ratio))
            .collect();
        p.sort_by(|a, b| a.0.total_cmp(&b.0));
        p
    };
    let (h, a) = (pts(&report.hausdorff), pts(&report.area));
    let lines = ratio_lines(
        h.iter().chain(&a).map(|p| p.0),
        &[
            ("paper: about 10, at equal hmin (004 5.1)", 10.0),
            ("1 (no gain)", 1.0),
        ],
    );
    let mut series = vec![
        Series {
            name: "equal Hausdorff distance".into(),
            points: h,
            show_fit_slope: false,
            style: SeriesStyle::LineMarkers,
        },
        Series {
            name: "equal relative area error".into(),
            points: a,
            show_fit_slope: false,
            style: SeriesStyle::LineMarkers,
        },
    ];
    series.extend(lines);
    LogLogPlot {
        title: format!("{}: isotropic / anisotropic vertices, fronts", report.shape),
        x_label: "error".into(),
        y_label: "isotropic / anisotropic vertices".into(),
        series,
        width: 700,
        height: 700,
    }
}

/// The three panels side by side: Hausdorff and area error against vertices (every run and the
/// fronts), and the ratio of the fronts at equal error (when the fronts overlap).
pub fn figure(report: &FrontsReport) -> Result<RgbImage> {
    let mut panels = vec![
        loglog_rgb(&front_panel(report, false))?,
        loglog_rgb(&front_panel(report, true))?,
    ];
    let rp = ratio_panel(report);
    if rp.series.iter().take(2).any(|s| !s.points.is_empty()) {
        panels.push(loglog_rgb(&rp)?);
    }
    RgbImage::side_by_side(&panels)
}
