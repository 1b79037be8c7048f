//! Edge collapse (MMG `colver_2d.c`, 004 §3.5): a vertex `a` with an edge shorter than `l_min`
//! is merged into the other end `b`. The two (one on a curve) triangles sharing the edge
//! disappear and their outer edges are glued.
//!
//! Rejected when: `a` is a corner, required, or a junction of labelled curves; `a` lies on a
//! boundary/interface curve and `(a, b)` is not an edge of that curve; the link condition fails
//! (the rings of `a` and `b` share a vertex other than the apexes of the edge); a triangle would
//! invert (exact `orient2d`); a new edge would be longer than `l_max`; or the worst `Q_ani` of the
//! ball would exceed the floor and be worse than before.

use super::topo::{local, Ctx, VClass};
use crate::adapt::pass::{run_pass, Operator};
use crate::mesh::{next, prev, NONE};
use crate::metric::Sym2;

/// A planned collapse of vertex `a` onto its neighbour `b`.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct CollapsePlan {
    /// The vertex removed.
    pub a: u32,
    /// The vertex it merges into (the other end of the short edge).
    pub b: u32,
}

/// Pure check of the collapse `a -> b`. `ctx.fan` must hold the fan of `a` (see `pass`); the fan
/// of `b` is loaded into `ctx.fan2`.
pub fn check_loaded(ctx: &mut Ctx, a: u32, b: u32) -> Option<CollapsePlan> {
    match ctx.vclass(a) {
        VClass::Fixed => return None,
        VClass::Curve { ends, .. } => {
            if ends[0] != b && ends[1] != b {
                return None;
            }
            // The curve must stay where it is: `a` within `curve_tol` of the new segment
            // (other end, b); exactly collinear for the default tolerance 0.
            let other = if ends[0] == b { ends[1] } else { ends[0] };
            let (po, pa, pb) = (ctx.p(other), ctx.p(a), ctx.p(b));
            let o = crate::geom::orient2d(po, pa, pb);
            if o != 0.0 && o.abs() > ctx.params.curve_tol * (pb - po).length() {
                return None;
            }
        }
        VClass::Free => {}
    }
    if ctx.fan.len() < 2 {
        return None;
    }
    let mesh = &*ctx.mesh;
    // The triangles holding the edge, and their apexes.
    let mut apex = [NONE; 2];
    let mut n_shared = 0;
    for &t in &ctx.fan {
        let tri = mesh.tris[t as usize];
        if tri.contains(&b) {
            let ia = local(tri, a);
            let ib = local(tri, b);
            let ic = 3 - ia - ib;
            if n_shared < 2 {
                apex[n_shared] = tri[ic];
            }
            n_shared += 1;
            // Outer edges (a, c) (opposite b) and (b, c) (opposite a) must not both be curves.
            let curve_ac =
                mesh.neighbours[t as usize][ib] == NONE || mesh.edge_ref[t as usize][ib] != 0;
            let curve_bc =
                mesh.neighbours[t as usize][ia] == NONE || mesh.edge_ref[t as usize][ia] != 0;
            if curve_ac && curve_bc {
                return None;
            }
        }
    }
    if n_shared == 0 || n_shared > 2 {
        return None;
    }
    // Link condition: ring(a) ∩ ring(b) = apexes.
    let mut fan2 = std::mem::take(&mut ctx.fan2);
    fan2.clear();
    mesh.for_each_fan_triangle(b, |t| fan2.push(t));
    let in_ring_b = |w: u32| fan2.iter().any(|&t| mesh.tris[t as usize].contains(&w));
    let mut ok = true;
    let (p_b, m_b) = (ctx.p(b), *ctx.m(b));
    let l_b = if ctx.fast_q {
        m_b
    } else {
        ctx.logm[b as usize]
    };
    let mut q_old: f64 = 1.0;
    let mut q_new: f64 = 1.0;
    for &t in &ctx.fan {
        let tri = mesh.tris[t as usize];
        q_old = q_old.max(ctx.q_tri(t));
        if tri.contains(&b) {
            continue;
        }
        let ia = local(tri, a);
        for w in [tri[next(ia)], tri[prev(ia)]] {
            if w != apex[0] && w != apex[1] && in_ring_b(w) {
                ok = false;
            }
        }
        let newtri = tri.map(|v| if v == a { b } else { v });
        let [p0, p1, p2] = newtri.map(|v| ctx.p(v));
        if crate::geom::orient2d(p0, p1, p2) <= 0.0 {
            ok = false;
            break;
        }
        q_new = q_new.max(ctx.q_moved(tri, a, p_b, &m_b, &l_b));
        // New edges b -> w must not be too long.
        for w in [tri[next(ia)], tri[prev(ia)]] {
            if w != apex[0] && w != apex[1] {
                let l = super::kernel::edge_length(p_b, ctx.p(w), &m_b, ctx.m(w));
                if l > ctx.params.l_max {
                    ok = false;
                }
            }
        }
        if !ok {
            break;
        }
    }
    ctx.fan2 = fan2;
    if !ok || !(q_new <= ctx.params.q_max || q_new <= q_old) {
        return None;
    }
    Some(CollapsePlan { a, b })
}

/// Pure check of the collapse `a -> b` (loads the fans itself).
#[cfg(test)]
pub fn check(ctx: &mut Ctx, a: u32, b: u32) -> Option<CollapsePlan> {
    ctx.load_fan(a);
    check_loaded(ctx, a, b)
}

/// Applies a collapse planned by [`check_loaded`] ([`crate::mesh::TriMesh::collapse_edge`]; the fan of
/// `a` must still be in `ctx.fan`).
pub fn apply(ctx: &mut Ctx, plan: &CollapsePlan) {
    let fan = std::mem::take(&mut ctx.fan);
    let (mesh, mut ws) = ctx.edit(Sym2::IDENTITY);
    mesh.collapse_edge(plan.a, plan.b, &fan, &mut ws);
    ctx.fan = fan;
}

/// The collapse operator: one pass over the vertices whose ball changed since the last collapse
/// pass, in vertex order. Each vertex with an edge shorter than `l_min` is collapsed onto the
/// end of its shortest such edge that passes the check (trying the others in order of length).
/// A vertex that received a collapse is not collapsed again in the same pass. With several
/// threads, which vertices have a short edge is first found on the state at the start of the
/// pass; the pass trusts a "no short edge" verdict only while the vertex's ball is unchanged
/// (`vmod`), so the collapses are the same for any number of threads.
#[derive(Default)]
pub(crate) struct Collapse {
    /// Generation of the previous collapse pass: only vertices modified since are examined.
    since: u32,
    /// The short edges of the vertex being checked: `(length, other end)`.
    short: Vec<(f64, u32)>,
}

impl Collapse {
    /// Whether `a` is a live vertex that may be removed and whose ball changed since the
    /// previous collapse pass.
    #[inline]
    fn candidate(&self, ctx: &Ctx, au: usize) -> bool {
        ctx.vmod[au] >= self.since
            && ctx.mesh.vert_tri[au] != NONE
            && !ctx.mesh.corner[au]
            && !ctx.mesh.required[au]
    }
}

impl Operator<Ctx<'_>> for Collapse {
    type Site = u32;
    type Key = u32;
    type Frozen = bool;
    type Plan = CollapsePlan;
    const SORTED: bool = false;

    fn sites(&mut self, ctx: &mut Ctx) -> Vec<u32> {
        self.since = ctx.last_collapse;
        ctx.new_pass();
        ctx.last_collapse = ctx.gen;
        (0..ctx.mesh.n_points() as u32).collect()
    }

    fn survey(&self, c: &Ctx, a: u32, evaluate: bool, out: &mut Vec<(u32, Option<bool>)>) {
        let frozen =
            evaluate.then(|| self.candidate(c, a as usize) && has_short_edge(c, a, c.params.l_min));
        out.push((a, frozen));
    }

    /// Not the target of a collapse in this pass, and still a candidate.
    fn admissible(&self, ctx: &Ctx, a: u32) -> bool {
        ctx.vstamp[a as usize] != ctx.gen && self.candidate(ctx, a as usize)
    }

    fn unchanged(&self, ctx: &Ctx, a: u32) -> bool {
        ctx.vmod[a as usize] != ctx.gen
    }

    fn check(&mut self, ctx: &mut Ctx, a: u32, frozen: Option<bool>) -> Option<CollapsePlan> {
        if frozen == Some(false) {
            return None;
        }
        let l_min = ctx.params.l_min;
        ctx.load_fan(a);
        let short = &mut self.short;
        short.clear();
        for k in 0..ctx.fan.len() {
            let tri = ctx.mesh.tris[ctx.fan[k] as usize];
            let ia = local(tri, a);
            // Each ring vertex once: the edge leaving a counter-clockwise, plus the last one of
            // an open fan.
            let w = tri[next(ia)];
            if let Some(l) = ctx.len_if_below(a, w, l_min) {
                short.push((l, w));
            }
            if k + 1 == ctx.fan.len() {
                let w2 = tri[prev(ia)];
                let first = ctx.mesh.tris[ctx.fan[0] as usize];
                if w2 != first[next(local(first, a))] {
                    if let Some(l) = ctx.len_if_below(a, w2, l_min) {
                        short.push((l, w2));
                    }
                }
            }
        }
        short.sort_unstable_by(|x, y| x.0.total_cmp(&y.0));
        short.iter().find_map(|&(_, b)| check_loaded(ctx, a, b))
    }

    /// Collapses, and marks the remaining end as not to be collapsed again in this pass.
    fn apply(&mut self, ctx: &mut Ctx, plan: CollapsePlan) {
        apply(ctx, &plan);
        ctx.vstamp[plan.b as usize] = ctx.gen;
    }
}

/// One collapse pass ([`Collapse`]); returns the number of collapses.
pub fn pass(ctx: &mut Ctx) -> usize {
    run_pass(&mut Collapse::default(), ctx)
}

/// Whether vertex `a` has an edge shorter than `l_min` (every edge of its ball that holds it).
fn has_short_edge(ctx: &Ctx, a: u32, l_min: f64) -> bool {
    let mut short = false;
    ctx.mesh.for_each_fan_triangle(a, |t| {
        let tri = ctx.mesh.tris[t as usize];
        let ia = local(tri, a);
        short = short
            || ctx.len_if_below(a, tri[next(ia)], l_min).is_some()
            || ctx.len_if_below(a, tri[prev(ia)], l_min).is_some();
    });
    short
}
