//! The options of the adaptation driver ([`AdaptOptions`]) and what it reports
//! ([`AdaptReport`], one [`PassReport`] per pass): plain data shared by the driver, the cycle
//! and the per-dimension operators.

use super::params::MetricInterpolation;
use crate::error::{Error, Result};
use serde::Serialize;

/// Options of [`adapt`](super::adapt). Build with `AdaptOptions::default().l_max(1.5).max_cycles(10)`.
#[derive(Debug, Clone, Serialize)]
pub struct AdaptOptions {
    /// Edges shorter than this in the metric are collapsed (default `1/sqrt(2)`).
    pub l_min: f64,
    /// Edges longer than this are split (default `sqrt(2)`).
    pub l_max: f64,
    /// Quality floor as a maximal `Q_ani`: collapses and moves may not create a worse triangle
    /// unless the ball was already worse (default 5).
    pub q_max: f64,
    /// How far a boundary/interface vertex removed by a collapse may lie off the new segment
    /// (absolute distance; default 0: polygonal curves keep their exact shape).
    pub curve_tol: f64,
    /// Use the anisotropic Delaunay insertion kernel instead of plain splits where possible
    /// (default true: on the r = 0.5 circle, eps 1e-4, it gave mean `Q_ani` 1.040 vs 1.043,
    /// worst 1.32 vs 1.37, and a quarter of the flips).
    pub insertion: bool,
    /// Maximal number of split/collapse cycles (default 20).
    pub max_cycles: usize,
    /// Final flip + smoothing sweeps after the cycles (default 3).
    pub final_sweeps: usize,
    /// Verify `Mesh2::check` after every pass and fail with the defect (for tests; costs time).
    pub check_each_pass: bool,
    /// Metric interpolation at new vertices when no source gives the metric (default
    /// log-Euclidean; `anisomesh adapt --input M --sol S` with a tensor field uses linear sizes,
    /// as mmg2d does with the same files).
    pub interpolation: MetricInterpolation,
    /// Which vertices the smoothing sweep of each cycle examines (default
    /// [`CycleSmoothing::Relaxing`]).
    pub cycle_smoothing: CycleSmoothing,
    /// Size gradation during the adaptation (default `None`): at the start of the first cycle and
    /// of every cycle after which the mesh has grown by 10% the vertex metric is graded over the current mesh with this growth factor `β > 1`
    /// ([`crate::metric::gradate`], the `-hgrad` of mmg2d), so that a metric given on a coarse
    /// background cannot jump by orders of magnitude between neighbouring vertices of the
    /// adapted mesh. Sizes only shrink. Only for metrics that no [`MetricSource`](super::MetricSource) re-evaluates.
    pub gradation: Option<f64>,
    /// Stop with [`crate::Error::TooLarge`] when a refinement pass leaves more vertices than
    /// this (default `None`: no limit): a guard against a metric that asks for far more
    /// vertices than expected. The mesh is then left as the pass left it (valid, not compacted).
    pub max_vertices: Option<usize>,
}

/// Which vertices the one smoothing sweep of a split/collapse cycle examines. The final sweeps
/// after the cycles relax from one to the next (each re-examines the neighbours of the previous
/// final sweep's moves).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Serialize)]
pub enum CycleSmoothing {
    /// The vertices whose ball changed since the previous cycle's sweep began: those the
    /// cycle's splits, collapses and flips touched, and the neighbours of the previous sweep's
    /// moves, so the relaxation continues from cycle to cycle.
    #[default]
    Relaxing,
    /// Only the vertices whose ball the cycle's own splits, collapses and flips changed. On the
    /// 10^5..10^6-vertex metric-file benchmark this is 1.3-1.6x faster for the whole
    /// adaptation, with edges in range 98.4% instead of 98.9% and mean `Q_ani` 1.047 instead
    /// of 1.038 (`examples/adapt_speed`).
    Touched,
}

impl Default for AdaptOptions {
    fn default() -> Self {
        AdaptOptions {
            l_min: std::f64::consts::FRAC_1_SQRT_2,
            l_max: std::f64::consts::SQRT_2,
            q_max: 5.0,
            curve_tol: 0.0,
            insertion: true,
            max_cycles: 20,
            final_sweeps: 3,
            check_each_pass: false,
            interpolation: MetricInterpolation::LogEuclidean,
            cycle_smoothing: CycleSmoothing::Relaxing,
            gradation: None,
            max_vertices: None,
        }
    }
}

impl AdaptOptions {
    /// Sets `l_min`.
    pub fn l_min(mut self, v: f64) -> Self {
        self.l_min = v;
        self
    }
    /// Sets `l_max`.
    pub fn l_max(mut self, v: f64) -> Self {
        self.l_max = v;
        self
    }
    /// Sets the quality floor (maximal `Q_ani`).
    pub fn q_max(mut self, v: f64) -> Self {
        self.q_max = v;
        self
    }
    /// Sets the curve tolerance of collapses.
    pub fn curve_tol(mut self, v: f64) -> Self {
        self.curve_tol = v;
        self
    }
    /// Turns the Delaunay insertion kernel on or off.
    pub fn insertion(mut self, v: bool) -> Self {
        self.insertion = v;
        self
    }
    /// Sets the cycle cap.
    pub fn max_cycles(mut self, v: usize) -> Self {
        self.max_cycles = v;
        self
    }
    /// Sets the number of final flip/smooth sweeps.
    pub fn final_sweeps(mut self, v: usize) -> Self {
        self.final_sweeps = v;
        self
    }
    /// Sets the metric interpolation at new vertices.
    pub fn interpolation(mut self, v: MetricInterpolation) -> Self {
        self.interpolation = v;
        self
    }
    /// Sets the size gradation applied at the start of every cycle (`None`: none).
    pub fn gradation(mut self, v: Option<f64>) -> Self {
        self.gradation = v;
        self
    }
    /// Sets the vertex limit of the refinement passes (`None`: none).
    pub fn max_vertices(mut self, v: Option<usize>) -> Self {
        self.max_vertices = v;
        self
    }
    /// Sets which vertices the smoothing sweep of each cycle examines.
    pub fn cycle_smoothing(mut self, v: CycleSmoothing) -> Self {
        self.cycle_smoothing = v;
        self
    }
    /// Turns on `check()` after every pass.
    pub fn check_each_pass(mut self, v: bool) -> Self {
        self.check_each_pass = v;
        self
    }

    pub(crate) fn validate(&self) -> Result<()> {
        if !(self.l_min > 0.0 && self.l_max.is_finite() && 2.0 * self.l_min <= self.l_max) {
            return Err(Error::InvalidInput(format!(
                "adapt: need 0 < 2 l_min <= l_max (got l_min {}, l_max {})",
                self.l_min, self.l_max
            )));
        }
        if let Some(b) = self.gradation {
            if !(b > 1.0 && b.is_finite()) {
                return Err(Error::InvalidInput(format!(
                    "adapt: the gradation factor must be finite and > 1 (got {b})"
                )));
            }
        }
        if self.q_max.is_nan() || self.q_max < 1.0 {
            return Err(Error::InvalidInput(format!(
                "adapt: the quality floor q_max must be >= 1 (got {})",
                self.q_max
            )));
        }
        Ok(())
    }
}

/// The kind of a pass.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
pub enum PassKind {
    /// Refinement: long edges split, or new vertices inserted by the Delaunay kernel.
    Split,
    /// Short edges collapsed.
    Collapse,
    /// Edges flipped toward better quality.
    Flip,
    /// Vertices relocated toward better quality.
    Smooth,
}

/// One pass: what, how many operations, how long.
#[derive(Debug, Clone, Serialize)]
pub struct PassReport {
    /// Which operator.
    pub kind: PassKind,
    /// Operations applied (new vertices, collapses, flips or moves).
    pub count: usize,
    /// Wall-clock seconds of the pass.
    pub seconds: f64,
}

/// What [`adapt`](super::adapt) did. `converged` means the last cycle split or collapsed at most one edge per
/// 2,000 vertices, or made as many splits as collapses (at most 8 each) and the same numbers as
/// the cycle before (a split/collapse limit cycle); `converged == false` means the cycle cap was reached with edges still
/// out of range: the mesh is valid, only not fully adapted.
#[derive(Debug, Clone, Default, Serialize)]
pub struct AdaptReport {
    /// Split/collapse cycles run.
    pub cycles: usize,
    /// Every pass in order.
    pub passes: Vec<PassReport>,
    /// New vertices (edge splits and Delaunay insertions).
    pub splits: usize,
    /// Edge collapses.
    pub collapses: usize,
    /// Edge flips.
    pub flips: usize,
    /// Vertex moves.
    pub moves: usize,
    /// Whether the stopping rule was met before the cycle cap (see above).
    pub converged: bool,
    /// Total wall-clock seconds.
    pub seconds: f64,
    /// Time spent grading the metric ([`AdaptOptions::gradation`]).
    pub gradation_seconds: f64,
}

impl AdaptReport {
    /// Records one pass of `kind` that made `count` changes in `seconds`.
    pub(crate) fn record_pass(&mut self, kind: PassKind, count: usize, seconds: f64) {
        match kind {
            PassKind::Split => self.splits += count,
            PassKind::Collapse => self.collapses += count,
            PassKind::Flip => self.flips += count,
            PassKind::Smooth => self.moves += count,
        }
        self.passes.push(PassReport {
            kind,
            count,
            seconds,
        });
    }

    /// Totals over the passes of one kind: `(number of passes, operations, seconds)`.
    pub fn pass_totals(&self, kind: PassKind) -> (usize, usize, f64) {
        self.passes
            .iter()
            .filter(|p| p.kind == kind)
            .fold((0, 0, 0.0), |(n, c, s), p| {
                (n + 1, c + p.count, s + p.seconds)
            })
    }

    /// Adds the counts, passes and time of `other` (one more adaptation round) to `self`;
    /// `converged` is left to the caller, whose stopping rule decides it.
    pub fn absorb(&mut self, other: &AdaptReport) {
        self.cycles += other.cycles;
        self.splits += other.splits;
        self.collapses += other.collapses;
        self.flips += other.flips;
        self.moves += other.moves;
        self.passes.extend(other.passes.iter().cloned());
        self.seconds += other.seconds;
        self.gradation_seconds += other.gradation_seconds;
    }
}
