//! What the steps and queries of a [`super::LevelSetBackend`] return: the per-step report, the
//! curvature samples.

use super::Dimension;
use serde::Serialize;

/// Wall-clock seconds of the phases of one step; a phase a back end does not have stays 0.
#[derive(Debug, Clone, Copy, Default, PartialEq, Serialize)]
pub struct PhaseTimes {
    /// Rebuilding the discretisation around the new zero level (re-adapting a mesh, rebuilding
    /// a narrow band, re-fitting an interface mesh).
    pub rebuild: f64,
    /// Assembling matrices and right-hand sides.
    pub assembly: f64,
    /// Solving the linear systems (and, for advection, tracing the characteristics).
    pub solve: f64,
    /// Redistancing.
    pub redistance: f64,
}

impl PhaseTimes {
    /// The sum of the phases.
    pub fn total(&self) -> f64 {
        self.rebuild + self.assembly + self.solve + self.redistance
    }
}

/// The outcome of one step of a back end (mean curvature, advection or redistancing).
#[derive(Debug, Clone, Default, PartialEq, Serialize)]
pub struct StepReport {
    /// The time after the step.
    pub time: f64,
    /// Degrees of freedom of the level-set function after the step.
    pub dof: usize,
    /// Wall-clock seconds of the whole step.
    pub seconds: f64,
    /// The seconds by phase.
    pub phases: PhaseTimes,
    /// Iterations of the linear solvers, summed over the step.
    pub linear_iterations: usize,
    /// Iterations of the back end's outer loop in the step (fixed-point iterations of the
    /// transient adaptation, 004 §3.5; nested iterations of the band, 000 §2.3; re-adaptation
    /// rounds).
    pub inner_iterations: usize,
    /// Whether every linear solve and inner loop reached its tolerance. `false` is a valid
    /// result of lower accuracy, not an error.
    pub converged: bool,
}

impl StepReport {
    /// The report of a step about to run: converged until a solve or inner loop says otherwise.
    pub(crate) fn begin() -> StepReport {
        StepReport {
            converged: true,
            ..StepReport::default()
        }
    }
}

/// Curvature samples on the zero level: `values[i]` is `κ = div(∇u/|∇u|)` at `points[i]`.
#[derive(Debug, Clone, PartialEq)]
pub struct CurvatureSamples<D: Dimension> {
    /// Points on the zero level.
    pub points: Vec<D::Point>,
    /// The curvature at each point.
    pub values: Vec<f64>,
}

impl<D: Dimension> CurvatureSamples<D> {
    /// The number of samples.
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Whether there are no samples.
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// The arithmetic mean of the samples (NaN when there are none).
    pub fn mean(&self) -> f64 {
        self.values.iter().sum::<f64>() / self.values.len() as f64
    }

    /// The smallest and largest sample (`(inf, -inf)` when there are none).
    pub fn range(&self) -> (f64, f64) {
        self.values
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &k| {
                (a.min(k), b.max(k))
            })
    }

    /// The largest relative deviation `max |κ_i − κ| / |κ|` from a reference curvature `κ`
    /// (001 §5's error measure).
    pub fn max_rel_error(&self, exact: f64) -> f64 {
        self.values
            .iter()
            .map(|k| ((k - exact) / exact).abs())
            .fold(0.0, f64::max)
    }
}
