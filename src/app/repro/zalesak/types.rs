//! The options of the Zalesak rotation and what it measures: the time series, the frames kept
//! for the figures, and the report with its summary table.

use std::path::PathBuf;

use serde::Serialize;

use super::exact::{EXACT_AREA, EXACT_PERIMETER, PAPER};
use super::sources::ErrorSources;
use anisomesh::adapt::{AdaptOptions, LevelSetMetric};
use anisomesh::advect::AdvectOptions;
use anisomesh::mesh::Mesh2;

/// Which meshes carry the level set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum ZalesakMesh {
    /// A fixed uniform `n x n` grid of `[-2, 2]²` (union-jack diagonals).
    Uniform { n: usize },
    /// Adaptation (004 §3.5) with the transient fixed point: sizes in `[hmin, hmin *
    /// stretching]`, anisotropic (004 eq. (6)) or its isotropic variant.
    Adapted {
        hmin: f64,
        stretching: f64,
        isotropic: bool,
    },
}

/// Options of the run (defaults as in 004 §5.1).
#[derive(Debug, Clone)]
pub struct ZalesakOptions {
    pub mesh: ZalesakMesh,
    /// Number of periods per revolution (16 = steps of π/8).
    pub periods: usize,
    /// Revolutions (1 = back to the start).
    pub revolutions: f64,
    /// The level-set metric (004 eq. (6): ε, band, gradation); its `hmin`, `hmax` and
    /// `isotropic` are taken from [`ZalesakMesh::Adapted`].
    pub metric: LevelSetMetric,
    /// The remeshing options of every adaptation.
    pub adapt: AdaptOptions,
    /// Adaptations of the initial mesh to the exact level set (from a 40 x 40 grid).
    pub initial_rounds: usize,
    /// Maximal fixed-point iterations per period (adapted meshes only).
    pub fixed_point_iterations: usize,
    /// Stop the fixed point when the mean L1 change of `u^{n+1}` is below this (004 §3.5).
    pub fixed_point_tol: f64,
    /// The advection step (foot scheme, evaluation, form).
    pub advect: AdvectOptions,
    /// Geometric redistancing (004 §2.2) of `u^{n+1}` after each period.
    pub redistance: bool,
    /// Restore the initial area after each period (004 §5.1 "mass correction").
    pub mass_correction: bool,
    /// Measure the error sources separately ([`ErrorSources`]; costs two extra advections per
    /// period).
    pub sources: bool,
    /// Also run a uniform mesh and an isotropic adapted mesh of similar vertex count.
    pub compare: bool,
    /// Output directory for `zalesak.json`, `zalesak.csv` and the figures (none: no files).
    pub out_dir: Option<PathBuf>,
}

impl Default for ZalesakOptions {
    fn default() -> Self {
        ZalesakOptions {
            mesh: ZalesakMesh::Adapted {
                hmin: 0.001,
                stretching: 200.0,
                isotropic: false,
            },
            // Pinned (not inherited from LevelSetMetric::default). Measured (one revolution,
            // relative area / perimeter error, vertices mean / max, CPU seconds): band 2e-3:
            // -2.8e-4 / -1.2e-3, 4,994 / 5,277, 5.0 s; band 3e-3: -2.4e-4 / -1.2e-3,
            // 5,987 / 6,255, 6.6 s; band 4e-3: -2.7e-4 / -8.4e-4, 6,958 / 7,353 (over the 7,000
            // target); band 1e-3: -2.3e-4 / -2.1e-3, 4,055 / 4,360, 4.2 s but interface
            // distance 5.9e-3 (1.6e-3 at band 2e-3). README "Zalesak slotted-disk rotation".
            metric: LevelSetMetric {
                eps: 1.2e-3,
                grade: 1.0,
                band: 2e-3,
                ..LevelSetMetric::default()
            },
            // At most 4 split/collapse cycles per adaptation: the remeshing starts from a mesh
            // already adapted to u^n (or to the previous iterate), and the cycles beyond the
            // first few only shuffle a few edges. Measured (default run, loaded machine): cap
            // 20 -> 589 cycles in 48 adaptations, 7.9 s remeshing, area -3.5e-4, perimeter
            // -1.2e-3; cap 4 -> 204 cycles, 5.2 s, -2.9e-4, +1.3e-3; cap 3 -> 4.6 s, -2.9e-4,
            // -9.6e-4.
            adapt: AdaptOptions::default().max_cycles(4),
            initial_rounds: 4,
            periods: 16,
            revolutions: 1.0,
            fixed_point_iterations: 5,
            fixed_point_tol: 1e-4,
            // Limited L2 projection (`AdvectOptions::limit`): without the limiter the projection
            // overshoots at a reflex slot corner and leaves a small spurious loop of the zero
            // level (area -2.9e-4, perimeter +1.3e-3, interface distance 2.9e-3); with it the
            // corner is only rounded (area -3.4e-4, perimeter -2.1e-3, distance 2.4e-3).
            advect: AdvectOptions {
                limit: true,
                ..AdvectOptions::default()
            },
            redistance: false,
            mass_correction: false,
            sources: false,
            compare: false,
            out_dir: None,
        }
    }
}

/// One row of the time series (after each period): the statistics `advect::run` reports.
pub type ZalesakSample = anisomesh::advect::StepStats;

/// A mesh and the level set on it at one time (kept for the figures, not serialised).
#[derive(Debug, Clone)]
pub struct Snapshot {
    pub period: usize,
    pub time: f64,
    pub mesh: Mesh2,
    pub u: Vec<f64>,
}

/// What the figures need: the meshes at the rotations `k π/2` (and the last one), and one
/// adapted mesh of a period with the level set at the period's start (on the previous mesh).
#[derive(Debug, Clone, Default)]
pub struct ZalesakFrames {
    pub snapshots: Vec<Snapshot>,
    /// `(start of the period on its own mesh, end of the period on the adapted mesh)`.
    pub period: Option<(Snapshot, Snapshot)>,
}

/// The outcome of a run.
#[derive(Debug, Clone, Serialize)]
pub struct ZalesakReport {
    pub mesh: ZalesakMesh,
    pub area_initial: f64,
    pub area_final: f64,
    pub perimeter_initial: f64,
    pub perimeter_final: f64,
    /// Max distance from the final zero level to the exact initial boundary, and from the
    /// exact boundary to the final zero level (their max: the sampled Hausdorff distance).
    pub interface_to_exact_max: f64,
    pub exact_to_interface_max: f64,
    pub vertices_mean: f64,
    pub vertices_max: usize,
    /// Fixed-point iterations per period (1 per period on a fixed mesh).
    pub fixed_point_iterations: Vec<usize>,
    pub seconds: f64,
    /// Seconds spent adapting (initial mesh included) and advecting/transferring.
    pub adapt_seconds: f64,
    pub advect_seconds: f64,
    /// Number of adaptations (initial rounds and fixed-point iterations) and their
    /// split/collapse cycles in total (0 on a uniform mesh).
    pub adaptations: usize,
    pub adapt_cycles: usize,
    pub series: Vec<ZalesakSample>,
    /// The error sources measured separately (option `sources`).
    pub sources: Option<ErrorSources>,
    /// The comparison runs (`--compare`): uniform and isotropic adapted meshes.
    pub compare_uniform: Option<Box<ZalesakReport>>,
    pub compare_isotropic: Option<Box<ZalesakReport>>,
    #[serde(skip)]
    pub frames: ZalesakFrames,
}

impl ZalesakReport {
    /// Relative errors of the final area and perimeter against the exact values.
    pub fn relative_errors(&self) -> (f64, f64) {
        (
            (self.area_final - EXACT_AREA) / EXACT_AREA,
            (self.perimeter_final - EXACT_PERIMETER) / EXACT_PERIMETER,
        )
    }

    /// A short name of the mesh family.
    pub fn label(&self) -> String {
        match self.mesh {
            ZalesakMesh::Uniform { n } => format!("uniform {n}x{n}"),
            ZalesakMesh::Adapted {
                hmin, isotropic, ..
            } => format!(
                "{} hmin {hmin:.1e}",
                if isotropic {
                    "isotropic"
                } else {
                    "anisotropic"
                }
            ),
        }
    }

    /// The table: measured, exact and paper values, then one line per comparison run.
    pub fn summary(&self) -> String {
        let (ea, ep) = self.relative_errors();
        let mut s = format!(
            "Zalesak ({:?}): {:.1} s (adapt {:.1} s in {} adaptations / {} cycles, advect {:.1} s), vertices mean {:.0} max {}\n\
             {:>10} {:>14} {:>14} {:>14}\n\
             {:>10} {:>14.10} {:>14.10} {:>14}\n\
             {:>10} {:>14.10} {:>14.10} {:>14}\n\
             {:>10} {:>14.10} {:>14.10} {:>14}\n\
             {:>10} {:>14.10} {:>14.10} {:>14}\n\
             final relative error: area {:+.3e}, perimeter {:+.3e}; interface distance max {:.2e} (exact->interface {:.2e})\n",
            self.mesh, self.seconds, self.adapt_seconds, self.adaptations, self.adapt_cycles, self.advect_seconds, self.vertices_mean, self.vertices_max,
            "", "measured", "exact", "paper",
            "area0", self.area_initial, EXACT_AREA, PAPER[0],
            "area1", self.area_final, EXACT_AREA, PAPER[1],
            "perim0", self.perimeter_initial, EXACT_PERIMETER, PAPER[2],
            "perim1", self.perimeter_final, EXACT_PERIMETER, PAPER[3],
            ea, ep, self.interface_to_exact_max, self.exact_to_interface_max,
        );
        if let Some(src) = &self.sources {
            s.push_str(&src.table());
        }
        let runs: Vec<&ZalesakReport> = std::iter::once(self)
            .chain(
                [&self.compare_uniform, &self.compare_isotropic]
                    .into_iter()
                    .flatten()
                    .map(|b| b.as_ref()),
            )
            .collect();
        if runs.len() > 1 {
            s.push_str(&format!(
                "{:<26} {:>9} {:>9} {:>11} {:>11} {:>11} {:>11} {:>9} {:>8}\n",
                "comparison",
                "verts",
                "max",
                "area0",
                "area1",
                "perim0",
                "perim1",
                "iface",
                "seconds"
            ));
            for r in runs {
                let rel = |a: f64, e: f64| (a - e) / e;
                s.push_str(&format!(
                    "{:<26} {:>9.0} {:>9} {:>+11.3e} {:>+11.3e} {:>+11.3e} {:>+11.3e} {:>9.2e} {:>8.1}\n",
                    r.label(),
                    r.vertices_mean,
                    r.vertices_max,
                    rel(r.area_initial, EXACT_AREA),
                    rel(r.area_final, EXACT_AREA),
                    rel(r.perimeter_initial, EXACT_PERIMETER),
                    rel(r.perimeter_final, EXACT_PERIMETER),
                    r.interface_to_exact_max.max(r.exact_to_interface_max),
                    r.seconds
                ));
            }
        }
        s
    }
}
