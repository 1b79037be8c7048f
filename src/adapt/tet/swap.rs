//! Swaps: the tetrahedral counterpart of the 2D flips, with no 2D analogue in their topology.
//! An interior edge whose shell has a tetrahedron of quality below [`Q_SWAP`] is removed when
//! the best retriangulation of its ring (3 → 2, n → 2n − 4 tetrahedra,
//! [`crate::mesh3::EditMesh3::best_edge_removal`]) raises the worst quality of the shell; then an
//! interior face between two tetrahedra one of which is below [`Q_SWAP`] is swapped 2 → 3 when
//! the three new tetrahedra are better than the two old ones. Worst first, with
//! improvements by at least 2% so that no swap undoes another, and no new edge longer than
//! `l_max` (a swap never undoes a split). Each candidate is checked on the current mesh when
//! its turn comes, so one pass applies every improving swap it finds (no independent set: a
//! pass that skipped the neighbours of each swap took tens of passes to settle).

use super::Ctx;
use crate::adapt::pass::{run_pass, Operator};
use crate::mesh3::edit::{sorted3, tet_face, EditMesh3};

/// Per vertex: whether it is a vertex of a live tetrahedron created or moved at or after pass
/// `since`. An edge or face with an unmarked vertex has no such tetrahedron around it, so the
/// search of its shell or face pair can be skipped (one sweep over the tetrahedra instead of a
/// ball scan per candidate).
fn fresh_vertices(m: &EditMesh3, since: u32) -> Vec<bool> {
    let mut fresh = vec![false; m.points.len()];
    for (tet, &stamp) in m.tets.iter().zip(&m.tet_stamp) {
        if stamp >= since && tet[0] != crate::mesh::NONE {
            for v in tet {
                fresh[*v as usize] = true;
            }
        }
    }
    fresh
}

/// Shells and face pairs whose worst quality (mean ratio) is below this are examined.
pub(crate) const Q_SWAP: f64 = 0.6;

/// Relative gain in the worst quality a swap must bring.
const GAIN: f64 = 1.02;

/// The edge-removal operator.
pub(crate) struct EdgeRemoval;

impl Operator<Ctx<'_>> for EdgeRemoval {
    type Site = (u64, u32, u32);
    type Key = (u64, u32, u32);
    type Frozen = ();
    type Plan = (u32, u32, Vec<[u32; 4]>);
    const SORTED: bool = true;

    /// The edges of the tetrahedra below [`Q_SWAP`] whose shell has a tetrahedron created or
    /// moved since the previous pass (an unchanged shell gives the verdict it gave then), each
    /// once with the worst quality of those tetrahedra.
    fn sites(&mut self, ctx: &mut Ctx<'_>) -> Vec<Self::Site> {
        let since = ctx.start(super::Op::EdgeRemoval);
        let bad = ctx.bad_tets(Q_SWAP, 0);
        let marked = fresh_vertices(&ctx.mesh, since);
        let mut e: Vec<(u32, u32, u64)> = Vec::with_capacity(6 * bad.len());
        for t in bad {
            let tet = ctx.mesh.tets[t as usize];
            let q = ctx.tq[t as usize].max(0.0).to_bits();
            for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                if marked[tet[i] as usize] && marked[tet[j] as usize] {
                    e.push((tet[i].min(tet[j]), tet[i].max(tet[j]), q));
                }
            }
        }
        e.sort_unstable();
        e.dedup_by_key(|x| (x.0, x.1));
        let m = &ctx.mesh;
        let fresh = |&(a, b, _): &(u32, u32, u64)| {
            m.ball[a as usize]
                .iter()
                .any(|&t| m.tet_stamp[t as usize] >= since && m.tets[t as usize].contains(&b))
        };
        e.into_iter()
            .filter(fresh)
            .map(|(a, b, q)| (q, a, b))
            .collect()
    }

    fn survey(&self, _: &Ctx<'_>, s: Self::Site, _: bool, out: &mut Vec<(Self::Key, Option<()>)>) {
        out.push((s, None));
    }

    fn admissible(&self, ctx: &Ctx<'_>, (_, a, b): Self::Key) -> bool {
        ctx.mesh.alive(a) && ctx.mesh.alive(b)
    }

    fn check(
        &mut self,
        ctx: &mut Ctx<'_>,
        (_, a, b): Self::Key,
        _: Option<()>,
    ) -> Option<Self::Plan> {
        let mut q0 = f64::INFINITY;
        for k in 0..ctx.mesh.ball[a as usize].len() {
            let t = ctx.mesh.ball[a as usize][k];
            if ctx.mesh.tets[t as usize].contains(&b) {
                q0 = q0.min(ctx.cached_quality(t));
            }
        }
        let c = &*ctx;
        let (q, tets) = c.mesh.best_edge_removal(
            a,
            b,
            GAIN * q0,
            |t| c.quality_of(t, None),
            |x, y| c.length(x, y) <= c.l_max,
        )?;
        (q > GAIN * q0).then_some((a, b, tets))
    }

    fn apply(&mut self, ctx: &mut Ctx<'_>, (a, b, tets): Self::Plan) {
        ctx.touch_ball(a);
        ctx.touch_ball(b);
        ctx.mesh.replace_shell(a, b, &tets);
    }
}

/// The face 2-3 swap operator.
pub(crate) struct FaceSwap;

impl Operator<Ctx<'_>> for FaceSwap {
    type Site = (u64, [u32; 3]);
    type Key = (u64, [u32; 3]);
    type Frozen = ();
    type Plan = ([u32; 3], [[u32; 4]; 3]);
    const SORTED: bool = true;

    /// The interior faces of the tetrahedra below [`Q_SWAP`] with one of their two tetrahedra
    /// created or moved since the previous pass, each once with the worst quality of those
    /// tetrahedra.
    fn sites(&mut self, ctx: &mut Ctx<'_>) -> Vec<Self::Site> {
        let since = ctx.start(super::Op::FaceSwap);
        let bad = ctx.bad_tets(Q_SWAP, 0);
        let marked = fresh_vertices(&ctx.mesh, since);
        let mut fs: Vec<([u32; 3], u64)> = Vec::with_capacity(4 * bad.len());
        for t in bad {
            let tet = ctx.mesh.tets[t as usize];
            let q = ctx.tq[t as usize].max(0.0).to_bits();
            for i in 0..4 {
                let f = sorted3(tet_face(&tet, i));
                if ctx.mesh.bfaces.contains_key(&f) {
                    continue;
                }
                let fresh = ctx.mesh.tet_stamp[t as usize] >= since
                    || (f.iter().all(|&v| marked[v as usize])
                        && ctx.mesh.face_pair(f).is_some_and(|p| {
                            p.iter().any(|&x| ctx.mesh.tet_stamp[x as usize] >= since)
                        }));
                if fresh {
                    fs.push((f, q));
                }
            }
        }
        fs.sort_unstable();
        fs.dedup_by_key(|x| x.0);
        fs.into_iter().map(|(f, q)| (q, f)).collect()
    }

    fn survey(&self, _: &Ctx<'_>, s: Self::Site, _: bool, out: &mut Vec<(Self::Key, Option<()>)>) {
        out.push((s, None));
    }

    fn admissible(&self, ctx: &Ctx<'_>, (_, f): Self::Key) -> bool {
        f.iter().all(|&v| ctx.mesh.alive(v))
    }

    fn check(&mut self, ctx: &mut Ctx<'_>, (_, f): Self::Key, _: Option<()>) -> Option<Self::Plan> {
        let ([t0, t1], new) = ctx.mesh.face_swap_plan(f)?;
        if ctx.length(new[0][0], new[0][1]) > ctx.l_max {
            return None;
        }
        let floor = GAIN * ctx.cached_quality(t0).min(ctx.cached_quality(t1));
        // Rejected at the first new tetrahedron that does not beat the floor (most checks
        // fail, usually on the first).
        new.iter()
            .all(|&t| ctx.quality_of(t, None) > floor)
            .then_some((f, new))
    }

    fn apply(&mut self, ctx: &mut Ctx<'_>, (f, new): Self::Plan) {
        for v in f {
            ctx.touch_ball(v);
        }
        ctx.mesh.face_swap_apply(f, new);
        for v in f {
            ctx.touch_ball(v);
        }
    }
}

/// One swap pass (edge removals, then face swaps); returns the number of swaps.
pub(crate) fn pass(ctx: &mut Ctx<'_>) -> usize {
    run_pass(&mut EdgeRemoval, ctx) + run_pass(&mut FaceSwap, ctx)
}
