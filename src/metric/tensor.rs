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
    /// Entry `(0, 0)`.
    pub xx: f64,
    /// Entry `(0, 1) = (1, 0)`.
    pub xy: f64,
    /// Entry `(1, 1)`.
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
    /// orthonormal eigenvectors (their signs are arbitrary; a diagonal tensor gives the exact axes).
    /// The small eigenvalue is computed as `det / l_max` when both have
    /// the same sign, which keeps it accurate at anisotropy ratios of 1e12.
    pub fn eigen(&self) -> ([f64; 2], [DVec2; 2]) {
        let mean = 0.5 * (self.xx + self.yy);
        let half_diff = 0.5 * (self.xx - self.yy);
        let r = half_diff.hypot(self.xy);
        if r == 0.0 {
            return ([mean, mean], [DVec2::X, DVec2::Y]);
        }
        if self.xy == 0.0 {
            // Diagonal: exact axes (the angle formula would give cos(π/2) ≈ 6e-17).
            return if self.xx <= self.yy {
                ([self.xx, self.yy], [DVec2::X, DVec2::Y])
            } else {
                ([self.yy, self.xx], [DVec2::Y, DVec2::X])
            };
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
        let mean = 0.5 * (self.xx + self.yy);
        let half_diff = 0.5 * (self.xx - self.yy);
        let r = half_diff.hypot(self.xy);
        if r == 0.0 || self.xy == 0.0 {
            let (l, v) = self.eigen();
            return Sym2::from_eigen([f(l[0]), f(l[1])], v);
        }
        // Without trigonometry: the spectral projector on the largest eigenvalue is
        // `v v^T = (I + [[cos 2θ, sin 2θ], [sin 2θ, -cos 2θ]]) / 2` with `cos 2θ = half_diff / r`,
        // `sin 2θ = xy / r`; the other projector is `I - v v^T`. Eigenvalues as in `eigen`.
        let (c2, s2) = (half_diff / r, self.xy / r);
        let det = self.det();
        let (mut lo, mut hi) = (mean - r, mean + r);
        if hi.abs() >= lo.abs() {
            if det > 0.0 && hi != 0.0 {
                lo = det / hi;
            }
        } else if det > 0.0 && lo != 0.0 {
            hi = det / lo;
        }
        let (fl, fh) = (f(lo), f(hi));
        let (sum, diff) = (0.5 * (fh + fl), 0.5 * (fh - fl));
        Sym2::new(sum + diff * c2, diff * s2, sum - diff * c2)
    }

    /// `|M|`: absolute values of the eigenvalues (used on Hessians).
    #[inline]
    pub fn abs(&self) -> Sym2 {
        self.map_eigen(f64::abs)
    }

    /// The metric with size `h[0]` along `dir` (normalised; the x axis when `dir` is zero or not
    /// finite) and size `h[1]` along its perpendicular: `d d^T / h0^2 + d⊥ d⊥^T / h1^2`
    /// (004 §3.3: `M = P Λ P^T` with `λ_i = 1 / h_i^2`).
    pub fn from_sizes(h: [f64; 2], dir: DVec2) -> Sym2 {
        let d = dir.try_normalize().unwrap_or(DVec2::X);
        Sym2::from_eigen([1.0 / (h[0] * h[0]), 1.0 / (h[1] * h[1])], [d, d.perp()])
    }

    /// The prescribed sizes `h_i = 1 / sqrt(λ_i)` in ascending-eigenvalue order (so the
    /// *largest* size first) and their unit directions (004 §3.3). SPD input (a non-positive
    /// eigenvalue gives an infinite or NaN size).
    pub fn sizes(&self) -> ([f64; 2], [DVec2; 2]) {
        let (l, v) = self.eigen();
        ([1.0 / l[0].sqrt(), 1.0 / l[1].sqrt()], v)
    }

    /// Entry-wise difference `self - o`.
    #[inline]
    pub fn sub(&self, o: &Sym2) -> Sym2 {
        Sym2::new(self.xx - o.xx, self.xy - o.xy, self.yy - o.yy)
    }

    /// Frobenius norm `sqrt(xx^2 + 2 xy^2 + yy^2)`.
    #[inline]
    pub fn norm(&self) -> f64 {
        (self.xx * self.xx + 2.0 * self.xy * self.xy + self.yy * self.yy).sqrt()
    }

    /// Congruence `A^T M A` for a general 2x2 matrix `A` given by its columns `(c0, c1)`:
    /// the metric `M` pulled back by the linear map `x -> A x`. Symmetric by construction.
    #[inline]
    pub fn congruence(&self, c0: DVec2, c1: DVec2) -> Sym2 {
        let m0 = self.mul_vec(c0);
        let m1 = self.mul_vec(c1);
        Sym2::new(c0.dot(m0), 0.5 * (c0.dot(m1) + c1.dot(m0)), c1.dot(m1))
    }

    /// Matrix logarithm `R diag(ln λ) R^T` (log-Euclidean framework, Arsigny et al.; the caller
    /// guarantees SPD — a non-positive eigenvalue gives NaN or `-inf`).
    #[inline]
    pub fn log(&self) -> Sym2 {
        self.map_eigen(f64::ln)
    }

    /// Matrix exponential `R diag(e^λ) R^T` (always SPD for finite input).
    #[inline]
    pub fn exp(&self) -> Sym2 {
        self.map_eigen(f64::exp)
    }

    /// Principal square root `R diag(sqrt λ) R^T` (SPD input).
    #[inline]
    pub fn sqrt(&self) -> Sym2 {
        self.map_eigen(f64::sqrt)
    }

    /// Matrix power `R diag(λ^p) R^T` (SPD input).
    #[inline]
    pub fn powf(&self, p: f64) -> Sym2 {
        self.map_eigen(|l| l.powf(p))
    }

    /// Bounds the metric: eigenvalues clamped to `[1/hmax^2, 1/hmin^2]` (sizes in `[hmin, hmax]`),
    /// then the small eigenvalue raised so that `λ_max / λ_min <= max_aniso^2` (size ratio at most
    /// `max_aniso`). Eigenvectors are kept. Non-positive eigenvalues (a singular or indefinite
    /// input such as a degenerate eq. (6) metric) become `1/hmax^2`, so any finite input gives an
    /// SPD result when `0 < hmin <= hmax` and `max_aniso >= 1`.
    pub fn bound(&self, hmin: f64, hmax: f64, max_aniso: f64) -> Sym2 {
        let (l, v) = self.eigen();
        let lo = 1.0 / (hmax * hmax);
        let hi = 1.0 / (hmin * hmin);
        let clamp = |x: f64| if x.is_nan() { x } else { x.max(lo).min(hi) };
        let (l0, l1) = (clamp(l[0]), clamp(l[1]));
        let a2 = max_aniso * max_aniso;
        let l0 = l0.max(l1 / a2);
        Sym2::from_eigen([l0, l1], v)
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

    fn close(a: &Sym2, b: &Sym2, rel: f64) -> bool {
        a.sub(b).norm() <= rel * a.norm().max(b.norm())
    }

    #[test]
    fn from_sizes_and_sizes_round_trip() {
        let dir = DVec2::new(3.0, 4.0);
        let m = Sym2::from_sizes([0.5, 0.01], dir);
        assert!((m.quad(dir / 5.0) - 4.0).abs() < 1e-12);
        assert!((m.quad(dir.perp() / 5.0) - 1e4).abs() < 1e-8);
        let (h, v) = m.sizes();
        assert!((h[0] - 0.5).abs() < 1e-14 && (h[1] - 0.01).abs() < 1e-16);
        assert!((v[0].dot(dir / 5.0)).abs() > 1.0 - 1e-14);
        // A zero direction falls back to the x axis.
        let m = Sym2::from_sizes([2.0, 1.0], DVec2::ZERO);
        assert_eq!(m, Sym2::new(0.25, 0.0, 1.0));
    }

    #[test]
    fn log_exp_sqrt_powf_are_consistent() {
        let m = Sym2::from_sizes([0.3, 1e-4], DVec2::new(1.0, -2.0));
        assert!(close(&m.log().exp(), &m, 1e-12));
        let r = m.sqrt();
        // I pulled back by sqrt(M) (columns of sqrt(M)) is sqrt(M)^2 = M.
        let rr = Sym2::IDENTITY.congruence(DVec2::new(r.xx, r.xy), DVec2::new(r.xy, r.yy));
        assert!(close(&rr, &m, 1e-12), "{rr:?} {m:?}");
        assert!(close(&m.powf(0.5), &r, 1e-12));
        assert!(close(&m.powf(-1.0), &m.inverse(), 1e-10));
        assert!((m.log().trace() - m.det().ln()).abs() < 1e-12 * m.det().ln().abs());
    }

    #[test]
    fn bound_clamps_sizes_and_anisotropy() {
        let m = Sym2::from_sizes([10.0, 1e-6], DVec2::new(1.0, 1.0));
        let b = m.bound(1e-3, 1.0, 50.0);
        let (h, v) = b.sizes();
        assert!((h[1] - 1e-3).abs() < 1e-15, "{h:?}");
        assert!((h[0] - 5e-2).abs() < 1e-14, "{h:?}");
        assert!((v[1].dot(DVec2::new(1.0, -1.0).normalize())).abs() > 1.0 - 1e-12);
        // Singular and indefinite inputs become SPD.
        let b = Sym2::new(0.0, 0.0, 0.0).bound(0.1, 2.0, 10.0);
        assert!(close(&b, &Sym2::iso(2.0), 1e-15));
        assert!(Sym2::new(1.0, 3.0, 1.0).bound(0.1, 2.0, 10.0).is_spd());
    }

    #[test]
    fn validate_rejects_nan_and_indefinite() {
        assert!(Sym2::new(1.0, 0.0, 1.0).validate(0).is_ok());
        assert!(Sym2::new(f64::NAN, 0.0, 1.0).validate(3).is_err());
        assert!(Sym2::new(1.0, 2.0, 1.0).validate(4).is_err());
        assert!(Sym2::new(-1.0, 0.0, -1.0).validate(5).is_err());
    }
}
