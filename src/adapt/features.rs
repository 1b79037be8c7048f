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
//! The insertion is [`Mesh2::insert_point`]: purely local, the triangle containing the point is
//! split into three, or, for a point on an edge, the one or two triangles sharing that edge are
//! split into two each, with the mesh edits of [`crate::mesh`].

use crate::error::Result;
use crate::geom::DVec2;
use crate::levelset::shapes::Shape;
use crate::mesh::Mesh2;

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
/// [`Mesh2::insert_point`].
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
        let v = mesh.insert_point(c)?.vertex();
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
        let w = mesh.insert_point(k)?.vertex();
        mesh.required[w as usize] = true;
        if w != v && mesh.label_edge(v, w, KINK_LABEL) {
            out.kink_edges.push([v, w]);
        }
    }
    Ok(out)
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
