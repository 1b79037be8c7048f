//! The zero level of a P1 field on a [`Mesh2`]: extraction by marching triangles, the enclosed
//! area and interface length, and the distance between a discrete interface and an exact shape
//! (the measures of 004 §5.1: area and perimeter conservation, interface error).
//!
//! Sign rule: a vertex is *negative* when `u < 0` and *non-negative* otherwise (`u == 0` counts as
//! positive). A triangle is cut when it has vertices of both kinds; its segment joins the two
//! crossing points on the edges whose end values differ in kind. A zero vertex therefore gives a
//! crossing point at the vertex itself, and the rule is the same for every triangle sharing it, so
//! segments always chain through shared edges.

use super::measure;
use super::shapes::Shape;
use crate::error::{Error, Result};
use crate::geom::{point_segment_distance, DVec2};
use crate::mesh::{check_p1_field, next, Mesh2};
use rstar::primitives::Line;
use rstar::RTree;
use std::collections::HashMap;

/// A piece of the zero level: a chain of points, closed when the last point joins the first (the
/// first point is not repeated). Closed curves run counter-clockwise around the negative region
/// (the negative side is on the left of every segment).
#[derive(Debug, Clone, PartialEq)]
pub struct Polyline {
    /// The points in order (the first is not repeated at the end of a closed curve).
    pub points: Vec<DVec2>,
    /// Whether the last point joins the first.
    pub closed: bool,
}

impl Polyline {
    /// The segments of the polyline (including the closing one).
    pub fn segments(&self) -> impl Iterator<Item = (DVec2, DVec2)> + '_ {
        let n = self.points.len();
        let m = if self.closed && n > 1 {
            n
        } else {
            n.saturating_sub(1)
        };
        (0..m).map(move |i| (self.points[i], self.points[(i + 1) % n]))
    }

    /// The points as an open path: a closed polyline repeats its first point at the end (ready
    /// for drawing, e.g. as a `plot::MeshPlot` overlay).
    pub fn path_points(&self) -> Vec<DVec2> {
        let mut p = self.points.clone();
        if self.closed && !p.is_empty() {
            p.push(p[0]);
        }
        p
    }

    /// Length of the polyline.
    pub fn length(&self) -> f64 {
        self.segments().map(|(a, b)| (b - a).length()).sum()
    }
}

/// The crossing point on the edge `(a, b)` with `u_a`, `u_b` of different kinds.
#[inline]
fn crossing(pa: DVec2, pb: DVec2, ua: f64, ub: f64) -> DVec2 {
    let t = ua / (ua - ub);
    pa + t * (pb - pa)
}

/// The oriented zero-level segment of triangle `t`, as `(exit edge, entry edge)` with edges
/// given as local indices, or `None` when the triangle is not cut. Walking the triangle
/// counter-clockwise, the exit edge goes from a negative to a non-negative vertex; the segment
/// from the exit point to the entry point has the negative side on its left.
fn cut_edges(mesh: &Mesh2, u: &[f64], t: usize) -> Option<(usize, usize)> {
    let tri = mesh.tris[t];
    let neg = tri.map(|v| u[v as usize] < 0.0);
    if neg[0] == neg[1] && neg[1] == neg[2] {
        return None;
    }
    // Local edge i joins next(i) -> prev(i) in CCW order.
    let mut exit = 0;
    let mut entry = 0;
    for i in 0..3 {
        let (a, b) = (next(i), next(next(i)));
        if neg[a] && !neg[b] {
            exit = i;
        } else if !neg[a] && neg[b] {
            entry = i;
        }
    }
    Some((exit, entry))
}

/// The crossing point on local edge `i` of triangle `t`.
fn edge_point(mesh: &Mesh2, u: &[f64], t: usize, i: usize) -> DVec2 {
    let [a, b] = mesh.edge_vertices(t, i);
    let (a, b) = (a as usize, b as usize);
    // Orient the interpolation from the smaller vertex index so both triangles sharing the edge
    // compute bit-identical points.
    let (a, b) = if a < b { (a, b) } else { (b, a) };
    crossing(mesh.points[a], mesh.points[b], u[a], u[b])
}

fn edge_key(mesh: &Mesh2, t: usize, i: usize) -> u64 {
    let [a, b] = mesh.edge_vertices(t, i);
    let (a, b) = (a.min(b) as u64, a.max(b) as u64);
    (a << 32) | b
}

/// Extracts the zero level of the P1 field `u` by marching triangles and chains the segments into
/// polylines through shared edges (closed curves counter-clockwise around `{u < 0}`). Repeated
/// points (segments of zero length through zero vertices) are dropped.
///
/// Errors: [`Error::InvalidField`] for a wrong length or a NaN/infinite value,
/// [`Error::EmptyLevelSet`] when no triangle is cut.
pub fn extract_zero_level(mesh: &Mesh2, u: &[f64]) -> Result<Vec<Polyline>> {
    check_p1_field(mesh.n_points(), u, "level set")?;
    // Oriented segments as (start edge key, end edge key, start point, end point).
    let mut segs: Vec<(u64, u64, DVec2, DVec2)> = Vec::new();
    for t in mesh.live_tris() {
        if let Some((exit, entry)) = cut_edges(mesh, u, t) {
            segs.push((
                edge_key(mesh, t, exit),
                edge_key(mesh, t, entry),
                edge_point(mesh, u, t, exit),
                edge_point(mesh, u, t, entry),
            ));
        }
    }
    if segs.is_empty() {
        return Err(Error::EmptyLevelSet(format!(
            "the field has no zero crossing on the {} triangles of the mesh",
            mesh.n_live_tris()
        )));
    }
    let by_start: HashMap<u64, usize> = segs.iter().enumerate().map(|(i, s)| (s.0, i)).collect();
    let ends: std::collections::HashSet<u64> = segs.iter().map(|s| s.1).collect();
    let mut used = vec![false; segs.len()];
    let mut out = Vec::new();
    // Open chains first (start edge is no segment's end: a boundary edge), then closed loops.
    let starts: Vec<usize> = (0..segs.len())
        .filter(|&i| !ends.contains(&segs[i].0))
        .chain(0..segs.len())
        .collect();
    for s0 in starts {
        if used[s0] {
            continue;
        }
        let mut points = vec![segs[s0].2];
        let mut s = s0;
        let mut closed = false;
        loop {
            used[s] = true;
            let end_key = segs[s].1;
            match by_start.get(&end_key) {
                Some(&n) if n == s0 => {
                    closed = true;
                    break;
                }
                Some(&n) if !used[n] => {
                    points.push(segs[s].3);
                    s = n;
                }
                _ => {
                    points.push(segs[s].3);
                    break;
                }
            }
        }
        points.dedup();
        if closed && points.len() > 1 && points.first() == points.last() {
            points.pop();
        }
        out.push(Polyline { points, closed });
    }
    Ok(out)
}

/// Exact area of `{u_h < 0}` for the P1 interpolant `u_h` on the live triangles of `mesh`: each
/// triangle is clipped by its linear function ([`super::measure`]: with one vertex of one sign and
/// values `a`, `b`, `c`, the corner at `a` has the fraction `a² / ((a - b)(a - c))` of the area).
/// Works when the interface meets the mesh boundary. Errors as [`extract_zero_level`], except
/// that an empty level set is not an error.
pub fn enclosed_area(mesh: &Mesh2, u: &[f64]) -> Result<f64> {
    check_p1_field(mesh.n_points(), u, "level set")?;
    Ok(measure::enclosed_sum(
        &mesh.points,
        mesh.live_tris().map(|t| mesh.tris[t]),
        u,
    ))
}

/// Total length of the zero level of the P1 field `u` on the live triangles of `mesh` (sum of the
/// segment lengths over cut triangles, [`super::measure`]; zero for an empty level set). Errors
/// on a wrong length or NaN values.
pub fn interface_length(mesh: &Mesh2, u: &[f64]) -> Result<f64> {
    check_p1_field(mesh.n_points(), u, "level set")?;
    Ok(mesh
        .live_tris()
        .filter_map(|t| measure::cell_interface_measure(&mesh.points, &mesh.tris[t], u))
        .sum())
}

/// Distances between a discrete interface and an exact shape.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct InterfaceError {
    /// `max |d(p)|` over points `p` sampled along the discrete interface (`d` the shape's signed
    /// distance).
    pub to_exact_max: f64,
    /// `max dist(q, discrete interface)` over points `q` sampled on the exact interface; NaN when
    /// the shape cannot sample its boundary.
    pub from_exact_max: f64,
    /// `max(to_exact_max, from_exact_max)`: the sampled Hausdorff distance (NaN if either is).
    pub hausdorff: f64,
}

/// Sampled two-sided distance between polylines and a shape: `samples_per_segment` points per
/// discrete segment (both ends included) measured with the shape's distance, and
/// `max(512, segments × samples_per_segment)` exact boundary samples measured against an R-tree
/// of the discrete segments. Exact for the shape's distance where that is exact (circle,
/// Zalesak); an estimate of the Hausdorff distance up to the sampling density. With no polyline
/// points every field is infinite.
pub fn interface_distance(
    polylines: &[Polyline],
    shape: &dyn Shape,
    samples_per_segment: usize,
) -> InterfaceError {
    let k = samples_per_segment.max(2);
    let mut lines = Vec::new();
    let mut to_exact: f64 = 0.0;
    for pl in polylines {
        if pl.points.len() == 1 {
            to_exact = to_exact.max(shape.distance(pl.points[0]).abs());
            lines.push(Line::new(pl.points[0].to_array(), pl.points[0].to_array()));
        }
        for (a, b) in pl.segments() {
            for i in 0..k {
                let p = a + (b - a) * (i as f64 / (k - 1) as f64);
                to_exact = to_exact.max(shape.distance(p).abs());
            }
            lines.push(Line::new(a.to_array(), b.to_array()));
        }
    }
    if lines.is_empty() {
        return InterfaceError {
            to_exact_max: f64::INFINITY,
            from_exact_max: f64::INFINITY,
            hausdorff: f64::INFINITY,
        };
    }
    let n_samples = (lines.len() * k).max(512);
    let from_exact = match shape.boundary_samples(n_samples) {
        Some(samples) => {
            let tree = RTree::bulk_load(lines);
            samples
                .iter()
                .map(|q| {
                    tree.nearest_neighbor(q.to_array())
                        .map_or(f64::INFINITY, |l| {
                            let (a, b) = (DVec2::from_array(l.from), DVec2::from_array(l.to));
                            point_segment_distance(*q, a, b).0
                        })
                })
                .fold(0.0, f64::max)
        }
        None => f64::NAN,
    };
    InterfaceError {
        to_exact_max: to_exact,
        from_exact_max: from_exact,
        // NaN propagates: f64::max would ignore it.
        hausdorff: if from_exact.is_nan() {
            f64::NAN
        } else {
            to_exact.max(from_exact)
        },
    }
}
