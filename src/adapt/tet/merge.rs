//! Edge contraction to a chosen point: the two ends of a short edge become one vertex placed
//! where its new edges are closest to unit length — at either end (a plain collapse), at the
//! metric midpoint, or at the mean of the points at unit metric distance from the neighbours
//! of both ends. Collapsing onto an end leaves the new edges as long as the edges from that end
//! plus the short edge, which in an anisotropic layer often exceeds `l_max`; a point between
//! the ends shares the excess out and makes many more of the short edges removable.
//!
//! The topology is that of collapsing `a` onto `b` (the link condition, the shell removed);
//! then `b` is moved to the chosen point. Boundary ends: the plain collapses only, unless both
//! are face vertices of one plane and one label joined by a boundary edge, in which case the
//! point stays in that plane.

use super::Ctx;
use crate::geom::DVec3;
use crate::mesh3::edit::{in_plane, onto_plane};
use crate::mesh3::{signed_volume, VertexKind};
use crate::metric::Sym3;

/// A checked contraction: remove `a`, move `b` to `p` with metric `m`; `q` the worst quality
/// of the new ball.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Merge {
    pub a: u32,
    pub b: u32,
    pub p: DVec3,
    pub m: Sym3,
    pub q: f64,
}

/// Whether `a` and `b` satisfy the link condition: every common neighbour lies in the shell
/// of the edge. `na`, `nb` are their sorted neighbours.
fn link_ok(ctx: &Ctx<'_>, a: u32, b: u32, na: &[u32], nb: &[u32]) -> bool {
    let mut shell_v: Vec<u32> = ctx.mesh.ball[a as usize]
        .iter()
        .map(|&t| ctx.mesh.tets[t as usize])
        .filter(|t| t.contains(&b))
        .flatten()
        .collect();
    if shell_v.is_empty() {
        return false;
    }
    shell_v.sort_unstable();
    shell_v.dedup();
    na.iter()
        .all(|v| nb.binary_search(v).is_err() || shell_v.binary_search(v).is_ok())
}

/// The tetrahedra after contracting `(a, b)` into `b` (those of the two balls without the
/// shell, `a` renamed `b`).
fn merged_tets(ctx: &Ctx<'_>, a: u32, b: u32) -> Vec<[u32; 4]> {
    let mut out = Vec::new();
    for &t in &ctx.mesh.ball[a as usize] {
        let tet = ctx.mesh.tets[t as usize];
        if !tet.contains(&b) {
            out.push(tet.map(|v| if v == a { b } else { v }));
        }
    }
    for &t in &ctx.mesh.ball[b as usize] {
        let tet = ctx.mesh.tets[t as usize];
        if !tet.contains(&a) {
            out.push(tet);
        }
    }
    out
}

/// The worst quality of `tets` with `b` at `p` with metric `m`, or `None` when one is not
/// positive or an edge from `b` to `nbs` would be longer than `l_max`.
fn evaluate(
    ctx: &Ctx<'_>,
    b: u32,
    p: DVec3,
    m: &Sym3,
    tets: &[[u32; 4]],
    nbs: &[u32],
) -> Option<f64> {
    for &c in nbs {
        let pc = ctx.mesh.points[c as usize];
        if Ctx::length_at(p, pc, m, &ctx.metric[c as usize]) > ctx.l_max {
            return None;
        }
    }
    let mut q = f64::INFINITY;
    for &t in tets {
        let x = t.map(|v| {
            if v == b {
                p
            } else {
                ctx.mesh.points[v as usize]
            }
        });
        if signed_volume(x[0], x[1], x[2], x[3]) <= 0.0 {
            return None;
        }
        q = q.min(ctx.quality_of(t, Some((b, p, m))));
    }
    Some(q)
}

/// The best contraction of the edge `(a, b)` (highest worst quality of the new ball) over the
/// candidate points, or `None` when no candidate is valid with every new edge at most `l_max`.
pub(crate) fn best_merge(ctx: &Ctx<'_>, a: u32, b: u32) -> Option<Merge> {
    let mut na = Vec::new();
    let mut nb = Vec::new();
    ctx.mesh.vertex_neighbours(a, &mut na);
    ctx.mesh.vertex_neighbours(b, &mut nb);
    if !link_ok(ctx, a, b, &na, &nb) {
        return None;
    }
    let (pa, pb) = (ctx.mesh.points[a as usize], ctx.mesh.points[b as usize]);
    let (ka, kb) = (ctx.mesh.vertex_kind(a), ctx.mesh.vertex_kind(b));
    // Which ends may move: `Some(normal)` for a face end, `None` for a fixed one.
    let free = match (ka, kb) {
        (VertexKind::Interior, VertexKind::Interior) => true,
        (VertexKind::Face(n1), VertexKind::Face(n2)) => {
            n1.cross(n2).length() < 1e-9 && ctx.mesh.is_boundary_edge(a, b) && same_label(ctx, a, b)
        }
        _ => false,
    };
    let mut nbs: Vec<u32> = na
        .iter()
        .chain(&nb)
        .copied()
        .filter(|&c| c != a && c != b)
        .collect();
    nbs.sort_unstable();
    nbs.dedup();
    let mut best: Option<Merge> = None;
    let consider = |x: u32, y: u32, p: DVec3, m: Sym3, best: &mut Option<Merge>| {
        let tets = merged_tets(ctx, x, y);
        if let Some(q) = evaluate(ctx, y, p, &m, &tets, &nbs) {
            if best.map_or(true, |bm| q > bm.q) {
                *best = Some(Merge {
                    a: x,
                    b: y,
                    p,
                    m,
                    q,
                });
            }
        }
    };
    // Plain collapses, boundary rules from the mesh's own check.
    for (x, y) in [(a, b), (b, a)] {
        if ctx.mesh.collapse_check(x, y).is_some() {
            let (p, m) = (ctx.mesh.points[y as usize], ctx.metric[y as usize]);
            consider(x, y, p, m, &mut best);
        }
    }
    if free {
        let Some(f) = ctx.source else {
            return best;
        };
        let e = pb - pa;
        let la = ctx.metric[a as usize].quad(e).sqrt();
        let lb = ctx.metric[b as usize].quad(e).sqrt();
        let t = super::split::metric_midpoint(la, lb).clamp(0.25, 0.75);
        let mid = pa + t * e;
        let mm = f(mid);
        let mut cands = vec![(mid, mm)];
        let mut target = DVec3::ZERO;
        for &c in &nbs {
            let pc = ctx.mesh.points[c as usize];
            let l = Ctx::length_at(mid, pc, &mm, &ctx.metric[c as usize]).max(1e-12);
            target += pc + (mid - pc) / l;
        }
        let mut pt = target / nbs.len().max(1) as f64;
        if let VertexKind::Face(n) = ka {
            pt = onto_plane(pa, n, pt);
        }
        cands.push((pt, f(pt)));
        // The topology of collapsing `a` onto `b` needs the link condition only (checked);
        // boundary triangles of the two face ends stay in their plane.
        for (p, m) in cands {
            if on_plane(ka, pa, p) {
                consider(a, b, p, m, &mut best);
            }
        }
    }
    best
}

/// Whether `p` may be the position of a merged vertex of kind `k` through `p0`: anywhere for
/// an interior vertex, in the plane for a face vertex.
fn on_plane(k: VertexKind, p0: DVec3, p: DVec3) -> bool {
    match k {
        VertexKind::Interior => true,
        VertexKind::Face(n) => in_plane(p0, n, p),
        VertexKind::Feature => false,
    }
}

/// Whether the boundary triangles of `a` and `b` carry one and the same label.
fn same_label(ctx: &Ctx<'_>, a: u32, b: u32) -> bool {
    let (mut fa, mut fb) = (Vec::new(), Vec::new());
    ctx.mesh.vertex_bfaces(a, &mut fa);
    ctx.mesh.vertex_bfaces(b, &mut fb);
    match fa.first() {
        Some(&(_, l)) => fa.iter().chain(&fb).all(|&(_, x)| x == l),
        None => false,
    }
}

/// Applies a checked contraction.
pub(crate) fn apply(ctx: &mut Ctx<'_>, mg: Merge) {
    ctx.touch_ball(mg.a);
    ctx.mesh.collapse_unchecked(mg.a, mg.b);
    ctx.mesh.set_point(mg.b, mg.p);
    ctx.metric[mg.b as usize] = mg.m;
    ctx.touch_ball(mg.b);
}
