//! Split long edges (004 §3.5): every edge longer than `l_max` in the metric is cut at its
//! metric midpoint, the point of the segment with equal metric length to both ends under the
//! geometric interpolation of the length density. Longest first, each checked on the current
//! mesh; a split of an edge with an interior end is refused when its midpoint lies within
//! metric distance [`FILTER`] of a vertex inserted earlier in the same pass (the insertion
//! filter: the edges crossing a thin layer have their metric midpoints next to each other, and
//! splitting them all refined the layer tangentially far beyond the metric). A boundary
//! edge's midpoint lies on its boundary plane or ridge, so the boundary keeps its shape.

use super::{mean_ratio, Ctx};
use crate::adapt::pass::{run_pass, Operator};
use crate::geom::DVec3;
use crate::metric::Sym3;

/// The insertion filter of the refinement passes (metric length, [`Ctx::split_filter`]), on
/// edges with an interior end (mmg's filter). Measured on UGAWG cube-linear (one thread, CPU
/// s, with collapses that try every short edge of a vertex): 0.7 on interior edges 98.27 % in
/// range, worst mean ratio 0.542, 9.3 s; off 97.97 % / 0.488, 13.7 s; 0.7 on every edge (the
/// boundary's too) left slivers of mean ratio 0.16 next to the ridges (98.14 %, 13.7 s), and
/// 0.5 on every edge 97.98 % / 0.149.
pub(crate) const FILTER: f64 = 0.7;

/// A split may not turn a tetrahedron of its shell into a child below this mean ratio, both
/// in the metric and in the Euclidean sense, unless the child is at least as good as its
/// parent in one of them. Without it the edges of a poor tetrahedron that are long in the
/// metric but short across it were split pass after pass, each split halving the volume of a
/// child and its quality with it: the 004 star ended with thousands of tetrahedra of mean
/// ratio down to 1e-13 along its deepest valleys, four vertices on one line (allowing each
/// split to lose a quarter of the quality only slowed the fall). The Euclidean half lets
/// through the splits of a start mesh that is poor only in the metric (UGAWG cube-linear's
/// Kuhn mesh: worst 0.004 in the metric, whose splits are what makes it good).
pub(crate) const QUALITY_FLOOR: f64 = 0.02;

/// Whether splitting `(a, b)` at `p` (metric `m`) keeps every child of the shell's
/// tetrahedra out of the degenerating splits of [`QUALITY_FLOOR`].
fn keeps_quality(ctx: &Ctx<'_>, a: u32, b: u32, p: DVec3, m: &Sym3) -> bool {
    let mut shell = Vec::new();
    ctx.mesh.shell(a, b, &mut shell);
    let euclid = |tet: [u32; 4], moved: Option<u32>| {
        let q = tet.map(|v| {
            if Some(v) == moved {
                p
            } else {
                ctx.mesh.points[v as usize]
            }
        });
        mean_ratio(q, &[Sym3::IDENTITY; 4])
    };
    shell.iter().all(|&t| {
        let tet = ctx.mesh.tets[t as usize];
        let in_metric = QUALITY_FLOOR.min(ctx.tet_quality(t));
        let in_space = QUALITY_FLOOR.min(euclid(tet, None));
        [a, b].iter().all(|&x| {
            ctx.quality_of(tet, Some((x, p, m))) >= in_metric || euclid(tet, Some(x)) >= in_space
        })
    })
}

/// Whether a vertex inserted earlier in this pass and adjacent to `a` or `b` lies within
/// metric length `ctx.split_filter` of the new point `p` (metric `m`): the insertion filter
/// that keeps a refinement pass from packing the midpoints of neighbouring long edges into
/// the same spot (the edges of one shell crossing a thin layer all have their metric midpoints
/// near each other). Refused splits come back in the next pass, on shorter edges.
fn too_close(ctx: &Ctx<'_>, a: u32, b: u32, p: DVec3, m: &Sym3) -> bool {
    for v in [a, b] {
        for &t in &ctx.mesh.ball[v as usize] {
            for w in ctx.mesh.tets[t as usize] {
                if w >= ctx.first_new
                    && Ctx::length_at(p, ctx.mesh.points[w as usize], m, &ctx.metric[w as usize])
                        < ctx.split_filter
                {
                    return true;
                }
            }
        }
    }
    false
}

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
        ctx.first_new = ctx.mesh.points.len() as u32;
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
        let boundary = ctx.mesh.on_boundary[a as usize] && ctx.mesh.on_boundary[b as usize];
        if ctx.split_filter > 0.0 && !boundary && too_close(ctx, a, b, p, &m) {
            return None;
        }
        if !keeps_quality(ctx, a, b, p, &m) {
            return None;
        }
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
