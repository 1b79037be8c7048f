//! Exact sharp features: inserting a vertex at a given point of a mesh (used by
//! [`super::adapt_to_shape`] to put a required vertex on every corner of a shape, so that the P1
//! level set is exactly zero there and its zero level passes through the corner).
//!
//! Around a corner the signed distance has a kink (a gradient jump along the medial axis, on the
//! convex side of the corner); a triangle of the corner's fan that straddles it interpolates the
//! distance to first order only, and its zero level cuts the boundary by a fraction of its size.
//! [`insert_corner_features`] therefore also lays a labelled edge from the corner along the kink
//! ([`kink_point`]).
//!
//! The insertion is purely local: the triangle containing the point is split into three, or, for
//! a point on an edge, the one or two triangles sharing that edge are split into two each. Labels
//! follow the split pieces (the halves of an edge keep its label, new interior edges get 0,
//! sub-domain labels are inherited), neighbours and vertex seeds are updated in place.

use crate::error::{Error, Result};
use crate::geom::{orient2d, DVec2};
use crate::levelset::shapes::Shape;
use crate::mesh::{next, prev, Location, Mesh2, NONE};

/// The edge label of the kink edges laid by [`insert_corner_features`] (the boundary labels of
/// [`Mesh2::rectangle`] are 1 to 4).
pub const KINK_LABEL: i32 = 99;

/// What [`insert_corner_features`] did.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CornerFeatures {
    /// The vertices placed on corners (all required).
    pub corners: Vec<u32>,
    /// The labelled kink edges `(corner vertex, far vertex)` (both required).
    pub kink_edges: Vec<[u32; 2]>,
}

/// Puts a required vertex exactly on every corner of `shape` ([`Shape::corners`]) that lies in
/// the closed rectangle `domain` (others are skipped) and, with `kink_length = Some(l)`, a
/// required vertex on the kink of the distance at distance `l` from the corner ([`kink_point`]),
/// joined to it by an edge labelled [`KINK_LABEL`] when the insertion made that edge (it does
/// when `l` is small against the corner's fan, as on a coarse mesh). Errors as
/// [`insert_point`].
pub fn insert_corner_features(
    mesh: &mut Mesh2,
    shape: &dyn Shape,
    domain: (DVec2, DVec2),
    kink_length: Option<f64>,
) -> Result<CornerFeatures> {
    let inside = |p: DVec2| p.cmpge(domain.0).all() && p.cmple(domain.1).all();
    let mut out = CornerFeatures::default();
    let corners: Vec<DVec2> = shape.corners().into_iter().filter(|&c| inside(c)).collect();
    for &c in &corners {
        let v = insert_point(mesh, c)?.vertex();
        mesh.required[v as usize] = true;
        out.corners.push(v);
    }
    let Some(l) = kink_length else {
        return Ok(out);
    };
    for (&c, &v) in corners.iter().zip(&out.corners) {
        let Some(k) = kink_point(shape, c, l).filter(|&k| inside(k)) else {
            continue;
        };
        let w = insert_point(mesh, k)?.vertex();
        mesh.required[w as usize] = true;
        if w != v && label_edge(mesh, v, w, KINK_LABEL) {
            out.kink_edges.push([v, w]);
        }
    }
    Ok(out)
}

/// Labels the edge `(a, b)` with `label` on both of its sides; `false` when there is no such
/// edge.
pub fn label_edge(mesh: &mut Mesh2, a: u32, b: u32, label: i32) -> bool {
    let mut found = false;
    for t in mesh.vertex_fan(a) {
        let t = t as usize;
        for i in 0..3 {
            let [x, y] = mesh.edge_vertices(t, i);
            if (x == a && y == b) || (x == b && y == a) {
                mesh.edge_ref[t][i] = label;
                found = true;
            }
        }
    }
    found
}

/// The point at distance `r` from the corner `c` where the gradient of the shape's distance
/// jumps the most (by at least 0.1, i.e. a turn of about 6°): where the kink of the distance (the
/// medial axis leaving the corner) crosses the circle of radius `r`. Found among 1,440 samples
/// of the circle, then by 50 bisections on the jump. `None` when no jump is that large (a smooth
/// point, or `r` too large to see the corner).
pub fn kink_point(shape: &dyn Shape, c: DVec2, r: f64) -> Option<DVec2> {
    const N: usize = 1440;
    let step = std::f64::consts::TAU / N as f64;
    // Offset by a fraction of a step so that no sample falls exactly on an axis-aligned piece.
    let at = |k: f64| {
        let th = (k + 0.2929) * step;
        c + r * DVec2::new(th.cos(), th.sin())
    };
    let grads: Vec<DVec2> = (0..N).map(|k| shape.gradient(at(k as f64))).collect();
    let (k, jump) = (0..N)
        .map(|k| (k, (grads[(k + 1) % N] - grads[k]).length()))
        .max_by(|a, b| a.1.total_cmp(&b.1))?;
    if !jump.is_finite() || jump < 0.1 {
        return None;
    }
    let (mut lo, mut hi) = (k as f64, k as f64 + 1.0);
    let g_lo = grads[k];
    for _ in 0..50 {
        let mid = 0.5 * (lo + hi);
        if (shape.gradient(at(mid)) - g_lo).length() < 0.5 * jump {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    Some(at(0.5 * (lo + hi)))
}

/// How [`insert_point`] placed the point.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Insertion {
    /// The point is an existing vertex: nothing changed.
    Existing(u32),
    /// A new vertex strictly inside a triangle (split into three).
    InTriangle(u32),
    /// A new vertex on an interior edge (two triangles split into two each).
    OnEdge(u32),
    /// A new vertex on a boundary edge (one triangle split into two).
    OnBoundary(u32),
}

impl Insertion {
    /// The index of the vertex at the point.
    pub fn vertex(self) -> u32 {
        match self {
            Insertion::Existing(v)
            | Insertion::InTriangle(v)
            | Insertion::OnEdge(v)
            | Insertion::OnBoundary(v) => v,
        }
    }
}

/// Inserts a vertex at `p` (exact coordinates) into `mesh` and returns where it went. The point
/// is located with exact orientation tests; a point equal to a vertex returns that vertex, a
/// point on an edge splits the edge. The new vertex has label 0 and is neither a corner nor
/// required (the caller sets these). The mesh stays valid ([`Mesh2::check`]) and its area is
/// unchanged.
///
/// Errors: `p` not finite, or outside the mesh ([`Error::InvalidInput`], naming the point).
pub fn insert_point(mesh: &mut Mesh2, p: DVec2) -> Result<Insertion> {
    if !p.is_finite() {
        return Err(Error::InvalidInput(format!(
            "insert_point: the point ({}, {}) is not finite",
            p.x, p.y
        )));
    }
    let seed = mesh.live_tris().next().map_or(NONE, |t| t as u32);
    let t = match mesh.locate(p, seed) {
        Location::Inside { tri, .. } => tri as usize,
        Location::Outside { .. } => {
            return Err(Error::InvalidInput(format!(
                "insert_point: the point ({}, {}) lies outside the mesh",
                p.x, p.y
            )))
        }
    };
    let pts = mesh.tri_points(t);
    // Exact orientation of p against each local edge i (opposite vertex i); all >= 0 here.
    let on: Vec<usize> = (0..3)
        .filter(|&i| orient2d(pts[next(i)], pts[prev(i)], p) == 0.0)
        .collect();
    match on.as_slice() {
        [] => Ok(Insertion::InTriangle(split_in_triangle(mesh, t, p))),
        [i] => {
            let nb = mesh.neighbours[t][*i];
            let v = split_on_edge(mesh, t, *i, p);
            Ok(if nb == NONE {
                Insertion::OnBoundary(v)
            } else {
                Insertion::OnEdge(v)
            })
        }
        // On two edges: the vertex they share (opposite the third).
        [i, j] => Ok(Insertion::Existing(mesh.tris[t][3 - i - j])),
        _ => Err(Error::InvalidInput(format!(
            "insert_point: triangle {t} is degenerate at ({}, {})",
            p.x, p.y
        ))),
    }
}

/// Appends a vertex at `p` (label 0, free) and returns its index.
fn push_vertex(mesh: &mut Mesh2, p: DVec2) -> u32 {
    let v = mesh.points.len() as u32;
    mesh.points.push(p);
    mesh.vert_ref.push(0);
    mesh.corner.push(false);
    mesh.required.push(false);
    mesh.vert_tri.push(NONE);
    v
}

/// Appends a triangle and returns its index (neighbours unset).
fn push_tri(mesh: &mut Mesh2, tri: [u32; 3], tref: i32) -> usize {
    mesh.tris.push(tri);
    mesh.neighbours.push([NONE; 3]);
    mesh.tri_ref.push(tref);
    mesh.edge_ref.push([0; 3]);
    mesh.tris.len() - 1
}

/// Makes the triangle across local edge `i` of `t` (if any) point back to `t` instead of `old`.
fn repoint(mesh: &mut Mesh2, t: usize, i: usize, old: usize) {
    let nb = mesh.neighbours[t][i];
    if nb == NONE {
        return;
    }
    if let Some(j) = mesh.mirror_edge(old, nb as usize) {
        mesh.neighbours[nb as usize][j] = t as u32;
    }
}

/// Sets the seed of every vertex of triangle `t` to `t`.
fn seed_vertices(mesh: &mut Mesh2, t: usize) {
    for v in mesh.tris[t] {
        mesh.vert_tri[v as usize] = t as u32;
    }
}

/// Splits triangle `t = [a, b, c]` at the interior point `p` into `[a, b, p]` (kept in slot
/// `t`), `[b, c, p]` and `[c, a, p]`.
fn split_in_triangle(mesh: &mut Mesh2, t: usize, p: DVec2) -> u32 {
    let v = push_vertex(mesh, p);
    let [a, b, c] = mesh.tris[t];
    let (nb, er, tref) = (mesh.neighbours[t], mesh.edge_ref[t], mesh.tri_ref[t]);
    let t1 = push_tri(mesh, [b, c, v], tref);
    let t2 = push_tri(mesh, [c, a, v], tref);
    let (tu, t1u, t2u) = (t as u32, t1 as u32, t2 as u32);
    mesh.tris[t] = [a, b, v];
    // Local edge 2 (opposite the new vertex) of each piece is an edge of the old triangle.
    mesh.neighbours[t] = [t1u, t2u, nb[2]];
    mesh.edge_ref[t] = [0, 0, er[2]];
    mesh.neighbours[t1] = [t2u, tu, nb[0]];
    mesh.edge_ref[t1] = [0, 0, er[0]];
    mesh.neighbours[t2] = [tu, t1u, nb[1]];
    mesh.edge_ref[t2] = [0, 0, er[1]];
    repoint(mesh, t1, 2, t);
    repoint(mesh, t2, 2, t);
    seed_vertices(mesh, t1);
    seed_vertices(mesh, t2);
    mesh.vert_tri[a as usize] = tu;
    mesh.vert_tri[v as usize] = tu;
    v
}

/// Splits triangle `t` across its local edge `i` at the point `v` on that edge: with
/// `[v0, v1, v2]` the triangle rotated so that `v0` is opposite the edge, `t` becomes
/// `[v0, v1, v]` and a new triangle `[v0, v, v2]` is returned. The two halves of the split edge
/// (local edge 0 of each piece) keep its label; their neighbours are left to the caller.
fn split_half(mesh: &mut Mesh2, t: usize, i: usize, v: u32) -> usize {
    let tri = mesh.tris[t];
    let (v0, v1, v2) = (tri[i], tri[next(i)], tri[prev(i)]);
    let (nb, er, tref) = (mesh.neighbours[t], mesh.edge_ref[t], mesh.tri_ref[t]);
    let s = push_tri(mesh, [v0, v, v2], tref);
    mesh.tris[t] = [v0, v1, v];
    // [v0, v1, v]: edge 0 = (v1, v) half, edge 1 = (v, v0) shared with s, edge 2 = (v0, v1),
    // the old edge opposite v2.
    mesh.neighbours[t] = [NONE, s as u32, nb[prev(i)]];
    mesh.edge_ref[t] = [er[i], 0, er[prev(i)]];
    // [v0, v, v2]: edge 0 = (v, v2) half, edge 1 = (v2, v0), the old edge opposite v1,
    // edge 2 = (v0, v) shared with t.
    mesh.neighbours[s] = [NONE, nb[next(i)], t as u32];
    mesh.edge_ref[s] = [er[i], er[next(i)], 0];
    repoint(mesh, s, 1, t);
    seed_vertices(mesh, s);
    mesh.vert_tri[v0 as usize] = t as u32;
    mesh.vert_tri[v1 as usize] = t as u32;
    s
}

/// Splits local edge `i` of `t` (and the triangle across it, if any) at the point `p`.
fn split_on_edge(mesh: &mut Mesh2, t: usize, i: usize, p: DVec2) -> u32 {
    let v = push_vertex(mesh, p);
    let u = mesh.neighbours[t][i];
    let j = (u != NONE)
        .then(|| mesh.mirror_edge(t, u as usize))
        .flatten();
    let s = split_half(mesh, t, i, v);
    if let (Some(j), true) = (j, u != NONE) {
        let u = u as usize;
        // Across: u = [w0, v2, v1] becomes [w0, v2, v] (u) and [w0, v, v1] (s2). The half
        // (v1, v) of t faces (v, v1) of s2; the half (v, v2) of s faces (v2, v) of u.
        let s2 = split_half(mesh, u, j, v);
        mesh.neighbours[t][0] = s2 as u32;
        mesh.neighbours[s2][0] = t as u32;
        mesh.neighbours[s][0] = u as u32;
        mesh.neighbours[u][0] = s as u32;
    }
    v
}
