//! The ball `|p - c| < R` in any dimension: [`Circle`] (the disk) in the plane, [`Sphere`] in
//! space, one generic type.

use std::f64::consts::{PI, TAU};

use super::space::{projector, ShapePoint};
use super::Shape;
use crate::geom::{DVec2, DVec3};

/// The ball of centre `centre` and radius `radius`: `d = |p - c| - R` (exact).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ball<P = DVec2> {
    /// Centre `c`.
    pub centre: P,
    /// Radius `R`.
    pub radius: f64,
}

/// The disk in the plane.
pub type Circle = Ball<DVec2>;
/// The ball in space (its boundary is the sphere).
pub type Sphere = Ball<DVec3>;

impl<P: ShapePoint> Shape<P> for Ball<P> {
    fn distance(&self, p: P) -> f64 {
        (p - self.centre).norm() - self.radius
    }
    /// `(p - c) / |p - c|`; the first axis at the centre, where the distance is not
    /// differentiable.
    fn gradient(&self, p: P) -> P {
        let d = p - self.centre;
        let r = d.norm();
        if r > 0.0 {
            P::from_fn(|i| d.coord(i) / r)
        } else {
            P::from_fn(|i| if i == 0 { 1.0 } else { 0.0 })
        }
    }
    /// `(I - n nᵀ) / |p - c|`; zero at the centre (the cone tip has no finite Hessian).
    fn hessian(&self, p: P) -> P::Hessian {
        let d = p - self.centre;
        let r = d.norm();
        if r > 0.0 {
            projector(P::from_fn(|i| d.coord(i) / r), 1.0 / r)
        } else {
            P::Hessian::default()
        }
    }
    /// `π R²` in the plane, `4/3 π R³` in space.
    fn exact_area(&self) -> Option<f64> {
        let r = self.radius;
        Some(if P::DIM == 2 {
            PI * r * r
        } else {
            4.0 / 3.0 * PI * r * r * r
        })
    }
    /// `2 π R` in the plane, `4 π R²` in space.
    fn exact_perimeter(&self) -> Option<f64> {
        let r = self.radius;
        Some(if P::DIM == 2 {
            TAU * r
        } else {
            2.0 * TAU * r * r
        })
    }
    /// [`ShapePoint::unit_sphere_samples`] scaled and moved onto the boundary.
    fn boundary_samples(&self, n: usize) -> Option<Vec<P>> {
        Some(
            P::unit_sphere_samples(n)
                .into_iter()
                .map(|u| self.centre + u.scaled(self.radius))
                .collect(),
        )
    }
    fn name(&self) -> String {
        format!(
            "{}(centre = {}, radius = {})",
            if P::DIM == 2 { "circle" } else { "sphere" },
            self.centre.describe(),
            self.radius
        )
    }
}
