//! The adaptation cycle (004 §3.5, with the explicit stopping rule of MMG's `mmg2d1.c`), written
//! against [`Remesher`] so that the operators of any dimension run the same cycle: refinement
//! passes (each followed by a flip pass) until none splits, a collapse pass, a flip pass, a
//! smoothing pass, the convergence test; then a few final flip and smoothing sweeps. Spatial
//! renumbering and metric gradation are interleaved as the mesh grows.

use super::options::{AdaptOptions, AdaptReport, CycleSmoothing, PassKind};
use crate::error::{Error, Result};
use std::time::Instant;

/// A mesh with its metric, fields and operators, as the cycle drives it: one pass of each kind,
/// the housekeeping between passes, and the invariant check. The triangle context
/// (`tri::Ctx`) implements it with its refinement, collapse, flip and smoothing operators, each
/// run by [`super::pass::run_pass`]; a tetrahedral context implements it the same way with its
/// own operators (face and edge swaps in the place of flips).
pub(crate) trait Remesher {
    /// The number of vertex slots (live and removed vertices until the next compaction).
    fn n_vertices(&self) -> usize;
    /// Runs one pass of `kind` and returns the number of changes (new vertices, collapses,
    /// flips or moves).
    fn run_pass(&mut self, kind: PassKind) -> usize;
    /// Renumbers the mesh along a space-filling curve (dropping removed entries) and carries
    /// the metric, fields and pass workspace along.
    fn renumber(&mut self);
    /// Grades the vertex metric over the current mesh with growth factor `beta`
    /// ([`crate::metric::gradate`]) and marks the elements around changed vertices as
    /// modified, so that the passes examine them again.
    fn grade(&mut self, beta: f64) -> Result<()>;
    /// Makes the next smoothing pass examine only the vertices whose ball changes after this
    /// call.
    fn smoothing_settled(&mut self);
    /// Verifies every mesh invariant.
    fn check(&self) -> Result<()>;
}

/// Runs one pass of `kind`, records it in `rep` and, with `opts.check_each_pass`, verifies the
/// mesh. Returns the pass's count.
fn record<R: Remesher>(
    r: &mut R,
    kind: PassKind,
    opts: &AdaptOptions,
    rep: &mut AdaptReport,
) -> Result<usize> {
    let t = Instant::now();
    let n = r.run_pass(kind);
    rep.record_pass(kind, n, t.elapsed().as_secs_f64());
    if opts.check_each_pass {
        r.check()?;
    }
    Ok(n)
}

/// The split/collapse cycles and the final sweeps of [`super::adapt`] (see the module docs),
/// adding every pass to `rep` and setting `rep.converged` by the stopping rule of
/// [`AdaptReport`]. Fails with [`Error::TooLarge`] when a refinement pass leaves more vertices
/// than `opts.max_vertices` (the mesh is then valid but not compacted), or with the defect when
/// `opts.check_each_pass` finds one.
pub(crate) fn run_cycles<R: Remesher>(
    r: &mut R,
    opts: &AdaptOptions,
    rep: &mut AdaptReport,
) -> Result<()> {
    // Spatial renumbering keeps fan walks cache-friendly as the mesh grows: whenever splits
    // have grown the vertex count by 30% since the last one, and at the start of a cycle when
    // they have added 10%. (On the eps 1e-5 speed case, growth steps of 50% instead of 30%
    // made the adaptation about 10% slower; 20% gained nothing more.)
    let mut renumbered_at = 0;
    let mut last_ops = None;
    let mut graded_at: Option<usize> = None;
    for _cycle in 0..opts.max_cycles {
        rep.cycles += 1;
        // Grade when the mesh has grown by 10% since the last grading: a new vertex gets a
        // metric interpolated from already graded neighbours, so later cycles rarely change
        // a metric, and a grading costs as much as a cycle.
        if let Some(beta) = opts.gradation {
            let n = r.n_vertices();
            if graded_at.map_or(true, |g| 10 * n >= 11 * g) {
                let t = Instant::now();
                r.grade(beta)?;
                rep.gradation_seconds += t.elapsed().as_secs_f64();
                graded_at = Some(n);
            }
        }
        let mut ns = 0;
        for _ in 0..64 {
            let n = r.n_vertices();
            if 10 * n >= 13 * renumbered_at.max(1) || (ns == 0 && 10 * n >= 11 * renumbered_at) {
                r.renumber();
                renumbered_at = r.n_vertices();
            }
            let n = record(r, PassKind::Split, opts, rep)?;
            ns += n;
            if let Some(limit) = opts.max_vertices.filter(|&l| r.n_vertices() > l) {
                return Err(Error::TooLarge(format!(
                    "the adaptation grew past {limit} vertices ({} after a refinement pass)",
                    r.n_vertices()
                )));
            }
            if n == 0 {
                break;
            }
            record(r, PassKind::Flip, opts, rep)?;
        }
        let nc = record(r, PassKind::Collapse, opts, rep)?;
        record(r, PassKind::Flip, opts, rep)?;
        record(r, PassKind::Smooth, opts, rep)?;
        if opts.cycle_smoothing == CycleSmoothing::Touched {
            r.smoothing_settled();
        }
        // Converged: the cycle changed (almost) nothing — at most 1 in 2,000 vertices — or
        // it made as many splits as collapses, at most 8 of each, and the same numbers as the
        // previous cycle: a split/collapse limit cycle (seen next to a labelled kink edge
        // between required vertices) that more cycles would only repeat.
        let nv = r.n_vertices();
        let repeated = last_ops == Some((ns, nc)) && ns == nc && ns + nc <= 16;
        if ns + nc <= nv / 2000 || repeated {
            rep.converged = true;
            break;
        }
        last_ops = Some((ns, nc));
    }
    for _ in 0..opts.final_sweeps {
        let nf = record(r, PassKind::Flip, opts, rep)?;
        let nm = record(r, PassKind::Smooth, opts, rep)?;
        if nf + nm == 0 {
            break;
        }
    }
    Ok(())
}
