//! The final quality sweep: the tetrahedra still below [`Q_BAD`] after the cycle are removed by
//! collapsing one of their edges, shortest in the metric first, when the collapse raises the
//! worst quality around the removed vertex by at least 2 % and makes no edge longer than
//! [`L_SWEEP`] (a little above `l_max`: the split/collapse cycle keeps every edge at most
//! `l_max`, which can leave a short edge of a flat tetrahedron between long edges). The
//! swaps and smoothing then tidy the neighbourhood.

use super::Ctx;

/// Tetrahedra with a mean ratio below this are swept.
pub(crate) const Q_BAD: f64 = 0.4;

/// The longest edge a sweep collapse may make.
const L_SWEEP: f64 = 1.6;

/// Relative gain in the worst quality a sweep collapse must bring.
const GAIN: f64 = 1.02;

/// One sweep over the tetrahedra below [`Q_BAD`], worst first; returns the number of collapses.
pub(crate) fn pass(ctx: &mut Ctx<'_>) -> usize {
    ctx.next_pass();
    let bad = ctx.bad_tets(Q_BAD, 0);
    let mut bad: Vec<(u64, u32)> = bad
        .into_iter()
        .map(|t| (ctx.tq[t as usize].max(0.0).to_bits(), t))
        .collect();
    bad.sort_unstable();
    let mut count = 0;
    let mut nb = Vec::new();
    for (_, t) in bad {
        let tet = ctx.mesh.tets[t as usize];
        if tet[0] == crate::mesh::NONE || ctx.tet_quality(t) >= Q_BAD {
            continue;
        }
        let mut edges: Vec<(f64, u32, u32)> = Vec::with_capacity(12);
        for (i, j) in [(0, 1), (0, 2), (0, 3), (1, 2), (1, 3), (2, 3)] {
            let l = ctx.length(tet[i], tet[j]);
            edges.push((l, tet[i], tet[j]));
            edges.push((l, tet[j], tet[i]));
        }
        edges.sort_by(|x, y| x.0.total_cmp(&y.0));
        for (_, a, b) in edges {
            let Some(new) = ctx.mesh.collapse_check(a, b) else {
                continue;
            };
            let before = ctx.ball_quality(a);
            let after = new
                .iter()
                .map(|&n| ctx.quality_of(n, None))
                .fold(f64::INFINITY, f64::min);
            if after <= GAIN * before {
                continue;
            }
            ctx.mesh.vertex_neighbours(a, &mut nb);
            if nb.iter().any(|&c| c != b && ctx.length(b, c) > L_SWEEP) {
                continue;
            }
            ctx.touch_ball(a);
            ctx.mesh.collapse_unchecked(a, b);
            ctx.touch_ball(b);
            count += 1;
            break;
        }
    }
    count
}
