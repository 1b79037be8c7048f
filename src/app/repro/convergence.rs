//! Error versus vertex count (issue 3 item 7): anisotropic-adapted, isotropic-adapted and uniform
//! meshes around one shape, each measured by the interface error of the nodal interpolant of the
//! shape's exact signed distance.
//!
//! For every mesh of a sweep, `u_h = I_h d` ([`anisomesh::levelset::nodal_distance`]) and its zero
//! level `Γ_h` give:
//! - the two-sided interface distance `d_H(Γ_h, Γ)` ([`anisomesh::levelset::interface_distance`]);
//! - the relative area error `|A(u_h < 0) - A| / A` ([`anisomesh::levelset::enclosed_area`] against
//!   [`Shape::exact_area`]) and the relative perimeter error (the measures of 004 §5.1);
//! - the vertex count and the seconds spent generating the mesh;
//! - the Hausdorff distance split into the part attained within [`CORNER_RADIUS`] of a corner
//!   of the shape and the rest ([`hausdorff_split`]: on the Zalesak disk the corners decided
//!   before the corner features of [`ShapeAdaptOptions::features`]; with them the rest does).
//!
//! The three families:
//! 1. **anisotropic**: the geometric metric of 004 eq. (6), `M = ∇u∇uᵀ/h_min² + |D²u|/ε`, with
//!    exact derivatives of the shape, adapted by [`anisomesh::adapt::adapt_to_shape`] (evaluate →
//!    adapt rounds until the vertex count settles, default options). `ε` decreases over the
//!    sweep and `h_min = 0.1 √ε`, the other parameters are those of `anisomesh adapt`
//!    ([`metric_for`]), so that `ε = 1e-4` is the paper's setting (004 §5.1: `h_min = 0.001`,
//!    `h_max = 0.2`). A fixed `h_min` would not make a sweep: the isotropic variant would be the
//!    same mesh for every `ε`. Optionally the kinks of the distance (the medial axis at the slot
//!    corners) are seen at the scale `h_min` ([`ConvergenceOptions::kink_scale`]).
//! 2. **isotropic**: the same source with `isotropic = true` (`M` replaced by `λ_max I`, the
//!    smallest size of eq. (6) in every direction), same `ε`, same bounds and band.
//! 3. **uniform**: `Mesh2::rectangle` union-jack grids of the domain at increasing resolution.
//!
//! On the Zalesak disk the installed peers ([`PEER_KINDS`]) are run on the anisotropic family's
//! metric at every `ε` ([`crate::app::repro::peers::run_peer_with`]).
//!
//! Domains: Zalesak `[-2, 2]²` (004 §5.1), circle and flower `[-1, 1]²` (their doc comments in
//! [`anisomesh::levelset::shape_by_name`]).
//!
//! "Anisotropy pays" ([`AnisotropyGain`]): at equal Hausdorff error — each family's vertex count
//! interpolated log-log between its sweep points, and from the fitted power laws — the ratio of
//! isotropic to anisotropic vertex counts, and the plain ratio at equal `ε`. The paper's own
//! comparison (004 §5.1: about 10 times more vertices for "the corresponding isotropic graded
//! mesh" at `h_min = 0.001`) is at equal smallest size, not at equal error:
//! [`super::convergence_claim`].

use std::path::PathBuf;
use std::time::Instant;

use serde::Serialize;

use crate::app::plot::fit_loglog_slope;
use anisomesh::adapt::{adapt_to_shape, LevelSetMetric, ShapeAdaptOptions};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::levelset::{
    enclosed_area, extract_zero_level, interface_distance, interface_length, nodal_distance,
    shape_by_name, Polyline, Shape,
};
use anisomesh::mesh::{GridPattern, Mesh2};

pub use super::convergence_figure::{figure, write_csv};
use super::peers::{find_program, run_peer_with, PeerKind, PeerOptions, PeerResult};

/// Options of [`run`] (the CLI `anisomesh convergence --shape ...` maps onto these).
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
    /// On the Zalesak disk, also run the installed peers ([`PEER_KINDS`]) on the anisotropic
    /// family's metric at every `ε` of the sweep (skipped with a printed note when a peer is not
    /// on `PATH`).
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
    /// The part of it attained within [`CORNER_RADIUS`] of a corner of the shape
    /// ([`hausdorff_split`]; 0 for shapes without corners).
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

/// What [`run`] measured.
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

/// The domain `(lo, hi)` of a benchmark shape: `[-2, 2]²` for Zalesak (004 §5.1), `[-1, 1]²`
/// for the circle and the flower.
pub fn domain_of(shape: &str) -> Result<(DVec2, DVec2)> {
    match shape.trim().to_ascii_lowercase().as_str() {
        "zalesak" => Ok((DVec2::splat(-2.0), DVec2::splat(2.0))),
        "circle" | "flower" => Ok((DVec2::splat(-1.0), DVec2::splat(1.0))),
        _ => shape_by_name(shape).map(|_| (DVec2::splat(-1.0), DVec2::splat(1.0))),
    }
}

/// The sweep: `ε` values of the adapted families and cells per side of the uniform grids.
///
/// Full: `points` values of `ε` log-spaced from `1e-2` to `1e-4` (the last one gives the paper's
/// `h_min = 0.001`); grids halving from 800 cells per side on Zalesak (641,601 vertices, the
/// uniform mesh quoted in issue 3) and from 512 on the circle and the flower.
/// Quick: `min(points, 3)` values from `1e-2` in steps of `10^{-1/2}`, and three grids of 32 to
/// 128 cells (Zalesak 64 to 256).
pub fn sweep(shape: &str, points: usize, quick: bool) -> Result<(Vec<f64>, Vec<usize>)> {
    if points < 2 {
        return Err(Error::InvalidInput(format!(
            "convergence: need at least 2 sweep points per family (got {points})"
        )));
    }
    let zalesak = shape.trim().eq_ignore_ascii_case("zalesak");
    let eps_max: f64 = 1e-2;
    let (eps_min, n_max): (f64, usize) = if quick {
        let n = points.min(3);
        (eps_max * 10f64.powf(-0.5 * (n - 1) as f64), n)
    } else {
        (eps_max * 1e-2, points)
    };
    // Powers of ten computed as such, so that the last full point is exactly `1e-4` (the default
    // `anisomesh adapt` setting; the corner errors react to the last bit of `h_min`).
    let eps = (0..n_max)
        .map(|k| {
            let t = k as f64 / (n_max - 1) as f64;
            10f64.powf(eps_max.log10() + t * (eps_min.log10() - eps_max.log10()))
        })
        .collect();
    let top: usize = match (quick, zalesak) {
        (true, true) => 256,
        (true, false) => 128,
        (false, true) => 800,
        (false, false) => 512,
    };
    let n_grids = if quick { 3 } else { points };
    let mut cells: Vec<usize> = (0..n_grids).map(|k| top >> k).filter(|&c| c >= 4).collect();
    cells.reverse();
    Ok((eps, cells))
}

#[cfg(test)]
/// The level-set metric of the adapted families at `ε`: the default `anisomesh adapt` setting
/// ([`LevelSetMetric::default`]: band `5 ε`, sizes growing at rate 1 outside it, anisotropy at
/// most 1e4, `h_max = 0.2`) with `h_min = 0.1 √ε`, so that `ε = 1e-4` is exactly the default run
/// (004 §5.1: `h_min = 0.001`, `h_max = 0.2`).
pub fn metric_for(eps: f64, isotropic: bool) -> LevelSetMetric {
    metric_with(eps, isotropic, None, None)
}

/// [`metric_for`] with the band half-width `band_hmin h_min` and the growth rate `grade` outside
/// it where given (the "equal settings" variations of the anisotropy-pays comparison).
pub fn metric_with(
    eps: f64,
    isotropic: bool,
    band_hmin: Option<f64>,
    grade: Option<f64>,
) -> LevelSetMetric {
    let d = LevelSetMetric::default();
    let hmin = eps.sqrt() / 10.0;
    LevelSetMetric {
        eps,
        hmin,
        band: band_hmin.map_or(d.band * (eps / d.eps), |k| k * hmin),
        grade: grade.unwrap_or(d.grade),
        isotropic,
        ..d
    }
}

/// A mesh of `domain` adapted to the zero level of `shape` with the metric `lm`, by
/// [`adapt_to_shape`] with its default rounds, tolerance and corner features, kinks resolved at
/// `kink_scale`, the metric graded with the factor `gradation` ([`anisomesh::metric::gradate`];
/// `None`: the default of [`ShapeAdaptOptions::gradation`]). Returns the mesh and whether the
/// rounds settled.
fn adapted_mesh(
    shape: &dyn Shape,
    domain: (DVec2, DVec2),
    lm: LevelSetMetric,
    kink_scale: Option<f64>,
    gradation: Option<f64>,
) -> Result<(Mesh2, bool)> {
    let d = ShapeAdaptOptions::default();
    let opts = ShapeAdaptOptions {
        metric: lm,
        kink_scale,
        gradation: gradation.or(d.gradation),
        ..d
    };
    let (mesh, _u, rep) = adapt_to_shape(shape, domain, &opts)?;
    Ok((mesh, rep.converged))
}

/// A mesh adapted with `lm` ([`adapted_mesh`]) measured as a row of `family` with the sweep
/// parameter `parameter` ([`row`]; `seconds` is the adaptation time).
#[allow(clippy::too_many_arguments)]
pub(super) fn adapted_row(
    family: Family,
    parameter: f64,
    lm: LevelSetMetric,
    shape: &dyn Shape,
    domain: (DVec2, DVec2),
    corners: &[DVec2],
    kink_scale: Option<f64>,
    gradation: Option<f64>,
) -> Result<ConvergenceRow> {
    let t = Instant::now();
    let (mesh, converged) = adapted_mesh(shape, domain, lm, kink_scale, gradation)?;
    let secs = t.elapsed().as_secs_f64();
    row(
        family, parameter, lm.hmin, &mesh, shape, corners, secs, converged,
    )
}

/// Radius of the corner neighbourhoods of [`hausdorff_split`] in the sweep (the slot of the
/// Zalesak disk is 0.12 wide).
pub const CORNER_RADIUS: f64 = 0.02;

/// The corners of a benchmark shape (where its distance has kinks): [`Shape::corners`] of
/// [`shape_by_name`] (the four slot corners of the Zalesak disk, none for the circle and the
/// flower); empty for an unknown name.
pub fn corners_of(shape: &str) -> Vec<DVec2> {
    shape_by_name(shape).map_or_else(|_| Vec::new(), |s| s.corners())
}

/// A shape whose boundary samples are restricted to one side of a corner neighbourhood (the
/// exact → discrete direction of [`interface_distance`] restricted to a region).
struct Restricted<'a> {
    shape: &'a dyn Shape,
    corners: &'a [DVec2],
    radius: f64,
    near: bool,
}

impl Restricted<'_> {
    fn keeps(&self, p: DVec2) -> bool {
        near_corner(p, self.corners, self.radius) == self.near
    }
}

fn near_corner(p: DVec2, corners: &[DVec2], radius: f64) -> bool {
    corners.iter().any(|c| (p - *c).length() < radius)
}

impl Shape for Restricted<'_> {
    fn distance(&self, p: DVec2) -> f64 {
        self.shape.distance(p)
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        self.shape
            .boundary_samples(n)
            .map(|v| v.into_iter().filter(|&p| self.keeps(p)).collect())
    }
    fn name(&self) -> String {
        self.shape.name()
    }
}

/// The two-sided interface distance of [`interface_distance`] split by region: `(near, rest)`,
/// the largest distance attained within `radius` of one of `corners` and elsewhere (points of
/// `Γ_h` measured by `|d|`, samples of `Γ` by their distance to `Γ_h`; 4 samples per segment).
/// `max(near, rest)` is the Hausdorff distance. With no corners `near` is 0.
pub fn hausdorff_split(
    lines: &[Polyline],
    shape: &dyn Shape,
    corners: &[DVec2],
    radius: f64,
) -> (f64, f64) {
    let (mut near, mut rest): (f64, f64) = (0.0, 0.0);
    let k = 4;
    for pl in lines {
        for (a, b) in pl.segments() {
            for i in 0..k {
                let p = a + (b - a) * (i as f64 / (k - 1) as f64);
                let d = shape.distance(p).abs();
                if near_corner(p, corners, radius) {
                    near = near.max(d);
                } else {
                    rest = rest.max(d);
                }
            }
        }
    }
    for (is_near, acc) in [(true, &mut near), (false, &mut rest)] {
        let r = Restricted {
            shape,
            corners,
            radius,
            near: is_near,
        };
        let from = interface_distance(lines, &r, k).from_exact_max;
        if from.is_finite() {
            *acc = acc.max(from);
        }
    }
    (near, rest)
}

/// The interface measures of the nodal interpolant of `shape`'s distance on `mesh`:
/// `(hausdorff, relative area error, relative perimeter error)`. Errors: a shape without exact
/// area or perimeter, an empty zero level.
pub fn measure(mesh: &Mesh2, shape: &dyn Shape) -> Result<(f64, f64, f64)> {
    let u = nodal_distance(mesh, shape);
    let lines = extract_zero_level(mesh, &u)?;
    let hausdorff = interface_distance(&lines, shape, 4).hausdorff;
    let area = shape.exact_area().ok_or_else(|| {
        Error::InvalidInput(format!(
            "convergence: shape {} has no exact area",
            shape.name()
        ))
    })?;
    let perimeter = shape.exact_perimeter().ok_or_else(|| {
        Error::InvalidInput(format!(
            "convergence: shape {} has no exact perimeter",
            shape.name()
        ))
    })?;
    let a = enclosed_area(mesh, &u)?;
    let l = interface_length(mesh, &u)?;
    Ok((
        hausdorff,
        (a - area).abs() / area,
        (l - perimeter).abs() / perimeter,
    ))
}

#[allow(clippy::too_many_arguments)]
fn row(
    family: Family,
    parameter: f64,
    hmin: f64,
    mesh: &Mesh2,
    shape: &dyn Shape,
    corners: &[DVec2],
    seconds: f64,
    converged: bool,
) -> Result<ConvergenceRow> {
    let (hausdorff, area_rel_error, perimeter_rel_error) = measure(mesh, shape)?;
    let u = nodal_distance(mesh, shape);
    let lines = extract_zero_level(mesh, &u)?;
    let (hausdorff_corners, hausdorff_rest) =
        hausdorff_split(&lines, shape, corners, CORNER_RADIUS);
    Ok(ConvergenceRow {
        family,
        parameter,
        hmin,
        vertices: mesh.n_points(),
        triangles: mesh.n_live_tris(),
        hausdorff,
        hausdorff_corners,
        hausdorff_rest,
        area_rel_error,
        perimeter_rel_error,
        seconds,
        converged,
    })
}

/// The peers run beside the sweep on the Zalesak disk: mmg2d and BAMG given the anisotropic
/// family's metric at the vertices of their meshes, and BAMG with its own Hessian metric of the
/// level set (`adaptmesh(Th, u, err = ε)`).
pub const PEER_KINDS: [PeerKind; 3] = [
    PeerKind::Mmg2dMetric,
    PeerKind::BamgMetric,
    PeerKind::BamgLevelSet,
];

/// The peers' fixed point (as [`crate::app::repro::peers`]): from a 50 x 50 grid, six adapter calls
/// (issue 3 quotes mmg2d after six passes); quick: a 30 x 30 grid and two calls.
fn peer_options(opts: &ConvergenceOptions) -> PeerOptions {
    let d = PeerOptions::default();
    PeerOptions {
        background: if opts.quick { 30 } else { 50 },
        iterations: if opts.quick { 2 } else { 6 },
        timeout: std::time::Duration::from_secs(if opts.quick { 60 } else { 600 }),
        work_dir: d
            .work_dir
            .join(format!("convergence-{}", std::process::id())),
        kink_scale: opts.kink_scale,
        ..d
    }
}

/// Runs the installed peers of [`PEER_KINDS`] at every `ε` (quick: the first only); a peer not
/// on `PATH` is skipped with a printed note (and listed once in the result with its status).
fn run_peers(eps_list: &[f64], opts: &ConvergenceOptions) -> Vec<PeerResult> {
    let popts = peer_options(opts);
    let mut out = Vec::new();
    for kind in PEER_KINDS {
        let Some(program) = kind.program() else {
            continue;
        };
        if find_program(program).is_none() {
            println!(
                "note: {program} not found on PATH: the measured {} series is skipped",
                kind.slug()
            );
            out.push(PeerResult::unavailable(
                kind,
                f64::NAN,
                format!("{program} not on PATH"),
            ));
            continue;
        }
        for &eps in eps_list
            .iter()
            .take(if opts.quick { 1 } else { usize::MAX })
        {
            let m = metric_with(eps, false, opts.band_hmin, opts.grade);
            let r = run_peer_with(kind, &m, &popts);
            if !r.is_ok() {
                println!("note: {} at eps {eps:.1e}: {:?}", kind.slug(), r.status);
            }
            out.push(r);
        }
    }
    let _ = std::fs::remove_dir_all(&popts.work_dir);
    out
}

/// Runs the sweep of the three families on `opts.shape`, fits the slopes, computes the
/// anisotropy gain, runs the installed peers (Zalesak, `opts.peers`) and, with `out_dir`, writes
/// `convergence_<shape>.csv` and the three-panel figure `convergence_<shape>.png`
/// ([`super::convergence_figure`]).
///
/// Errors: an unknown shape, fewer than 2 points, adaptation or I/O failures (never a missing
/// peer).
pub fn run(opts: &ConvergenceOptions) -> Result<ConvergenceReport> {
    let shape = shape_by_name(&opts.shape)?;
    let name = opts.shape.trim().to_ascii_lowercase();
    let domain = domain_of(&name)?;
    let corners = corners_of(&name);
    let (eps_list, cells) = sweep(&name, opts.points, opts.quick)?;
    let mut rows = Vec::new();
    for &eps in &eps_list {
        for (family, iso) in [(Family::Anisotropic, false), (Family::Isotropic, true)] {
            let lm = metric_with(eps, iso, opts.band_hmin, opts.grade);
            rows.push(adapted_row(
                family,
                eps,
                lm,
                shape.as_ref(),
                domain,
                &corners,
                opts.kink_scale,
                None,
            )?);
        }
    }
    for &n in &cells {
        let t = Instant::now();
        let mesh = Mesh2::rectangle(domain.0, domain.1, n, n, GridPattern::UnionJack)?;
        let secs = t.elapsed().as_secs_f64();
        let h = (domain.1.x - domain.0.x) / n as f64;
        rows.push(row(
            Family::Uniform,
            n as f64,
            h,
            &mesh,
            shape.as_ref(),
            &corners,
            secs,
            true,
        )?);
    }
    let fits = [Family::Anisotropic, Family::Isotropic, Family::Uniform]
        .into_iter()
        .map(|f| {
            let pts = |g: fn(&ConvergenceRow) -> f64| -> Vec<(f64, f64)> {
                rows.iter()
                    .filter(|r| r.family == f)
                    .map(|r| (r.vertices as f64, g(r)))
                    .collect()
            };
            FamilyFit {
                family: f,
                hausdorff_slope: fit_loglog_slope(&pts(|r| r.hausdorff)),
                area_slope: fit_loglog_slope(&pts(|r| r.area_rel_error)),
            }
        })
        .collect();
    let gain = anisotropy_gain(&rows);
    let peers = if opts.peers && name == "zalesak" {
        run_peers(&eps_list, opts)
    } else {
        Vec::new()
    };
    let mut report = ConvergenceReport {
        shape: name.clone(),
        domain: [domain.0.x, domain.0.y, domain.1.x, domain.1.y],
        rows,
        fits,
        gain,
        peers,
        files: Vec::new(),
    };
    if let Some(dir) = &opts.out_dir {
        std::fs::create_dir_all(dir).map_err(|e| Error::io(dir, e))?;
        let csv = dir.join(format!("convergence_{name}.csv"));
        write_csv(&csv, &report)?;
        let png = dir.join(format!("convergence_{name}.png"));
        figure(&report)?.save_png(&png)?;
        report.files = vec![csv, png];
    }
    Ok(report)
}

/// The vertex count at which a family reaches the error `e`: the first crossing of `e` by the
/// piecewise log-log line through its `(vertices, error)` points sorted by vertices; `None`
/// when `e` is outside the range of the family's errors.
pub fn vertices_at_error(points: &[(f64, f64)], e: f64) -> Option<f64> {
    let mut p: Vec<(f64, f64)> = points
        .iter()
        .copied()
        .filter(|(n, y)| *n > 0.0 && *y > 0.0 && n.is_finite() && y.is_finite())
        .collect();
    p.sort_by(|a, b| a.0.total_cmp(&b.0));
    let le = e.ln();
    for w in p.windows(2) {
        let (n0, e0) = (w[0].0.ln(), w[0].1.ln());
        let (n1, e1) = (w[1].0.ln(), w[1].1.ln());
        let (lo, hi) = (e0.min(e1), e0.max(e1));
        if le >= lo && le <= hi {
            if e1 == e0 {
                return Some(w[0].0);
            }
            let t = (le - e0) / (e1 - e0);
            return Some((n0 + t * (n1 - n0)).exp());
        }
    }
    None
}

/// Isotropic over anisotropic vertex counts at equal error, from `(vertices, error)` points of
/// each family: at every anisotropic error inside the isotropic range (the isotropic count
/// interpolated by [`vertices_at_error`]) and at every isotropic error inside the anisotropic
/// range; sorted by decreasing error.
pub fn equal_error_ratios(ani: &[(f64, f64)], iso: &[(f64, f64)]) -> Vec<GainPoint> {
    let point = |error: f64, anisotropic_vertices: f64, isotropic_vertices: f64| GainPoint {
        error,
        anisotropic_vertices,
        isotropic_vertices,
        ratio: isotropic_vertices / anisotropic_vertices,
    };
    let mut out: Vec<GainPoint> = ani
        .iter()
        .filter_map(|&(na, e)| vertices_at_error(iso, e).map(|ni| point(e, na, ni)))
        .chain(
            iso.iter()
                .filter_map(|&(ni, e)| vertices_at_error(ani, e).map(|na| point(e, na, ni))),
        )
        .collect();
    out.sort_by(|a, b| b.error.total_cmp(&a.error));
    out
}

/// The median ratio of `points` (the geometric mean of the middle two for an even count; `None`
/// for no point).
pub fn median_ratio(points: &[GainPoint]) -> Option<f64> {
    let mut r: Vec<f64> = points.iter().map(|g| g.ratio).collect();
    r.sort_by(f64::total_cmp);
    match r.len() {
        0 => None,
        n if n % 2 == 1 => Some(r[n / 2]),
        n => Some((r[n / 2 - 1] * r[n / 2]).sqrt()),
    }
}

/// The gain of anisotropy over the rows (see [`AnisotropyGain`]).
pub fn anisotropy_gain(rows: &[ConvergenceRow]) -> AnisotropyGain {
    let pts = |f: Family, err: fn(&ConvergenceRow) -> f64| -> Vec<(f64, f64)> {
        rows.iter()
            .filter(|r| r.family == f)
            .map(|r| (r.vertices as f64, err(r)))
            .collect()
    };
    let (ani, iso) = (
        pts(Family::Anisotropic, |r| r.hausdorff),
        pts(Family::Isotropic, |r| r.hausdorff),
    );
    let (ani_area, iso_area) = (
        pts(Family::Anisotropic, |r| r.area_rel_error),
        pts(Family::Isotropic, |r| r.area_rel_error),
    );
    let at_equal_area_error = equal_error_ratios(&ani_area, &iso_area)
        .into_iter()
        .map(|g| (g.error, g.ratio))
        .collect();
    let at_equal_error = equal_error_ratios(&ani, &iso);
    let median_at_equal_error = median_ratio(&at_equal_error);
    let at_equal_eps = rows
        .iter()
        .filter(|r| r.family == Family::Anisotropic)
        .filter_map(|a| {
            rows.iter()
                .find(|r| r.family == Family::Isotropic && r.parameter == a.parameter)
                .map(|i| (a.parameter, i.vertices as f64 / a.vertices as f64))
        })
        .collect();
    AnisotropyGain {
        at_equal_error,
        median_at_equal_error,
        at_equal_eps,
        fitted: fitted_gain(&ani, &iso, 4),
        at_equal_area_error,
    }
}

/// Least-squares line `log N = a + b log e` through `(N, e)` points; `None` with fewer than two
/// distinct errors.
fn fit_vertices_on_error(points: &[(f64, f64)]) -> Option<(f64, f64)> {
    let logs: Vec<(f64, f64)> = points
        .iter()
        .filter(|(n, e)| *n > 0.0 && *e > 0.0 && n.is_finite() && e.is_finite())
        .map(|(n, e)| (e.ln(), n.ln()))
        .collect();
    let k = logs.len() as f64;
    if logs.len() < 2 {
        return None;
    }
    let mx = logs.iter().map(|p| p.0).sum::<f64>() / k;
    let my = logs.iter().map(|p| p.1).sum::<f64>() / k;
    let sxx: f64 = logs.iter().map(|p| (p.0 - mx).powi(2)).sum();
    let sxy: f64 = logs.iter().map(|p| (p.0 - mx) * (p.1 - my)).sum();
    (sxx > 0.0).then(|| (my - sxy / sxx * mx, sxy / sxx))
}

/// `count` errors log-spaced over the overlap of the two families' error ranges and the ratio
/// `N_iso(e) / N_ani(e)` of their fitted power laws there (empty when the ranges do not
/// overlap).
pub fn fitted_gain(ani: &[(f64, f64)], iso: &[(f64, f64)], count: usize) -> Vec<(f64, f64)> {
    let range = |p: &[(f64, f64)]| {
        p.iter()
            .map(|q| q.1)
            .filter(|e| *e > 0.0 && e.is_finite())
            .fold((f64::INFINITY, 0.0f64), |(lo, hi), e| {
                (lo.min(e), hi.max(e))
            })
    };
    let ((alo, ahi), (ilo, ihi)) = (range(ani), range(iso));
    let (lo, hi) = (alo.max(ilo), ahi.min(ihi));
    let (Some((aa, ba)), Some((ai, bi))) = (fit_vertices_on_error(ani), fit_vertices_on_error(iso))
    else {
        return Vec::new();
    };
    if lo >= hi || lo.is_nan() || hi.is_nan() || count == 0 {
        return Vec::new();
    }
    (0..count)
        .map(|k| {
            let t = if count == 1 {
                0.5
            } else {
                k as f64 / (count - 1) as f64
            };
            let le = hi.ln() + t * (lo.ln() - hi.ln());
            (le.exp(), (ai - aa + (bi - ba) * le).exp())
        })
        .collect()
}
