//! Implicit shapes given by signed distance functions (negative inside, positive outside; 004
//! §2.1: the level set is `u = ±d`).
//!
//! Shapes are generic over the point type ([`ShapePoint`]: `DVec2`, the default, or `DVec3`).
//! [`Ball`] ([`Circle`] in the plane, [`Sphere`] in space), [`Torus`] (space) and [`Zalesak`]
//! (plane) have exact signed distances with analytic gradients (and Hessians, but for the torus);
//! [`Flower`] has a first-order normalised distance; [`Union`], [`Intersection`] and
//! [`Difference`] combine two shapes by min/max; any [`Expr`] is a shape whose "distance" is just
//! its value. [`shape_by_name`] builds the shapes the benchmarks use.

mod ball;
mod csg;
mod jet;
mod normalized;
mod space;
mod star;
mod torus;

pub use ball::{Ball, Circle, Sphere};
pub use csg::{Difference, Intersection, Rotated, Union};
pub use normalized::{normalized_distance, Normalized};
pub use space::ShapePoint;
pub use star::StarSurface;
pub use torus::Torus;

use super::arcpoly::{ArcPolygon, Piece};
use super::expr::Expr;
use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::metric::Sym2;
use space::projector;
use std::f64::consts::{PI, TAU};

/// A shape given by a signed distance function (negative inside), on points `P` of the plane
/// (`DVec2`, the default: `dyn Shape` is a planar shape) or of space (`DVec3`).
pub trait Shape<P: ShapePoint = DVec2>: Send + Sync {
    /// Signed distance (or, where documented, an approximation of it) from `p` to the boundary.
    fn distance(&self, p: P) -> f64;

    /// Gradient of [`Shape::distance`]. The default uses central differences with step
    /// `1e-6 max(1, |p|_∞)`.
    fn gradient(&self, p: P) -> P {
        space::fd_gradient(|q| self.distance(q), p)
    }

    /// Hessian of [`Shape::distance`]. The default uses second differences with step
    /// `1e-4 max(1, |p|_∞)` (truncation error O(h²), round-off O(eps/h²) ≈ 1e-8).
    fn hessian(&self, p: P) -> P::Hessian {
        space::fd_hessian(|q| self.distance(q), p)
    }

    /// Exact measure of the inside (area in 2D, volume in 3D), when known in closed form or by
    /// exact geometry.
    fn exact_area(&self) -> Option<f64> {
        None
    }

    /// Exact measure of the boundary (length in 2D, area in 3D), when known.
    fn exact_perimeter(&self) -> Option<f64> {
        None
    }

    /// About `n` points on the exact interface (for the exact → discrete Hausdorff direction),
    /// or `None` when the shape cannot sample its boundary.
    fn boundary_samples(&self, _n: usize) -> Option<Vec<P>> {
        None
    }

    /// The sharp points of the boundary (corners: points where the tangent jumps), exactly on
    /// the zero level, or empty for a smooth shape (the default). The distance has a kink there
    /// that a P1 level set cannot follow unless a vertex sits on the corner itself;
    /// [`crate::adapt::adapt_to_shape`] inserts one at each ([`crate::adapt::ShapeAdaptOptions::features`]).
    fn corners(&self) -> Vec<P> {
        Vec::new()
    }

    /// Whether [`Shape::distance`] is a signed distance, at least near the zero level (`true`,
    /// the default). A level-set function that is not one (an [`Expr`] such as
    /// `x^2/a^2 + y^2/b^2 - 1`) says `false`, and [`crate::adapt::run`] sees it through
    /// [`Normalized`], whose quantities do not depend on its scale.
    fn is_distance(&self) -> bool {
        true
    }

    /// A short human-readable name.
    fn name(&self) -> String;
}

/// Implements [`Shape`] for a pointer type by forwarding every method to the shape it points to.
macro_rules! forward_shape {
    ($ptr:ty) => {
        impl<P: ShapePoint, S: Shape<P> + ?Sized> Shape<P> for $ptr {
            fn distance(&self, p: P) -> f64 {
                (**self).distance(p)
            }
            fn gradient(&self, p: P) -> P {
                (**self).gradient(p)
            }
            fn hessian(&self, p: P) -> P::Hessian {
                (**self).hessian(p)
            }
            fn exact_area(&self) -> Option<f64> {
                (**self).exact_area()
            }
            fn exact_perimeter(&self) -> Option<f64> {
                (**self).exact_perimeter()
            }
            fn boundary_samples(&self, n: usize) -> Option<Vec<P>> {
                (**self).boundary_samples(n)
            }
            fn corners(&self) -> Vec<P> {
                (**self).corners()
            }
            fn is_distance(&self) -> bool {
                (**self).is_distance()
            }
            fn name(&self) -> String {
                (**self).name()
            }
        }
    };
}

forward_shape!(Box<S>);
forward_shape!(&S);

/// Zalesak's slotted disk (004 §5.1; geometry in `papers/README.md`): the disk of radius `radius`
/// centred at `centre` minus the slot `|x - centre.x| <= half_width`, `y <= slot_top`, cut from the
/// bottom of the disk.
///
/// The signed distance is exact: the boundary is split into the arc (the circle without the
/// small bottom arc inside the slot), the two slot walls and the slot top, and the distance is
/// the minimum over these pieces — which also covers the four corners (the arc/wall corners at
/// the bottom and the reflex wall/top corners), since a piece's closest point may be its end
/// point. The sign comes from the exact inside test. Area and perimeter are computed from the
/// pieces (Green's theorem), not tabulated.
#[derive(Debug, Clone, PartialEq)]
pub struct Zalesak {
    /// Centre of the disk.
    pub centre: DVec2,
    /// Radius of the disk.
    pub radius: f64,
    /// Half the width of the slot.
    pub half_width: f64,
    /// Height `y` of the slot's top.
    pub slot_top: f64,
    curve: ArcPolygon,
}

impl Default for Zalesak {
    /// The benchmark disk: radius 0.5 at (0, 0.75), slot `|x| <= 0.06` up to `y = 0.85`.
    fn default() -> Self {
        Zalesak::new(DVec2::new(0.0, 0.75), 0.5, 0.06, 0.85)
            .expect("the default Zalesak parameters are valid")
    }
}

impl Zalesak {
    /// A slotted disk. Requires `0 < half_width < radius` and a slot top strictly inside the
    /// disk above the slot's bottom corners.
    pub fn new(centre: DVec2, radius: f64, half_width: f64, slot_top: f64) -> Result<Zalesak> {
        let ok = centre.is_finite()
            && radius.is_finite()
            && radius > 0.0
            && half_width > 0.0
            && half_width < radius;
        if !ok {
            return Err(Error::InvalidInput(format!(
                "Zalesak disk: need 0 < half_width ({half_width}) < radius ({radius}) and a finite centre"
            )));
        }
        let depth = (radius * radius - half_width * half_width).sqrt();
        let y_bottom = centre.y - depth;
        let y_top_arc = centre.y + depth;
        if !(slot_top > y_bottom && slot_top < y_top_arc) {
            return Err(Error::InvalidInput(format!(
                "Zalesak disk: slot top {slot_top} must lie in ({y_bottom}, {y_top_arc})"
            )));
        }
        let (w, c) = (half_width, centre);
        // Angle of the bottom-right corner (c.x + w, y_bottom) seen from the centre.
        let start = (-depth).atan2(w);
        let span = TAU - 2.0 * (w / radius).asin();
        let br = DVec2::new(c.x + w, y_bottom);
        let bl = DVec2::new(c.x - w, y_bottom);
        let tl = DVec2::new(c.x - w, slot_top);
        let tr = DVec2::new(c.x + w, slot_top);
        let curve = ArcPolygon {
            pieces: vec![
                Piece::Arc {
                    centre: c,
                    radius,
                    start,
                    span,
                },
                Piece::Segment { a: bl, b: tl },
                Piece::Segment { a: tl, b: tr },
                Piece::Segment { a: tr, b: br },
            ],
        };
        Ok(Zalesak {
            centre,
            radius,
            half_width,
            slot_top,
            curve,
        })
    }

    /// Exact inside test (strict: boundary points are not inside).
    pub fn contains(&self, p: DVec2) -> bool {
        let in_disk = (p - self.centre).length() < self.radius;
        let in_slot = (p.x - self.centre.x).abs() < self.half_width && p.y < self.slot_top;
        in_disk && !in_slot
    }

    fn sign(&self, p: DVec2) -> f64 {
        if self.contains(p) {
            -1.0
        } else {
            1.0
        }
    }
}

impl Shape for Zalesak {
    fn distance(&self, p: DVec2) -> f64 {
        self.sign(p) * self.curve.closest(p).dist
    }
    /// `s (p - q) / |p - q|` for the closest boundary point `q`; on the boundary (within
    /// round-off of it, where `p - q` is noise), the outward normal of the closest piece.
    fn gradient(&self, p: DVec2) -> DVec2 {
        let c = self.curve.closest(p);
        if c.dist > 64.0 * f64::EPSILON * p.abs().max_element().max(1.0) {
            self.sign(p) * (p - c.point) / c.dist
        } else {
            c.normal
        }
    }
    /// Zero where the closest point is inside a straight piece; `±(I - n n^T)/|p - c|` where it is
    /// inside the arc; `s (I - g g^T)/|p - q|` where it is a corner `q`. Zero on corners.
    fn hessian(&self, p: DVec2) -> Sym2 {
        let c = self.curve.closest(p);
        if let Some(centre) = c.arc_centre {
            let d = p - centre;
            let rho = d.length();
            if rho == 0.0 {
                return Sym2::default();
            }
            let factor = if c.dist == 0.0 {
                1.0
            } else {
                self.sign(p) * (rho - self.radius).signum()
            };
            projector(d / rho, factor / rho)
        } else if c.at_end && c.dist > 0.0 {
            let g = (p - c.point) / c.dist;
            projector(g, self.sign(p) / c.dist)
        } else {
            Sym2::default()
        }
    }
    fn exact_area(&self) -> Option<f64> {
        Some(self.curve.area())
    }
    fn exact_perimeter(&self) -> Option<f64> {
        Some(self.curve.perimeter())
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        Some(self.curve.samples(n))
    }
    /// The four slot corners, exactly: `(c.x ∓ w, c.y - sqrt(R² - w²))` where the slot walls
    /// meet the circle and `(c.x ∓ w, slot_top)` at the slot top (the junctions of the pieces).
    fn corners(&self) -> Vec<DVec2> {
        self.curve.corners()
    }
    fn name(&self) -> String {
        "zalesak".into()
    }
}

/// The "flower" `r(θ) = r0 + a cos(k θ)` around `centre` (polar coordinates about the centre).
///
/// The distance is approximate: `f / |∇f|` with `f = ρ - r(θ)`, i.e.
/// `(ρ - r(θ)) / sqrt(1 + (r'(θ)/ρ)²)` — the first-order normalisation, exact on the curve to
/// first order (zero level exact, unit gradient on the curve) but not a true distance away from
/// it. Area is exact (`π r0² + π a²/2` for `k >= 1`); the perimeter is integrated by the periodic
/// trapezoidal rule (spectrally accurate).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flower {
    /// Centre of the polar coordinates.
    pub centre: DVec2,
    /// Mean radius `r0`.
    pub r0: f64,
    /// Amplitude `a` of the petals.
    pub a: f64,
    /// Number of petals `k`.
    pub k: u32,
}

impl Flower {
    /// A flower; requires `r0 > |a|` (so that `r(θ) > 0`) and `k >= 1`.
    pub fn new(centre: DVec2, r0: f64, a: f64, k: u32) -> Result<Flower> {
        if !(centre.is_finite() && r0.is_finite() && a.is_finite() && r0 > a.abs() && k >= 1) {
            return Err(Error::InvalidInput(format!(
                "flower: need r0 > |a| and k >= 1 (got r0 = {r0}, a = {a}, k = {k})"
            )));
        }
        Ok(Flower { centre, r0, a, k })
    }

    fn r(&self, theta: f64) -> f64 {
        self.r0 + self.a * (self.k as f64 * theta).cos()
    }

    fn dr(&self, theta: f64) -> f64 {
        -self.a * self.k as f64 * (self.k as f64 * theta).sin()
    }
}

impl Shape for Flower {
    fn distance(&self, p: DVec2) -> f64 {
        let d = p - self.centre;
        let rho = d.length();
        if rho == 0.0 {
            return -(self.r0 - self.a.abs());
        }
        let theta = d.y.atan2(d.x);
        let q = self.dr(theta) / rho;
        (rho - self.r(theta)) / (1.0 + q * q).sqrt()
    }
    fn exact_area(&self) -> Option<f64> {
        Some(PI * self.r0 * self.r0 + 0.5 * PI * self.a * self.a)
    }
    fn exact_perimeter(&self) -> Option<f64> {
        let m = 4096 * self.k as usize;
        let h = TAU / m as f64;
        let sum: f64 = (0..m)
            .map(|i| {
                let t = i as f64 * h;
                self.r(t).hypot(self.dr(t))
            })
            .sum();
        Some(sum * h)
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        Some(
            (0..n)
                .map(|i| {
                    let t = TAU * i as f64 / n as f64;
                    let (s, c) = t.sin_cos();
                    self.centre + self.r(t) * DVec2::new(c, s)
                })
                .collect(),
        )
    }
    fn name(&self) -> String {
        format!("flower(r0 = {}, a = {}, k = {})", self.r0, self.a, self.k)
    }
}

impl Shape for Expr {
    /// The expression's value (not a distance unless the expression is one).
    fn distance(&self, p: DVec2) -> f64 {
        self.eval(p)
    }
    fn is_distance(&self) -> bool {
        false
    }
    fn name(&self) -> String {
        self.source().to_string()
    }
}

/// The names [`shape_by_name`] accepts.
pub const SHAPE_NAMES: [&str; 3] = ["circle", "zalesak", "flower"];

/// The benchmark shapes by name:
/// - `"circle"`: radius 0.5 at the origin (meant for the domain `[-1, 1]²`);
/// - `"zalesak"`: [`Zalesak::default`] (radius 0.5 at (0, 0.75), slot `|x| <= 0.06` up to
///   `y = 0.85`; domain `[-2, 2]²`, 004 §5.1);
/// - `"flower"`: `r = 0.5 + 0.1 cos(5θ)` at the origin (domain `[-1, 1]²`; curvature radius
///   between about 0.076 in the valleys and 0.12 at the petal tips).
///
/// Names are case-insensitive; any other name is an error listing the valid ones.
pub fn shape_by_name(name: &str) -> Result<Box<dyn Shape>> {
    match name.trim().to_ascii_lowercase().as_str() {
        "circle" => Ok(Box::new(Circle {
            centre: DVec2::ZERO,
            radius: 0.5,
        })),
        "zalesak" => Ok(Box::new(Zalesak::default())),
        "flower" => Ok(Box::new(Flower::new(DVec2::ZERO, 0.5, 0.1, 5)?)),
        _ => Err(Error::InvalidInput(format!(
            "unknown shape '{name}': valid shapes are {}",
            SHAPE_NAMES.join(", ")
        ))),
    }
}

/// The nodal interpolant `u_h = I_h d` of a shape's distance on the vertices of `mesh` (the P1
/// level set of 004 §2.1), computed in parallel.
pub fn nodal_distance(mesh: &crate::mesh::Mesh2, shape: &dyn Shape) -> Vec<f64> {
    use rayon::prelude::*;
    mesh.points.par_iter().map(|&p| shape.distance(p)).collect()
}
