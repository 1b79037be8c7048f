//! Vertex smoothing: each free vertex is pulled by its edges as springs of rest length 1 in the
//! metric, `d = (1/n) Σ_i (1 − 1/l_i)(p_i − p)` over its `n` neighbours `p_i` at metric
//! distance `l_i` (long edges pull, short ones push); the move is tried at full, half and a
//! quarter step and kept at the first that raises the worst quality of the ball (mean ratio) by
//! 0.5 %
//! with every tetrahedron positive. A pass examines the vertices whose ball changed since the
//! previous one. Face vertices move in their boundary plane; ridge and
//! corner vertices stay.

use super::Ctx;
use crate::adapt::pass::{run_pass, Operator};
use crate::geom::DVec3;
use crate::mesh3::edit::onto_plane;
use crate::mesh3::VertexKind;
use crate::metric::Sym3;

/// Relative gain in the worst quality of the ball a move must bring (smaller gains moved
/// thousands of vertices per pass without changing the worst quality).
const GAIN: f64 = 1.005;

/// The smoothing operator.
pub(crate) struct Smooth;

impl Operator<Ctx<'_>> for Smooth {
    type Site = u32;
    type Key = u32;
    type Frozen = ();
    type Plan = (u32, DVec3, Sym3);
    const SORTED: bool = false;

    fn sites(&mut self, ctx: &mut Ctx<'_>) -> Vec<u32> {
        ctx.changed_vertices(super::Op::Smooth)
    }

    fn survey(&self, _: &Ctx<'_>, v: u32, _: bool, out: &mut Vec<(u32, Option<()>)>) {
        out.push((v, None));
    }

    fn admissible(&self, ctx: &Ctx<'_>, v: u32) -> bool {
        ctx.mesh.alive(v)
    }

    fn check(&mut self, ctx: &mut Ctx<'_>, v: u32, _: Option<()>) -> Option<Self::Plan> {
        let normal = match ctx.mesh.vertex_kind(v) {
            VertexKind::Interior => None,
            VertexKind::Face(n) => Some(n),
            VertexKind::Feature => return None,
        };
        let p = ctx.mesh.points[v as usize];
        let mut nb = Vec::new();
        ctx.mesh.vertex_neighbours(v, &mut nb);
        let mut d = DVec3::ZERO;
        for &w in &nb {
            let l = ctx.length(v, w).max(1e-12);
            d += (1.0 - 1.0 / l) * (ctx.mesh.points[w as usize] - p);
        }
        d /= nb.len() as f64;
        if let Some(n) = normal {
            d -= n * d.dot(n);
        }
        let (q0, mut first) = ctx.ball_worst(v);
        for step in [1.0, 0.5, 0.25] {
            let np = match normal {
                // Exactly in the plane (an axis-aligned plane's coordinate is kept exactly).
                Some(n) => onto_plane(p, n, p + step * d),
                None => p + step * d,
            };
            let m = match ctx.source {
                Some(f) => f(np),
                None => ctx.metric[v as usize],
            };
            let better = ctx
                .ball_min_above(v, q0 * GAIN, &mut first, |t| {
                    ctx.quality_of(t, Some((v, np, &m)))
                })
                .is_some();
            if better && ctx.mesh.move_valid(v, np) {
                return Some((v, np, m));
            }
        }
        None
    }

    fn apply(&mut self, ctx: &mut Ctx<'_>, (v, p, m): Self::Plan) {
        if ctx.mesh.move_vertex(v, p) {
            ctx.metric[v as usize] = m;
            ctx.touch_ball(v);
        }
    }
}

/// One smoothing pass; returns the number of moves.
pub(crate) fn pass(ctx: &mut Ctx<'_>) -> usize {
    run_pass(&mut Smooth, ctx)
}
