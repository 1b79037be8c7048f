//! Vertex relocation (MMG `movpt_2d.c`, 004 §3.5): a free vertex moves toward the average of the
//! ideal positions its ring offers, i.e. for each triangle `(v, a, b)` of its fan the apex of the
//! unit equilateral triangle on `(a, b)` in the element metric `M`:
//!
//! `x* = (a + b)/2 + (sqrt(3)/2) / sqrt(det M) · adj(M) · R90 (b - a)`
//!
//! (the image of the Euclidean apex through `M^{-1/2}`; `R90` is the rotation by +90°). The move
//! is tried at full, half and quarter step and kept only if no triangle inverts and the worst
//! `Q_ani` of the fan decreases. The metric and fields at the new position come from the source
//! or are interpolated in the old fan.

use super::topo::{local, Ctx, VClass};
use crate::adapt::pass::{run_pass, Operator};
use crate::geom::{barycentric, orient2d, DVec2};
use crate::mesh::{next, prev, NONE};
use crate::metric::Sym2;

/// Relative improvement of the worst fan quality a move must bring.
const GAIN: f64 = 0.999;

/// A planned move of vertex `v` to `p`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MovePlan {
    /// The vertex moved.
    pub v: u32,
    /// Its new position.
    pub p: DVec2,
}

/// The ideal apex position opposite the edge `a -> b` in the metric `m` (see the module docs).
#[inline]
pub fn ideal_apex(a: DVec2, b: DVec2, m: &Sym2) -> DVec2 {
    let e = b - a;
    let r = DVec2::new(-e.y, e.x);
    let adj_r = DVec2::new(m.yy * r.x - m.xy * r.y, -m.xy * r.x + m.xx * r.y);
    0.5 * (a + b) + (0.5 * 3f64.sqrt() / m.det().sqrt()) * adj_r
}

/// Pure check for a free vertex `v` (fan loaded in `ctx.fan`).
pub fn check_loaded(ctx: &Ctx, v: u32) -> Option<MovePlan> {
    check_fan(ctx, v, &ctx.fan)
}

/// Pure check for a free vertex `v` whose counter-clockwise fan is `fan`.
pub fn check_fan(ctx: &Ctx, v: u32, fan: &[u32]) -> Option<MovePlan> {
    if fan.len() < 3 || ctx.vclass_in(v, fan) != VClass::Free {
        return None;
    }
    let mesh = &*ctx.mesh;
    let pv = ctx.p(v);
    let mv = *ctx.m(v);
    let lv = if ctx.fast_q { mv } else { ctx.logm[v as usize] };
    let mut target = DVec2::ZERO;
    let mut q_old: f64 = 1.0;
    for &t in fan {
        let tri = mesh.tris[t as usize];
        let iv = local(tri, v);
        let (a, b) = (tri[next(iv)], tri[prev(iv)]);
        let (ma, mb) = (ctx.m(a), ctx.m(b));
        let m = Sym2::new(
            (mv.xx + ma.xx + mb.xx) / 3.0,
            (mv.xy + ma.xy + mb.xy) / 3.0,
            (mv.yy + ma.yy + mb.yy) / 3.0,
        );
        target += ideal_apex(ctx.p(a), ctx.p(b), &m);
        q_old = q_old.max(ctx.q_tri(t));
    }
    target /= fan.len() as f64;
    // Q_ani >= 1: nothing can improve a fan whose worst quality is within the gain of 1.
    if !target.is_finite() || q_old * GAIN <= 1.0 {
        return None;
    }
    // A move is kept when every triangle of the fan improves on `GAIN * q_old` (a NaN quality
    // is skipped, as `f64::max` over the fan skips it) and none inverts. Quality first: a
    // triangle whose floating-point area is not positive has Q_ani = +inf and fails it; the
    // exact orientation tests decide the near-degenerate rest.
    let bound = GAIN * q_old;
    for omega in [1.0, 0.5, 0.25] {
        let p = pv + omega * (target - pv);
        if p == pv {
            return None;
        }
        let improves = fan.iter().all(|&t| {
            let q = ctx.q_moved(mesh.tris[t as usize], v, p, &mv, &lv);
            q < bound || q.is_nan()
        });
        let valid = improves
            && fan.iter().all(|&t| {
                let tri = mesh.tris[t as usize];
                let iv = local(tri, v);
                orient2d(p, ctx.p(tri[next(iv)]), ctx.p(tri[prev(iv)])) > 0.0
            });
        if valid {
            return Some(MovePlan { v, p });
        }
    }
    None
}

/// Applies a move ([`crate::mesh::TriMesh::move_vertex`]): the metric and fields at the new
/// position come from the source, else from interpolation in the old fan triangle containing
/// the new position.
pub fn apply(ctx: &mut Ctx, plan: &MovePlan) {
    let v = plan.v;
    let mut verts = [v; 3];
    let mut w = [1.0, 0.0, 0.0];
    for &t in &ctx.fan {
        let tri = ctx.mesh.tris[t as usize];
        let [a, b, c] = tri.map(|x| ctx.p(x));
        let l = barycentric(a, b, c, plan.p);
        if l.iter().all(|&x| x >= -1e-12) {
            verts = tri;
            w = l;
            break;
        }
    }
    let m = ctx.sample(plan.p, &verts, &w);
    let fan = std::mem::take(&mut ctx.fan);
    let (mesh, mut ws) = ctx.edit(m);
    mesh.move_vertex(v, plan.p, &fan, &mut ws);
    ctx.fan = fan;
}

/// The smoothing operator: one sweep, in vertex order, over the free vertices whose ball
/// changed since the last sweep; each accepted move is applied at once (Gauss-Seidel: a vertex
/// sees the moves of the vertices before it, and a vertex whose ball such a move changed is
/// examined when its turn comes). No frozen verdicts: every check is on the current state.
#[derive(Default)]
pub(crate) struct Smooth {
    /// Generation of the previous smoothing pass: only vertices modified since are examined.
    since: u32,
}

impl Operator<Ctx<'_>> for Smooth {
    type Site = u32;
    type Key = u32;
    type Frozen = ();
    type Plan = MovePlan;
    const SORTED: bool = false;

    fn sites(&mut self, ctx: &mut Ctx) -> Vec<u32> {
        self.since = ctx.last_smooth;
        ctx.new_pass();
        ctx.last_smooth = ctx.gen;
        (0..ctx.mesh.n_points() as u32).collect()
    }

    fn survey(&self, _ctx: &Ctx, v: u32, _evaluate: bool, out: &mut Vec<(u32, Option<()>)>) {
        out.push((v, None));
    }

    /// A live vertex whose ball changed since the previous smoothing pass.
    fn admissible(&self, ctx: &Ctx, v: u32) -> bool {
        ctx.mesh.vert_tri[v as usize] != NONE && ctx.vmod[v as usize] >= self.since
    }

    fn check(&mut self, ctx: &mut Ctx, v: u32, _frozen: Option<()>) -> Option<MovePlan> {
        ctx.load_fan(v);
        check_loaded(ctx, v)
    }

    fn apply(&mut self, ctx: &mut Ctx, plan: MovePlan) {
        apply(ctx, &plan);
    }
}

/// One smoothing sweep ([`Smooth`]); returns the number of moves.
pub fn pass(ctx: &mut Ctx) -> usize {
    run_pass(&mut Smooth::default(), ctx)
}
