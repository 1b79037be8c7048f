//! Edge flip (MMG `swapar_2d.c`, 004 §3.5): the diagonal of the convex quadrilateral formed by
//! two triangles is swapped when that lowers the worse `Q_ani` of the pair. Boundary and labelled
//! edges are never flipped, so curves and sub-domain labels are preserved; the area is preserved
//! exactly (same quadrilateral).

use super::topo::Ctx;
use crate::adapt::pass::{run_pass, Operator};
use crate::geom::orient2d;
use crate::mesh::{next, prev, NONE};
use crate::metric::Sym2;

/// Relative improvement of the worse quality a flip must bring (avoids cycling).
const GAIN: f64 = 0.99;

/// A planned flip of local edge `i` of triangle `t`, made by [`check`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlipPlan {
    /// A triangle holding the edge.
    pub t: u32,
    /// The local index of the edge in `t` (the edge opposite vertex `i`).
    pub i: u8,
    /// The qualities of the two new triangles when `check` computed them (`apply` caches them).
    pub(crate) q: Option<[f64; 2]>,
}

/// Pure check: whether flipping edge `(t, i)` is valid (convex quadrilateral, unlabelled interior
/// edge) and lowers `max(Q_ani)` of the two triangles by at least 1%.
pub fn check(ctx: &Ctx, t: u32, i: usize) -> Option<FlipPlan> {
    let mesh = &*ctx.mesh;
    let tu = t as usize;
    let t2 = mesh.neighbours[tu][i];
    if t2 == NONE || mesh.edge_ref[tu][i] != 0 {
        return None;
    }
    let t2u = t2 as usize;
    let tri = mesh.tris[tu];
    let (c, a, b) = (tri[i], tri[next(i)], tri[prev(i)]);
    let j = mesh.mirror_edge(tu, t2u)?;
    let d = mesh.tris[t2u][j];
    let q_old = ctx.q_tri(t).max(ctx.q_tri(t2));
    // Q_ani >= 1: no flip can bring the worse quality below GAIN * q_old when q_old <= 1/GAIN.
    if q_old * GAIN <= 1.0 {
        return None;
    }
    // Quality first, the exact orientation tests (convex quadrilateral) last: a triangle whose
    // floating-point area is not positive has Q_ani = +inf and fails the quality test, the
    // exact tests decide the near-degenerate rest. The conditions are those of a convexity
    // test followed by `max(q1, q2) < bound` (`f64::max` skips a NaN), in a cheaper order.
    let bound = GAIN * q_old;
    let q1 = ctx.q([c, a, d]);
    if q1 >= bound {
        return None;
    }
    let q2 = ctx.q([d, b, c]);
    let q_new = q1.max(q2);
    if q_new >= bound || q_new.is_nan() {
        return None;
    }
    let (pa, pb, pc, pd) = (ctx.p(a), ctx.p(b), ctx.p(c), ctx.p(d));
    (orient2d(pc, pa, pd) > 0.0 && orient2d(pc, pd, pb) > 0.0).then_some(FlipPlan {
        t,
        i: i as u8,
        q: Some([q1, q2]),
    })
}

/// Applies a flip ([`crate::mesh::TriMesh::flip_edge`]): `(c, a, b) + (d, b, a)` becomes
/// `(c, a, d) + (d, b, c)`.
pub fn apply(ctx: &mut Ctx, plan: &FlipPlan) {
    let t = plan.t;
    let (mesh, mut ws) = ctx.edit(Sym2::IDENTITY);
    let t2 = mesh.flip_edge(t, plan.i as usize, &mut ws);
    if let Some([q1, q2]) = plan.q {
        // `check` evaluated exactly these triangles, `(c, a, d)` and `(d, b, c)`, with `Ctx::q`.
        ctx.set_q(t, q1);
        ctx.set_q(t2, q2);
    }
}

/// The flip operator: one sweep over the interior edges next to triangles modified since the
/// last sweep, in triangle order, each accepted flip applied at once. With several threads the
/// checks are first evaluated on the state at the start of the sweep (the frozen verdict of
/// each edge); the sweep uses such a verdict only while neither triangle of the edge has
/// changed, so the flips are the same for any number of threads.
pub(crate) struct Flip;

impl Flip {
    /// Whether the edge from `t` to its neighbour `nb` is checked from `nb` first: `nb` is a
    /// listed triangle of lower index.
    #[inline]
    fn checked_before(ctx: &Ctx, t: u32, nb: u32) -> bool {
        nb < t && ctx.tseen[nb as usize] == ctx.gen
    }
}

impl Operator<Ctx<'_>> for Flip {
    type Site = u32;
    type Key = (u32, u8);
    type Frozen = bool;
    type Plan = FlipPlan;
    const SORTED: bool = false;

    fn sites(&mut self, ctx: &mut Ctx) -> Vec<u32> {
        ctx.new_pass();
        let from = ctx.flip_pos;
        ctx.flip_pos = ctx.log.len();
        ctx.logged_since(from)
    }

    fn survey(&self, c: &Ctx, t: u32, evaluate: bool, out: &mut Vec<((u32, u8), Option<bool>)>) {
        for i in 0..3 {
            let frozen = evaluate.then(|| {
                let nb = c.mesh.neighbours[t as usize][i];
                nb != NONE && !Self::checked_before(c, t, nb) && check(c, t, i).is_some()
            });
            out.push(((t, i as u8), frozen));
        }
    }

    /// An interior edge, unless it was already checked from its neighbour and neither triangle
    /// has changed since (same answer).
    fn admissible(&self, ctx: &Ctx, (t, i): (u32, u8)) -> bool {
        let nb = ctx.mesh.neighbours[t as usize][i as usize];
        nb != NONE && !(self.unchanged(ctx, (t, i)) && Self::checked_before(ctx, t, nb))
    }

    fn unchanged(&self, ctx: &Ctx, (t, i): (u32, u8)) -> bool {
        let nb = ctx.mesh.neighbours[t as usize][i as usize];
        ctx.tstamp[t as usize] != ctx.gen && ctx.tstamp[nb as usize] != ctx.gen
    }

    fn check(
        &mut self,
        ctx: &mut Ctx,
        (t, i): (u32, u8),
        frozen: Option<bool>,
    ) -> Option<FlipPlan> {
        match frozen {
            Some(ok) => ok.then_some(FlipPlan { t, i, q: None }),
            None => check(ctx, t, i as usize),
        }
    }

    fn apply(&mut self, ctx: &mut Ctx, plan: FlipPlan) {
        apply(ctx, &plan);
    }
}

/// One flip sweep ([`Flip`]); returns the number of flips.
pub fn pass(ctx: &mut Ctx) -> usize {
    run_pass(&mut Flip, ctx)
}
