//! Worst-element repair after the conformity loop: each tetrahedron rated below a quality
//! target (the smaller of its mean ratio in the mean and in the largest vertex metric),
//! worst first, has its vertices moved by a compass search on the worst quality of their ball
//! (steps along the principal directions of the vertex metric, a fifth of the local size
//! halved down to a fortieth; face vertices in their plane, ridge and corner vertices fixed),
//! then, if still below the target, one of its edges contracted
//! ([`super::merge::best_merge`]) when that raises the worst quality around it by 2 %. No
//! change makes an edge leave `[l_min, l_max]` that was in it (moves) or makes an edge longer
//! than `l_max` (contractions), so the repair does not cost conformity.

use super::Ctx;
use crate::geom::DVec3;
use crate::mesh3::edit::onto_plane;
use crate::mesh3::VertexKind;
use crate::metric::Sym3;

/// Relative gain in the worst quality a contraction must bring.
const GAIN: f64 = 1.02;

/// How many edges from a vertex at `p` with metric `m` to `nb` are outside `[l_min, l_max]`.
fn out_of_range(ctx: &Ctx<'_>, p: DVec3, m: &Sym3, nb: &[u32]) -> usize {
    nb.iter()
        .filter(|&&w| {
            let l = Ctx::length_at(p, ctx.mesh.points[w as usize], m, &ctx.metric[w as usize]);
            !(ctx.l_min..=ctx.l_max).contains(&l)
        })
        .count()
}

/// The rating of the tetrahedron `t` (with vertex `v` at `p` with metric `m` when it is one
/// of them): the smaller of its mean ratio in the mean of the vertex metrics
/// ([`Ctx::quality_of`]) and in the vertex metric of largest determinant (the UGAWG form,
/// [`crate::metric::conformity::mean_ratio`]), so that a repaired element is good in both.
fn rating(ctx: &Ctx<'_>, t: [u32; 4], moved: Option<(u32, DVec3, &Sym3)>) -> f64 {
    rating_above(ctx, t, moved, f64::NEG_INFINITY)
}

/// [`rating`], or the first of its two mean ratios when that is already at most `floor` (the
/// rating is then at most `floor` too).
fn rating_above(ctx: &Ctx<'_>, t: [u32; 4], moved: Option<(u32, DVec3, &Sym3)>, floor: f64) -> f64 {
    let q = ctx.quality_of(t, moved);
    if q <= floor {
        return q;
    }
    let mut pts = [DVec3::ZERO; 4];
    let mut big = Sym3::default();
    let mut det = f64::NEG_INFINITY;
    for k in 0..4 {
        let (p, m) = match moved {
            Some((v, p, m)) if v == t[k] => (p, *m),
            _ => (ctx.mesh.points[t[k] as usize], ctx.metric[t[k] as usize]),
        };
        pts[k] = p;
        if m.det() > det {
            det = m.det();
            big = m;
        }
    }
    q.min(crate::metric::conformity::mean_ratio(pts, &big))
}

/// The worst [`rating`] of the ball of `v` with `v` at `p` with metric `m`, or `None` as soon
/// as one is at most `floor` ([`Ctx::ball_min_above`]).
fn ball_rating_above(
    ctx: &Ctx<'_>,
    v: u32,
    p: DVec3,
    m: &Sym3,
    floor: f64,
    first: &mut usize,
) -> Option<f64> {
    ctx.ball_min_above(v, floor, first, |t| {
        rating_above(ctx, t, Some((v, p, m)), floor)
    })
}

/// Compass search on the worst quality of the ball of `v` (see the module docs); returns
/// whether `v` moved.
pub(crate) fn optimise_vertex(ctx: &mut Ctx<'_>, v: u32) -> bool {
    let Some(f) = ctx.source else {
        return false;
    };
    let normal = match ctx.mesh.vertex_kind(v) {
        VertexKind::Interior => None,
        VertexKind::Face(n) => Some(n),
        VertexKind::Feature => return false,
    };
    let mut nb = Vec::new();
    ctx.mesh.vertex_neighbours(v, &mut nb);
    let p0 = ctx.mesh.points[v as usize];
    let m0 = ctx.metric[v as usize];
    let out0 = out_of_range(ctx, p0, &m0, &nb);
    let (lam, vecs) = m0.eigen();
    let mut dirs: Vec<DVec3> = Vec::with_capacity(6);
    for k in 0..3 {
        let mut d = vecs[k] / lam[k].max(1e-300).sqrt();
        if let Some(n) = normal {
            d -= n * d.dot(n);
        }
        if d.length() > 1e-3 / lam[k].max(1e-300).sqrt() {
            dirs.push(d);
            dirs.push(-d);
        }
    }
    let (mut p, mut m) = (p0, m0);
    let mut first = 0;
    let Some(mut q) = ball_rating_above(ctx, v, p, &m, f64::NEG_INFINITY, &mut first) else {
        return false;
    };
    let q_start = q;
    let mut step = 0.2;
    while step > 0.024 {
        let mut moved = false;
        for &d in &dirs {
            let np = match normal {
                Some(n) => onto_plane(p0, n, p + step * d),
                None => p + step * d,
            };
            let nm = f(np);
            let Some(nq) = ball_rating_above(ctx, v, np, &nm, q * 1.001, &mut first) else {
                continue;
            };
            if out_of_range(ctx, np, &nm, &nb) <= out0 && ctx.mesh.move_valid(v, np) {
                (p, m, q) = (np, nm, nq);
                moved = true;
                break;
            }
        }
        if !moved {
            step *= 0.5;
        }
    }
    if q > q_start && ctx.mesh.move_vertex(v, p) {
        ctx.metric[v as usize] = m;
        ctx.touch_ball(v);
        true
    } else {
        false
    }
}

/// Repair passes that remember the stamp at which the search from a vertex, and the
/// contractions of a tetrahedron's edges, last failed: both are deterministic, so they are not
/// repeated while the balls involved are unchanged (their vertices' stamps are older). Every
/// change starts a new stamp.
#[derive(Debug, Default)]
pub(crate) struct Repair {
    /// Per vertex: the stamp of its last failed search (0: none).
    failed: Vec<u32>,
    /// Per tetrahedron (its vertices): the stamp of its last failed contractions.
    uncontracted: std::collections::HashMap<[u32; 4], u32>,
}

impl Repair {
    /// One repair pass over the tetrahedra below `q_target`; returns the number of changes.
    pub(crate) fn pass(&mut self, ctx: &mut Ctx<'_>, q_target: f64) -> usize {
        ctx.next_pass();
        let mut bad: Vec<(u64, u32)> = (0..ctx.mesh.tets.len() as u32)
            .filter(|&t| ctx.mesh.tets[t as usize][0] != crate::mesh::NONE)
            .map(|t| {
                (
                    rating(ctx, ctx.mesh.tets[t as usize], None)
                        .max(0.0)
                        .to_bits(),
                    t,
                )
            })
            .filter(|&(q, _)| f64::from_bits(q) < q_target)
            .collect();
        bad.sort_unstable();
        let mut count = 0;
        let n = ctx.mesh.points.len();
        ctx.stamp.resize(ctx.stamp.len().max(n), 0);
        self.failed.resize(n, 0);
        for (_, t) in bad {
            let tet = ctx.mesh.tets[t as usize];
            if tet[0] == crate::mesh::NONE || rating(ctx, tet, None) >= q_target {
                continue;
            }
            for v in tet {
                if ctx.stamp[v as usize] < self.failed[v as usize] {
                    continue;
                }
                if optimise_vertex(ctx, v) {
                    count += 1;
                    ctx.next_pass();
                } else {
                    self.failed[v as usize] = ctx.pass;
                }
            }
            if ctx.mesh.tets[t as usize] != tet || rating(ctx, tet, None) >= q_target {
                continue;
            }
            let unchanged = |s: u32| tet.iter().all(|&v| ctx.stamp[v as usize] < s);
            if self.uncontracted.get(&tet).is_some_and(|&s| unchanged(s)) {
                continue;
            }
            let mut edges: Vec<(f64, u32, u32)> = Vec::with_capacity(6);
            for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
                edges.push((ctx.length(tet[i], tet[j]), tet[i], tet[j]));
            }
            edges.sort_by(|x, y| x.0.total_cmp(&y.0));
            let mut contracted = false;
            for (_, a, b) in edges {
                let Some(mg) = super::merge::best_merge(ctx, a, b) else {
                    continue;
                };
                let before = ctx.ball_quality(a).min(ctx.ball_quality(b));
                if mg.q > GAIN * before {
                    super::merge::apply(ctx, mg);
                    count += 1;
                    ctx.next_pass();
                    contracted = true;
                    break;
                }
            }
            if !contracted {
                self.uncontracted.insert(tet, ctx.pass);
            }
        }
        count
    }
}
