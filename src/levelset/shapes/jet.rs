//! Second-order forward differentiation in three variables: a [`Jet`] carries a value, its
//! gradient and its Hessian through sums, products, quotients and square roots (the chain rule
//! applied exactly), so a shape written as a formula in `x, y, z` gets exact first and second
//! derivatives ([`super::StarSurface`]).

use crate::geom::DVec3;
use crate::metric::Sym3;

/// A value with its gradient and Hessian in `(x, y, z)`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Jet {
    /// The value.
    pub v: f64,
    /// The gradient.
    pub g: DVec3,
    /// The Hessian.
    pub h: Sym3,
}

/// `a bᵀ + b aᵀ`.
#[inline]
fn sym_outer2(a: DVec3, b: DVec3) -> Sym3 {
    Sym3::new(
        2.0 * a.x * b.x,
        a.x * b.y + b.x * a.y,
        a.x * b.z + b.x * a.z,
        2.0 * a.y * b.y,
        a.y * b.z + b.y * a.z,
        2.0 * a.z * b.z,
    )
}

impl Jet {
    /// The coordinate `i` (0, 1, 2) of the point `p` as a variable.
    pub fn var(p: DVec3, i: usize) -> Jet {
        let mut g = DVec3::ZERO;
        g[i] = 1.0;
        Jet {
            v: p[i],
            g,
            h: Sym3::default(),
        }
    }

    /// A constant.
    pub fn constant(v: f64) -> Jet {
        Jet {
            v,
            g: DVec3::ZERO,
            h: Sym3::default(),
        }
    }

    /// `self + o`.
    #[inline]
    pub fn add(self, o: Jet) -> Jet {
        Jet {
            v: self.v + o.v,
            g: self.g + o.g,
            h: self.h.add(&o.h),
        }
    }

    /// `self − o`.
    #[inline]
    pub fn sub(self, o: Jet) -> Jet {
        self.add(o.scale(-1.0))
    }

    /// `s self`.
    #[inline]
    pub fn scale(self, s: f64) -> Jet {
        Jet {
            v: s * self.v,
            g: s * self.g,
            h: self.h.scale(s),
        }
    }

    /// `self o` (product rule).
    #[inline]
    pub fn mul(self, o: Jet) -> Jet {
        Jet {
            v: self.v * o.v,
            g: self.v * o.g + o.v * self.g,
            h: o.h
                .scale(self.v)
                .add(&self.h.scale(o.v))
                .add(&sym_outer2(self.g, o.g)),
        }
    }

    /// `1 / self` (the value must not be zero).
    #[inline]
    pub fn recip(self) -> Jet {
        let r = 1.0 / self.v;
        let r2 = r * r;
        Jet {
            v: r,
            g: -r2 * self.g,
            h: self
                .h
                .scale(-r2)
                .add(&Sym3::outer(self.g).scale(2.0 * r2 * r)),
        }
    }

    /// `√self` (the value must be positive).
    #[inline]
    pub fn sqrt(self) -> Jet {
        let s = self.v.sqrt();
        Jet {
            v: s,
            g: self.g / (2.0 * s),
            h: self
                .h
                .scale(0.5 / s)
                .add(&Sym3::outer(self.g).scale(-0.25 / (s * s * s))),
        }
    }
}
