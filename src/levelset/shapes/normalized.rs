//! A level-set function that is not a distance, seen through quantities that do not depend on
//! its scale (004 eq. (6) assumes a signed distance, 004 §2.1).
//!
//! For `f` with `∇f ≠ 0` near its zero level, the signed distance `d` to the zero level
//! satisfies, on the zero level,
//!
//! ```text
//! d ≈ f / |∇f|,   ∇d = n = ∇f / |∇f|,   D²d = P D²f P / |∇f|,   P = I - n nᵀ,
//! ```
//!
//! (`P D²f P / |∇f|` is the shape operator: its eigenvalue along the level line is the curvature
//! `div(∇f/|∇f|)`; in space its two eigenvalues in the tangent plane are the principal
//! curvatures). All three are unchanged when `f` is multiplied by a constant `c > 0`, so a
//! metric built from them — and the mesh adapted to it — is the same for `f` and `c f`; the band
//! of eq. (6) is measured in distance. Away from the zero level `f / |∇f|` is only a first-order
//! distance; it is clipped to `±cap` (e.g. the domain's diameter) where `∇f` vanishes.

use super::Shape;
use crate::geom::{DVec2, DVec3};
use crate::metric::{Sym2, Sym3};

/// `f` through its first-order distance, unit normal and shape operator (module documentation).
pub struct Normalized<S> {
    /// The level-set function.
    pub inner: S,
    /// The largest distance reported (where `∇f` vanishes).
    pub cap: f64,
}

/// `f(p)/|∇f(p)|` clipped to `±cap` (`±cap` where `∇f` vanishes): the value of [`Normalized`]
/// for a borrowed function.
pub fn normalized_distance<S: Shape + ?Sized>(f: &S, p: DVec2, cap: f64) -> f64 {
    clipped_quotient(f.distance(p), f.gradient(p).length(), cap)
}

fn clipped_quotient(f: f64, len: f64, cap: f64) -> f64 {
    let d = if len > 0.0 {
        f / len
    } else {
        f64::INFINITY * f.signum()
    };
    if d.is_nan() {
        0.0
    } else {
        d.clamp(-cap, cap)
    }
}

impl<S: Shape> Normalized<S> {
    /// `f / |∇f|` clipped to `±cap`, the unit normal (zero where `∇f = 0`), and the shape operator.
    fn parts(&self, p: DVec2) -> (f64, DVec2, Sym2) {
        let g = self.inner.gradient(p);
        let len = g.length();
        let d = clipped_quotient(self.inner.distance(p), len, self.cap);
        if !(len > 0.0 && len.is_finite()) {
            return (d, DVec2::ZERO, Sym2::scalar(0.0));
        }
        let n = g / len;
        let t = n.perp();
        // P D²f P = (tᵀ D²f t) t tᵀ in 2D.
        let h = self.inner.hessian(p);
        let k = h.quad(t) / len;
        (d, n, Sym2::outer(t).scale(k))
    }
}

impl<S: Shape> Shape for Normalized<S> {
    fn distance(&self, p: DVec2) -> f64 {
        self.parts(p).0
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.parts(p).1
    }
    fn hessian(&self, p: DVec2) -> Sym2 {
        self.parts(p).2
    }
    fn exact_area(&self) -> Option<f64> {
        self.inner.exact_area()
    }
    fn exact_perimeter(&self) -> Option<f64> {
        self.inner.exact_perimeter()
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        self.inner.boundary_samples(n)
    }
    fn corners(&self) -> Vec<DVec2> {
        self.inner.corners()
    }
    fn is_distance(&self) -> bool {
        true
    }
    fn name(&self) -> String {
        self.inner.name()
    }
}

impl<S: Shape<DVec3>> Normalized<S> {
    /// In space: `f / |∇f|` clipped to `±cap`, the unit normal `n` (zero where `∇f = 0`) and the
    /// shape operator `P D²f P / |∇f|`, `P = I − n nᵀ` (module documentation), from one
    /// evaluation of the inner gradient and Hessian.
    pub fn parts3(&self, p: DVec3) -> (f64, DVec3, Sym3) {
        let g = self.inner.gradient(p);
        let len = g.length();
        let d = clipped_quotient(self.inner.distance(p), len, self.cap);
        if !(len > 0.0 && len.is_finite()) {
            return (d, DVec3::ZERO, Sym3::scalar(0.0));
        }
        let n = g / len;
        let proj = Sym3::IDENTITY.sub(&Sym3::outer(n));
        let h = self.inner.hessian(p);
        // P H P by columns: P (H (P e_i)).
        let c = [DVec3::X, DVec3::Y, DVec3::Z].map(|e| proj.mul_vec(h.mul_vec(proj.mul_vec(e))));
        let php = Sym3::new(
            c[0].x,
            0.5 * (c[1].x + c[0].y),
            0.5 * (c[2].x + c[0].z),
            c[1].y,
            0.5 * (c[2].y + c[1].z),
            c[2].z,
        );
        (d, n, php.scale(1.0 / len))
    }
}

impl<S: Shape<DVec3>> Shape<DVec3> for Normalized<S> {
    fn distance(&self, p: DVec3) -> f64 {
        clipped_quotient(
            self.inner.distance(p),
            self.inner.gradient(p).length(),
            self.cap,
        )
    }
    fn gradient(&self, p: DVec3) -> DVec3 {
        self.parts3(p).1
    }
    fn hessian(&self, p: DVec3) -> Sym3 {
        self.parts3(p).2
    }
    fn exact_area(&self) -> Option<f64> {
        self.inner.exact_area()
    }
    fn exact_perimeter(&self) -> Option<f64> {
        self.inner.exact_perimeter()
    }
    fn is_distance(&self) -> bool {
        true
    }
    fn name(&self) -> String {
        self.inner.name()
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levelset::Sphere;

    /// `f = c (|x|² − R²)` around a sphere: `f/|∇f|` is `(|x|² − R²)/(2|x|)`, the normal is
    /// radial and the shape operator at `|x| = R` has the curvature `1/R` twice in the tangent
    /// plane and zero along the normal, whatever `c`.
    struct Quadric(f64, f64);
    impl Shape<DVec3> for Quadric {
        fn distance(&self, p: DVec3) -> f64 {
            self.0 * (p.length_squared() - self.1 * self.1)
        }
        fn name(&self) -> String {
            "quadric".into()
        }
    }

    #[test]
    fn sphere_quadric_gives_distance_normal_and_curvatures() {
        let r = 0.4;
        let p = DVec3::new(1.0, -2.0, 0.5).normalize() * r;
        for c in [1e-3, 1.0, 50.0] {
            let s = Normalized {
                inner: Quadric(c, r),
                cap: 4.0,
            };
            let (d, n, h) = s.parts3(p);
            assert!(d.abs() < 1e-9, "{d}");
            assert!((n - p / r).length() < 1e-6, "{n:?}");
            let (mut l, _) = h.eigen();
            l.sort_by(f64::total_cmp);
            assert!(l[0].abs() < 1e-4, "{l:?}");
            assert!(
                (l[1] - 1.0 / r).abs() < 1e-4 && (l[2] - 1.0 / r).abs() < 1e-4,
                "{l:?}"
            );
            // Off the surface: the first-order distance (|x|² − R²)/(2|x|).
            let q = p * 1.1;
            let want = (q.length_squared() - r * r) / (2.0 * q.length());
            assert!((s.distance(q) - want).abs() < 1e-7);
        }
        // The sphere's own distance is unchanged (up to round-off).
        let s = Normalized {
            inner: Sphere {
                centre: DVec3::ZERO,
                radius: r,
            },
            cap: 4.0,
        };
        assert!((s.distance(p * 1.5) - 0.5 * r).abs() < 1e-12);
    }
}
