//! Metric sources: where the metric (and optionally the P1 fields) at a new vertex come from.
//!
//! A [`MetricSource`] is queried by the operators whenever they create or move a vertex: an
//! analytic source (a shape with exact derivatives) re-evaluates the metric and the level set
//! exactly there, which keeps the adapted mesh consistent with the geometry instead of with an
//! interpolation of it.

use crate::geom::DVec2;
use crate::metric::Sym2;

/// Where the metric at a point comes from. `metric_at` returning `None` means "interpolate from
/// the surrounding vertices"; `fields_at` returning `false` means the same for the P1 fields.
pub trait MetricSource: Sync {
    /// The metric at `p`, or `None` to interpolate.
    fn metric_at(&self, p: DVec2) -> Option<Sym2>;
    /// Writes the values of the carried P1 fields at `p` into `out` and returns `true`, or
    /// returns `false` to interpolate them.
    fn fields_at(&self, _p: DVec2, _out: &mut [f64]) -> bool {
        false
    }
}

/// The source that always interpolates (a given metric field, e.g. read from a `.sol`).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoSource;

impl MetricSource for NoSource {
    fn metric_at(&self, _p: DVec2) -> Option<Sym2> {
        None
    }
}
