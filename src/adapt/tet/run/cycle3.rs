//! The split / collapse / swap / smoothing cycle of [`super::run3`] on tetrahedra (004 §3.5, the
//! cycle of [`crate::adapt::cycle::run_cycles`] with two changes measured on the 004 star):
//!
//! - within the refinement passes of a cycle, a swap pass follows a refinement pass only while
//!   that pass split at least 1 % of the vertices (and after the first two). On tetrahedra a
//!   swap pass creates new edges, some of them long in the metric, so refinement and swap
//!   passes alternating to the end fed each other: at ε = 2·10⁻² the cycle ran 64 refinement
//!   passes of about 280 splits, each followed by a swap pass of about 1,200 swaps, and the swap
//!   passes took 80 % of the run;
//! - a cycle converges when it splits and collapses at most `churn` of the vertices (1/200 for
//!   the target metric, 1/50 for a continuation stage, whose mesh only has to be close to the
//!   next stage's), instead of 1/2,000: the remaining changes are left to the final quality
//!   sweep and the length polish, which follow.
//!
//! The mesh is renumbered along a Hilbert curve ([`Remesher::renumber`]) whenever it has grown
//! by 30 % (10 % once a cycle stops splitting), and at the start of a cycle once the changes
//! since the last renumbering reach a quarter of the vertex count: swaps and collapses put new
//! tetrahedra in freed slots anywhere in the arrays, and the passes are bound by the memory
//! latency of walking balls whose tetrahedra lie far apart (UGAWG cube-linear scaled to 10⁶
//! vertices: 447 → 392 processor seconds, at 10⁵ 3–7 % less, the same conformity and
//! quality).

use std::time::Instant;

use crate::adapt::cycle::Remesher;
use crate::adapt::options::{AdaptOptions, AdaptReport, PassKind};
use crate::error::{Error, Result};

use super::super::Ctx;

/// Runs one pass of `kind`, records it in `rep` and, with `opts.check_each_pass`, verifies the
/// mesh.
fn record(
    ctx: &mut Ctx<'_>,
    kind: PassKind,
    opts: &AdaptOptions,
    rep: &mut AdaptReport,
) -> Result<usize> {
    let t = Instant::now();
    let n = ctx.run_pass(kind);
    rep.record_pass(kind, n, t.elapsed().as_secs_f64());
    if opts.check_each_pass {
        ctx.check()?;
    }
    Ok(n)
}

/// Refinement passes whose split count is below `1 / SWAP_AFTER` of the vertices are not
/// followed by a swap pass (module documentation).
const SWAP_AFTER: usize = 100;

/// At most this many refinement passes per cycle.
const MAX_SPLIT_PASSES: usize = 32;

/// The cycles (module documentation): at most `max_cycles` and `opts.max_cycles`, until a cycle changes at most
/// `nv / churn` vertices; then up to `opts.final_sweeps` swap and smoothing passes. Errors:
/// more vertices than `opts.max_vertices` after a refinement pass, a defect found by the
/// per-pass check.
pub(super) fn cycles(
    ctx: &mut Ctx<'_>,
    opts: &AdaptOptions,
    churn: usize,
    max_cycles: usize,
    rep: &mut AdaptReport,
) -> Result<()> {
    let mut renumbered_at = 0;
    let changes = |rep: &AdaptReport| rep.splits + rep.collapses + rep.flips + rep.moves;
    let mut changes_at = changes(rep);
    for _ in 0..max_cycles.min(opts.max_cycles) {
        rep.cycles += 1;
        let mut ns = 0;
        for pass in 0..MAX_SPLIT_PASSES {
            let nv = ctx.n_vertices();
            if 10 * nv >= 13 * renumbered_at.max(1)
                || (ns == 0 && 10 * nv >= 11 * renumbered_at)
                || (pass == 0 && 4 * (changes(rep) - changes_at) >= nv)
            {
                ctx.renumber();
                renumbered_at = ctx.n_vertices();
                changes_at = changes(rep);
            }
            let n = record(ctx, PassKind::Split, opts, rep)?;
            ns += n;
            if let Some(limit) = opts.max_vertices.filter(|&l| ctx.n_vertices() > l) {
                return Err(Error::TooLarge(format!(
                    "the adaptation grew past {limit} vertices ({} after a refinement pass)",
                    ctx.n_vertices()
                )));
            }
            if n == 0 {
                break;
            }
            if pass < 2 || n * SWAP_AFTER >= nv {
                record(ctx, PassKind::Flip, opts, rep)?;
            }
        }
        let nc = record(ctx, PassKind::Collapse, opts, rep)?;
        record(ctx, PassKind::Flip, opts, rep)?;
        record(ctx, PassKind::Smooth, opts, rep)?;
        if (ns + nc) * churn.max(1) <= ctx.n_vertices() {
            rep.converged = true;
            break;
        }
    }
    for _ in 0..opts.final_sweeps {
        let nf = record(ctx, PassKind::Flip, opts, rep)?;
        let nm = record(ctx, PassKind::Smooth, opts, rep)?;
        if nf + nm == 0 {
            break;
        }
    }
    Ok(())
}
