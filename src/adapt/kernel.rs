//! The metric quantities the operators evaluate, as thin wrappers so that each operator reads
//! `len(a, b)` and `quality(p, m)`.
//!
//! TEMPORARY: until `crate::metric` lands on main these are local; they will call
//! `metric::edge_length` and `metric::q_ani` then.

use crate::geom::DVec2;
use crate::metric::Sym2;

/// Metric length of the edge `pa -> pb` with endpoint metrics `ma`, `mb` (geometric
/// interpolation of the endpoint lengths, as MMG).
#[inline]
pub fn edge_length(pa: DVec2, pb: DVec2, ma: &Sym2, mb: &Sym2) -> f64 {
    let e = pb - pa;
    let la = ma.quad(e).sqrt();
    let lb = mb.quad(e).sqrt();
    let r = la / lb;
    if (r - 1.0).abs() < 1e-3 {
        0.5 * (la + lb)
    } else {
        (la - lb) / r.ln()
    }
}

/// `Q_ani` of 004 §3.4 for the triangle `p` in the element metric (arithmetic mean of the three
/// vertex metrics): 1 for a unit equilateral triangle, larger is worse; infinite for an inverted
/// or flat triangle.
#[inline]
pub fn q_ani(p: [DVec2; 3], m: [&Sym2; 3]) -> f64 {
    let mk = Sym2::new(
        (m[0].xx + m[1].xx + m[2].xx) / 3.0,
        (m[0].xy + m[1].xy + m[2].xy) / 3.0,
        (m[0].yy + m[1].yy + m[2].yy) / 3.0,
    );
    let (e0, e1, e2) = (p[1] - p[0], p[2] - p[1], p[0] - p[2]);
    let area = 0.5 * e0.perp_dot(p[2] - p[0]);
    if area <= 0.0 {
        return f64::INFINITY;
    }
    let s = mk.quad(e0) + mk.quad(e1) + mk.quad(e2);
    s / (4.0 * 3f64.sqrt() * area * mk.det().sqrt())
}

/// Log-Euclidean interpolation of metrics with weights summing to one.
pub fn interpolate(w: &[(f64, &Sym2)]) -> Sym2 {
    let mut acc = Sym2::new(0.0, 0.0, 0.0);
    for (wi, m) in w {
        acc = acc.add(&m.map_eigen(|l| l.ln()).scale(*wi));
    }
    acc.map_eigen(f64::exp)
}
