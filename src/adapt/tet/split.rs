//! Split long edges (004 §3.5): every edge longer than `l_max` in the metric is cut at its
//! metric midpoint, the point of the segment with equal metric length to both ends under the
//! geometric interpolation of the length density. Longest first; the edges split in one pass
//! have no vertex in common with the balls already changed (an independent set). A boundary
//! edge's midpoint lies on its boundary plane or ridge, so the boundary keeps its shape.

use super::Ctx;
use crate::adapt::pass::{run_pass, Operator};
use crate::geom::DVec3;
use crate::metric::Sym3;

/// The split operator.
pub(crate) struct Split;

/// A checked split: edge, new point, its metric.
pub(crate) struct Plan {
    a: u32,
    b: u32,
    p: DVec3,
    m: Sym3,
}

/// The parameter `t` of the metric midpoint of an edge with end lengths `la`, `lb`: with
/// `ℓ(t) = la^{1-t} lb^t`, half of `∫_0^1 ℓ` is reached at `r^t = (1 + r) / 2`, `r = lb / la`.
pub(crate) fn metric_midpoint(la: f64, lb: f64) -> f64 {
    let r = lb / la;
    if (r - 1.0).abs() < 1e-9 {
        0.5
    } else {
        ((1.0 + r) / 2.0).ln() / r.ln()
    }
}

impl Operator<Ctx<'_>> for Split {
    type Site = u32;
    type Key = (u64, u32, u32);
    type Frozen = ();
    type Plan = Plan;
    const SORTED: bool = true;

    fn sites(&mut self, ctx: &mut Ctx<'_>) -> Vec<u32> {
        ctx.changed_vertices(super::Op::Split)
    }

    fn survey(&self, ctx: &Ctx<'_>, a: u32, _: bool, out: &mut Vec<(Self::Key, Option<()>)>) {
        let mut nb = Vec::new();
        ctx.mesh.vertex_neighbours(a, &mut nb);
        for &b in nb.iter().filter(|&&b| b > a) {
            let l = ctx.length(a, b);
            if l > ctx.l_max {
                out.push(((u64::MAX - l.to_bits(), a, b), None));
            }
        }
    }

    fn admissible(&self, ctx: &Ctx<'_>, (_, a, b): Self::Key) -> bool {
        ctx.mesh.alive(a) && ctx.mesh.alive(b)
    }

    fn check(&mut self, ctx: &mut Ctx<'_>, (_, a, b): Self::Key, _: Option<()>) -> Option<Plan> {
        let (pa, pb) = (ctx.mesh.points[a as usize], ctx.mesh.points[b as usize]);
        let e = pb - pa;
        let la = ctx.metric[a as usize].quad(e).sqrt();
        let lb = ctx.metric[b as usize].quad(e).sqrt();
        if Ctx::length_at(pa, pb, &ctx.metric[a as usize], &ctx.metric[b as usize]) <= ctx.l_max {
            return None;
        }
        let t = metric_midpoint(la, lb).clamp(0.25, 0.75);
        let p = pa + t * e;
        if !ctx.mesh.split_valid(a, b, p) {
            return None;
        }
        let m = ctx.metric_on_edge(a, b, t, p);
        Some(Plan { a, b, p, m })
    }

    fn apply(&mut self, ctx: &mut Ctx<'_>, plan: Plan) {
        if let Some(v) = ctx.mesh.split_edge(plan.a, plan.b, plan.p) {
            ctx.metric.push(plan.m);
            debug_assert_eq!(ctx.metric.len(), v as usize + 1);
            ctx.touch_ball(v);
        }
    }
}

/// One refinement pass; returns the number of new vertices.
pub(crate) fn pass(ctx: &mut Ctx<'_>) -> usize {
    run_pass(&mut Split, ctx)
}
