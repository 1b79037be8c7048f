//! Polygonal domains for the initial mesher: a [`PolygonDomain`] is one outer boundary loop,
//! holes, and interface loops (closed curves inside the domain that separate sub-domains, e.g. a
//! circle whose inside gets another `tri_ref`). Each loop carries an edge label and an optional
//! target edge length `h`.
//!
//! The loops are validated here before the triangulation (`cdt.rs`) sees them (spade panics on
//! intersecting constraints): too few points, non-finite or out-of-range coordinates, repeated
//! consecutive points, zero-area loops, self-intersecting or mutually intersecting/touching
//! loops, and loops outside the outer boundary are all reported as [`Error::InvalidInput`].

use crate::error::{Error, Result};
use crate::geom::{orient2d, DVec2};
use rstar::{primitives::GeomWithData, primitives::Rectangle, RTree, AABB};

/// The role of a loop in a [`PolygonDomain`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoopKind {
    /// The outer boundary (exactly one).
    Boundary,
    /// A hole: its inside is not meshed.
    Hole,
    /// An interface: its inside is meshed with sub-domain label `inside_ref`.
    Interface {
        /// Sub-domain label of the triangles inside the loop.
        inside_ref: i32,
    },
}

/// A closed polygonal loop (the closing segment is implied; a repeated first point at the end is
/// dropped).
#[derive(Debug, Clone, PartialEq)]
pub struct DomainLoop {
    /// The loop's vertices in order.
    pub points: Vec<DVec2>,
    /// Edge label of the loop's segments (also the vertex label of its vertices).
    pub label: i32,
    /// Target edge length along the loop: segments longer than `h` are subdivided.
    pub h: Option<f64>,
    /// Outer boundary, hole or interface.
    pub kind: LoopKind,
}

/// A polygonal domain with holes and interfaces, and refinement parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct PolygonDomain {
    /// The loops; the first is the outer boundary.
    pub loops: Vec<DomainLoop>,
    /// Sub-domain label of triangles not inside any interface loop.
    pub domain_ref: i32,
    /// Upper bound on triangle areas (spade's `with_max_allowed_area`).
    pub max_area: Option<f64>,
    /// Minimum angle in degrees for Ruppert refinement (0 to 34; spade's `AngleLimit`).
    pub min_angle_deg: Option<f64>,
}

/// `n` points on the circle of centre `c` and radius `r`, counter-clockwise.
pub fn circle_points(c: DVec2, r: f64, n: usize) -> Vec<DVec2> {
    (0..n)
        .map(|k| {
            let a = std::f64::consts::TAU * k as f64 / n as f64;
            c + r * DVec2::new(a.cos(), a.sin())
        })
        .collect()
}

impl PolygonDomain {
    /// A domain bounded by `outer`, whose segments get label `label`.
    pub fn new(outer: Vec<DVec2>, label: i32) -> Self {
        PolygonDomain {
            loops: vec![DomainLoop {
                points: outer,
                label,
                h: None,
                kind: LoopKind::Boundary,
            }],
            domain_ref: 0,
            max_area: None,
            min_angle_deg: None,
        }
    }

    /// Adds a hole with edge label `label`.
    pub fn hole(mut self, points: Vec<DVec2>, label: i32) -> Self {
        self.loops.push(DomainLoop {
            points,
            label,
            h: None,
            kind: LoopKind::Hole,
        });
        self
    }

    /// Adds an interface loop with edge label `label`; triangles inside get `inside_ref`.
    pub fn interface(mut self, points: Vec<DVec2>, label: i32, inside_ref: i32) -> Self {
        self.loops.push(DomainLoop {
            points,
            label,
            h: None,
            kind: LoopKind::Interface { inside_ref },
        });
        self
    }

    /// Sets the target edge length of the loop added last.
    pub fn with_size(mut self, h: f64) -> Self {
        if let Some(l) = self.loops.last_mut() {
            l.h = Some(h);
        }
        self
    }

    /// Sets the maximum triangle area.
    pub fn with_max_area(mut self, a: f64) -> Self {
        self.max_area = Some(a);
        self
    }

    /// Sets the minimum angle (degrees) of the Delaunay refinement.
    pub fn with_min_angle(mut self, deg: f64) -> Self {
        self.min_angle_deg = Some(deg);
        self
    }
}

pub(super) fn invalid(msg: String) -> Error {
    Error::InvalidInput(format!("polygon domain: {msg}"))
}

/// Twice the signed area of a closed polygon.
pub(super) fn loop_area2(p: &[DVec2]) -> f64 {
    (0..p.len())
        .map(|i| p[i].perp_dot(p[(i + 1) % p.len()]))
        .sum()
}

/// Crossing-number point-in-polygon test (the point is assumed off the polygon).
pub(super) fn inside(p: &[DVec2], q: DVec2) -> bool {
    let mut c = false;
    for i in 0..p.len() {
        let (a, b) = (p[i], p[(i + 1) % p.len()]);
        if (a.y > q.y) != (b.y > q.y) {
            let x = a.x + (q.y - a.y) / (b.y - a.y) * (b.x - a.x);
            if q.x < x {
                c = !c;
            }
        }
    }
    c
}

/// Whether `p` lies on the closed segment `[a, b]` (exact collinearity).
fn on_segment(a: DVec2, b: DVec2, p: DVec2) -> bool {
    orient2d(a, b, p) == 0.0 && (p - a).dot(p - b) <= 0.0
}

/// Whether closed segments `[p1, p2]` and `[q1, q2]` share a point (exact predicates).
fn segments_touch(p1: DVec2, p2: DVec2, q1: DVec2, q2: DVec2) -> bool {
    let d1 = orient2d(q1, q2, p1);
    let d2 = orient2d(q1, q2, p2);
    let d3 = orient2d(p1, p2, q1);
    let d4 = orient2d(p1, p2, q2);
    if d1 * d2 < 0.0 && d3 * d4 < 0.0 {
        return true;
    }
    on_segment(q1, q2, p1)
        || on_segment(q1, q2, p2)
        || on_segment(p1, p2, q1)
        || on_segment(p1, p2, q2)
}

/// Cleans and validates the loops: returns them without a repeated closing point.
pub(super) fn validate(d: &PolygonDomain) -> Result<Vec<Vec<DVec2>>> {
    if let Some(a) = d.max_area {
        if !(a.is_finite() && a > 0.0) {
            return Err(invalid(format!(
                "max_area must be positive and finite, got {a}"
            )));
        }
    }
    if let Some(a) = d.min_angle_deg {
        if !(0.0..=34.0).contains(&a) {
            return Err(invalid(format!(
                "min_angle must lie in [0, 34] degrees (refinement may not terminate above), got {a}"
            )));
        }
    }
    if d.loops.first().map(|l| l.kind) != Some(LoopKind::Boundary)
        || d.loops.iter().skip(1).any(|l| l.kind == LoopKind::Boundary)
    {
        return Err(invalid(
            "the first loop, and only it, must be the outer boundary".into(),
        ));
    }
    let mut loops = Vec::with_capacity(d.loops.len());
    for (k, l) in d.loops.iter().enumerate() {
        let mut p = l.points.clone();
        if p.len() > 1 && p.first() == p.last() {
            p.pop();
        }
        if p.len() < 3 {
            return Err(invalid(format!(
                "loop {k} has {} points, at least 3 are needed",
                p.len()
            )));
        }
        for (i, q) in p.iter().enumerate() {
            let ok = |x: f64| x == 0.0 || (x.abs() > 1e-40 && x.abs() < 1e60);
            if !(q.is_finite() && ok(q.x) && ok(q.y)) {
                return Err(invalid(format!("loop {k}, point {i}: bad coordinate {q}")));
            }
            if p[(i + 1) % p.len()] == *q {
                return Err(invalid(format!(
                    "loop {k}, point {i}: repeated consecutive point {q}"
                )));
            }
        }
        if let Some(h) = l.h {
            if !(h.is_finite() && h > 0.0) {
                return Err(invalid(format!(
                    "loop {k}: target size h must be positive, got {h}"
                )));
            }
        }
        loops.push(p);
    }
    check_intersections(&loops)?;
    for (k, p) in loops.iter().enumerate() {
        if loop_area2(p) == 0.0 {
            return Err(invalid(format!("loop {k} is degenerate (zero area)")));
        }
    }
    // Nesting: every other loop lies inside the outer one; nothing lies inside a hole.
    for (k, l) in loops.iter().enumerate().skip(1) {
        if !inside(&loops[0], l[0]) {
            return Err(invalid(format!(
                "loop {k} is not inside the outer boundary"
            )));
        }
        for (j, h) in loops.iter().enumerate().skip(1) {
            if j != k && d.loops[j].kind == LoopKind::Hole && inside(h, l[0]) {
                return Err(invalid(format!("loop {k} lies inside hole {j}")));
            }
        }
    }
    Ok(loops)
}

/// No two segments of the loops touch, except consecutive segments of one loop at their shared
/// vertex (and those must not fold back onto each other).
fn check_intersections(loops: &[Vec<DVec2>]) -> Result<()> {
    type Seg = GeomWithData<Rectangle<[f64; 2]>, (usize, usize)>;
    let mut segs: Vec<Seg> = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        for i in 0..l.len() {
            let (a, b) = (l[i], l[(i + 1) % l.len()]);
            let r = Rectangle::from_corners(a.min(b).to_array(), a.max(b).to_array());
            segs.push(GeomWithData::new(r, (k, i)));
        }
    }
    let seg = |(k, i): (usize, usize)| {
        let l = &loops[k];
        (l[i], l[(i + 1) % l.len()])
    };
    let tree = RTree::bulk_load(segs.clone());
    for s in &segs {
        let (k, i) = s.data;
        let (a, b) = seg((k, i));
        let env = AABB::from_corners(a.min(b).to_array(), a.max(b).to_array());
        for o in tree.locate_in_envelope_intersecting(env) {
            let (k2, j) = o.data;
            if (k2, j) <= (k, i) {
                continue;
            }
            let (c, d) = seg((k2, j));
            let n = loops[k].len();
            let adjacent = k == k2 && (j == (i + 1) % n || i == (j + 1) % n);
            if adjacent {
                // Shared vertex: an error only if the two segments overlap (fold back).
                let (p, q, r) = if j == (i + 1) % n {
                    (a, b, d)
                } else {
                    (c, d, b)
                };
                if orient2d(p, q, r) == 0.0 && (p - q).dot(r - q) > 0.0 {
                    return Err(invalid(format!(
                        "loop {k} folds back on itself at point {}",
                        if j == (i + 1) % n { j } else { i }
                    )));
                }
            } else if segments_touch(a, b, c, d) {
                return Err(invalid(if k == k2 {
                    format!("loop {k} intersects itself (segments {i} and {j})")
                } else {
                    format!("loops {k} and {k2} intersect or touch (segments {i} and {j})")
                }));
            }
        }
    }
    Ok(())
}

/// The sub-domain label of the region containing `c`, or `None` outside the domain.
pub(super) fn classify(d: &PolygonDomain, loops: &[Vec<DVec2>], c: DVec2) -> Option<i32> {
    if !inside(&loops[0], c) {
        return None;
    }
    let mut best: Option<(f64, i32)> = None;
    for (k, l) in loops.iter().enumerate().skip(1) {
        if !inside(l, c) {
            continue;
        }
        match d.loops[k].kind {
            LoopKind::Hole => return None,
            LoopKind::Interface { inside_ref } => {
                let a = loop_area2(l).abs();
                if best.map_or(true, |(ba, _)| a < ba) {
                    best = Some((a, inside_ref));
                }
            }
            LoopKind::Boundary => {}
        }
    }
    Some(best.map_or(d.domain_ref, |(_, r)| r))
}

#[cfg(test)]
mod tests {
    use super::super::from_polygon;
    use super::*;

    fn square(lo: f64, hi: f64) -> Vec<DVec2> {
        vec![
            DVec2::new(lo, lo),
            DVec2::new(hi, lo),
            DVec2::new(hi, hi),
            DVec2::new(lo, hi),
        ]
    }

    #[test]
    fn invalid_polygons_are_errors_not_panics() {
        let bowtie = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 0.0),
            DVec2::new(0.0, 1.0),
        ];
        let e = from_polygon(&bowtie, &[], None, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("intersects itself"), "{e}");
        let line = vec![DVec2::ZERO, DVec2::X, DVec2::new(2.0, 0.0)];
        let e = from_polygon(&line, &[], None, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("folds back") || e.contains("zero area"), "{e}");
        let e = from_polygon(&square(0.0, 1.0), &[square(0.5, 1.5)], None, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("intersect"), "{e}");
        let e = from_polygon(&square(0.0, 1.0), &[square(2.0, 3.0)], None, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("not inside"), "{e}");
        let mut nan = square(0.0, 1.0);
        nan[1].x = f64::NAN;
        assert!(from_polygon(&nan, &[], None, None).is_err());
        let e = from_polygon(&square(0.0, 1.0), &[], Some(-1.0), None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("max_area"), "{e}");
        let e = from_polygon(&square(0.0, 1.0), &[], None, Some(60.0))
            .unwrap_err()
            .to_string();
        assert!(e.contains("min_angle"), "{e}");
        let dup = vec![DVec2::ZERO, DVec2::X, DVec2::X, DVec2::Y];
        assert!(from_polygon(&dup, &[], None, None).is_err());
        let fold = vec![DVec2::ZERO, DVec2::new(2.0, 0.0), DVec2::X, DVec2::Y];
        let e = from_polygon(&fold, &[], None, None)
            .unwrap_err()
            .to_string();
        assert!(e.contains("folds back") || e.contains("intersect"), "{e}");
    }
}
