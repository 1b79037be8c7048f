//! The refinement pass (004 §3.5): edges longer than `l_max` in the metric get a new vertex at
//! their metric midpoint, by a plain edge split (`split.rs`) or by the anisotropic Delaunay
//! insertion kernel (`insert.rs`), which both plan from the same [`split::SplitPlan`].

use super::topo::{parallel_worth, Ctx};
use super::{insert, split};
use crate::mesh::{next, prev, NONE};
use rayon::prelude::*;

/// Sort key of a split candidate: longest first by classes of a quarter octave (edges of
/// length 1.41 to 2^24), then by triangle index — which keeps the new vertices (appended in this
/// order) close in memory to their neighbours — then local edge.
#[inline]
fn split_key(l: f64, t: u32, i: usize) -> u64 {
    let class = (96.0 - (4.0 * l.log2()).floor()).clamp(0.0, 255.0) as u64;
    (class << 40) | (u64::from(t) << 2) | i as u64
}

/// One refinement pass: every edge longer than `l_max` next to a triangle modified since the
/// last refinement pass, longest first, at most one new vertex per triangle per pass (an
/// independent set). Each edge that passes the split check ([`split::check`]) gets its new
/// vertex by the Delaunay insertion kernel ([`insert`]) when `params.insertion` is set and the
/// insertion is valid (unlabelled interior edges), else by a plain split ([`split::apply`]).
/// Returns the number of new vertices.
pub fn pass(ctx: &mut Ctx, cand: &mut Vec<u64>) -> usize {
    ctx.new_pass();
    let from = ctx.split_pos;
    ctx.split_pos = ctx.log.len();
    cand.clear();
    let l_max = ctx.params.l_max;
    // Only edges of triangles modified since the last split pass. An edge shared by two listed
    // triangles is measured once, from the one of lower index, and gets a key for each side (the
    // check is not symmetric in the last bits of the new point, and the apply loop tries the
    // second side when the first fails). The keys are unique, so their order does not depend
    // on how they were collected.
    let list = ctx.logged_since(from);
    let gen = ctx.gen;
    let keys = |c: &Ctx, t: u32, out: &mut dyn FnMut(u64)| {
        let tri = c.mesh.tris[t as usize];
        for i in 0..3 {
            let nb = c.mesh.neighbours[t as usize][i];
            let nb_listed = nb != NONE && c.tseen[nb as usize] == gen;
            if nb_listed && nb < t {
                continue;
            }
            if let Some(l) = c.len_if_above(tri[next(i)], tri[prev(i)], l_max) {
                out(split_key(l, t, i));
                if nb_listed {
                    if let Some(j) = c.mesh.mirror_edge(t as usize, nb as usize) {
                        out(split_key(l, nb, j));
                    }
                }
            }
        }
    };
    if parallel_worth(list.len()) {
        let c: &Ctx = ctx;
        cand.par_extend(list.par_iter().flat_map_iter(|&t| {
            let mut v = Vec::new();
            keys(c, t, &mut |k| v.push(k));
            v
        }));
        cand.par_sort_unstable();
    } else {
        for &t in &list {
            keys(ctx, t, &mut |k| cand.push(k));
        }
        cand.sort_unstable();
    }
    let mut count = 0;
    for &key in cand.iter() {
        let (t, i) = ((key >> 2) as u32, (key & 3) as u8);
        let tu = t as usize;
        if ctx.tstamp[tu] == ctx.gen {
            continue;
        }
        let nb = ctx.mesh.neighbours[tu][i as usize];
        if nb != NONE && ctx.tstamp[nb as usize] == ctx.gen {
            continue;
        }
        if let Some(plan) = split::check(ctx, t, i as usize) {
            if ctx.params.insertion {
                if let Some(ins) = insert::check(ctx, &plan) {
                    insert::apply(ctx, &ins);
                    count += 1;
                    continue;
                }
            }
            split::apply(ctx, &plan);
            count += 1;
        }
    }
    count
}
