//! `Sym3`: a symmetric 3x3 tensor, the storage type of a 3D metric (6 numbers), for `mesh3` and
//! the 3D surface example of 004 §5.
//!
//! The eigen-decomposition is the closed form of `metric::eigen3` (the isolated eigenvalue from
//! the trigonometric formula, the other two by one Jacobi rotation in its orthogonal complement),
//! checked by its residual, with nalgebra's `SymmetricEigen` (implicit QR on the tridiagonal
//! form) as the fallback; the closed form takes half the time (printed by the `eigen3` test). Measured accuracy (tests
//! `eigen_accuracy_at_high_anisotropy` here and `closed_form_accuracy_random_and_anisotropic` in
//! `eigen3`, random rotations of spectra with ratios up to 1e12 and nearly equal pairs): the
//! residual `‖AV − VΛ‖` is within 1e-15 `‖A‖` and the eigenvectors orthonormal to ~1e-15; each
//! eigenvalue is accurate to ~`ε ‖A‖` in absolute terms, so the smallest one has a relative error
//! of up to ~2e-10 at eigenvalue ratio 1e6 (size ratio 1e3) and up to ~3e-4 at ratio 1e12 (size
//! ratio 1e6), as for the iterative solver. The latter is the limit set by rounding the six stored
//! entries (a perturbation of `ε ‖A‖` moves `λ_min` by as much), not by the algorithm.
//!
//! The operations mirror [`super::Sym2`] (both implement [`super::SymTensor`]); bounding and
//! intersection by simultaneous reduction (004 §3.5) are the generic ones written once for both.

use glam::DVec3;
use nalgebra::{Matrix3, SymmetricEigen};

use super::SymTensor;
use crate::error::{Error, Result};

/// Symmetric 3x3 matrix `[[xx, xy, xz], [xy, yy, yz], [xz, yz, zz]]`.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Sym3 {
    /// Entry `(0, 0)`.
    pub xx: f64,
    /// Entry `(0, 1)`.
    pub xy: f64,
    /// Entry `(0, 2)`.
    pub xz: f64,
    /// Entry `(1, 1)`.
    pub yy: f64,
    /// Entry `(1, 2)`.
    pub yz: f64,
    /// Entry `(2, 2)`.
    pub zz: f64,
}

impl Sym3 {
    /// The identity.
    pub const IDENTITY: Sym3 = Sym3::scalar(1.0);

    /// From the six entries `xx, xy, xz, yy, yz, zz`.
    #[inline]
    pub const fn new(xx: f64, xy: f64, xz: f64, yy: f64, yz: f64, zz: f64) -> Sym3 {
        Sym3 {
            xx,
            xy,
            xz,
            yy,
            yz,
            zz,
        }
    }

    /// `s I`.
    #[inline]
    pub const fn scalar(s: f64) -> Sym3 {
        Sym3::new(s, 0.0, 0.0, s, 0.0, s)
    }

    /// The isotropic metric of size `h`: `I / h^2`.
    #[inline]
    pub fn iso(h: f64) -> Sym3 {
        Sym3::scalar(1.0 / (h * h))
    }

    /// The outer product `v v^T`.
    #[inline]
    pub fn outer(v: DVec3) -> Sym3 {
        Sym3::new(
            v.x * v.x,
            v.x * v.y,
            v.x * v.z,
            v.y * v.y,
            v.y * v.z,
            v.z * v.z,
        )
    }

    /// Entry-wise scaling.
    #[inline]
    pub fn scale(&self, s: f64) -> Sym3 {
        Sym3::new(
            self.xx * s,
            self.xy * s,
            self.xz * s,
            self.yy * s,
            self.yz * s,
            self.zz * s,
        )
    }

    /// Entry-wise sum.
    #[inline]
    pub fn add(&self, o: &Sym3) -> Sym3 {
        Sym3::new(
            self.xx + o.xx,
            self.xy + o.xy,
            self.xz + o.xz,
            self.yy + o.yy,
            self.yz + o.yz,
            self.zz + o.zz,
        )
    }

    /// Entry-wise difference.
    #[inline]
    pub fn sub(&self, o: &Sym3) -> Sym3 {
        self.add(&o.scale(-1.0))
    }

    /// Frobenius norm.
    #[inline]
    pub fn norm(&self) -> f64 {
        (self.xx * self.xx
            + self.yy * self.yy
            + self.zz * self.zz
            + 2.0 * (self.xy * self.xy + self.xz * self.xz + self.yz * self.yz))
            .sqrt()
    }

    /// Trace.
    #[inline]
    pub fn trace(&self) -> f64 {
        self.xx + self.yy + self.zz
    }

    /// Determinant.
    #[inline]
    pub fn det(&self) -> f64 {
        self.xx * (self.yy * self.zz - self.yz * self.yz)
            - self.xy * (self.xy * self.zz - self.yz * self.xz)
            + self.xz * (self.xy * self.yz - self.yy * self.xz)
    }

    /// `M v`.
    #[inline]
    pub fn mul_vec(&self, v: DVec3) -> DVec3 {
        DVec3::new(
            self.xx * v.x + self.xy * v.y + self.xz * v.z,
            self.xy * v.x + self.yy * v.y + self.yz * v.z,
            self.xz * v.x + self.yz * v.y + self.zz * v.z,
        )
    }

    /// The quadratic form `v^T M v`.
    #[inline]
    pub fn quad(&self, v: DVec3) -> f64 {
        v.dot(self.mul_vec(v))
    }

    /// Congruence `A^T M A` with `A = [c0, c1, c2]` given by columns (symmetric by construction).
    pub fn congruence(&self, c: [DVec3; 3]) -> Sym3 {
        let m = c.map(|ci| self.mul_vec(ci));
        let s = |i: usize, j: usize| 0.5 * (c[i].dot(m[j]) + c[j].dot(m[i]));
        Sym3::new(s(0, 0), s(0, 1), s(0, 2), s(1, 1), s(1, 2), s(2, 2))
    }

    /// As an nalgebra matrix.
    pub fn to_matrix(&self) -> Matrix3<f64> {
        Matrix3::new(
            self.xx, self.xy, self.xz, self.xy, self.yy, self.yz, self.xz, self.yz, self.zz,
        )
    }

    /// Eigenvalues ascending and the matching orthonormal eigenvectors: the closed form of
    /// `metric::eigen3` when it passes its residual check, otherwise nalgebra's
    /// `SymmetricEigen` (see the module documentation for the accuracy). A non-finite input gives
    /// NaN eigenvalues (never a hang or a panic).
    pub fn eigen(&self) -> ([f64; 3], [DVec3; 3]) {
        if !self.is_finite() {
            return ([f64::NAN; 3], [DVec3::X, DVec3::Y, DVec3::Z]);
        }
        if self.xy == 0.0 && self.xz == 0.0 && self.yz == 0.0 {
            return self.eigen_diagonal();
        }
        super::eigen3::eigen_closed_form(self).unwrap_or_else(|| self.eigen_iterative())
    }

    /// The eigen-decomposition of a diagonal tensor: its entries sorted, with the exact axes.
    fn eigen_diagonal(&self) -> ([f64; 3], [DVec3; 3]) {
        let mut idx = [
            (self.xx, DVec3::X),
            (self.yy, DVec3::Y),
            (self.zz, DVec3::Z),
        ];
        idx.sort_by(|a, b| a.0.total_cmp(&b.0));
        (idx.map(|x| x.0), idx.map(|x| x.1))
    }

    /// [`Sym3::eigen`] by nalgebra's `SymmetricEigen` alone (implicit QR; the reference and the
    /// fallback of the closed form).
    pub fn eigen_iterative(&self) -> ([f64; 3], [DVec3; 3]) {
        let nan = ([f64::NAN; 3], [DVec3::X, DVec3::Y, DVec3::Z]);
        if !self.is_finite() {
            return nan;
        }
        if self.xy == 0.0 && self.xz == 0.0 && self.yz == 0.0 {
            return self.eigen_diagonal();
        }
        let Some(e) = SymmetricEigen::try_new(self.to_matrix(), f64::EPSILON, 10_000) else {
            return nan;
        };
        let mut idx = [0usize, 1, 2];
        idx.sort_by(|&a, &b| e.eigenvalues[a].total_cmp(&e.eigenvalues[b]));
        let col = |k: usize| {
            let c = e.eigenvectors.column(k);
            DVec3::new(c[0], c[1], c[2]).normalize()
        };
        (idx.map(|k| e.eigenvalues[k]), idx.map(col))
    }

    /// `R diag(l) R^T`.
    pub fn from_eigen(l: [f64; 3], v: [DVec3; 3]) -> Sym3 {
        Sym3::outer(v[0])
            .scale(l[0])
            .add(&Sym3::outer(v[1]).scale(l[1]))
            .add(&Sym3::outer(v[2]).scale(l[2]))
    }

    /// `R diag(f(l)) R^T`.
    pub fn map_eigen(&self, f: impl Fn(f64) -> f64) -> Sym3 {
        let (l, v) = self.eigen();
        Sym3::from_eigen(l.map(f), v)
    }

    /// Matrix logarithm (SPD input).
    pub fn log(&self) -> Sym3 {
        self.map_eigen(f64::ln)
    }

    /// Matrix exponential.
    pub fn exp(&self) -> Sym3 {
        self.map_eigen(f64::exp)
    }

    /// Matrix power (SPD input).
    pub fn powf(&self, p: f64) -> Sym3 {
        self.map_eigen(|l| l.powf(p))
    }

    /// Absolute values of the eigenvalues.
    pub fn abs(&self) -> Sym3 {
        self.map_eigen(f64::abs)
    }

    /// Sizes clamped to `[hmin, hmax]`, then every eigenvalue raised to at least
    /// `λ_max / max_aniso²` (as [`super::Sym2::bound`]).
    pub fn bound(&self, hmin: f64, hmax: f64, max_aniso: f64) -> Sym3 {
        SymTensor::bound(self, hmin, hmax, max_aniso)
    }

    /// Whether all entries are finite.
    #[inline]
    pub fn is_finite(&self) -> bool {
        [self.xx, self.xy, self.xz, self.yy, self.yz, self.zz]
            .iter()
            .all(|x| x.is_finite())
    }

    /// Whether finite and positive definite (Sylvester's criterion).
    pub fn is_spd(&self) -> bool {
        self.is_finite()
            && self.xx > 0.0
            && self.xx * self.yy - self.xy * self.xy > 0.0
            && self.det() > 0.0
    }

    /// An error naming `vertex` unless the tensor is SPD.
    pub fn validate(&self, vertex: usize) -> Result<()> {
        if self.is_spd() {
            return Ok(());
        }
        let (l, _) = self.eigen();
        Err(Error::InvalidMetric {
            vertex,
            msg: format!(
                "3D metric not positive definite (eigenvalues {:e}, {:e}, {:e})",
                l[0], l[1], l[2]
            ),
        })
    }

    /// Intersection by simultaneous reduction (004 §3.5), as [`super::intersect()`]: with the
    /// better-conditioned tensor `A = V Λ V^T` as base, `C = Λ^{-1/2} V^T B V Λ^{-1/2} = Q diag(μ)
    /// Q^T` and `A ∩ B = V Λ^{1/2} Q diag(max(1, μ)) Q^T Λ^{1/2} V^T`.
    pub fn intersect(&self, other: &Sym3) -> Sym3 {
        super::intersect(self, other)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A rotation from Euler-like angles, as three orthonormal columns.
    fn rotation(a: f64, b: f64, c: f64) -> [DVec3; 3] {
        let m = glam::DMat3::from_euler(glam::EulerRot::ZYX, a, b, c);
        [m.x_axis, m.y_axis, m.z_axis]
    }

    fn rel(a: &Sym3, b: &Sym3) -> f64 {
        a.sub(b).norm() / a.norm().max(b.norm())
    }

    #[test]
    fn eigen_accuracy_at_high_anisotropy() {
        let mut worst = [0.0f64; 2];
        for (k, &ratio) in [1e6f64, 1e12].iter().enumerate() {
            for i in 0..50 {
                let t = i as f64;
                let v = rotation(0.7 * t, 0.3 + 0.11 * t, 1.9 * t);
                let l = [1.0, ratio.sqrt(), ratio];
                let m = Sym3::from_eigen(l, v);
                let (le, ve) = m.eigen();
                // Orthonormal vectors and a reconstruction exact to round-off.
                for a in 0..3 {
                    for b in 0..3 {
                        let d = ve[a].dot(ve[b]) - if a == b { 1.0 } else { 0.0 };
                        assert!(d.abs() < 1e-14);
                    }
                }
                let rr = rel(&Sym3::from_eigen(le, ve), &m);
                assert!(rr < 1e-14, "{rr}");
                for j in 0..3 {
                    worst[k] = worst[k].max((le[j] / l[j] - 1.0).abs());
                }
            }
        }
        eprintln!("Sym3 eigenvalue relative error, ratios 1e6 / 1e12: {worst:?}");
        // Measured: 2.8e-10 at ratio 1e6 and 1.8e-4 at ratio 1e12 (ε‖M‖ absolute error).
        assert!(worst[0] < 1e-9, "ratio 1e6: {worst:?}");
        assert!(worst[1] < 1e-3, "ratio 1e12: {worst:?}");
    }

    #[test]
    fn intersect_log_exp_bound() {
        let v = rotation(0.3, 1.1, -0.4);
        let a = Sym3::from_eigen([1.0, 1e2, 1e4], v);
        let b = Sym3::from_eigen([1e4, 1.0, 3.0], v);
        // Coaxial: eigenvalue-wise max.
        assert!(rel(&a.intersect(&b), &Sym3::from_eigen([1e4, 1e2, 1e4], v)) < 1e-12);
        assert!(rel(&a.intersect(&a), &a) < 1e-12);
        let w = rotation(-1.0, 0.2, 2.0);
        let c = Sym3::from_eigen([2.0, 50.0, 7e3], w);
        let r = a.intersect(&c);
        assert!(r.is_spd());
        for k in 0..50 {
            let t = k as f64 * 0.37;
            let u = DVec3::new(
                t.cos() * (2.0 * t).sin(),
                t.sin() * (2.0 * t).sin(),
                (2.0 * t).cos(),
            );
            assert!(r.quad(u) >= a.quad(u).max(c.quad(u)) * (1.0 - 1e-10));
        }
        assert!(rel(&a.log().exp(), &a) < 1e-12);
        assert!((a.log().trace() - a.det().ln()).abs() < 1e-12 * a.det().ln());
        let bd = a.bound(0.05, 0.5, 5.0);
        let (l, _) = bd.eigen();
        assert!(
            (l[2] - 400.0).abs() < 1e-9 && (l[0] - 16.0).abs() < 1e-10,
            "{l:?}"
        );
        assert!(Sym3::new(f64::NAN, 0.0, 0.0, 1.0, 0.0, 1.0).eigen().0[0].is_nan());
        assert!(Sym3::new(1.0, 2.0, 0.0, 1.0, 0.0, 1.0).validate(7).is_err());
        assert!((Sym3::from_eigen([2.0, 3.0, 5.0], w).det() - 30.0).abs() < 1e-12);
    }
}
