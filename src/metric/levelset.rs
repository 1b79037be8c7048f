//! The geometric metric of a level-set interface, 004 §4.2 eq. (6), and metric bounds.
//!
//! With `u` the (signed-distance-like) level-set function, `hmin` the smallest allowed size and
//! `ε` the prescribed bound on the Hausdorff distance between the interface and its piecewise
//! affine approximation,
//!
//! ```text
//! M = ∇u ∇u^T / hmin^2 + |D²u| / ε                                   (004 eq. (6))
//! ```
//!
//! The first term asks for size `hmin` across the interface (`|∇u| = 1` for a distance), the
//! second for sizes `l_i = sqrt(ε / κ_i)` along the principal curvature directions (Corollaries 1
//! and 2 of 004: `d(Γ_h, Γ) ≲ l² κ`). `|D²u|` is the Hessian with its eigenvalues replaced by their
//! absolute values, so that `M` is positive semi-definite; it may still be singular (a straight
//! interface far from any curvature), which is why the caller applies [`MetricBounds`].

use super::SymTensor;
use crate::error::{Error, Result};
#[cfg(test)]
use {super::Sym2, crate::geom::DVec2};

/// `∇u ∇u^T / hmin² + |D²u| / ε`, 004 eq. (6), unbounded (positive semi-definite; apply
/// [`MetricBounds::apply`] before use). Needs `hmin > 0` and `ε > 0`; otherwise the entries are
/// infinite or NaN. The same formula in 2D ([`super::Sym2`]) and 3D ([`super::Sym3`]).
pub fn geometric_metric<const D: usize, S: SymTensor<D>>(
    grad: S::Vec,
    hess: &S,
    hmin: f64,
    eps: f64,
) -> S {
    S::outer(grad)
        .scale(1.0 / (hmin * hmin))
        .add(&hess.abs().scale(1.0 / eps))
}

/// Size bounds applied to every metric: sizes in `[hmin, hmax]` and size ratio at most
/// `max_aniso` (see [`super::Sym2::bound`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MetricBounds {
    /// Smallest size.
    pub hmin: f64,
    /// Largest size.
    pub hmax: f64,
    /// Largest ratio of the sizes of one metric.
    pub max_aniso: f64,
}

impl MetricBounds {
    /// Checked constructor: `0 < hmin <= hmax < inf` and `max_aniso >= 1`.
    pub fn new(hmin: f64, hmax: f64, max_aniso: f64) -> Result<MetricBounds> {
        let b = MetricBounds {
            hmin,
            hmax,
            max_aniso,
        };
        b.validate()?;
        Ok(b)
    }

    /// An error unless `0 < hmin <= hmax < inf` and `1 <= max_aniso` (`max_aniso` may be
    /// infinite: no anisotropy limit).
    pub fn validate(&self) -> Result<()> {
        let ok = self.hmin > 0.0
            && self.hmin <= self.hmax
            && self.hmax.is_finite()
            && self.max_aniso >= 1.0;
        if ok {
            Ok(())
        } else {
            Err(Error::InvalidInput(format!(
                "bad metric bounds hmin = {}, hmax = {}, max_aniso = {}: need 0 < hmin <= hmax \
                 (finite) and max_aniso >= 1",
                self.hmin, self.hmax, self.max_aniso
            )))
        }
    }

    /// `m` bounded: eigenvalues clamped to `[1/hmax², 1/hmin²]`, then the anisotropy limited
    /// ([`SymTensor::bound`]; in 2D exactly [`super::Sym2::bound`]).
    #[inline]
    pub fn apply<const D: usize, S: SymTensor<D>>(&self, m: &S) -> S {
        m.bound(self.hmin, self.hmax, self.max_aniso)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn circle_distance_gives_normal_and_tangential_sizes() {
        // u = |x| - R at x = (R, 0): ∇u = (1, 0), D²u = diag(0, 1/R).
        let r = 0.5;
        let (hmin, eps) = (1e-3, 1e-4);
        let m = geometric_metric(DVec2::X, &Sym2::new(0.0, 0.0, 1.0 / r), hmin, eps);
        assert!((m.xx - 1.0 / (hmin * hmin)).abs() < 1e-6);
        assert_eq!(m.xy, 0.0);
        // Tangential size sqrt(ε R) = sqrt(ε / κ).
        let (h, _) = m.sizes();
        assert!((h[0] - (eps * r).sqrt()).abs() < 1e-15, "{h:?}");
        // A negative curvature gives the same metric (|D²u|).
        let m2 = geometric_metric(DVec2::X, &Sym2::new(0.0, 0.0, -1.0 / r), hmin, eps);
        assert_eq!(m, m2);
    }

    #[test]
    fn bounds_validate_and_apply() {
        assert!(MetricBounds::new(0.0, 1.0, 10.0).is_err());
        assert!(MetricBounds::new(0.1, 0.01, 10.0).is_err());
        assert!(MetricBounds::new(0.1, 1.0, 0.5).is_err());
        assert!(MetricBounds::new(0.1, f64::NAN, 2.0).is_err());
        let b = MetricBounds::new(1e-3, 0.5, 100.0).unwrap();
        let m = geometric_metric(DVec2::ZERO, &Sym2::default(), 1e-3, 1e-4);
        assert_eq!(b.apply(&m), Sym2::iso(0.5));
        let m = geometric_metric(DVec2::new(0.0, 1.0), &Sym2::default(), 1e-4, 1e-4);
        let (h, _) = b.apply(&m).sizes();
        assert!(
            (h[1] - 1e-3).abs() < 1e-15 && (h[0] - 0.1).abs() < 1e-13,
            "{h:?}"
        );
    }
}
