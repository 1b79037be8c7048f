//! Edge flip (MMG `swapar_2d.c`, 004 §3.5): the diagonal of the convex quadrilateral formed by
//! two triangles is swapped when that lowers the worse `Q_ani` of the pair. Boundary and labelled
//! edges are never flipped, so curves and sub-domain labels are preserved; the area is preserved
//! exactly (same quadrilateral).

use super::topo::{parallel_worth, Ctx};
use crate::geom::orient2d;
use crate::mesh::{next, prev, NONE};
use crate::metric::Sym2;
use rayon::prelude::*;

/// Relative improvement of the worse quality a flip must bring (avoids cycling).
const GAIN: f64 = 0.99;

/// A planned flip of local edge `i` of triangle `t`, made by [`check`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlipPlan {
    pub t: u32,
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

/// One flip sweep over the interior edges next to triangles modified since the last sweep, in
/// triangle order, each accepted flip applied at once. With several threads the checks are
/// first evaluated in parallel on the state at the start of the sweep; the sweep then uses such
/// a result only while neither triangle of the edge has changed, so the flips are the same for
/// any number of threads. Returns the number of flips.
pub fn pass(ctx: &mut Ctx) -> usize {
    ctx.new_pass();
    let from = ctx.flip_pos;
    ctx.flip_pos = ctx.log.len();
    let list = ctx.logged_since(from);
    let gen = ctx.gen;
    // An edge shared with a listed triangle of lower index is checked from there first.
    let checked_before = |ctx: &Ctx, t: u32, nb: u32| nb < t && ctx.tseen[nb as usize] == gen;
    let pre: Option<Vec<u8>> = parallel_worth(list.len()).then(|| {
        let c: &Ctx = ctx;
        list.par_iter()
            .map(|&t| {
                let mut mask = 0u8;
                for i in 0..3 {
                    let nb = c.mesh.neighbours[t as usize][i];
                    if nb != NONE && !checked_before(c, t, nb) && check(c, t, i).is_some() {
                        mask |= 1 << i;
                    }
                }
                mask
            })
            .collect()
    });
    let mut count = 0;
    for (k, &t) in list.iter().enumerate() {
        for i in 0..3 {
            let nb = ctx.mesh.neighbours[t as usize][i];
            if nb == NONE {
                continue;
            }
            let unchanged = ctx.tstamp[t as usize] != gen && ctx.tstamp[nb as usize] != gen;
            // Already checked from `nb` and neither triangle has changed since: same answer.
            if unchanged && checked_before(ctx, t, nb) {
                continue;
            }
            let plan = match &pre {
                Some(pre) if unchanged => (pre[k] >> i & 1 == 1).then_some(FlipPlan {
                    t,
                    i: i as u8,
                    q: None,
                }),
                _ => check(ctx, t, i),
            };
            if let Some(plan) = plan {
                apply(ctx, &plan);
                count += 1;
            }
        }
    }
    count
}
