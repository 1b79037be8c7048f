//! [`ShapePoint`]: the point types shapes are defined on (`DVec2` in the plane, `DVec3` in
//! space), with the symmetric tensor type of their Hessians, and the derivatives by differences
//! that [`super::Shape`] falls back on, written once for both.

use std::f64::consts::TAU;
use std::fmt::Debug;
use std::ops::{Add, Sub};

use crate::geom::{DVec2, DVec3};
use crate::metric::{Sym2, Sym3, SymTensor};

/// A point of `R^2` or `R^3` on which a [`super::Shape`] is evaluated: the little arithmetic the
/// generic shapes need, plus the Hessian type ([`Sym2`], [`Sym3`]).
pub trait ShapePoint:
    Copy + Debug + PartialEq + Send + Sync + 'static + Add<Output = Self> + Sub<Output = Self>
{
    /// The symmetric tensor of second derivatives at such a point.
    type Hessian: Copy + Debug + Default + PartialEq + Send + Sync + 'static;
    /// The dimension.
    const DIM: usize;
    /// The point with coordinates `f(0), .., f(DIM - 1)`.
    fn from_fn(f: impl Fn(usize) -> f64) -> Self;
    /// Coordinate `i`.
    fn coord(self, i: usize) -> f64;
    /// `s v`.
    fn scaled(self, s: f64) -> Self;
    /// Euclidean length.
    fn norm(self) -> f64;
    /// `max_i |x_i|`.
    fn max_abs(self) -> f64;
    /// The symmetric tensor with entries `f(i, j)`, `i <= j`.
    fn hessian_from_fn(f: impl Fn(usize, usize) -> f64) -> Self::Hessian;
    /// `s H`.
    fn hessian_scale(h: &Self::Hessian, s: f64) -> Self::Hessian;
    /// `n` points on the unit circle (equally spaced, counter-clockwise from `(1, 0)`) or the
    /// unit sphere (a Fibonacci lattice, `z` descending).
    fn unit_sphere_samples(n: usize) -> Vec<Self>;
    /// The coordinates as `(x, y)` or `(x, y, z)`.
    fn describe(self) -> String;
}

impl ShapePoint for DVec2 {
    type Hessian = Sym2;
    const DIM: usize = 2;
    #[inline]
    fn from_fn(f: impl Fn(usize) -> f64) -> Self {
        DVec2::new(f(0), f(1))
    }
    #[inline]
    fn coord(self, i: usize) -> f64 {
        self[i]
    }
    #[inline]
    fn scaled(self, s: f64) -> Self {
        s * self
    }
    #[inline]
    fn norm(self) -> f64 {
        self.length()
    }
    #[inline]
    fn max_abs(self) -> f64 {
        self.abs().max_element()
    }
    #[inline]
    fn hessian_from_fn(f: impl Fn(usize, usize) -> f64) -> Sym2 {
        <Sym2 as SymTensor<2>>::from_fn(f)
    }
    #[inline]
    fn hessian_scale(h: &Sym2, s: f64) -> Sym2 {
        h.scale(s)
    }
    fn unit_sphere_samples(n: usize) -> Vec<Self> {
        (0..n)
            .map(|i| {
                let (s, c) = (TAU * i as f64 / n as f64).sin_cos();
                DVec2::new(c, s)
            })
            .collect()
    }
    fn describe(self) -> String {
        format!("({}, {})", self.x, self.y)
    }
}

impl ShapePoint for DVec3 {
    type Hessian = Sym3;
    const DIM: usize = 3;
    #[inline]
    fn from_fn(f: impl Fn(usize) -> f64) -> Self {
        DVec3::new(f(0), f(1), f(2))
    }
    #[inline]
    fn coord(self, i: usize) -> f64 {
        self[i]
    }
    #[inline]
    fn scaled(self, s: f64) -> Self {
        s * self
    }
    #[inline]
    fn norm(self) -> f64 {
        self.length()
    }
    #[inline]
    fn max_abs(self) -> f64 {
        self.abs().max_element()
    }
    #[inline]
    fn hessian_from_fn(f: impl Fn(usize, usize) -> f64) -> Sym3 {
        <Sym3 as SymTensor<3>>::from_fn(f)
    }
    #[inline]
    fn hessian_scale(h: &Sym3, s: f64) -> Sym3 {
        SymTensor::scale(h, s)
    }
    fn unit_sphere_samples(n: usize) -> Vec<Self> {
        let golden = std::f64::consts::PI * (3.0 - 5f64.sqrt());
        (0..n)
            .map(|i| {
                let z = 1.0 - (2 * i + 1) as f64 / n as f64;
                let r = (1.0 - z * z).max(0.0).sqrt();
                let (s, c) = (golden * i as f64).sin_cos();
                DVec3::new(r * c, r * s, z)
            })
            .collect()
    }
    fn describe(self) -> String {
        format!("({}, {}, {})", self.x, self.y, self.z)
    }
}

/// Central differences `(f(p + h e_i) - f(p - h e_i)) / 2h` with `h = 1e-6 max(1, |p|_∞)`.
pub(crate) fn fd_gradient<P: ShapePoint>(f: impl Fn(P) -> f64, p: P) -> P {
    let h = 1e-6 * p.max_abs().max(1.0);
    let step = |i: usize, s: f64| P::from_fn(|k| if k == i { s } else { 0.0 });
    let d: Vec<f64> = (0..P::DIM)
        .map(|i| f(p + step(i, h)) - f(p - step(i, h)))
        .collect();
    P::from_fn(|i| d[i] / (2.0 * h))
}

/// Second differences with `h = 1e-4 max(1, |p|_∞)` (truncation error O(h²), round-off
/// O(eps/h²) ≈ 1e-8): `(f(p + h e_i) - 2 f(p) + f(p - h e_i)) / h²` on the diagonal and
/// `(f(p + h e_i + h e_j) - f(p + h e_i - h e_j) - f(p - h e_i + h e_j) + f(p - h e_i - h e_j))
/// / 4h²` off it.
pub(crate) fn fd_hessian<P: ShapePoint>(f: impl Fn(P) -> f64, p: P) -> P::Hessian {
    let h = 1e-4 * p.max_abs().max(1.0);
    let at = |i: usize, si: f64, j: usize, sj: f64| {
        f(p + P::from_fn(|k| {
            if k == i {
                si
            } else if k == j {
                sj
            } else {
                0.0
            }
        }))
    };
    let f0 = f(p);
    P::hessian_from_fn(|i, j| {
        if i == j {
            (at(i, h, i, h) - 2.0 * f0 + at(i, -h, i, -h)) / (h * h)
        } else {
            (at(i, h, j, h) - at(i, h, j, -h) - at(i, -h, j, h) + at(i, -h, j, -h)) / (4.0 * h * h)
        }
    })
}

/// `s (I - n nᵀ)` for a unit `n`: the Hessian of `|p - c|` (with `s = 1 / |p - c|`) and of the
/// distance to a point or a round boundary.
pub(crate) fn projector<P: ShapePoint>(n: P, s: f64) -> P::Hessian {
    P::hessian_from_fn(|i, j| {
        if i == j {
            s * (1.0 - n.coord(i) * n.coord(i))
        } else {
            -s * n.coord(i) * n.coord(j)
        }
    })
}
