//! [`SymTensor`]: the one trait over the symmetric tensors [`Sym2`] and [`Sym3`], so that metric
//! mathematics is written once for both dimensions.
//!
//! The storage types keep their own inherent methods (the closed-form eigen-decomposition and
//! `map_eigen` of `Sym2`, nalgebra's for `Sym3`); the trait methods call them. What is the same
//! formula in every dimension is a provided method or a generic function over the trait:
//! bounding ([`SymTensor::bound`]), sizes, `log`/`exp`/`powf`, intersection by simultaneous
//! reduction ([`super::intersect()`]), log-Euclidean interpolation ([`super::interpolate_log`]),
//! edge length and `Q_ani` ([`super::length`]), the geometric metric of 004 eq. (6)
//! ([`super::geometric_metric`]).

use std::fmt::Debug;

use super::{Sym2, Sym3};
use crate::error::{Error, Result};
use crate::geom::{DVec2, DVec3, Point};

/// A symmetric `D x D` tensor used as a Riemannian metric (or a Hessian): `|v|_M = sqrt(v^T M v)`
/// and, for `M = R diag(λ) R^T`, sizes `h_i = 1 / sqrt(λ_i)` along the eigenvectors (004 §3.3).
pub trait SymTensor<const D: usize>:
    Copy + Debug + Default + PartialEq + Send + Sync + 'static
{
    /// The vector type the tensor acts on.
    type Vec: Point<D>;

    /// The identity.
    const IDENTITY: Self;

    /// The tensor with upper-triangle entries `f(i, j)`, `i <= j`.
    fn from_fn(f: impl Fn(usize, usize) -> f64) -> Self;
    /// Entry `(i, j)`.
    fn get(&self, i: usize, j: usize) -> f64;
    /// `s I`.
    fn scalar(s: f64) -> Self;
    /// The outer product `v v^T`.
    fn outer(v: Self::Vec) -> Self;
    /// Determinant.
    fn det(&self) -> f64;
    /// Trace.
    fn trace(&self) -> f64;
    /// `M v`.
    fn mul_vec(&self, v: Self::Vec) -> Self::Vec;
    /// The quadratic form `v^T M v` (squared length of `v` in the metric).
    fn quad(&self, v: Self::Vec) -> f64;
    /// Entry-wise scaling.
    fn scale(&self, s: f64) -> Self;
    /// Entry-wise sum.
    fn add(&self, o: &Self) -> Self;
    /// Entry-wise difference.
    fn sub(&self, o: &Self) -> Self;
    /// Frobenius norm.
    fn norm(&self) -> f64;
    /// Congruence `A^T M A` with `A` given by its columns: `M` pulled back by `x -> A x`.
    fn congruence(&self, cols: [Self::Vec; D]) -> Self;
    /// Eigenvalues ascending and the matching orthonormal eigenvectors.
    fn eigen(&self) -> ([f64; D], [Self::Vec; D]);
    /// `R diag(l) R^T` from eigenvalues and orthonormal eigenvectors.
    fn from_eigen(l: [f64; D], v: [Self::Vec; D]) -> Self;
    /// `R diag(f(λ)) R^T`.
    fn map_eigen(&self, f: impl Fn(f64) -> f64) -> Self;
    /// Whether all entries are finite.
    fn is_finite(&self) -> bool;
    /// Whether finite and positive definite.
    fn is_spd(&self) -> bool;
    /// Whether positive semi-definite by its principal minors (all `>= 0`; no eigen
    /// decomposition), e.g. to test `B <= A` in the SPD order as `A − B >= 0`.
    fn is_psd(&self) -> bool;

    /// The isotropic metric of size `h`: `I / h²`.
    #[inline]
    fn iso(h: f64) -> Self {
        Self::scalar(1.0 / (h * h))
    }
    /// `|M|`: absolute values of the eigenvalues (used on Hessians).
    #[inline]
    fn abs(&self) -> Self {
        self.map_eigen(f64::abs)
    }
    /// Matrix logarithm (log-Euclidean framework; SPD input).
    #[inline]
    fn log(&self) -> Self {
        self.map_eigen(f64::ln)
    }
    /// Matrix exponential.
    #[inline]
    fn exp(&self) -> Self {
        self.map_eigen(f64::exp)
    }
    /// Principal square root (SPD input).
    #[inline]
    fn sqrt(&self) -> Self {
        self.map_eigen(f64::sqrt)
    }
    /// Matrix power `R diag(λ^p) R^T` (SPD input).
    #[inline]
    fn powf(&self, p: f64) -> Self {
        self.map_eigen(|l| l.powf(p))
    }
    /// The prescribed sizes `h_i = 1 / sqrt(λ_i)` in ascending-eigenvalue order (largest size
    /// first) and their unit directions (004 §3.3).
    #[inline]
    fn sizes(&self) -> ([f64; D], [Self::Vec; D]) {
        let (l, v) = self.eigen();
        (l.map(|x| 1.0 / x.sqrt()), v)
    }

    /// Bounds the metric: eigenvalues clamped to `[1/hmax², 1/hmin²]` (sizes in `[hmin, hmax]`),
    /// then every eigenvalue but the largest raised to at least `λ_max / max_aniso²` (size ratio
    /// at most `max_aniso`). Eigenvectors are kept; NaN eigenvalues stay NaN. Non-positive
    /// eigenvalues become `1/hmax²`, so any finite input gives an SPD result when
    /// `0 < hmin <= hmax` and `max_aniso >= 1`.
    fn bound(&self, hmin: f64, hmax: f64, max_aniso: f64) -> Self {
        let (l, v) = self.eigen();
        Self::from_eigen(bound_eigenvalues(l, hmin, hmax, max_aniso), v)
    }

    /// `A ∩ B` by simultaneous reduction (004 §3.5): [`super::intersect()`].
    #[inline]
    fn intersect(&self, other: &Self) -> Self {
        super::intersect(self, other)
    }

    /// An error naming `vertex` unless the tensor is symmetric positive definite.
    fn validate(&self, vertex: usize) -> Result<()> {
        if !self.is_finite() {
            return Err(Error::InvalidMetric {
                vertex,
                msg: format!("non-finite entry in {self:?}"),
            });
        }
        if !self.is_spd() {
            let (l, _) = self.eigen();
            let l: Vec<String> = l.iter().map(|x| format!("{x:e}")).collect();
            return Err(Error::InvalidMetric {
                vertex,
                msg: format!("not positive definite (eigenvalues {})", l.join(", ")),
            });
        }
        Ok(())
    }
}

/// The eigenvalues of [`SymTensor::bound`] from the ascending eigenvalues `l`: clamped to
/// `[1/hmax², 1/hmin²]`, then all but the largest raised to at least `λ_max / max_aniso²` (NaN
/// stays NaN).
pub fn bound_eigenvalues<const D: usize>(
    l: [f64; D],
    hmin: f64,
    hmax: f64,
    max_aniso: f64,
) -> [f64; D] {
    let lo = 1.0 / (hmax * hmax);
    let hi = 1.0 / (hmin * hmin);
    let mut l = l.map(|x| if x.is_nan() { x } else { x.max(lo).min(hi) });
    let floor = l[D - 1] / (max_aniso * max_aniso);
    for x in &mut l[..D - 1] {
        *x = x.max(floor);
    }
    l
}

impl SymTensor<2> for Sym2 {
    type Vec = DVec2;
    const IDENTITY: Self = Sym2::IDENTITY;

    #[inline]
    fn from_fn(f: impl Fn(usize, usize) -> f64) -> Self {
        Sym2::new(f(0, 0), f(0, 1), f(1, 1))
    }
    #[inline]
    fn get(&self, i: usize, j: usize) -> f64 {
        match (i, j) {
            (0, 0) => self.xx,
            (1, 1) => self.yy,
            _ => self.xy,
        }
    }
    #[inline]
    fn scalar(s: f64) -> Self {
        Sym2::scalar(s)
    }
    #[inline]
    fn iso(h: f64) -> Self {
        Sym2::iso(h)
    }
    #[inline]
    fn outer(v: DVec2) -> Self {
        Sym2::outer(v)
    }
    #[inline]
    fn det(&self) -> f64 {
        Sym2::det(self)
    }
    #[inline]
    fn trace(&self) -> f64 {
        Sym2::trace(self)
    }
    #[inline]
    fn mul_vec(&self, v: DVec2) -> DVec2 {
        Sym2::mul_vec(self, v)
    }
    #[inline]
    fn quad(&self, v: DVec2) -> f64 {
        Sym2::quad(self, v)
    }
    #[inline]
    fn scale(&self, s: f64) -> Self {
        Sym2::scale(self, s)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Sym2::add(self, o)
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        Sym2::sub(self, o)
    }
    #[inline]
    fn norm(&self) -> f64 {
        Sym2::norm(self)
    }
    #[inline]
    fn congruence(&self, cols: [DVec2; 2]) -> Self {
        Sym2::congruence(self, cols[0], cols[1])
    }
    #[inline]
    fn eigen(&self) -> ([f64; 2], [DVec2; 2]) {
        Sym2::eigen(self)
    }
    #[inline]
    fn from_eigen(l: [f64; 2], v: [DVec2; 2]) -> Self {
        Sym2::from_eigen(l, v)
    }
    #[inline]
    fn map_eigen(&self, f: impl Fn(f64) -> f64) -> Self {
        Sym2::map_eigen(self, f)
    }
    #[inline]
    fn is_finite(&self) -> bool {
        self.xx.is_finite() && self.xy.is_finite() && self.yy.is_finite()
    }
    #[inline]
    fn is_spd(&self) -> bool {
        Sym2::is_spd(self)
    }
    #[inline]
    fn is_psd(&self) -> bool {
        self.xx >= 0.0 && self.yy >= 0.0 && self.det() >= 0.0
    }
    #[inline]
    fn validate(&self, vertex: usize) -> Result<()> {
        Sym2::validate(self, vertex)
    }
}

impl SymTensor<3> for Sym3 {
    type Vec = DVec3;
    const IDENTITY: Self = Sym3::IDENTITY;

    #[inline]
    fn from_fn(f: impl Fn(usize, usize) -> f64) -> Self {
        Sym3::new(f(0, 0), f(0, 1), f(0, 2), f(1, 1), f(1, 2), f(2, 2))
    }
    #[inline]
    fn get(&self, i: usize, j: usize) -> f64 {
        match (i.min(j), i.max(j)) {
            (0, 0) => self.xx,
            (0, 1) => self.xy,
            (0, 2) => self.xz,
            (1, 1) => self.yy,
            (1, 2) => self.yz,
            _ => self.zz,
        }
    }
    #[inline]
    fn scalar(s: f64) -> Self {
        Sym3::scalar(s)
    }
    #[inline]
    fn iso(h: f64) -> Self {
        Sym3::iso(h)
    }
    #[inline]
    fn outer(v: DVec3) -> Self {
        Sym3::outer(v)
    }
    #[inline]
    fn det(&self) -> f64 {
        Sym3::det(self)
    }
    #[inline]
    fn trace(&self) -> f64 {
        Sym3::trace(self)
    }
    #[inline]
    fn mul_vec(&self, v: DVec3) -> DVec3 {
        Sym3::mul_vec(self, v)
    }
    #[inline]
    fn quad(&self, v: DVec3) -> f64 {
        Sym3::quad(self, v)
    }
    #[inline]
    fn scale(&self, s: f64) -> Self {
        Sym3::scale(self, s)
    }
    #[inline]
    fn add(&self, o: &Self) -> Self {
        Sym3::add(self, o)
    }
    #[inline]
    fn sub(&self, o: &Self) -> Self {
        Sym3::sub(self, o)
    }
    #[inline]
    fn norm(&self) -> f64 {
        Sym3::norm(self)
    }
    #[inline]
    fn congruence(&self, cols: [DVec3; 3]) -> Self {
        Sym3::congruence(self, cols)
    }
    #[inline]
    fn eigen(&self) -> ([f64; 3], [DVec3; 3]) {
        Sym3::eigen(self)
    }
    #[inline]
    fn from_eigen(l: [f64; 3], v: [DVec3; 3]) -> Self {
        Sym3::from_eigen(l, v)
    }
    #[inline]
    fn map_eigen(&self, f: impl Fn(f64) -> f64) -> Self {
        Sym3::map_eigen(self, f)
    }
    #[inline]
    fn is_finite(&self) -> bool {
        Sym3::is_finite(self)
    }
    #[inline]
    fn is_spd(&self) -> bool {
        Sym3::is_spd(self)
    }
    #[inline]
    fn is_psd(&self) -> bool {
        let (a, b, c) = (self.xx, self.yy, self.zz);
        a >= 0.0
            && b >= 0.0
            && c >= 0.0
            && a * b - self.xy * self.xy >= 0.0
            && a * c - self.xz * self.xz >= 0.0
            && b * c - self.yz * self.yz >= 0.0
            && self.det() >= 0.0
    }
    #[inline]
    fn validate(&self, vertex: usize) -> Result<()> {
        Sym3::validate(self, vertex)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The provided `bound` gives the same bits as `Sym2::bound` and `Sym3::bound`.
    #[test]
    fn generic_bound_matches_the_inherent_ones() {
        let m = Sym2::from_sizes([10.0, 1e-6], DVec2::new(1.0, 1.0));
        for (hmin, hmax, a) in [(1e-3, 1.0, 50.0), (1e-7, 20.0, 1e9), (0.1, 0.2, 1.0)] {
            assert_eq!(SymTensor::bound(&m, hmin, hmax, a), m.bound(hmin, hmax, a));
        }
        let s = Sym3::from_eigen([1.0, 1e2, 1e4], [DVec3::X, DVec3::Y, DVec3::Z]);
        assert_eq!(
            SymTensor::bound(&s, 0.05, 0.5, 5.0),
            s.bound(0.05, 0.5, 5.0)
        );
        assert_eq!(
            Sym2::from_fn(|i, j| (i + 2 * j) as f64),
            Sym2::new(0.0, 2.0, 3.0)
        );
        assert_eq!(
            SymTensor::get(&Sym3::from_fn(|i, j| (i + 3 * j) as f64), 2, 1),
            7.0
        );
    }
}
