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

/// The share of edges with metric length in `[l_min, l_max]` (lengths as the loop sees them,
/// [`loop_length`]).
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

/// Lengths from the end metrics ([`Ctx::length`]) within this factor of `l_min` or `l_max`
/// are integrated along the edge ([`loop_length`]).
const NEAR: f64 = 1.25;

/// Gauss panels (two points each) of the integrated length.
const PANELS: usize = 4;

/// The metric length of the edge `(a, b)` as the loop judges it. The length from the end
/// metrics (the geometric interpolation of the length density, [`Ctx::length`]) is not the
/// length in the field: where the size varies linearly along the edge the true length is
/// the smaller `la lb ln(la/lb) / (la − lb)` (004 §3.3; [`crate::metric::length::linear_size_length`]),
/// and across a kink of the size it is larger. So near the ends of `[l_min, l_max]` (within
/// [`NEAR`]) the length is integrated in the source field, `∫_0^1 sqrt(eᵀ M(a + t e) e) dt`
/// by [`PANELS`] panels of 2-point Gauss quadrature, as the UGAWG statistics integrate it
/// ([`crate::metric::conformity_analytic`]); elsewhere, and without a source, the end-metric
/// length is used. On UGAWG cube-linear 81 of the 986 edges the statistics measure shorter than
/// `1/√2` had an end-metric length in range.
pub(crate) fn loop_length(ctx: &Ctx<'_>, a: u32, b: u32) -> f64 {
    let l = ctx.length(a, b);
    let near = (ctx.l_min / NEAR..ctx.l_min * NEAR).contains(&l)
        || (ctx.l_max / NEAR..ctx.l_max * NEAR).contains(&l);
    let Some(f) = ctx.source.filter(|_| near) else {
        return l;
    };
    let (pa, pb) = (ctx.mesh.points[a as usize], ctx.mesh.points[b as usize]);
    let e = pb - pa;
    let h = 1.0 / PANELS as f64;
    let g = 0.5 * h / 3f64.sqrt();
    let mut s = 0.0;
    for k in 0..PANELS {
        let c = (k as f64 + 0.5) * h;
        s += f(pa + e * (c - g)).quad(e).sqrt() + f(pa + e * (c + g)).quad(e).sqrt();
    }
    0.5 * h * s
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
            f(a, b, loop_length(ctx, a, b));
        }
    }
}

/// The edges shorter than `l_min`, shortest first (ties by end points).
fn short_edges(ctx: &Ctx<'_>) -> Vec<(u64, u32, u32)> {
    let mut short = Vec::new();
    for_each_edge_length(ctx, |a, b, l| {
        if l < ctx.l_min {
            short.push((l.to_bits(), a, b));
        }
    });
    short.sort_unstable();
    short
}

/// One pass of conformity collapses (see the module docs); returns the number applied.
pub(crate) fn collapse_pass(ctx: &mut Ctx<'_>) -> usize {
    ctx.next_pass();
    let short = short_edges(ctx);
    let mut count = 0;
    for (_, a, b) in short {
        if !ctx.mesh.alive(a) || !ctx.mesh.alive(b) || loop_length(ctx, a, b) >= ctx.l_min {
            continue;
        }
        let Some(mg) = super::merge::best_merge(ctx, a, b) else {
            continue;
        };
        let floor = ctx.ball_quality(a).min(ctx.ball_quality(b)).min(Q_KEEP);
        if mg.q >= floor {
            super::merge::apply(ctx, mg);
            count += 1;
        }
    }
    count
}

/// One pass of *short-edge removals*: every interior edge still shorter than `l_min` after
/// the conformity collapses, shortest first, is removed by the best retriangulation of its
/// shell without it (n → 2n − 4, [`crate::mesh3::EditMesh3::best_edge_removal`]) whose new
/// edges are all in `[l_min, l_max]` and whose worst quality is at least the old shell's worst
/// or [`Q_KEEP`]. Each removal takes one short edge away and adds none, and no vertex goes:
/// the counterpart of a collapse where the collapse would make a long edge or a poor
/// tetrahedron. Returns the number of removals.
pub(crate) fn short_edge_removal_pass(ctx: &mut Ctx<'_>) -> usize {
    ctx.next_pass();
    let short = short_edges(ctx);
    let mut count = 0;
    let mut shell = Vec::new();
    for (_, a, b) in short {
        if !ctx.mesh.alive(a) || !ctx.mesh.alive(b) || !ctx.mesh.is_edge(a, b) {
            continue;
        }
        ctx.mesh.shell(a, b, &mut shell);
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
            continue;
        };
        if q >= floor {
            ctx.touch_ball(a);
            ctx.touch_ball(b);
            ctx.mesh.replace_shell(a, b, &tets);
            count += 1;
        }
    }
    count
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

/// One pass of length smoothing over every live vertex (see the module docs); returns the
/// number of moves.
pub(crate) fn length_smooth_pass(ctx: &mut Ctx<'_>) -> usize {
    ctx.next_pass();
    let Some(f) = ctx.source else {
        return 0;
    };
    let mut nb = Vec::new();
    let mut count = 0;
    for v in 0..ctx.mesh.points.len() as u32 {
        if !ctx.mesh.alive(v) {
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
    for _ in 0..ROUNDS {
        let nc = record(ctx, PassKind::Collapse, opts, rep, collapse_pass)?
            + record(ctx, PassKind::Flip, opts, rep, short_edge_removal_pass)?;
        let ns = record(ctx, PassKind::Split, opts, rep, super::split::pass)?;
        record(ctx, PassKind::Flip, opts, rep, super::swap::pass)?;
        let nm = record(ctx, PassKind::Smooth, opts, rep, length_smooth_pass)?;
        let s = in_range_share(ctx);
        if nc + ns + nm == 0 || s <= share + 1e-4 {
            break;
        }
        share = s;
    }
    for _ in 0..3 {
        let n = record(ctx, PassKind::Smooth, opts, rep, |c| {
            super::improve::pass(c, Q_REPAIR)
        })?;
        record(ctx, PassKind::Flip, opts, rep, super::swap::pass)?;
        if n == 0 {
            break;
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mesh3::{EditMesh3, Mesh3};
    use crate::metric::length::linear_size_length;

    /// The size `0.02 + z` across, 1 along x and y.
    fn layer(p: DVec3) -> Sym3 {
        let h = 0.02 + p.z;
        Sym3::new(1.0, 0.0, 0.0, 1.0, 0.0, 1.0 / (h * h))
    }

    /// Near `l_min` the loop measures an edge in the field: along an edge of linearly varying
    /// size the exact length `∫ dz / h` is reproduced to 5e-5, where the end-metric length is
    /// off by more than 3 %; far from `[l_min, l_max]`'s ends the end-metric length is kept.
    #[test]
    fn near_the_bounds_lengths_are_integrated_in_the_field() {
        // ln((0.02 + L) / 0.02) = 0.75: an edge along z just above l_min.
        let lz = 0.02 * (0.75f64.exp() - 1.0);
        let mesh = Mesh3::kuhn_box(DVec3::ZERO, DVec3::new(3.0, 3.0, lz), [1; 3]).unwrap();
        let edit = EditMesh3::from_mesh(&mesh).unwrap();
        let metric: Vec<Sym3> = edit.points.iter().map(|&p| layer(p)).collect();
        let f: &(dyn Fn(DVec3) -> Sym3 + Sync) = &layer;
        let ctx = Ctx::new(edit, metric, Some(f));
        let at = |p: DVec3| {
            ctx.mesh
                .points
                .iter()
                .position(|&q| (q - p).length() < 1e-12)
                .unwrap() as u32
        };
        let (a, b) = (at(DVec3::ZERO), at(DVec3::new(0.0, 0.0, lz)));
        assert!(ctx.mesh.is_edge(a, b));
        let exact = linear_size_length(lz / 0.02, lz / (0.02 + lz));
        assert!((exact - 0.75).abs() < 1e-12);
        let (ends, field) = (ctx.length(a, b), loop_length(&ctx, a, b));
        assert!((field - exact).abs() < 5e-5 * exact, "{field} vs {exact}");
        assert!(ends > 1.03 * exact, "{ends} vs {exact}");
        // An edge of length 3 along x: far from both ends of the range.
        let c = at(DVec3::new(3.0, 0.0, 0.0));
        assert!(ctx.mesh.is_edge(a, c));
        assert_eq!(loop_length(&ctx, a, c), ctx.length(a, c));
    }
}
