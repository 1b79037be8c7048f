//! The star-shaped surface of 004 §5 (its Fig. 5): in spherical coordinates around a centre,
//! `ρ(θ, φ) = r0 + a cos 6θ cos² 3φ` with `θ` the azimuth and `φ ∈ [−π/2, π/2]` the elevation;
//! the level set `u(p) = |p − c| − ρ(θ(p), φ(p))` (negative inside, not a distance function).

use std::f64::consts::{PI, TAU};

use super::jet::Jet;
use super::Shape;
use crate::geom::DVec3;
use crate::metric::Sym3;

/// The star-shaped surface `|p − c| = r0 + a cos 6θ cos² 3φ` (004 §5; `r0 = 0.45`, `a = 0.3`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StarSurface {
    /// Centre `c`.
    pub centre: DVec3,
    /// Mean radius `r0`.
    pub r0: f64,
    /// Amplitude `a` (`a < r0` keeps the surface star-shaped around `c`).
    pub amplitude: f64,
}

impl StarSurface {
    /// The surface of 004 §5: `r0 = 0.45`, `a = 0.3`, centred at the origin (domain `[−1, 1]³`).
    pub const PAPER: StarSurface = StarSurface {
        centre: DVec3::ZERO,
        r0: 0.45,
        amplitude: 0.3,
    };

    /// The radius `ρ(θ, φ)` in the direction of azimuth `theta` and elevation `phi`.
    pub fn radius_at(&self, theta: f64, phi: f64) -> f64 {
        let c3 = (3.0 * phi).cos();
        self.r0 + self.amplitude * (6.0 * theta).cos() * c3 * c3
    }

    /// The radius in the direction of `d` (any non-zero vector).
    pub fn radius_towards(&self, d: DVec3) -> f64 {
        let r = d.length();
        let theta = d.y.atan2(d.x);
        let phi = if r > 0.0 {
            (d.z / r).clamp(-1.0, 1.0).asin()
        } else {
            0.0
        };
        self.radius_at(theta, phi)
    }

    /// `u` at `p` with its exact gradient and Hessian, from the Cartesian form of the radius:
    /// with `d = p − c = (x, y, z)`, `s² = x² + y²` and `r² = s² + z²`,
    /// `cos 6θ = Re((x + iy)⁶) / s⁶` and `cos 3φ = s (s² − 3z²) / r³`, so
    /// `u = r − r0 − a Re((x + iy)⁶) (s² − 3z²)² / (s⁴ r⁶)`, a quotient of polynomials
    /// differentiated exactly ([`Jet`]). On the axis through the centre (`s = 0`) the last term
    /// is `O(s²)` with a direction-dependent second derivative: its value and gradient are zero
    /// there and its Hessian is taken as zero (the mean over the directions around the axis).
    /// At the centre itself the gradient and Hessian are zero.
    fn jet(&self, p: DVec3) -> Jet {
        let d = p - self.centre;
        let [x, y, z] = [0, 1, 2].map(|i| Jet::var(d, i));
        let s2 = x.mul(x).add(y.mul(y));
        let r2 = s2.add(z.mul(z));
        if r2.v == 0.0 {
            return Jet::constant(-self.radius_towards(d));
        }
        let r = r2.sqrt();
        let u = r.sub(Jet::constant(self.r0));
        if s2.v == 0.0 {
            return u;
        }
        // (x + iy)² = (x² − y², 2xy), then the cube: (x + iy)⁶ = ((x + iy)²)³.
        let (a, b) = (x.mul(x).sub(y.mul(y)), x.mul(y).scale(2.0));
        let (a2, b2) = (a.mul(a).sub(b.mul(b)), a.mul(b).scale(2.0));
        let re6 = a2.mul(a).sub(b2.mul(b));
        let q = s2.sub(z.mul(z).scale(3.0));
        let den = s2.mul(s2).mul(r2).mul(r2).mul(r2);
        let term = re6.mul(q).mul(q).mul(den.recip());
        u.sub(term.scale(self.amplitude))
    }

    /// The enclosed volume `∫∫ ρ³/3 cos φ dφ dθ`, by Gauss–Legendre quadrature in `φ` and the
    /// trapezoidal rule in `θ` (exact for this trigonometric polynomial to round-off).
    fn volume(&self) -> f64 {
        // ρ³ is a trigonometric polynomial of degree 18 in θ: 64 trapezoidal points are exact.
        let nt = 64;
        // In φ, cos φ · (polynomial in cos² 3φ of degree 3) on [−π/2, π/2]: composite Gauss.
        let (nodes, weights) = gauss5();
        let panels = 64;
        let dphi = PI / panels as f64;
        let mut sum = 0.0;
        for i in 0..nt {
            let theta = TAU * i as f64 / nt as f64;
            for p in 0..panels {
                let lo = -0.5 * PI + p as f64 * dphi;
                for (x, w) in nodes.iter().zip(weights) {
                    let phi = lo + 0.5 * dphi * (x + 1.0);
                    let r = self.radius_at(theta, phi);
                    sum += w * 0.5 * dphi * r * r * r / 3.0 * phi.cos();
                }
            }
        }
        sum * TAU / nt as f64
    }
}

fn gauss5() -> ([f64; 5], [f64; 5]) {
    let a = (5.0 - 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let b = (5.0 + 2.0 * (10.0f64 / 7.0).sqrt()).sqrt() / 3.0;
    let wa = (322.0 + 13.0 * 70.0f64.sqrt()) / 900.0;
    let wb = (322.0 - 13.0 * 70.0f64.sqrt()) / 900.0;
    ([-b, -a, 0.0, a, b], [wb, wa, 128.0 / 225.0, wa, wb])
}

impl Shape<DVec3> for StarSurface {
    /// `|p − c| − ρ(θ, φ)`: zero on the surface, negative inside; not a distance (its gradient
    /// has length between 1 and about 1 + |∇ρ|/ρ).
    fn distance(&self, p: DVec3) -> f64 {
        let d = p - self.centre;
        d.length() - self.radius_towards(d)
    }
    /// Exact: the Cartesian form of `u` differentiated exactly (second-order forward mode).
    fn gradient(&self, p: DVec3) -> DVec3 {
        self.jet(p).g
    }
    /// Exact, as the gradient; on the axis the angular term contributes zero.
    fn hessian(&self, p: DVec3) -> Sym3 {
        self.jet(p).h
    }
    fn is_distance(&self) -> bool {
        false
    }
    fn exact_area(&self) -> Option<f64> {
        Some(self.volume())
    }
    fn name(&self) -> String {
        format!("star(r0 = {}, a = {})", self.r0, self.amplitude)
    }
}
