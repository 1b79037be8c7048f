//! The geometric metric of 004 eq. (6) with size bounds and growth outside a band around the
//! zero level, written once for `Sym2` and `Sym3`: the metric `anisomesh metric` writes for a
//! level set.
//!
//! With `u` the signed distance, `∇u`, `D²u` its derivatives: `M = bounds(∇u∇uᵀ/hmin² +
//! |D²u|/ε)` where `|u| <= band`; beyond, every size `h_i = λ_i^{-1/2}` grows as
//! `min(hmax, h_i + grade (|u| - band))` (an analytic gradation, continuous across the band's
//! edge).

use super::levelset::{geometric_metric, MetricBounds};
use super::SymTensor;

/// The parameters of [`banded_metric`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandedMetric {
    /// Interface accuracy ε of eq. (6).
    pub eps: f64,
    /// Size bounds (`hmin` is also the normal size of eq. (6)).
    pub bounds: MetricBounds,
    /// Half-width of the band where eq. (6) applies.
    pub band: f64,
    /// Growth rate of the sizes outside the band (`inf`: `hmax` right outside).
    pub grade: f64,
}

/// The metric at a point with level-set value `u`, gradient `grad`, Hessian `hess` (module
/// documentation).
pub fn banded_metric<const D: usize, S: SymTensor<D>>(
    p: &BandedMetric,
    u: f64,
    grad: S::Vec,
    hess: &S,
) -> S {
    let b = &p.bounds;
    let m = b.apply(&geometric_metric(grad, hess, b.hmin, p.eps));
    let d = u.abs() - p.band;
    if d <= 0.0 {
        return m;
    }
    if !p.grade.is_finite() {
        return S::iso(b.hmax);
    }
    let (l, v) = m.eigen();
    let grow = |l: f64| {
        let h = (1.0 / l.sqrt() + p.grade * d).min(b.hmax);
        1.0 / (h * h)
    };
    S::from_eigen(l.map(grow), v)
}
