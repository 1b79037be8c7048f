//! Closed curves made of straight segments and circular arcs: exact distance, length, enclosed
//! area (Green's theorem) and arc-length sampling. The geometric kernel of
//! [`super::shapes::Zalesak`].

use crate::geom::{point_segment_distance, DVec2};
use std::f64::consts::TAU;

/// One piece of a closed boundary, traversed counter-clockwise around the enclosed region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) enum Piece {
    /// The segment from `a` to `b`.
    Segment { a: DVec2, b: DVec2 },
    /// The arc of the circle `(centre, radius)` from angle `start` through `span > 0` radians
    /// counter-clockwise.
    Arc {
        centre: DVec2,
        radius: f64,
        start: f64,
        span: f64,
    },
}

/// The closest point of a piece to a query point.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Closest {
    /// Distance to the piece.
    pub dist: f64,
    /// The closest point.
    pub point: DVec2,
    /// Outward unit normal of the piece at `point` (for an end point, the normal of this piece).
    pub normal: DVec2,
    /// `Some(centre)` when the closest point is inside an arc (the distance then varies as
    /// `|p - centre|`), `None` otherwise.
    pub arc_centre: Option<DVec2>,
    /// Whether the closest point is an end point of the piece (a corner of the curve).
    pub at_end: bool,
}

impl Piece {
    /// Length of the piece.
    pub fn length(&self) -> f64 {
        match *self {
            Piece::Segment { a, b } => (b - a).length(),
            Piece::Arc { radius, span, .. } => radius * span,
        }
    }

    /// The point at fraction `s` in `[0, 1]` of the piece (by arc length).
    pub fn point_at(&self, s: f64) -> DVec2 {
        match *self {
            Piece::Segment { a, b } => a + s * (b - a),
            Piece::Arc {
                centre,
                radius,
                start,
                span,
            } => {
                let (sn, cs) = (start + s * span).sin_cos();
                centre + radius * DVec2::new(cs, sn)
            }
        }
    }

    /// Unit tangent (direction of traversal) at fraction `s` in `[0, 1]`.
    pub fn tangent_at(&self, s: f64) -> DVec2 {
        match *self {
            Piece::Segment { a, b } => (b - a).normalize_or_zero(),
            Piece::Arc { start, span, .. } => {
                let (sn, cs) = (start + s * span).sin_cos();
                DVec2::new(-sn, cs)
            }
        }
    }

    /// The end point (`s = 1`), exact for a segment.
    fn end(&self) -> DVec2 {
        match *self {
            Piece::Segment { b, .. } => b,
            Piece::Arc { .. } => self.point_at(1.0),
        }
    }

    /// The start point (`s = 0`), exact for a segment.
    fn start(&self) -> DVec2 {
        match *self {
            Piece::Segment { a, .. } => a,
            Piece::Arc { .. } => self.point_at(0.0),
        }
    }

    /// Contribution `1/2 ∮ (x dy - y dx)` of the piece to the enclosed area.
    pub fn area_term(&self) -> f64 {
        match *self {
            Piece::Segment { a, b } => 0.5 * a.perp_dot(b),
            Piece::Arc {
                centre,
                radius,
                span,
                ..
            } => {
                // x = c + R e(θ): x × dx = R c × e'(θ) dθ + R² dθ.
                let chord = self.point_at(1.0) - self.point_at(0.0);
                0.5 * (centre.perp_dot(chord) + radius * radius * span)
            }
        }
    }

    /// Closest point of the piece to `p`.
    pub fn closest(&self, p: DVec2) -> Closest {
        match *self {
            Piece::Segment { a, b } => {
                let (dist, t) = point_segment_distance(p, a, b);
                let tangent = (b - a).normalize_or_zero();
                Closest {
                    dist,
                    point: a + t * (b - a),
                    normal: DVec2::new(tangent.y, -tangent.x),
                    arc_centre: None,
                    at_end: t <= 0.0 || t >= 1.0,
                }
            }
            Piece::Arc {
                centre,
                radius,
                start,
                span,
            } => {
                let d = p - centre;
                let rho = d.length();
                let phi = d.y.atan2(d.x);
                let rel = (phi - start).rem_euclid(TAU);
                if rho > 0.0 && rel <= span {
                    let normal = d / rho;
                    Closest {
                        dist: (rho - radius).abs(),
                        point: centre + radius * normal,
                        normal,
                        arc_centre: Some(centre),
                        at_end: false,
                    }
                } else if rho == 0.0 {
                    // Every arc point is at distance `radius`; take the first end.
                    let q = self.point_at(0.0);
                    Closest {
                        dist: radius,
                        point: q,
                        normal: (q - centre) / radius,
                        arc_centre: Some(centre),
                        at_end: false,
                    }
                } else {
                    let (q0, q1) = (self.point_at(0.0), self.point_at(1.0));
                    let q = if (p - q0).length_squared() <= (p - q1).length_squared() {
                        q0
                    } else {
                        q1
                    };
                    Closest {
                        dist: (p - q).length(),
                        point: q,
                        normal: (q - centre) / radius,
                        arc_centre: None,
                        at_end: true,
                    }
                }
            }
        }
    }
}

/// A closed curve of pieces, counter-clockwise around the enclosed region.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct ArcPolygon {
    pub pieces: Vec<Piece>,
}

impl ArcPolygon {
    /// The closest point of the whole curve to `p` (minimum over pieces: exact for any curve).
    pub fn closest(&self, p: DVec2) -> Closest {
        let mut best = self.pieces[0].closest(p);
        for piece in &self.pieces[1..] {
            let c = piece.closest(p);
            if c.dist < best.dist {
                best = c;
            }
        }
        best
    }

    /// The junctions of consecutive pieces where the tangent turns (by more than about 1e-9
    /// rad): the corners of the curve. A junction takes the coordinates of a segment's end point
    /// when one of the two pieces is a segment (exact input), else the arc's computed end.
    pub fn corners(&self) -> Vec<DVec2> {
        let n = self.pieces.len();
        (0..n)
            .filter_map(|i| {
                let (p, q) = (&self.pieces[i], &self.pieces[(i + 1) % n]);
                let (t0, t1) = (p.tangent_at(1.0), q.tangent_at(0.0));
                if t0.perp_dot(t1).abs() <= 1e-9 && t0.dot(t1) > 0.0 {
                    return None;
                }
                Some(match (p, q) {
                    (_, Piece::Segment { .. }) => q.start(),
                    _ => p.end(),
                })
            })
            .collect()
    }

    /// Total length.
    pub fn perimeter(&self) -> f64 {
        self.pieces.iter().map(Piece::length).sum()
    }

    /// Enclosed area by Green's theorem, `1/2 ∮ (x dy - y dx)`.
    pub fn area(&self) -> f64 {
        self.pieces.iter().map(Piece::area_term).sum()
    }

    /// `n` points equally spaced in arc length along the curve (the first at the start of the
    /// first piece).
    pub fn samples(&self, n: usize) -> Vec<DVec2> {
        let total = self.perimeter();
        let mut out = Vec::with_capacity(n);
        let mut piece = 0;
        let mut before = 0.0; // arc length before `piece`
        for i in 0..n {
            let s = total * i as f64 / n as f64;
            while piece + 1 < self.pieces.len() && s > before + self.pieces[piece].length() {
                before += self.pieces[piece].length();
                piece += 1;
            }
            let len = self.pieces[piece].length();
            let frac = if len > 0.0 {
                ((s - before) / len).clamp(0.0, 1.0)
            } else {
                0.0
            };
            out.push(self.pieces[piece].point_at(frac));
        }
        out
    }
}
