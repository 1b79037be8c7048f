//! Initial meshes of polygonal domains: constrained Delaunay triangulation with Ruppert-style
//! refinement (maximum area, minimum angle) through `spade`, copied into a [`Mesh2`].
//!
//! A [`PolygonDomain`] is one outer boundary loop, holes, and interface loops (closed curves
//! inside the domain that separate sub-domains, e.g. a circle whose inside gets another
//! `tri_ref`). Each loop carries an edge label and an optional target edge length `h` (its
//! segments are subdivided to at most `h`; the angle criterion then grades the mesh away from
//! fine loops). Corners are flagged (and required) where a loop turns by more than 30 degrees.
//!
//! Inputs are validated before spade sees them (spade panics on intersecting constraints):
//! too few points, non-finite or out-of-range coordinates, repeated consecutive points, zero-area
//! loops, self-intersecting or mutually intersecting/touching loops, and loops outside the outer
//! boundary are all reported as [`Error::InvalidInput`].

use super::{next, prev, Mesh2, NONE};
use crate::error::{Error, Result};
use crate::geom::{orient2d, DVec2};
use rstar::{primitives::GeomWithData, primitives::Rectangle, RTree, AABB};
use spade::{
    AngleLimit, ConstrainedDelaunayTriangulation, Point2, RefinementParameters, Triangulation,
};
use std::collections::{HashMap, HashSet};

/// The role of a loop in a [`PolygonDomain`].
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum LoopKind {
    /// The outer boundary (exactly one).
    Boundary,
    /// A hole: its inside is not meshed.
    Hole,
    /// An interface: its inside is meshed with sub-domain label `inside_ref`.
    Interface { inside_ref: i32 },
}

/// A closed polygonal loop (the closing segment is implied; a repeated first point at the end is
/// dropped).
#[derive(Debug, Clone, PartialEq)]
pub struct DomainLoop {
    pub points: Vec<DVec2>,
    /// Edge label of the loop's segments (also the vertex label of its vertices).
    pub label: i32,
    /// Target edge length along the loop: segments longer than `h` are subdivided.
    pub h: Option<f64>,
    pub kind: LoopKind,
}

/// A polygonal domain with holes and interfaces, and refinement parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct PolygonDomain {
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

    /// Meshes the domain; see the module documentation.
    pub fn mesh(&self) -> Result<Mesh2> {
        mesh_domain(self)
    }
}

/// Constrained Delaunay mesh of the polygon `outer` minus `holes` (outer edges labelled 1, hole
/// `k` labelled `k + 2`), refined to `max_area` and `min_angle_deg` when given.
pub fn from_polygon(
    outer: &[DVec2],
    holes: &[Vec<DVec2>],
    max_area: Option<f64>,
    min_angle_deg: Option<f64>,
) -> Result<Mesh2> {
    let mut d = PolygonDomain::new(outer.to_vec(), 1);
    for (k, h) in holes.iter().enumerate() {
        d = d.hole(h.clone(), k as i32 + 2);
    }
    d.max_area = max_area;
    d.min_angle_deg = min_angle_deg;
    d.mesh()
}

fn invalid(msg: String) -> Error {
    Error::InvalidInput(format!("polygon domain: {msg}"))
}

/// Twice the signed area of a closed polygon.
fn loop_area2(p: &[DVec2]) -> f64 {
    (0..p.len())
        .map(|i| p[i].perp_dot(p[(i + 1) % p.len()]))
        .sum()
}

/// Crossing-number point-in-polygon test (the point is assumed off the polygon).
fn inside(p: &[DVec2], q: DVec2) -> bool {
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
fn validate(d: &PolygonDomain) -> Result<Vec<Vec<DVec2>>> {
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

fn mesh_domain(d: &PolygonDomain) -> Result<Mesh2> {
    let loops = validate(d)?;
    // Vertices: each loop's points with subdivision points; constraint edges between them.
    let mut pts: Vec<DVec2> = Vec::new();
    let mut edges: Vec<[usize; 2]> = Vec::new();
    let mut corner = Vec::new();
    let mut label = Vec::new();
    for (k, l) in loops.iter().enumerate() {
        let start = pts.len();
        let n = l.len();
        for i in 0..n {
            let (a, b) = (l[i], l[(i + 1) % n]);
            let (u, w) = (a - l[(i + n - 1) % n], b - a);
            let turn = u.perp_dot(w).atan2(u.dot(w)).abs();
            corner.push(turn > 30f64.to_radians());
            label.push(d.loops[k].label);
            pts.push(a);
            let pieces = match d.loops[k].h {
                Some(h) => ((b - a).length() / h).ceil().max(1.0),
                None => 1.0,
            };
            if pieces > 1e7 {
                return Err(invalid(format!(
                    "loop {k}: target size too small for its length"
                )));
            }
            for s in 1..pieces as usize {
                corner.push(false);
                label.push(d.loops[k].label);
                pts.push(a + (b - a) * (s as f64 / pieces));
            }
        }
        let m = pts.len() - start;
        for i in 0..m {
            edges.push([start + i, start + (i + 1) % m]);
        }
    }
    let n_input = pts.len();
    let verts: Vec<Point2<f64>> = pts.iter().map(|p| Point2::new(p.x, p.y)).collect();
    let mut conflicts = 0usize;
    let mut cdt: ConstrainedDelaunayTriangulation<Point2<f64>> =
        ConstrainedDelaunayTriangulation::try_bulk_load_cdt(verts, edges, |_| conflicts += 1)
            .map_err(|e| invalid(format!("triangulation failed: {e:?}")))?;
    if conflicts > 0 || cdt.num_vertices() != n_input {
        return Err(invalid(
            "loops overlap (duplicate points or intersecting segments after subdivision)".into(),
        ));
    }
    let has_interfaces = d
        .loops
        .iter()
        .any(|l| matches!(l.kind, LoopKind::Interface { .. }));
    if d.max_area.is_some() || d.min_angle_deg.is_some() {
        let outer_area = 0.5 * loop_area2(&loops[0]).abs();
        let estimate = d.max_area.map_or(0.0, |a| 4.0 * outer_area / a);
        if estimate > 5e7 {
            return Err(invalid(format!(
                "max_area {} would need about {estimate:.0} vertices",
                d.max_area.unwrap_or(0.0)
            )));
        }
        let cap = (estimate as usize).max(10 * n_input) + 1000;
        let mut params = RefinementParameters::<f64>::new()
            .with_angle_limit(AngleLimit::from_deg(d.min_angle_deg.unwrap_or(0.0)))
            .exclude_outer_faces(!has_interfaces)
            .with_max_additional_vertices(cap);
        if let Some(a) = d.max_area {
            params = params.with_max_allowed_area(a);
        }
        cdt.refine(params);
    }
    extract(d, &loops, &cdt, &corner, &label)
}

/// Copies the triangles inside the domain into a `Mesh2` with labels.
fn extract(
    d: &PolygonDomain,
    loops: &[Vec<DVec2>],
    cdt: &ConstrainedDelaunayTriangulation<Point2<f64>>,
    corner: &[bool],
    label: &[i32],
) -> Result<Mesh2> {
    let pos: Vec<DVec2> = cdt
        .vertices()
        .map(|v| {
            let p = v.position();
            DVec2::new(p.x, p.y)
        })
        .collect();
    let mut tris: Vec<[u32; 3]> = Vec::with_capacity(cdt.num_inner_faces());
    for f in cdt.inner_faces() {
        let mut t = f.vertices().map(|v| v.fix().index() as u32);
        if orient2d(pos[t[0] as usize], pos[t[1] as usize], pos[t[2] as usize]) < 0.0 {
            t.swap(1, 2);
        }
        tris.push(t);
    }
    let constraint: HashSet<(u32, u32)> = cdt
        .undirected_edges()
        .filter(|e| e.is_constraint_edge())
        .map(|e| {
            let [a, b] = e.vertices().map(|v| v.fix().index() as u32);
            (a.min(b), a.max(b))
        })
        .collect();
    // Regions: flood fill across non-constraint edges.
    let mut half: HashMap<(u32, u32), usize> = HashMap::with_capacity(3 * tris.len());
    for (t, tri) in tris.iter().enumerate() {
        for i in 0..3 {
            half.insert((tri[next(i)], tri[prev(i)]), t);
        }
    }
    let mut region = vec![usize::MAX; tris.len()];
    let mut region_ref: Vec<Option<i32>> = Vec::new();
    for seed in 0..tris.len() {
        if region[seed] != usize::MAX {
            continue;
        }
        let r = region_ref.len();
        let tri = tris[seed];
        let c = (pos[tri[0] as usize] + pos[tri[1] as usize] + pos[tri[2] as usize]) / 3.0;
        region_ref.push(classify(d, loops, c));
        region[seed] = r;
        let mut stack = vec![seed];
        while let Some(t) = stack.pop() {
            for i in 0..3 {
                let (a, b) = (tris[t][next(i)], tris[t][prev(i)]);
                if constraint.contains(&(a.min(b), a.max(b))) {
                    continue;
                }
                if let Some(&nb) = half.get(&(b, a)) {
                    if region[nb] == usize::MAX {
                        region[nb] = r;
                        stack.push(nb);
                    }
                }
            }
        }
    }
    // Keep the triangles of the domain; renumber vertices in spade order.
    let mut vmap = vec![NONE; pos.len()];
    let mut kept = Vec::new();
    let mut kept_ref = Vec::new();
    for (t, tri) in tris.iter().enumerate() {
        if let Some(r) = region_ref[region[t]] {
            kept.push(*tri);
            kept_ref.push(r);
            for &v in tri {
                vmap[v as usize] = 0;
            }
        }
    }
    let mut points = Vec::new();
    for (v, m) in vmap.iter_mut().enumerate() {
        if *m == 0 {
            *m = points.len() as u32;
            points.push(pos[v]);
        }
    }
    let old_of: Vec<usize> = (0..pos.len()).filter(|&v| vmap[v] != NONE).collect();
    let kept: Vec<[u32; 3]> = kept.iter().map(|t| t.map(|v| vmap[v as usize])).collect();
    let mut mesh = Mesh2::from_parts(points, kept, kept_ref)?;
    // Labels of constraint edges from the nearest input loop segment.
    let seg_label = SegmentLabels::new(d, loops);
    for ([a, b], t, i) in mesh.edges() {
        let (oa, ob) = (old_of[a as usize] as u32, old_of[b as usize] as u32);
        let (t, i) = (t as usize, i as usize);
        let lab = if constraint.contains(&(oa.min(ob), oa.max(ob))) {
            seg_label.at(0.5 * (mesh.points[a as usize] + mesh.points[b as usize]))
        } else {
            0
        };
        mesh.edge_ref[t][i] = lab;
        let nb = mesh.neighbours[t][i];
        if nb != NONE {
            if let Some(j) = mesh.mirror_edge(t, nb as usize) {
                mesh.edge_ref[nb as usize][j] = lab;
            }
        }
        if lab != 0 {
            mesh.vert_ref[a as usize] = lab;
            mesh.vert_ref[b as usize] = lab;
        }
    }
    for (new, &old) in old_of.iter().enumerate() {
        if old < corner.len() {
            mesh.corner[new] = corner[old];
            mesh.required[new] = corner[old];
            mesh.vert_ref[new] = label[old];
        }
    }
    mesh.check()?;
    Ok(mesh)
}

/// The sub-domain label of the region containing `c`, or `None` outside the domain.
fn classify(d: &PolygonDomain, loops: &[Vec<DVec2>], c: DVec2) -> Option<i32> {
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

/// Nearest-segment lookup of loop labels.
struct SegmentLabels {
    tree: RTree<GeomWithData<rstar::primitives::Line<[f64; 2]>, i32>>,
}

impl SegmentLabels {
    fn new(d: &PolygonDomain, loops: &[Vec<DVec2>]) -> Self {
        let mut v = Vec::new();
        for (k, l) in loops.iter().enumerate() {
            for i in 0..l.len() {
                let (a, b) = (l[i], l[(i + 1) % l.len()]);
                v.push(GeomWithData::new(
                    rstar::primitives::Line::new(a.to_array(), b.to_array()),
                    d.loops[k].label,
                ));
            }
        }
        SegmentLabels {
            tree: RTree::bulk_load(v),
        }
    }

    fn at(&self, p: DVec2) -> i32 {
        self.tree
            .nearest_neighbor(p.to_array())
            .map_or(0, |s| s.data)
    }
}

#[cfg(test)]
mod tests {
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
    fn square_with_hole_area_and_labels() {
        let hole: Vec<DVec2> = square(0.4, 0.6).into_iter().rev().collect();
        let m = from_polygon(&square(0.0, 1.0), &[hole], Some(0.002), Some(25.0)).unwrap();
        m.check().unwrap();
        assert!((m.area() - 0.96).abs() < 1e-12, "area {}", m.area());
        assert!(m.live_tris().all(|t| m.tri_area(t) <= 0.002 * (1.0 + 1e-9)));
        let b = m.boundary_edges();
        let len = |l: i32| -> f64 {
            b.iter()
                .filter(|e| e.2 == l)
                .map(|e| (m.points[e.0 as usize] - m.points[e.1 as usize]).length())
                .sum()
        };
        assert!((len(1) - 4.0).abs() < 1e-12 && (len(2) - 0.8).abs() < 1e-12);
        assert_eq!(m.corner.iter().filter(|&&c| c).count(), 8);
        assert_eq!(m.boundary_loops().len(), 2);
        // Minimum angle (spade guarantees the limit away from input angles; here all are 90°).
        let min_angle = m
            .live_tris()
            .flat_map(|t| {
                let p = m.tri_points(t);
                (0..3).map(move |i| {
                    let (u, v) = (p[next(i)] - p[i], p[prev(i)] - p[i]);
                    u.perp_dot(v).atan2(u.dot(v)).to_degrees()
                })
            })
            .fold(180.0, f64::min);
        assert!(min_angle > 24.0, "min angle {min_angle}");
    }

    #[test]
    fn interface_circle_refined() {
        let c = DVec2::splat(0.5);
        let m = PolygonDomain::new(square(0.0, 1.0), 1)
            .interface(circle_points(c, 0.25, 64), 5, 7)
            .with_size(0.02)
            .with_min_angle(25.0)
            .mesh()
            .unwrap();
        m.check().unwrap();
        assert!((m.area() - 1.0).abs() < 1e-12);
        let inner: f64 = m
            .live_tris()
            .filter(|&t| m.tri_ref[t] == 7)
            .map(|t| m.tri_area(t))
            .sum();
        // Inscribed 64-gon of radius 0.25: (64/2) r^2 sin(2 pi / 64).
        let polygon = 32.0 * 0.0625 * (std::f64::consts::TAU / 64.0).sin();
        assert!((inner - polygon).abs() < 1e-12, "{inner} vs {polygon}");
        // Interface edges labelled 5, no longer than h.
        let iface: Vec<_> = m
            .edges()
            .into_iter()
            .filter(|&(_, t, i)| m.edge_ref[t as usize][i as usize] == 5)
            .collect();
        assert!(
            iface.len() >= 64
                && iface.iter().all(|&([a, b], _, _)| {
                    (m.points[a as usize] - m.points[b as usize]).length() <= 0.02 + 1e-12
                })
        );
        assert!(iface
            .iter()
            .all(|&(_, t, i)| m.neighbours[t as usize][i as usize] != NONE));
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

    #[test]
    fn unrefined_polygon_uses_only_input_points() {
        let l = vec![
            DVec2::new(0.0, 0.0),
            DVec2::new(2.0, 0.0),
            DVec2::new(2.0, 1.0),
            DVec2::new(1.0, 1.0),
            DVec2::new(1.0, 2.0),
            DVec2::new(0.0, 2.0),
            DVec2::new(0.0, 0.0),
        ];
        let m = from_polygon(&l, &[], None, None).unwrap();
        assert_eq!((m.n_points(), m.n_tris()), (6, 4));
        assert!((m.area() - 3.0).abs() < 1e-14);
        // The re-entrant corner turns by 90°: all six vertices are corners.
        assert_eq!(m.corner.iter().filter(|&&c| c).count(), 6);
    }
}
