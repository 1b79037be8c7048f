//! Interpolation-error metrics from Hessians: the multiscale `L^p` metric of the continuous-mesh
//! framework (Loseille & Alauzet, "Continuous mesh framework", SIAM J. Numer. Anal. 2011, part II).
//!
//! For a P1 interpolation of `u` with Hessian `H` on a 2D domain, the metric minimising the
//! `L^p` norm of the interpolation error at a given complexity `C` is
//!
//! ```text
//! M_Lp = D det(|H|)^{-1/(2p+2)} |H|,     D = C / ∫_Ω det(|H|)^{p/(2p+2)} dx,
//! ```
//!
//! (`-1/(2p+d)` with `d = 2`; `sqrt(det M_Lp) = D det|H|^{p/(2p+2)}`, so `D` makes
//! `C(M_Lp) = C`). `p = 1, 2` weight the small-amplitude features more than `p = ∞`
//! (`M = D |H|`). The target complexity comes from the target vertex count through
//! `C = sqrt(3) N / 2` ([`super::complexity()`]).
//!
//! **Practicalities.**
//! - `|H|` is floored before the normalisation: its small eigenvalue is raised to
//!   `λ_max / max_aniso²` (the anisotropy limit is applied *before* `det` is taken, otherwise a
//!   one-dimensional feature, `det H = 0`, would blow the normalisation up), and all eigenvalues to
//!   `1e-12` times the largest eigenvalue of the field (a zero Hessian then gets the largest size
//!   after bounding). An identically zero Hessian field gives the uniform metric.
//! - Bounding ([`MetricBounds`]) changes the complexity, so `D` is re-solved on the *bounded*
//!   field: `f(ln D) = ln C(bound(D M_0)) - ln C` is non-decreasing with slope in `[0, 1]`, and is
//!   solved by fixed-point/secant steps and, once bracketed, Illinois regula falsi, to a relative
//!   `2e-3` in complexity. If the bounds make the target unreachable (every size clamped), the
//!   closest field is returned and [`LpReport::reached`] is false.

use rayon::prelude::*;

use super::complexity::{complexity_for_vertices, complexity_of_density};
use super::levelset::MetricBounds;
use super::Sym2;
use crate::error::{Error, Result};
use crate::mesh::Mesh2;

/// Relative floor of Hessian eigenvalues (times the largest eigenvalue of the field).
pub const HESSIAN_FLOOR_REL: f64 = 1e-12;

/// Relative tolerance on the complexity reached by the normalisation.
pub const LP_COMPLEXITY_TOL: f64 = 2e-3;

/// How the normalisation went.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LpReport {
    /// The factor `D` of the (bounded) metric.
    pub scale: f64,
    /// Complexity of the returned field.
    pub complexity: f64,
    /// Complexity asked for (`sqrt(3) N / 2`).
    pub target_complexity: f64,
    /// Complexity evaluations made.
    pub evaluations: usize,
    /// Whether `|complexity / target - 1| <= LP_COMPLEXITY_TOL`.
    pub reached: bool,
}

/// The multiscale `L^p` metric `D det(|H|)^{-1/(2p+2)} |H|`, bounded, with `D` chosen so that the
/// bounded field predicts `target_vertices` vertices (module documentation). `p > 0` (`p = ∞`
/// allowed). Errors: a Hessian field of the wrong length or with non-finite entries (naming the
/// vertex), bad bounds, `p <= 0`, `target_vertices == 0`, or a mesh of zero area.
pub fn multiscale_lp(
    mesh: &Mesh2,
    hessians: &[Sym2],
    p: f64,
    target_vertices: usize,
    bounds: &MetricBounds,
) -> Result<Vec<Sym2>> {
    lp_metric(mesh, hessians, p, target_vertices, bounds, false).map(|(m, _)| m)
}

/// The isotropic variant of [`multiscale_lp`]: `|H|` replaced by `λ_max(|H|) I`, so
/// `M = D λ_max^{p/(p+1)} I`.
pub fn interpolation_error_metric_iso(
    mesh: &Mesh2,
    hessians: &[Sym2],
    p: f64,
    target_vertices: usize,
    bounds: &MetricBounds,
) -> Result<Vec<Sym2>> {
    lp_metric(mesh, hessians, p, target_vertices, bounds, true).map(|(m, _)| m)
}

/// [`multiscale_lp`] (or its isotropic variant) with the report of the normalisation.
pub fn lp_metric(
    mesh: &Mesh2,
    hessians: &[Sym2],
    p: f64,
    target_vertices: usize,
    bounds: &MetricBounds,
    isotropic: bool,
) -> Result<(Vec<Sym2>, LpReport)> {
    bounds.validate()?;
    if p.is_nan() || p <= 0.0 {
        return Err(Error::InvalidInput(format!(
            "L^p norm exponent p = {p} must be > 0"
        )));
    }
    if target_vertices == 0 {
        return Err(Error::InvalidInput(
            "the target vertex count must be positive".into(),
        ));
    }
    if hessians.len() != mesh.n_points() {
        return Err(Error::InvalidField {
            name: "hessian".into(),
            msg: format!(
                "{} tensors for {} vertices",
                hessians.len(),
                mesh.n_points()
            ),
        });
    }
    if let Some(v) = hessians
        .iter()
        .position(|h| !(h.xx.is_finite() && h.xy.is_finite() && h.yy.is_finite()))
    {
        return Err(Error::InvalidField {
            name: "hessian".into(),
            msg: format!("non-finite entry at vertex {v}: {:?}", hessians[v]),
        });
    }

    let m0 = unscaled_metrics(hessians, p, bounds.max_aniso, isotropic);
    let d0: Vec<f64> = m0.iter().map(|m| m.det().sqrt()).collect();
    let c0 = complexity_of_density(mesh, &d0);
    if !(c0 > 0.0 && c0.is_finite()) {
        return Err(Error::InvalidInput(format!(
            "cannot normalise a metric on a mesh of area {} (complexity {c0})",
            mesh.area()
        )));
    }
    let target = complexity_for_vertices(target_vertices as f64);
    let eval = |x: f64| -> (Vec<Sym2>, f64) {
        let s = x.exp();
        let scale_bound = |m: &Sym2| bounds.apply(&m.scale(s));
        // Order-preserving parallel map: the result does not depend on the thread count.
        let m: Vec<Sym2> = if m0.len() >= 4096 {
            m0.par_iter().map(scale_bound).collect()
        } else {
            m0.iter().map(scale_bound).collect()
        };
        let d: Vec<f64> = m.iter().map(|m| m.det().sqrt()).collect();
        let c = complexity_of_density(mesh, &d);
        (m, c)
    };
    let tol = (1.0 + LP_COMPLEXITY_TOL).ln();
    let mut x = (target / c0).ln();
    let (mut m, mut c) = eval(x);
    let mut f = (c / target).ln();
    let mut evaluations = 1;
    // Bracket ends (x, f) with f < 0 and f > 0.
    let mut lo: Option<(f64, f64)> = None;
    let mut hi: Option<(f64, f64)> = None;
    let mut prev: Option<(f64, f64)> = None;
    let mut side = 0i32; // Illinois: which end was kept twice
    let mut best = (f.abs(), x, c);
    while f.abs() > tol && evaluations < 60 {
        if f < 0.0 {
            lo = Some((x, f));
        } else {
            hi = Some((x, f));
        }
        let next = match (lo, hi) {
            (Some((xl, fl)), Some((xh, fh))) => {
                // Illinois regula falsi: halve the value of an end kept twice in a row.
                let (fl, fh) = match side {
                    s if s <= -2 => (fl * 0.5, fh),
                    s if s >= 2 => (fl, fh * 0.5),
                    _ => (fl, fh),
                };
                let xn = xl - fl * (xh - xl) / (fh - fl);
                if xn.is_finite() && xn > xl.min(xh) && xn < xl.max(xh) {
                    xn
                } else {
                    0.5 * (xl + xh)
                }
            }
            _ => {
                // Not yet bracketed: secant slope clipped to [1e-3, 1] (the true slope is in
                // [0, 1]), or a fixed-point step.
                let slope = match prev {
                    Some((xp, fp)) if x != xp => ((f - fp) / (x - xp)).clamp(1e-3, 1.0),
                    _ => 1.0,
                };
                if let Some((xp, fp)) = prev {
                    if (f - fp).abs() < 1e-9 * (x - xp).abs() && (x - xp).abs() > 1.0 {
                        break; // flat: every size clamped, the target cannot be reached
                    }
                }
                x - f / slope
            }
        };
        prev = Some((x, f));
        x = next;
        let r = eval(x);
        m = r.0;
        c = r.1;
        let fn_ = (c / target).ln();
        evaluations += 1;
        side = if fn_ < 0.0 {
            if side < 0 {
                side - 1
            } else {
                -1
            }
        } else if side > 0 {
            side + 1
        } else {
            1
        };
        f = fn_;
        if f.abs() < best.0 {
            best = (f.abs(), x, c);
        }
    }
    if f.abs() > best.0 {
        let r = eval(best.1);
        m = r.0;
        c = r.1;
        x = best.1;
        evaluations += 1;
    }
    let report = LpReport {
        scale: x.exp(),
        complexity: c,
        target_complexity: target,
        evaluations,
        reached: (c / target - 1.0).abs() <= LP_COMPLEXITY_TOL,
    };
    Ok((m, report))
}

/// `det(|H|)^{-1/(2p+2)} |H|` per vertex, with `|H|` floored (module documentation).
fn unscaled_metrics(hessians: &[Sym2], p: f64, max_aniso: f64, isotropic: bool) -> Vec<Sym2> {
    let eig: Vec<([f64; 2], [crate::geom::DVec2; 2])> =
        hessians.iter().map(|h| h.abs().eigen()).collect();
    let lmax = eig.iter().map(|(l, _)| l[1]).fold(0.0, f64::max);
    if lmax == 0.0 {
        return vec![Sym2::IDENTITY; hessians.len()];
    }
    let floor = (HESSIAN_FLOOR_REL * lmax).max(f64::MIN_POSITIVE);
    let a2 = max_aniso * max_aniso;
    let expo = if p.is_infinite() {
        0.0
    } else {
        -1.0 / (2.0 * p + 2.0)
    };
    eig.into_iter()
        .map(|(l, v)| {
            let l1 = l[1].max(floor);
            let l0 = if isotropic {
                l1
            } else {
                l[0].max(l1 / a2).max(floor)
            };
            let s = (l0 * l1).powf(expo);
            Sym2::from_eigen([s * l0, s * l1], v)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec2;
    use crate::mesh::GridPattern;
    use crate::metric::complexity::{complexity, predicted_vertices};

    fn unit_square(n: usize) -> Mesh2 {
        Mesh2::rectangle(DVec2::ZERO, DVec2::ONE, n, n, GridPattern::UnionJack).unwrap()
    }

    #[test]
    fn constant_hessian_gives_the_closed_form() {
        let mesh = unit_square(8);
        let h = Sym2::from_sizes([1.0, 0.1], DVec2::new(1.0, 2.0)); // |H| with det 100
        let hs = vec![h; mesh.n_points()];
        let free = MetricBounds::new(1e-9, 1e9, 1e9).unwrap();
        let n = 5000;
        for p in [1.0, 2.0, f64::INFINITY] {
            let (m, r) = lp_metric(&mesh, &hs, p, n, &free, false).unwrap();
            assert!(r.reached && r.evaluations == 1, "{r:?}");
            // C = D det^{p/(2p+2)} on the unit square, D = C / det^{p/(2p+2)}.
            let c = complexity_for_vertices(n as f64);
            let e = if p.is_infinite() {
                0.5
            } else {
                p / (2.0 * p + 2.0)
            };
            let expo = if p.is_infinite() {
                0.0
            } else {
                -1.0 / (2.0 * p + 2.0)
            };
            let d = c / 100f64.powf(e);
            let expect = h.scale(d * 100f64.powf(expo));
            assert!(m[7].sub(&expect).norm() < 1e-10 * expect.norm(), "p = {p}");
            assert!((predicted_vertices(complexity(&mesh, &m)) / n as f64 - 1.0).abs() < 1e-10);
        }
    }

    #[test]
    fn rejects_bad_input() {
        let mesh = unit_square(2);
        let b = MetricBounds::new(1e-3, 1.0, 100.0).unwrap();
        let mut hs = vec![Sym2::IDENTITY; mesh.n_points()];
        assert!(multiscale_lp(&mesh, &hs, 0.0, 100, &b).is_err());
        assert!(multiscale_lp(&mesh, &hs, 2.0, 0, &b).is_err());
        assert!(multiscale_lp(&mesh, &hs[1..], 2.0, 100, &b).is_err());
        hs[3].xy = f64::NAN;
        let e = multiscale_lp(&mesh, &hs, 2.0, 100, &b).unwrap_err();
        assert!(e.to_string().contains("vertex 3"), "{e}");
    }

    #[test]
    fn zero_hessian_gives_uniform_metric() {
        let mesh = unit_square(4);
        let hs = vec![Sym2::default(); mesh.n_points()];
        let b = MetricBounds::new(1e-3, 1.0, 100.0).unwrap();
        let (m, r) = lp_metric(&mesh, &hs, 2.0, 1000, &b, false).unwrap();
        assert!(r.reached);
        let h = m[0].sizes().0;
        assert!((h[0] - h[1]).abs() < 1e-12 && m.iter().all(|x| *x == m[0]));
        // A target below what hmax allows cannot be reached: all sizes hmax.
        let (m, r) = lp_metric(&mesh, &hs, 2.0, 1, &b, false).unwrap();
        assert!(!r.reached);
        assert!((m[0].sizes().0[0] - 1.0).abs() < 1e-12);
    }
}
