//! The pass skeleton every adaptation operator shares, in the phases of Omega_h's refinement
//! (candidates, predicted change, filter, independent set, topology change):
//!
//! 1. **sites**: the operator starts its pass and lists where to look (the elements changed
//!    since its previous pass, or every vertex);
//! 2. **survey**: each site yields its candidates, evaluated on the state at the start of the
//!    pass, in parallel over the sites when that is worth it ([`parallel_worth`]); a candidate
//!    may carry the verdict of its check on that frozen state;
//! 3. **order**: the candidates are sorted by key (or kept in site order);
//! 4. **visit**, sequentially in that order: a candidate no longer admissible (an element
//!    already changed in this pass, a vertex removed) is skipped, which makes the applied
//!    changes an independent set where the operator asks for one; a frozen verdict is used only
//!    while its surroundings are unchanged, else the check is evaluated on the current state;
//!    an accepted plan is applied at once; the pass returns the number applied.
//!
//! Because a frozen verdict is used only where the sequential check would see the same state,
//! the result does not depend on the number of threads. The skeleton knows nothing of the
//! dimension: an operator on triangles or on tetrahedra implements [`Operator`] for its context.

use rayon::prelude::*;

/// Whether a pass over `n` sites should evaluate its survey in parallel: with more than one
/// rayon thread and enough work. The passes use the frozen verdicts only where the sequential
/// check would see the same state, so the outcome does not depend on this choice.
#[inline]
pub(crate) fn parallel_worth(n: usize) -> bool {
    n >= 4096 && rayon::current_num_threads() > 1
}

/// One adaptation operator as seen by [`run_pass`]: where it looks, what it checks, how it
/// applies a change. `C` is the operator context (mesh, metric, fields and the pass
/// workspace).
pub(crate) trait Operator<C> {
    /// Where the pass looks: an element or a vertex index.
    type Site: Copy + Send + Sync;
    /// One candidate change, identified so that the visit order is the order of the keys
    /// (when [`Operator::SORTED`]); keys of one pass are unique.
    type Key: Copy + Ord + Send;
    /// The verdict of the check on the state at the start of the pass.
    type Frozen: Send;
    /// A checked change, ready to apply.
    type Plan;
    /// Whether the candidates are visited in key order (else in the order the survey gives).
    const SORTED: bool;

    /// Starts the pass (stamps, logs) and lists its sites.
    fn sites(&mut self, ctx: &mut C) -> Vec<Self::Site>;

    /// Appends the candidates of `site` to `out`, evaluated on the state at the start of the
    /// pass (no change to the context). With `evaluate`, also their frozen verdicts where the
    /// operator has them; without it, every verdict is `None`.
    fn survey(
        &self,
        ctx: &C,
        site: Self::Site,
        evaluate: bool,
        out: &mut Vec<(Self::Key, Option<Self::Frozen>)>,
    );

    /// Whether `key` is still to be visited now: not excluded by changes already applied in
    /// this pass.
    fn admissible(&self, ctx: &C, key: Self::Key) -> bool;

    /// Whether the surroundings of `key` are unchanged since the start of the pass, so that its
    /// frozen verdict still holds (by default never: for operators without frozen verdicts).
    fn unchanged(&self, _ctx: &C, _key: Self::Key) -> bool {
        false
    }

    /// The plan for `key` on the current state; `frozen` is the verdict of the survey when it
    /// still holds.
    fn check(
        &mut self,
        ctx: &mut C,
        key: Self::Key,
        frozen: Option<Self::Frozen>,
    ) -> Option<Self::Plan>;

    /// Applies a plan that [`Operator::check`] has just returned.
    fn apply(&mut self, ctx: &mut C, plan: Self::Plan);
}

/// Runs one pass of `op` (sites, survey, order, visit; see the module docs) and returns the
/// number of changes applied.
pub(crate) fn run_pass<C, O>(op: &mut O, ctx: &mut C) -> usize
where
    C: Sync,
    O: Operator<C> + Sync,
{
    let sites = op.sites(ctx);
    let mut cand: Vec<(O::Key, Option<O::Frozen>)> = Vec::new();
    if parallel_worth(sites.len()) {
        let (c, o): (&C, &O) = (ctx, op);
        // `fold` keeps the sites of each chunk in order, and collecting keeps the chunks in
        // order: the candidates come out in site order, as in the sequential survey.
        cand.par_extend(
            sites
                .par_iter()
                .fold(Vec::new, |mut v, &s| {
                    o.survey(c, s, true, &mut v);
                    v
                })
                .flat_map_iter(|v| v),
        );
        if O::SORTED {
            cand.par_sort_unstable_by_key(|x| x.0);
        }
    } else {
        for &s in &sites {
            op.survey(ctx, s, false, &mut cand);
        }
        if O::SORTED {
            cand.sort_unstable_by_key(|x| x.0);
        }
    }
    let mut count = 0;
    for (key, frozen) in cand {
        if !op.admissible(ctx, key) {
            continue;
        }
        let frozen = frozen.filter(|_| op.unchanged(ctx, key));
        if let Some(plan) = op.check(ctx, key, frozen) {
            op.apply(ctx, plan);
            count += 1;
        }
    }
    count
}
