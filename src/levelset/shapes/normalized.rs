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
//! `div(∇f/|∇f|)`). All three are unchanged when `f` is multiplied by a constant `c > 0`, so a
//! metric built from them — and the mesh adapted to it — is the same for `f` and `c f`; the band
//! of eq. (6) is measured in distance. Away from the zero level `f / |∇f|` is only a first-order
//! distance; it is clipped to `±cap` (e.g. the domain's diameter) where `∇f` vanishes.

use super::Shape;
use crate::geom::DVec2;
use crate::metric::Sym2;

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
