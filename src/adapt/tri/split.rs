//! Edge split (MMG `split_2d.c`, 004 §3.5): an edge longer than `l_max` in the metric gets a new
//! vertex at its metric midpoint; the two (or one, on the boundary) triangles sharing it become
//! four (two). The new vertex lies on the segment, so boundary and interface curves stay where
//! they are and areas are preserved; it inherits the edge label as its vertex label. The pass
//! that chooses the edges (and between a split and an insertion) is `refine.rs`.

use super::topo::Ctx;
use crate::geom::{orient2d, DVec2};
use crate::mesh::{next, prev, NONE};

/// A planned split of local edge `i` of triangle `t` at parameter `s` from its first vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplitPlan {
    /// A triangle holding the edge.
    pub t: u32,
    /// The local index of the edge in `t` (the edge opposite vertex `i`).
    pub i: u8,
    /// Parameter along `a -> b` (`a = tris[t][next(i)]`).
    pub s: f64,
    /// The new vertex position.
    pub p: DVec2,
}

/// The metric midpoint parameter of an edge whose endpoint lengths are `la`, `lb`: with the size
/// varying linearly along the edge, the point at equal metric distance from both ends is at
/// `s = sqrt(lb) / (sqrt(la) + sqrt(lb))` (closer to the end that wants smaller elements).
#[inline]
pub fn metric_midpoint(la: f64, lb: f64) -> f64 {
    let (a, b) = (la.sqrt(), lb.sqrt());
    let s = b / (a + b);
    if s.is_finite() {
        s.clamp(0.25, 0.75)
    } else {
        0.5
    }
}

/// Pure check: whether edge `(t, i)` is longer than `l_max` and can be split validly. Returns the
/// plan, never modifies the mesh.
pub fn check(ctx: &Ctx, t: u32, i: usize) -> Option<SplitPlan> {
    let mesh = &*ctx.mesh;
    let tri = mesh.tris[t as usize];
    let (c, a, b) = (tri[i], tri[next(i)], tri[prev(i)]);
    let (pa, pb) = (ctx.p(a), ctx.p(b));
    let e = pb - pa;
    let (la, lb) = ctx.end_lengths(a, b);
    if crate::metric::length::geometric_mean_length(la, lb) <= ctx.params.l_max {
        return None;
    }
    let s = metric_midpoint(la, lb);
    let p = pa + s * e;
    if p == pa || p == pb {
        return None;
    }
    let pc = ctx.p(c);
    if orient2d(pc, pa, p) <= 0.0 || orient2d(pc, p, pb) <= 0.0 {
        return None;
    }
    let t2 = mesh.neighbours[t as usize][i];
    if t2 != NONE {
        let t2u = t2 as usize;
        let j = mesh.mirror_edge(t as usize, t2u)?;
        let pd = ctx.p(mesh.tris[t2u][j]);
        if orient2d(pd, pb, p) <= 0.0 || orient2d(pd, p, pa) <= 0.0 {
            return None;
        }
    }
    Some(SplitPlan {
        t,
        i: i as u8,
        s,
        p,
    })
}

/// Applies a split ([`crate::mesh::TriMesh::split_edge`]): returns the new vertex. Metric and
/// fields at the new vertex come from the source when it has them, else by interpolation along
/// the edge. On a boundary or labelled edge the new vertex takes the edge label.
pub fn apply(ctx: &mut Ctx, plan: &SplitPlan) -> u32 {
    let (tu, i) = (plan.t as usize, plan.i as usize);
    let tri = ctx.mesh.tris[tu];
    let (a, b) = (tri[next(i)], tri[prev(i)]);
    let r_ab = ctx.mesh.edge_ref[tu][i];
    let curve = ctx.mesh.neighbours[tu][i] == NONE || r_ab != 0;
    let m_new = ctx.sample(plan.p, &[a, b], &[1.0 - plan.s, plan.s]);
    let (mesh, mut ws) = ctx.edit(m_new);
    let m = mesh.add_vertex(plan.p, if curve { r_ab } else { 0 }, &mut ws);
    mesh.split_edge(plan.t, i, m, &mut ws);
    m
}
