//! One transport run of a [`Case`] through [`anisomesh::advect::run`], and its report: the
//! area and perimeter before and after, the mesh sizes, the time, and for flows that bring the
//! shape back the symmetric-difference area and the Hausdorff distance to the initial shape.

use super::cases::Case;
use anisomesh::adapt::{AdaptOptions, LevelSetMetric};
use anisomesh::advect::{
    self, hausdorff, symmetric_difference, FixedPointOptions, MeshFamily, RunOptions, RunResult,
    StepStats,
};
use anisomesh::error::Result;
use anisomesh::levelset::interface::extract_zero_level;
use serde::Serialize;

/// Which meshes carry the level set.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub enum Family {
    /// Anisotropic adaptation (004 eq. (6)).
    Anisotropic,
    /// The isotropic variant of the same metric.
    Isotropic,
    /// A fixed uniform `n x n` grid.
    Uniform {
        /// Cells per side.
        n: usize,
    },
}

/// The options of one run.
#[derive(Debug, Clone)]
pub struct RunSettings {
    /// The mesh family.
    pub family: Family,
    /// `hmin`, `hmax`, `eps` and `band` of the metric (adapted families).
    pub sizes: [f64; 4],
    /// Growth rate of the sizes away from the band.
    pub grade: f64,
    /// Number of periods.
    pub periods: usize,
    /// Fixed-point iterations per period (at most).
    pub fixed_point_iterations: usize,
    /// Split/collapse cycle cap of each adaptation.
    pub max_cycles: usize,
    /// Geometric redistancing after each period.
    pub redistance: bool,
    /// Quadratic (limited) interpolation at the feet instead of P1.
    pub quadratic: bool,
    /// Sub-steps of the feet (RK4) per period.
    pub substeps: usize,
    /// Restore the initial area after each period.
    pub mass_correction: bool,
    /// Times whose states are kept for the figures.
    pub snapshot_times: Vec<f64>,
}

impl RunSettings {
    /// The defaults of `case`: anisotropic, its sizes and periods.
    pub fn for_case(case: &Case) -> RunSettings {
        RunSettings {
            family: Family::Anisotropic,
            sizes: case.sizes,
            grade: 1.0,
            periods: case.periods,
            fixed_point_iterations: 2,
            max_cycles: 4,
            redistance: true,
            quadratic: false,
            substeps: 4,
            mass_correction: false,
            snapshot_times: Vec::new(),
        }
    }

    /// The library options.
    pub fn options(&self, case: &Case) -> RunOptions {
        let [hmin, hmax, eps, band] = self.sizes;
        let mesh = match self.family {
            Family::Uniform { n } => MeshFamily::Uniform { n },
            f => MeshFamily::Adapted {
                metric: LevelSetMetric {
                    hmin,
                    hmax,
                    eps,
                    band,
                    grade: self.grade,
                    isotropic: f == Family::Isotropic,
                    ..LevelSetMetric::default()
                },
                adapt: AdaptOptions::default().max_cycles(self.max_cycles),
                initial_n: 40,
                initial_rounds: 4,
            },
        };
        RunOptions {
            domain: case.domain,
            t_start: 0.0,
            t_end: case.t_end,
            periods: self.periods,
            mesh,
            fixed_point: FixedPointOptions {
                max_iterations: self.fixed_point_iterations.max(1),
                tol: 1e-4,
                advect: advect::AdvectOptions {
                    limit: true,
                    foot: advect::FootOptions {
                        scheme: advect::FootScheme::Rk4,
                        substeps: self.substeps.max(1),
                    },
                    interp: if self.quadratic {
                        advect::Interpolation::QUADRATIC
                    } else {
                        advect::Interpolation::P1
                    },
                    ..advect::AdvectOptions::default()
                },
                ..FixedPointOptions::default()
            },
            redistance: self.redistance,
            mass_correction: self.mass_correction,
            snapshot_times: self.snapshot_times.clone(),
        }
    }
}

/// The measures of a run (`advect.json`).
#[derive(Debug, Clone, Serialize)]
pub struct AdvectReport {
    /// The case and its inputs.
    pub case: String,
    /// The initial shape.
    pub shape: String,
    /// The velocity `U; V`.
    pub velocity: String,
    /// The domain `[x0, y0, x1, y1]`.
    pub domain: [f64; 4],
    /// The final time.
    pub t_end: f64,
    /// Number of periods.
    pub periods: usize,
    /// The mesh family.
    pub family: Family,
    /// `hmin`, `hmax`, `eps`, `band` (adapted families).
    pub sizes: [f64; 4],
    /// Area of the initial and final `{u < 0}`.
    pub area_initial: f64,
    /// Area of the final `{u < 0}`.
    pub area_final: f64,
    /// Length of the initial and final zero level.
    pub perimeter_initial: f64,
    /// Length of the final zero level.
    pub perimeter_final: f64,
    /// Mean and largest vertex count.
    pub vertices_mean: f64,
    /// Largest vertex count.
    pub vertices_max: usize,
    /// Wall-clock seconds (total, adaptation, advection).
    pub seconds: f64,
    /// Seconds spent adapting.
    pub adapt_seconds: f64,
    /// Seconds spent advecting.
    pub advect_seconds: f64,
    /// `|{u_T < 0} Δ {phi_0 < 0}|` when the exact final shape is the initial one.
    pub area_symmetric_difference: Option<f64>,
    /// Sampled Hausdorff distance between the final and the initial zero levels (same case).
    pub hausdorff: Option<f64>,
    /// The measures after every period.
    pub series: Vec<StepStats>,
}

impl AdvectReport {
    /// Relative area change `(area_final - area_initial) / area_initial`.
    pub fn area_error(&self) -> f64 {
        (self.area_final - self.area_initial) / self.area_initial
    }

    /// The symmetric difference relative to the initial area (NaN when not measured).
    pub fn symmetric_difference_relative(&self) -> f64 {
        self.area_symmetric_difference
            .map_or(f64::NAN, |s| s / self.area_initial)
    }

    /// A short name of the mesh family.
    pub fn label(&self) -> String {
        match self.family {
            Family::Uniform { n } => format!("uniform {n}x{n}"),
            Family::Anisotropic => format!("anisotropic hmin {:.1e}", self.sizes[0]),
            Family::Isotropic => format!("isotropic hmin {:.1e}", self.sizes[0]),
        }
    }

    /// A one-run summary.
    pub fn summary(&self) -> String {
        format!(
            "{} ({}), T = {}, {} periods: {:.1} s (adapt {:.1} s, advect {:.1} s), vertices mean {:.0} max {}\n\
             area {:.8} -> {:.8} ({:+.3e}), perimeter {:.6} -> {:.6}; symmetric difference {:.3e} ({:.3} % of the area), Hausdorff {:.2e}\n",
            self.case,
            self.label(),
            self.t_end,
            self.periods,
            self.seconds,
            self.adapt_seconds,
            self.advect_seconds,
            self.vertices_mean,
            self.vertices_max,
            self.area_initial,
            self.area_final,
            self.area_error(),
            self.perimeter_initial,
            self.perimeter_final,
            self.area_symmetric_difference.unwrap_or(f64::NAN),
            100.0 * self.symmetric_difference_relative(),
            self.hausdorff.unwrap_or(f64::NAN),
        )
    }
}

/// Runs `case` with `settings`; returns the report and the library's result (meshes, frames).
pub fn run(case: &Case, settings: &RunSettings) -> Result<(AdvectReport, RunResult)> {
    let opts = settings.options(case);
    let r = advect::run(&*case.phi0, &case.velocity, &opts)?;
    let (sd, hd) = if case.returns {
        let phi = &*case.phi0;
        let sd = symmetric_difference(&r.last.mesh, &r.last.u, phi, 3)?;
        let a = extract_zero_level(&r.initial.mesh, &r.initial.u)?;
        let b = extract_zero_level(&r.last.mesh, &r.last.u)?;
        (Some(sd), Some(hausdorff(&a, &b, 4)))
    } else {
        (None, None)
    };
    let (lo, hi) = case.domain;
    let first = &r.steps[0];
    let last = r.steps.last().unwrap_or(first);
    let report = AdvectReport {
        case: case.name.clone(),
        shape: case.shape_source.clone(),
        velocity: format!("{}; {}", case.velocity.u.source(), case.velocity.v.source()),
        domain: [lo.x, lo.y, hi.x, hi.y],
        t_end: case.t_end,
        periods: settings.periods,
        family: settings.family,
        sizes: settings.sizes,
        area_initial: first.area,
        area_final: last.area,
        perimeter_initial: first.perimeter,
        perimeter_final: last.perimeter,
        vertices_mean: r.vertices_mean(),
        vertices_max: r.vertices_max(),
        seconds: r.seconds,
        adapt_seconds: r.adapt_seconds,
        advect_seconds: r.advect_seconds,
        area_symmetric_difference: sd,
        hausdorff: hd,
        series: r.steps.clone(),
    };
    Ok((report, r))
}
