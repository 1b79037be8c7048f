//! The solid torus around the `z` axis (003 §8, Example 1: `R = 0.4`, `r = 0.2`).

use std::f64::consts::{PI, TAU};

use super::Shape;
use crate::geom::DVec3;

/// The solid torus of centre `centre`, axis `z`, major radius `major` (centre to tube centre) and
/// minor radius `minor` (tube): `d = sqrt((ρ - R)² + z²) - r` with `ρ = sqrt(x² + y²)` relative
/// to the centre (exact for `r <= R`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Torus {
    /// Centre.
    pub centre: DVec3,
    /// Major radius `R`.
    pub major: f64,
    /// Minor radius `r`.
    pub minor: f64,
}

impl Torus {
    /// The torus of 003 §8, Example 1: `R = 0.4`, `r = 0.2` at the origin.
    pub const PAPER: Torus = Torus {
        centre: DVec3::ZERO,
        major: 0.4,
        minor: 0.2,
    };
}

impl Shape<DVec3> for Torus {
    fn distance(&self, p: DVec3) -> f64 {
        let p = p - self.centre;
        (p.z * p.z + ((p.x * p.x + p.y * p.y).sqrt() - self.major).powi(2)).sqrt() - self.minor
    }
    /// `(p - q) / |p - q|` for the nearest point `q` of the core circle; on the axis (`ρ = 0`)
    /// the radial part is taken along `x`, on the core circle the gradient is `x`-directed
    /// outwards (the distance is not differentiable there).
    fn gradient(&self, p: DVec3) -> DVec3 {
        let p = p - self.centre;
        let rho = (p.x * p.x + p.y * p.y).sqrt();
        let radial = if rho > 0.0 {
            DVec3::new(p.x / rho, p.y / rho, 0.0)
        } else {
            DVec3::X
        };
        let d = (rho - self.major) * radial + DVec3::new(0.0, 0.0, p.z);
        let w = d.length();
        if w > 0.0 {
            d / w
        } else {
            radial
        }
    }
    /// `2 π² R r²`.
    fn exact_area(&self) -> Option<f64> {
        Some(2.0 * PI * PI * self.major * self.minor * self.minor)
    }
    /// `4 π² R r`.
    fn exact_perimeter(&self) -> Option<f64> {
        Some(4.0 * PI * PI * self.major * self.minor)
    }
    /// A `k × k` grid in the two angles, `k = ceil(sqrt(n))`.
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec3>> {
        let k = (n as f64).sqrt().ceil().max(1.0) as usize;
        let mut out = Vec::with_capacity(k * k);
        for i in 0..k {
            let (st, ct) = (TAU * i as f64 / k as f64).sin_cos();
            for j in 0..k {
                let (sp, cp) = (TAU * j as f64 / k as f64).sin_cos();
                let rho = self.major + self.minor * cp;
                out.push(self.centre + DVec3::new(rho * ct, rho * st, self.minor * sp));
            }
        }
        Some(out)
    }
    fn name(&self) -> String {
        format!(
            "torus(centre = ({}, {}, {}), R = {}, r = {})",
            self.centre.x, self.centre.y, self.centre.z, self.major, self.minor
        )
    }
}
