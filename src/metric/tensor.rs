//! `Sym2`: a symmetric 2x2 tensor, the storage type of a 2D Riemannian metric (3 numbers).
//!
//! A metric `M` prescribes unit length: a vector `v` has length `sqrt(v^T M v)`. With the spectral
//! decomposition `M = R diag(l1, l2) R^T` the prescribed sizes along the eigenvectors are
//! `h_i = 1 / sqrt(l_i)` (004 §3.3).

use crate::error::{Error, Result};
use crate::geom::DVec2;

/// Symmetric 2x2 matrix `[[xx, xy], [xy, yy]]`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sym2 {
    pub xx: f64,
    pub xy: f64,
    pub yy: f64,
}

impl Sym2 {
    /// The identity.
    pub const IDENTITY: Sym2 = Sym2 {
        xx: 1.0,
        xy: 0.0,
        yy: 1.0,
    };

    /// `[[xx, xy], [xy, yy]]`.
    #[inline]
    pub const fn new(xx: f64, xy: f64, yy: f64) -> Sym2 {
        Sym2 { xx, xy, yy }
    }

    /// `s I`.
    #[inline]
    pub const fn scalar(s: f64) -> Sym2 {
        Sym2 {
            xx: s,
            xy: 0.0,
            yy: s,
        }
    }

    /// The isotropic metric of size `h`: `I / h^2`.
    #[inline]
    pub fn iso(h: f64) -> Sym2 {
        Sym2::scalar(1.0 / (h * h))
    }

    /// The outer product `v v^T`.
    #[inline]
    pub fn outer(v: DVec2) -> Sym2 {
        Sym2::new(v.x * v.x, v.x * v.y, v.y * v.y)
    }

    /// Determinant.
    #[inline]
    pub fn det(&self) -> f64 {
        self.xx.mul_add(self.yy, -self.xy * self.xy)
    }

    /// Trace.
    #[inline]
    pub fn trace(&self) -> f64 {
        self.xx + self.yy
    }

    /// `M v`.
    #[inline]
    pub fn mul_vec(&self, v: DVec2) -> DVec2 {
        DVec2::new(self.xx * v.x + self.xy * v.y, self.xy * v.x + self.yy * v.y)
    }

    /// The quadratic form `v^T M v` (squared length of `v` in the metric).
    #[inline]
    pub fn quad(&self, v: DVec2) -> f64 {
        self.xx * v.x * v.x + 2.0 * self.xy * v.x * v.y + self.yy * v.y * v.y
    }

    /// Inverse (the caller guarantees a non-zero determinant).
    #[inline]
    pub fn inverse(&self) -> Sym2 {
        let d = self.det();
        Sym2::new(self.yy / d, -self.xy / d, self.xx / d)
    }

    /// Entry-wise scaling.
    #[inline]
    pub fn scale(&self, s: f64) -> Sym2 {
        Sym2::new(self.xx * s, self.xy * s, self.yy * s)
    }

    /// Entry-wise sum.
    #[inline]
    pub fn add(&self, o: &Sym2) -> Sym2 {
        Sym2::new(self.xx + o.xx, self.xy + o.xy, self.yy + o.yy)
    }

    /// Closed-form eigen-decomposition: eigenvalues ascending `[l_min, l_max]` and the matching
    /// orthonormal eigenvectors. The small eigenvalue is computed as `det / l_max` when both have
    /// the same sign, which keeps it accurate at anisotropy ratios of 1e12.
    pub fn eigen(&self) -> ([f64; 2], [DVec2; 2]) {
        let mean = 0.5 * (self.xx + self.yy);
        let half_diff = 0.5 * (self.xx - self.yy);
        let r = half_diff.hypot(self.xy);
        if r == 0.0 {
            return ([mean, mean], [DVec2::X, DVec2::Y]);
        }
        // Angle of the eigenvector of the largest eigenvalue.
        let theta = 0.5 * self.xy.atan2(half_diff);
        let (s, c) = theta.sin_cos();
        let v_max = DVec2::new(c, s);
        let v_min = DVec2::new(-s, c);
        let hi = mean + r;
        let lo = mean - r;
        let det = self.det();
        let (lo, hi) = if hi.abs() >= lo.abs() {
            let lo = if det > 0.0 && hi != 0.0 { det / hi } else { lo };
            (lo, hi)
        } else {
            let hi = if det > 0.0 && lo != 0.0 { det / lo } else { hi };
            (lo, hi)
        };
        ([lo, hi], [v_min, v_max])
    }

    /// `R diag(l) R^T` from eigenvalues and (orthonormal) eigenvectors.
    #[inline]
    pub fn from_eigen(l: [f64; 2], v: [DVec2; 2]) -> Sym2 {
        Sym2::outer(v[0])
            .scale(l[0])
            .add(&Sym2::outer(v[1]).scale(l[1]))
    }

    /// Applies `f` to the eigenvalues: `R diag(f(l)) R^T`.
    #[inline]
    pub fn map_eigen(&self, f: impl Fn(f64) -> f64) -> Sym2 {
        let (l, v) = self.eigen();
        Sym2::from_eigen([f(l[0]), f(l[1])], v)
    }

    /// `|M|`: absolute values of the eigenvalues (used on Hessians).
    #[inline]
    pub fn abs(&self) -> Sym2 {
        self.map_eigen(f64::abs)
    }

    /// Whether all entries are finite and both eigenvalues are strictly positive.
    #[inline]
    pub fn is_spd(&self) -> bool {
        self.xx.is_finite()
            && self.xy.is_finite()
            && self.yy.is_finite()
            && self.xx > 0.0
            && self.det() > 0.0
    }

    /// An error naming `vertex` unless the tensor is symmetric positive definite.
    pub fn validate(&self, vertex: usize) -> Result<()> {
        if !(self.xx.is_finite() && self.xy.is_finite() && self.yy.is_finite()) {
            return Err(Error::InvalidMetric {
                vertex,
                msg: format!("non-finite entry in {self:?}"),
            });
        }
        if !self.is_spd() {
            let (l, _) = self.eigen();
            return Err(Error::InvalidMetric {
                vertex,
                msg: format!("not positive definite (eigenvalues {:e}, {:e})", l[0], l[1]),
            });
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn eigen_reconstructs_and_is_orthonormal() {
        for &(a, b, c) in &[
            (2.0, 0.3, 1.0),
            (1.0, 0.0, 1.0),
            (1e6, 0.0, 1.0),
            (1.0, -0.7, 1.0),
            (1e12, 3e5, 1.0),
        ] {
            let m = Sym2::new(a, b, c);
            let (l, v) = m.eigen();
            assert!(l[0] <= l[1]);
            assert!((v[0].dot(v[1])).abs() < 1e-14);
            let r = Sym2::from_eigen(l, v);
            let scale = m.xx.abs().max(m.yy.abs());
            assert!((r.xx - m.xx).abs() <= 1e-12 * scale, "{m:?} {r:?}");
            assert!((r.xy - m.xy).abs() <= 1e-12 * scale);
            assert!((r.yy - m.yy).abs() <= 1e-12 * scale);
            assert!((l[0] * l[1] - m.det()).abs() <= 1e-12 * m.det().abs().max(1e-300));
        }
    }

    #[test]
    fn validate_rejects_nan_and_indefinite() {
        assert!(Sym2::new(1.0, 0.0, 1.0).validate(0).is_ok());
        assert!(Sym2::new(f64::NAN, 0.0, 1.0).validate(3).is_err());
        assert!(Sym2::new(1.0, 2.0, 1.0).validate(4).is_err());
        assert!(Sym2::new(-1.0, 0.0, -1.0).validate(5).is_err());
    }
}
