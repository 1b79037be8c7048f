//! Shapes built from other shapes: union, intersection and difference by min/max of the
//! distances, and rigid rotation.

use super::Shape;
use crate::geom::DVec2;
use crate::metric::Sym2;

/// Picks the derivative of whichever operand is active in a min/max combination.
fn pick<S: Shape + ?Sized, T: Shape + ?Sized>(
    first_active: bool,
    a: &S,
    b: &T,
    negate_b: bool,
    p: DVec2,
) -> (DVec2, Sym2) {
    if first_active {
        (a.gradient(p), a.hessian(p))
    } else {
        let s = if negate_b { -1.0 } else { 1.0 };
        (s * b.gradient(p), b.hessian(p).scale(s))
    }
}

/// Keeps the samples of `from` for which `keep` holds.
fn filtered(from: &dyn Shape, n: usize, keep: impl Fn(DVec2) -> bool) -> Option<Vec<DVec2>> {
    Some(
        from.boundary_samples(n)?
            .into_iter()
            .filter(|&p| keep(p))
            .collect(),
    )
}

/// The corners of `from` for which `keep` holds.
fn corners_where(from: &dyn Shape, keep: impl Fn(DVec2) -> bool) -> Vec<DVec2> {
    from.corners().into_iter().filter(|&p| keep(p)).collect()
}

/// Union `A ∪ B`: `min(d_A, d_B)`. A distance bound: exact outside the union; inside, exact
/// away from the seams where the two boundaries cross, and an underestimate of `|d|` where the
/// closest point of one boundary lies inside the other shape.
pub struct Union {
    /// The first operand `A`.
    pub a: Box<dyn Shape>,
    /// The second operand `B`.
    pub b: Box<dyn Shape>,
}

impl Shape for Union {
    fn distance(&self, p: DVec2) -> f64 {
        self.a.distance(p).min(self.b.distance(p))
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        let first = self.a.distance(p) <= self.b.distance(p);
        pick(first, &self.a, &self.b, false, p).0
    }
    fn hessian(&self, p: DVec2) -> Sym2 {
        let first = self.a.distance(p) <= self.b.distance(p);
        pick(first, &self.a, &self.b, false, p).1
    }
    /// The samples of each operand that lie outside (or on) the other: exactly the points of the
    /// union's boundary.
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        let mut s = filtered(&*self.a, n, |p| self.b.distance(p) >= 0.0)?;
        s.extend(filtered(&*self.b, n, |p| self.a.distance(p) >= 0.0)?);
        Some(s)
    }
    /// The operands' corners on the union's boundary; the seams where the two boundaries cross
    /// are corners too but are not computed.
    fn corners(&self) -> Vec<DVec2> {
        let mut c = corners_where(&*self.a, |p| self.b.distance(p) >= 0.0);
        c.extend(corners_where(&*self.b, |p| self.a.distance(p) >= 0.0));
        c
    }
    fn name(&self) -> String {
        format!("union({}, {})", self.a.name(), self.b.name())
    }
}

/// Intersection `A ∩ B`: `max(d_A, d_B)`. A distance bound: exact inside; outside, exact away
/// from the seams where the two boundaries cross and an underestimate near them.
pub struct Intersection {
    /// The first operand `A`.
    pub a: Box<dyn Shape>,
    /// The second operand `B`.
    pub b: Box<dyn Shape>,
}

impl Shape for Intersection {
    fn distance(&self, p: DVec2) -> f64 {
        self.a.distance(p).max(self.b.distance(p))
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        let first = self.a.distance(p) >= self.b.distance(p);
        pick(first, &self.a, &self.b, false, p).0
    }
    fn hessian(&self, p: DVec2) -> Sym2 {
        let first = self.a.distance(p) >= self.b.distance(p);
        pick(first, &self.a, &self.b, false, p).1
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        let mut s = filtered(&*self.a, n, |p| self.b.distance(p) <= 0.0)?;
        s.extend(filtered(&*self.b, n, |p| self.a.distance(p) <= 0.0)?);
        Some(s)
    }
    /// The operands' corners on the intersection's boundary (seams not computed).
    fn corners(&self) -> Vec<DVec2> {
        let mut c = corners_where(&*self.a, |p| self.b.distance(p) <= 0.0);
        c.extend(corners_where(&*self.b, |p| self.a.distance(p) <= 0.0));
        c
    }
    fn name(&self) -> String {
        format!("intersection({}, {})", self.a.name(), self.b.name())
    }
}

/// Difference `A \ B = A ∩ Bᶜ`: `max(d_A, -d_B)`. A distance bound: exact inside; outside,
/// exact away from the seams and an underestimate near them.
pub struct Difference {
    /// The first operand `A`.
    pub a: Box<dyn Shape>,
    /// The second operand `B`.
    pub b: Box<dyn Shape>,
}

impl Shape for Difference {
    fn distance(&self, p: DVec2) -> f64 {
        self.a.distance(p).max(-self.b.distance(p))
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        let first = self.a.distance(p) >= -self.b.distance(p);
        pick(first, &self.a, &self.b, true, p).0
    }
    fn hessian(&self, p: DVec2) -> Sym2 {
        let first = self.a.distance(p) >= -self.b.distance(p);
        pick(first, &self.a, &self.b, true, p).1
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        let mut s = filtered(&*self.a, n, |p| self.b.distance(p) >= 0.0)?;
        s.extend(filtered(&*self.b, n, |p| self.a.distance(p) <= 0.0)?);
        Some(s)
    }
    /// The operands' corners on the difference's boundary (seams not computed).
    fn corners(&self) -> Vec<DVec2> {
        let mut c = corners_where(&*self.a, |p| self.b.distance(p) >= 0.0);
        c.extend(corners_where(&*self.b, |p| self.a.distance(p) <= 0.0));
        c
    }
    fn name(&self) -> String {
        format!("difference({}, {})", self.a.name(), self.b.name())
    }
}

/// A shape rotated by `angle` (radians, counter-clockwise) about `pivot`: the exact solution of
/// a rigid rotation such as Zalesak's `u = (-y, x)` (004 §5.1) at time `t = angle`. Distances,
/// derivatives, area, perimeter and boundary samples are those of the inner shape, rotated.
pub struct Rotated {
    /// The shape before rotation.
    pub shape: Box<dyn Shape>,
    /// Centre of the rotation.
    pub pivot: DVec2,
    /// Angle in radians, counter-clockwise.
    pub angle: f64,
}

impl Rotated {
    /// `p` rotated by `sign * angle` about the pivot.
    fn turn(&self, p: DVec2, sign: f64) -> DVec2 {
        let (s, c) = (sign * self.angle).sin_cos();
        let d = p - self.pivot;
        self.pivot + DVec2::new(c * d.x - s * d.y, s * d.x + c * d.y)
    }

    fn turn_vec(&self, v: DVec2, sign: f64) -> DVec2 {
        let (s, c) = (sign * self.angle).sin_cos();
        DVec2::new(c * v.x - s * v.y, s * v.x + c * v.y)
    }
}

impl Shape for Rotated {
    fn distance(&self, p: DVec2) -> f64 {
        self.shape.distance(self.turn(p, -1.0))
    }
    fn gradient(&self, p: DVec2) -> DVec2 {
        self.turn_vec(self.shape.gradient(self.turn(p, -1.0)), 1.0)
    }
    /// `R H R^T` with `H` the inner Hessian at the rotated-back point.
    fn hessian(&self, p: DVec2) -> Sym2 {
        let h = self.shape.hessian(self.turn(p, -1.0));
        let (s, c) = self.angle.sin_cos();
        // Columns of R H R^T from H applied to the rotated-back basis.
        let (e1, e2) = (DVec2::new(c, -s), DVec2::new(s, c));
        let (h1, h2) = (
            self.turn_vec(h.mul_vec(e1), 1.0),
            self.turn_vec(h.mul_vec(e2), 1.0),
        );
        Sym2::new(h1.x, 0.5 * (h1.y + h2.x), h2.y)
    }
    fn exact_area(&self) -> Option<f64> {
        self.shape.exact_area()
    }
    fn exact_perimeter(&self) -> Option<f64> {
        self.shape.exact_perimeter()
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        Some(
            self.shape
                .boundary_samples(n)?
                .into_iter()
                .map(|p| self.turn(p, 1.0))
                .collect(),
        )
    }
    /// The inner shape's corners, rotated (on the zero level up to round-off).
    fn corners(&self) -> Vec<DVec2> {
        self.shape
            .corners()
            .into_iter()
            .map(|p| self.turn(p, 1.0))
            .collect()
    }
    fn name(&self) -> String {
        format!("rotated({}, {} rad)", self.shape.name(), self.angle)
    }
}
