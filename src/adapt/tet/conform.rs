//! The final conformity loop: after the split / collapse / swap / smoothing cycle has reached
//! its fixed point, the edges still outside `[l_min, l_max]` are worked on directly, in rounds
//! of
//! 1. *conformity collapses* ([`collapse_pass`]): every edge shorter than `l_min`, shortest
//!    first, is collapsed in whichever direction leaves the better new ball, when the new
//!    edges are at most `l_max` and the worst quality of the new ball is at least the worst of
//!    the old one or [`Q_KEEP`];
//!    then *short-edge removals* ([`short_edge_removal_pass`]): the interior edges still
//!    shorter than `l_min` are removed by retriangulating their shells, when the new edges
//!    are in range and the quality stays as for the collapses;
//! 2. a split pass (edges longer than `l_max`), a swap pass;
//! 3. *length smoothing* ([`length_smooth_pass`]): each free vertex moves toward the mean of
//!    the points at unit metric distance from its neighbours along its current edges, accepted
//!    when the squared log-lengths of its edges decrease, no edge leaves the range, and the
//!    worst quality of its ball stays at least its old worst or [`Q_KEEP`];
//!
//! until the share of edges in range stops rising (004 §3.5: all edges in `[l_min, l_max]`,
//! quality near one). Every candidate is checked on the current mesh when its turn comes and
//! the visits are sequential in a fixed order, so the result does not depend on the thread
//! count.

use super::Ctx;
use crate::adapt::cycle::Remesher;
use crate::adapt::options::{AdaptOptions, AdaptReport, PassKind};
use crate::error::Result;
use crate::geom::DVec3;
use crate::mesh3::edit::onto_plane;
use crate::mesh3::VertexKind;
use crate::metric::Sym3;
use std::time::Instant;

/// Quality (mean ratio) a conformity collapse or move may go down to when the ball was better.
pub(crate) const Q_KEEP: f64 = 0.5;

/// Tetrahedra below this quality are repaired after the loop ([`super::improve`]).
const Q_REPAIR: f64 = 0.55;

/// Most rounds of the loop.
const ROUNDS: usize = 16;

/// The share of edges with metric length in `[l_min, l_max]` (lengths as the operators see
/// them, [`Ctx::length`]).
pub(crate) fn in_range_share(ctx: &Ctx<'_>) -> f64 {
    let (mut n, mut inr) = (0usize, 0usize);
    for_each_edge_length(ctx, |_, _, l| {
        n += 1;
        if (ctx.l_min..=ctx.l_max).contains(&l) {
            inr += 1;
        }
    });
    inr as f64 / n.max(1) as f64
}

/// Calls `f(a, b, length)` once for every edge `a < b` of the live mesh, in vertex order.
fn for_each_edge_length(ctx: &Ctx<'_>, mut f: impl FnMut(u32, u32, f64)) {
    let mut nb = Vec::new();
    for a in 0..ctx.mesh.points.len() as u32 {
        if !ctx.mesh.alive(a) {
            continue;
        }
        ctx.mesh.vertex_neighbours(a, &mut nb);
        for &b in nb.iter().filter(|&&b| b > a) {
            f(a, b, ctx.length(a, b));
        }
    }
}

/// Per vertex: whether its ball changed at or after pass `since` (a vertex added since the
/// stamps were last resized counts as changed); with `rings`, also whether a neighbour's ball
/// did.
fn changed_since(ctx: &Ctx<'_>, since: u32, rings: bool) -> Vec<bool> {
    let n = ctx.mesh.points.len();
    let mut changed: Vec<bool> = (0..n)
        .map(|v| ctx.mesh.alive(v as u32) && ctx.stamp.get(v).map_or(true, |&s| s >= since))
        .collect();
    if rings && since > 0 {
        let mut nb = Vec::new();
        let seeds: Vec<u32> = (0..n as u32).filter(|&v| changed[v as usize]).collect();
        for v in seeds {
            ctx.mesh.vertex_neighbours(v, &mut nb);
            for &w in &nb {
                changed[w as usize] = true;
            }
        }
    }
    changed
}

/// The edges shorter than `l_min` with a `changed` end (each from its smaller end, as the
/// operators measure it: the last bits of a length depend on the direction).
fn short_edges(ctx: &Ctx<'_>, changed: &[bool], out: &mut Vec<(u64, u32, u32)>) {
    let mut nb = Vec::new();
    for a in 0..ctx.mesh.points.len() as u32 {
        if !changed[a as usize] {
            continue;
        }
        ctx.mesh.vertex_neighbours(a, &mut nb);
        // Each edge once: from its smaller end, or from its only changed end.
        for &b in nb.iter().filter(|&&b| b > a || !changed[b as usize]) {
            let (a, b) = (a.min(b), a.max(b));
            let l = ctx.length(a, b);
            if l < ctx.l_min {
                out.push((l.to_bits(), a, b));
            }
        }
    }
}

/// Whether the ball of `v` is unchanged since pass `since`.
fn unchanged(ctx: &Ctx<'_>, v: u32, since: u32) -> bool {
    ctx.stamp.get(v as usize).is_some_and(|&s| s < since)
}

/// The short edges of one kind of conformity pass, shortest first (ties by end points): every
/// edge shorter than `l_min`, found around the vertices changed since pass `since` (`rings`:
/// and their neighbours) plus those of `refused` (the edges the same pass refused in the
/// previous round) whose surroundings are unchanged. A refused edge whose surroundings are
/// still unchanged when its turn comes is refused again without a look: a collapse depends
/// only on the balls of the edge's ends, a removal only on the balls of its shell's vertices.
fn candidates(
    ctx: &Ctx<'_>,
    since: u32,
    rings: bool,
    refused: &[(u64, u32, u32)],
) -> Vec<(u64, u32, u32)> {
    let changed = changed_since(ctx, since, rings);
    let mut list = Vec::new();
    short_edges(ctx, &changed, &mut list);
    list.extend(refused.iter().filter(|&&(_, a, b)| {
        ctx.mesh.alive(a) && ctx.mesh.alive(b) && !changed[a as usize] && !changed[b as usize]
    }));
    list.sort_unstable();
    list
}

/// What became of one short edge in a pass of [`over_short_edges`].
enum Outcome {
    /// Nothing to do any more (gone, or no longer short).
    Gone,
    /// Refused: tried again in the next round only if something near it changes.
    Refused,
    /// Applied.
    Applied,
}

/// One pass over the short edges of [`candidates`] (changed since pass `since`, or refused in
/// the previous round), shortest first, each given to `attempt`; `refused` receives the edges
/// refused now. Returns the number applied.
fn over_short_edges(
    ctx: &mut Ctx<'_>,
    since: u32,
    rings: bool,
    refused: &mut Vec<(u64, u32, u32)>,
    mut attempt: impl FnMut(&mut Ctx<'_>, u32, u32) -> Outcome,
) -> usize {
    ctx.next_pass();
    let short = candidates(ctx, since, rings, refused);
    refused.clear();
    let mut count = 0;
    for e @ (_, a, b) in short {
        match attempt(ctx, a, b) {
            Outcome::Gone => {}
            Outcome::Refused => refused.push(e),
            Outcome::Applied => count += 1,
        }
    }
    count
}

/// One pass of conformity collapses (see the module docs) over the short edges; `refused`
/// holds the edges the pass refused in the previous round (started at pass `since`) and
/// receives those it refuses now. Returns the number applied.
pub(crate) fn collapse_pass(
    ctx: &mut Ctx<'_>,
    since: u32,
    refused: &mut Vec<(u64, u32, u32)>,
) -> usize {
    over_short_edges(ctx, since, false, refused, |ctx, a, b| {
        if !ctx.mesh.alive(a) || !ctx.mesh.alive(b) || ctx.length(a, b) >= ctx.l_min {
            return Outcome::Gone;
        }
        if unchanged(ctx, a, since) && unchanged(ctx, b, since) {
            return Outcome::Refused;
        }
        let Some(mg) = super::merge::best_merge(ctx, a, b) else {
            return Outcome::Refused;
        };
        let floor = ctx.ball_quality(a).min(ctx.ball_quality(b)).min(Q_KEEP);
        if mg.q >= floor {
            super::merge::apply(ctx, mg);
            Outcome::Applied
        } else {
            Outcome::Refused
        }
    })
}

/// One pass of *short-edge removals*: every interior edge still shorter than `l_min` after
/// the conformity collapses, shortest first, is removed by the best retriangulation of its
/// shell without it (n → 2n − 4, [`crate::mesh3::EditMesh3::best_edge_removal`]) whose new
/// edges are all in `[l_min, l_max]` and whose worst quality is at least the old shell's worst
/// or [`Q_KEEP`]. Each removal takes one short edge away and adds none, and no vertex goes:
/// the counterpart of a collapse where the collapse would make a long edge or a poor
/// tetrahedron. `since` and `refused` as for [`collapse_pass`]. Returns the number of removals.
pub(crate) fn short_edge_removal_pass(
    ctx: &mut Ctx<'_>,
    since: u32,
    refused: &mut Vec<(u64, u32, u32)>,
) -> usize {
    let mut shell = Vec::new();
    over_short_edges(ctx, since, true, refused, |ctx, a, b| {
        if !ctx.mesh.alive(a) || !ctx.mesh.alive(b) || !ctx.mesh.is_edge(a, b) {
            return Outcome::Gone;
        }
        ctx.mesh.shell(a, b, &mut shell);
        let same = shell.iter().all(|&t| {
            let tet = ctx.mesh.tets[t as usize];
            tet.iter().all(|&v| unchanged(ctx, v, since))
        });
        if same {
            return Outcome::Refused;
        }
        let q0 = shell
            .iter()
            .map(|&t| ctx.tet_quality(t))
            .fold(f64::INFINITY, f64::min);
        let floor = q0.min(Q_KEEP);
        let c = &*ctx;
        let Some((q, tets)) = c.mesh.best_edge_removal(
            a,
            b,
            floor,
            |t| c.quality_of(t, None),
            |x, y| (c.l_min..=c.l_max).contains(&c.length(x, y)),
        ) else {
            return Outcome::Refused;
        };
        if q >= floor {
            ctx.touch_ball(a);
            ctx.touch_ball(b);
            ctx.mesh.replace_shell(a, b, &tets);
            Outcome::Applied
        } else {
            Outcome::Refused
        }
    })
}

/// `Σ ln² l` over the edges from a vertex at `p` with metric `m` to its neighbours `nb`, and
/// how many of them are outside `[l_min, l_max]`.
fn length_energy(ctx: &Ctx<'_>, p: DVec3, m: &Sym3, nb: &[u32]) -> (f64, usize) {
    let (mut e, mut out) = (0.0, 0);
    for &w in nb {
        let l = Ctx::length_at(p, ctx.mesh.points[w as usize], m, &ctx.metric[w as usize]);
        let ll = l.max(1e-300).ln();
        e += ll * ll;
        if !(ctx.l_min..=ctx.l_max).contains(&l) {
            out += 1;
        }
    }
    (e, out)
}

/// One pass of length smoothing over the live vertices whose ball changed at or after pass
/// `since` (see the module docs); returns the number of moves.
pub(crate) fn length_smooth_pass(ctx: &mut Ctx<'_>, since: u32) -> usize {
    ctx.next_pass();
    let Some(f) = ctx.source else {
        return 0;
    };
    let mut nb = Vec::new();
    let mut count = 0;
    for v in 0..ctx.mesh.points.len() as u32 {
        // A vertex whose ball is unchanged since the previous round was not moved then and
        // would not be now.
        if !ctx.mesh.alive(v) || unchanged(ctx, v, since) {
            continue;
        }
        let normal = match ctx.mesh.vertex_kind(v) {
            VertexKind::Interior => None,
            VertexKind::Face(n) => Some(n),
            VertexKind::Feature => continue,
        };
        ctx.mesh.vertex_neighbours(v, &mut nb);
        let p = ctx.mesh.points[v as usize];
        let m0 = ctx.metric[v as usize];
        let (e0, out0) = length_energy(ctx, p, &m0, &nb);
        if out0 == 0 && e0 < 0.05 * nb.len() as f64 {
            continue;
        }
        let mut target = DVec3::ZERO;
        for &w in &nb {
            let pw = ctx.mesh.points[w as usize];
            let l = ctx.length(v, w).max(1e-12);
            target += pw + (p - pw) / l;
        }
        let mut d = target / nb.len() as f64 - p;
        if let Some(n) = normal {
            d -= n * d.dot(n);
        }
        let q0 = ctx.ball_quality(v);
        let floor = q0.min(Q_KEEP);
        for step in [1.0, 0.5, 0.25] {
            let np = match normal {
                Some(n) => onto_plane(p, n, p + step * d),
                None => p + step * d,
            };
            let m = f(np);
            let (e1, out1) = length_energy(ctx, np, &m, &nb);
            if e1 >= e0 || out1 > out0 {
                continue;
            }
            let q = ctx.mesh.ball[v as usize]
                .iter()
                .map(|&t| ctx.quality_of(ctx.mesh.tets[t as usize], Some((v, np, &m))))
                .fold(f64::INFINITY, f64::min);
            if q >= floor && ctx.mesh.move_valid(v, np) {
                ctx.mesh.set_point(v, np);
                ctx.metric[v as usize] = m;
                ctx.touch_ball(v);
                count += 1;
                break;
            }
        }
    }
    count
}

/// Records one pass in `rep` and checks the mesh when asked.
fn record(
    ctx: &mut Ctx<'_>,
    kind: PassKind,
    opts: &AdaptOptions,
    rep: &mut AdaptReport,
    pass: impl FnOnce(&mut Ctx<'_>) -> usize,
) -> Result<usize> {
    let t = Instant::now();
    let n = pass(ctx);
    rep.record_pass(kind, n, t.elapsed().as_secs_f64());
    if opts.check_each_pass {
        ctx.check()?;
    }
    Ok(n)
}

/// The conformity loop (see the module docs), recorded in `rep`.
pub(crate) fn polish(ctx: &mut Ctx<'_>, opts: &AdaptOptions, rep: &mut AdaptReport) -> Result<()> {
    // The end game splits every long edge it finds: no insertion filter.
    ctx.split_filter = 0.0;
    let mut share = in_range_share(ctx);
    // Each round examines what changed since the previous one began (everything at first).
    let mut since = 0;
    let (mut refused_collapses, mut refused_removals) = (Vec::new(), Vec::new());
    for _ in 0..ROUNDS {
        let round = ctx.pass + 1;
        let nc = record(ctx, PassKind::Collapse, opts, rep, |c| {
            collapse_pass(c, since, &mut refused_collapses)
        })? + record(ctx, PassKind::Flip, opts, rep, |c| {
            short_edge_removal_pass(c, since, &mut refused_removals)
        })?;
        let ns = record(ctx, PassKind::Split, opts, rep, super::split::pass)?;
        record(ctx, PassKind::Flip, opts, rep, super::swap::pass)?;
        let nm = record(ctx, PassKind::Smooth, opts, rep, |c| {
            length_smooth_pass(c, since)
        })?;
        since = round;
        let s = in_range_share(ctx);
        if nc + ns + nm == 0 || s <= share + 1e-4 {
            break;
        }
        share = s;
    }
    let mut repair = super::improve::Repair::default();
    for _ in 0..3 {
        let n = record(ctx, PassKind::Smooth, opts, rep, |c| {
            repair.pass(c, Q_REPAIR)
        })?;
        record(ctx, PassKind::Flip, opts, rep, super::swap::pass)?;
        if n == 0 {
            break;
        }
    }
    Ok(())
}
