//! The refinement operator (004 §3.5): edges longer than `l_max` in the metric get a new vertex
//! at their metric midpoint, by a plain edge split (`split.rs`) or by the anisotropic Delaunay
//! insertion kernel (`insert.rs`), which both plan from the same [`split::SplitPlan`].

use super::insert::{self, InsertPlan};
use super::split::{self, SplitPlan};
use super::topo::Ctx;
use crate::adapt::pass::{run_pass, Operator};
use crate::mesh::{next, prev, NONE};

/// Sort key of a split candidate: longest first by classes of a quarter octave (edges of
/// length 1.41 to 2^24), then by triangle index — which keeps the new vertices (appended in this
/// order) close in memory to their neighbours — then local edge.
#[inline]
fn split_key(l: f64, t: u32, i: usize) -> u64 {
    let class = (96.0 - (4.0 * l.log2()).floor()).clamp(0.0, 255.0) as u64;
    (class << 40) | (u64::from(t) << 2) | i as u64
}

/// The triangle and local edge of a split key.
#[inline]
fn key_edge(key: u64) -> (u32, usize) {
    ((key >> 2) as u32, (key & 3) as usize)
}

/// A new vertex on a long edge: a plain split or a Delaunay insertion.
pub(crate) enum RefinePlan {
    /// Split the edge ([`split::apply`]).
    Split(SplitPlan),
    /// Insert by the Delaunay kernel ([`insert::apply`]).
    Insert(InsertPlan),
}

/// The refinement operator: sites are the triangles modified since the last refinement pass,
/// candidates their edges longer than `l_max` (measured on the state at the start of the pass),
/// longest first, at most one new vertex per triangle per pass (an independent set). Each edge
/// that passes the split check ([`split::check`]) gets its new vertex by the Delaunay insertion
/// kernel ([`insert`]) when `params.insertion` is set and the insertion is valid (unlabelled
/// interior edges), else by a plain split ([`split::apply`]).
pub(crate) struct Refine;

impl Operator<Ctx<'_>> for Refine {
    type Site = u32;
    type Key = u64;
    type Frozen = ();
    type Plan = RefinePlan;
    const SORTED: bool = true;

    fn sites(&mut self, ctx: &mut Ctx) -> Vec<u32> {
        ctx.new_pass();
        let from = ctx.split_pos;
        ctx.split_pos = ctx.log.len();
        ctx.logged_since(from)
    }

    /// An edge shared by two listed triangles is measured once, from the one of lower index,
    /// and gets a key for each side (the check is not symmetric in the last bits of the new
    /// point, and the visit tries the second side when the first fails). The keys are unique,
    /// so their order does not depend on how they were collected.
    fn survey(&self, c: &Ctx, t: u32, _evaluate: bool, out: &mut Vec<(u64, Option<()>)>) {
        let (gen, l_max) = (c.gen, c.params.l_max);
        let tri = c.mesh.tris[t as usize];
        for i in 0..3 {
            let nb = c.mesh.neighbours[t as usize][i];
            let nb_listed = nb != NONE && c.tseen[nb as usize] == gen;
            if nb_listed && nb < t {
                continue;
            }
            if let Some(l) = c.len_if_above(tri[next(i)], tri[prev(i)], l_max) {
                out.push((split_key(l, t, i), None));
                if nb_listed {
                    if let Some(j) = c.mesh.mirror_edge(t as usize, nb as usize) {
                        out.push((split_key(l, nb, j), None));
                    }
                }
            }
        }
    }

    /// Neither triangle of the edge has changed in this pass.
    fn admissible(&self, ctx: &Ctx, key: u64) -> bool {
        let (t, i) = key_edge(key);
        if ctx.tstamp[t as usize] == ctx.gen {
            return false;
        }
        let nb = ctx.mesh.neighbours[t as usize][i];
        nb == NONE || ctx.tstamp[nb as usize] != ctx.gen
    }

    fn check(&mut self, ctx: &mut Ctx, key: u64, _frozen: Option<()>) -> Option<RefinePlan> {
        let (t, i) = key_edge(key);
        let plan = split::check(ctx, t, i)?;
        if ctx.params.insertion {
            if let Some(ins) = insert::check(ctx, &plan) {
                return Some(RefinePlan::Insert(ins));
            }
        }
        Some(RefinePlan::Split(plan))
    }

    fn apply(&mut self, ctx: &mut Ctx, plan: RefinePlan) {
        match plan {
            RefinePlan::Split(p) => {
                split::apply(ctx, &p);
            }
            RefinePlan::Insert(p) => {
                insert::apply(ctx, &p);
            }
        }
    }
}

/// One refinement pass ([`Refine`]); returns the number of new vertices.
pub fn pass(ctx: &mut Ctx) -> usize {
    run_pass(&mut Refine, ctx)
}
