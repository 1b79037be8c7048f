//! Edge split (MMG `split_2d.c`, 004 §3.5): an edge longer than `l_max` in the metric gets a new
//! vertex at its metric midpoint; the two (or one, on the boundary) triangles sharing it become
//! four (two). The new vertex lies on the segment, so boundary and interface curves stay where
//! they are and areas are preserved; it inherits the edge label as its vertex label.

use super::topo::{parallel_worth, Ctx};
use crate::geom::{orient2d, DVec2};
use crate::mesh::{next, prev, NONE};
use rayon::prelude::*;

/// A planned split of local edge `i` of triangle `t` at parameter `s` from its first vertex.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SplitPlan {
    pub t: u32,
    pub i: u8,
    /// Parameter along `a -> b` (`a = tris[t][next(i)]`).
    pub s: f64,
    /// The new vertex position.
    pub p: DVec2,
}

/// The metric midpoint parameter of an edge whose endpoint lengths are `la`, `lb`: with the size
/// varying linearly along the edge, the point at equal metric distance from both ends is at
/// `s = sqrt(lb) / (sqrt(la) + sqrt(lb))` (closer to the end that wants smaller elements).
#[inline]
pub fn metric_midpoint(la: f64, lb: f64) -> f64 {
    let (a, b) = (la.sqrt(), lb.sqrt());
    let s = b / (a + b);
    if s.is_finite() {
        s.clamp(0.25, 0.75)
    } else {
        0.5
    }
}

/// Pure check: whether edge `(t, i)` is longer than `l_max` and can be split validly. Returns the
/// plan, never modifies the mesh.
pub fn check(ctx: &Ctx, t: u32, i: usize) -> Option<SplitPlan> {
    let mesh = &*ctx.mesh;
    let tri = mesh.tris[t as usize];
    let (c, a, b) = (tri[i], tri[next(i)], tri[prev(i)]);
    let (pa, pb) = (ctx.p(a), ctx.p(b));
    let e = pb - pa;
    let (la, lb) = ctx.end_lengths(a, b);
    if crate::metric::length::geometric_mean_length(la, lb) <= ctx.params.l_max {
        return None;
    }
    let s = metric_midpoint(la, lb);
    let p = pa + s * e;
    if p == pa || p == pb {
        return None;
    }
    let pc = ctx.p(c);
    if orient2d(pc, pa, p) <= 0.0 || orient2d(pc, p, pb) <= 0.0 {
        return None;
    }
    let t2 = mesh.neighbours[t as usize][i];
    if t2 != NONE {
        let t2u = t2 as usize;
        let j = mesh.mirror_edge(t as usize, t2u)?;
        let pd = ctx.p(mesh.tris[t2u][j]);
        if orient2d(pd, pb, p) <= 0.0 || orient2d(pd, p, pa) <= 0.0 {
            return None;
        }
    }
    Some(SplitPlan {
        t,
        i: i as u8,
        s,
        p,
    })
}

/// Sort key of a split candidate: longest first by classes of a quarter octave (edges of
/// length 1.41 to 2^24), then by triangle index — which keeps the new vertices (appended in this
/// order) close in memory to their neighbours — then local edge.
#[inline]
fn split_key(l: f64, t: u32, i: usize) -> u64 {
    let class = (96.0 - (4.0 * l.log2()).floor()).clamp(0.0, 255.0) as u64;
    (class << 40) | (u64::from(t) << 2) | i as u64
}

/// Applies a split: returns the new vertex. Metric and fields at the new vertex come from the
/// source when it has them, else by interpolation along the edge.
pub fn apply(ctx: &mut Ctx, plan: &SplitPlan) -> u32 {
    let t = plan.t;
    let tu = t as usize;
    let i = plan.i as usize;
    let tri = ctx.mesh.tris[tu];
    let (c, a, b) = (tri[i], tri[next(i)], tri[prev(i)]);
    let nbs = ctx.mesh.neighbours[tu];
    let refs = ctx.mesh.edge_ref[tu];
    let (n_bc, n_ca, t2) = (nbs[next(i)], nbs[prev(i)], nbs[i]);
    let (r_bc, r_ca, r_ab) = (refs[next(i)], refs[prev(i)], refs[i]);
    let curve = t2 == NONE || r_ab != 0;
    let m_new = ctx.sample(plan.p, &[a, b], &[1.0 - plan.s, plan.s]);
    let m = ctx.push_vertex(plan.p, m_new, if curve { r_ab } else { 0 });
    let tref = ctx.mesh.tri_ref[tu];
    let j_bc = if n_bc != NONE {
        ctx.mesh.mirror_edge(tu, n_bc as usize).unwrap_or(0)
    } else {
        0
    };
    // t := (c, a, m); t1 := (c, m, b)
    ctx.mesh.tris[tu] = [c, a, m];
    ctx.mesh.edge_ref[tu] = [r_ab, 0, r_ca];
    ctx.mesh.neighbours[tu] = [NONE, NONE, n_ca];
    ctx.touch(t);
    let t1 = ctx.push_tri([c, m, b], tref);
    ctx.mesh.edge_ref[t1 as usize] = [r_ab, r_bc, 0];
    ctx.link(t, 1, t1, 2);
    ctx.link(t1, 1, n_bc, j_bc);
    ctx.mesh.vert_tri[m as usize] = t;
    if ctx.mesh.vert_tri[b as usize] == t {
        ctx.mesh.vert_tri[b as usize] = t1;
    }
    if t2 != NONE {
        let t2u = t2 as usize;
        let tri2 = ctx.mesh.tris[t2u];
        let j = ctx.mesh.mirror_edge(tu, t2u).unwrap_or(0);
        let d = tri2[j];
        let nb2 = ctx.mesh.neighbours[t2u];
        let rf2 = ctx.mesh.edge_ref[t2u];
        // tri2 = (d, b, a) up to rotation: edge (a, d) is opposite b = local next(j),
        // edge (d, b) is opposite a = local prev(j).
        let (n_ad, n_db) = (nb2[next(j)], nb2[prev(j)]);
        let (r_ad, r_db) = (rf2[next(j)], rf2[prev(j)]);
        let j_ad = if n_ad != NONE {
            ctx.mesh.mirror_edge(t2u, n_ad as usize).unwrap_or(0)
        } else {
            0
        };
        let tref2 = ctx.mesh.tri_ref[t2u];
        // t2 := (d, b, m); t3 := (d, m, a)
        ctx.mesh.tris[t2u] = [d, b, m];
        ctx.mesh.edge_ref[t2u] = [r_ab, 0, r_db];
        ctx.mesh.neighbours[t2u] = [NONE, NONE, n_db];
        ctx.touch(t2);
        let t3 = ctx.push_tri([d, m, a], tref2);
        ctx.mesh.edge_ref[t3 as usize] = [r_ab, r_ad, 0];
        ctx.link(t2, 1, t3, 2);
        ctx.link(t3, 1, n_ad, j_ad);
        // Across the split edge: (a, m) is t.0 / t3.0, (m, b) is t1.0 / t2.0.
        ctx.link(t, 0, t3, 0);
        ctx.link(t1, 0, t2, 0);
        if ctx.mesh.vert_tri[a as usize] == t2 {
            ctx.mesh.vert_tri[a as usize] = t3;
        }
    }
    m
}

/// One split pass: every edge longer than `l_max` next to a triangle modified since the last
/// split pass, longest first, at most one split per triangle
/// per pass (an independent set). With `params.insertion` the Delaunay insertion kernel
/// ([`super::insert`]) is tried first on unlabelled interior edges. Returns the number of new
/// vertices.
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
        if let Some(plan) = check(ctx, t, i as usize) {
            if ctx.params.insertion {
                if let Some(ins) = super::insert::check(ctx, &plan) {
                    super::insert::apply(ctx, &ins);
                    count += 1;
                    continue;
                }
            }
            apply(ctx, &plan);
            count += 1;
        }
    }
    count
}
