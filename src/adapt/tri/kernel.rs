//! The metric quantities the operators evaluate, as thin wrappers over [`crate::metric`] so that
//! each operator reads `edge_length(..)` and `q_ani(..)` (no metric mathematics lives here).

use crate::geom::DVec2;
use crate::metric::{self, Sym2};

/// Metric length of the edge `pa -> pb` with endpoint metrics `ma`, `mb` ([`metric::edge_length`],
/// 004 §3.3).
#[inline]
pub fn edge_length(pa: DVec2, pb: DVec2, ma: &Sym2, mb: &Sym2) -> f64 {
    metric::edge_length(pa, pb, ma, mb)
}

/// `Q_ani` of the triangle `p` given the logarithms of its vertex metrics: the element metric
/// `exp((ln M_a + ln M_b + ln M_c) / 3)` is [`metric::element_metric`] with the logarithms cached.
#[inline]
pub fn q_ani_log(p: [DVec2; 3], l: [&Sym2; 3]) -> f64 {
    let s = l[0].add(l[1]).add(l[2]).scale(1.0 / 3.0);
    metric::q_ani(p, &s.exp())
}

/// `Q_ani` of the triangle `p` in the arithmetic mean of its vertex metrics: no eigen-solve, the
/// fast variant the operators use for their accept/reject decisions (within a few percent of
/// [`q_ani_log`] where the metric varies smoothly, and never optimistic: the arithmetic mean
/// dominates the log-Euclidean mean, so lengths are not under-estimated).
#[inline]
pub fn q_ani_mean(p: [DVec2; 3], m: [&Sym2; 3]) -> f64 {
    let s = m[0].add(m[1]).add(m[2]).scale(1.0 / 3.0);
    metric::q_ani(p, &s)
}

/// Weighted log-Euclidean interpolation of up to three metrics ([`metric::interpolate_log`]).
pub fn interpolate(w: &[(f64, &Sym2)]) -> Sym2 {
    let mut items = [(0.0, Sym2::IDENTITY); 3];
    let n = w.len().min(3);
    for k in 0..n {
        items[k] = (w[k].0, *w[k].1);
    }
    metric::interpolate_log(&items[..n])
}
