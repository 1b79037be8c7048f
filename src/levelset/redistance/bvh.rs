//! A bounding-volume hierarchy over segments (2D) or triangles (3D) for exact nearest-primitive
//! queries: the spatial index behind geometric redistancing (004 §2.2, "(m+n) log m").
//!
//! The tree is binary, built top-down by median splits along the longest axis of the centroid box
//! (O(m log² m)), stored as a flat array of nodes; leaves hold at most [`LEAF`] primitives. A query
//! is a depth-first branch and bound (nearer child first, boxes pruned when their distance is not
//! below the best found), O(log m) on average. Points are any [`Point<D>`].

use crate::geom::Point;

/// Maximum number of primitives in a leaf.
const LEAF: usize = 4;

#[derive(Debug, Clone, Copy)]
struct Node<P> {
    lo: P,
    hi: P,
    /// Leaf: first primitive in `order`; inner node: index of the left child (right = left + 1).
    first: u32,
    /// Number of primitives for a leaf, 0 for an inner node.
    count: u32,
}

/// The hierarchy: nodes plus the permutation of primitive indices.
#[derive(Debug, Clone)]
pub(crate) struct Bvh<P> {
    nodes: Vec<Node<P>>,
    order: Vec<u32>,
}

/// Squared distance from `p` to the box `[lo, hi]`.
#[inline]
fn box_dist2<const D: usize, P: Point<D>>(p: &P, lo: &P, hi: &P) -> f64 {
    let mut s = 0.0;
    for k in 0..D {
        let d = (lo[k] - p[k]).max(p[k] - hi[k]).max(0.0);
        s += d * d;
    }
    s
}

impl<P> Bvh<P> {
    /// Build from the bounding boxes `(lo, hi)` of `m >= 1` primitives.
    pub(crate) fn build<const D: usize>(boxes: &[(P, P)]) -> Bvh<P>
    where
        P: Point<D>,
    {
        let m = boxes.len();
        let centre: Vec<P> = boxes.iter().map(|(lo, hi)| (*lo + *hi) * 0.5).collect();
        let mut order: Vec<u32> = (0..m as u32).collect();
        let mut nodes = Vec::with_capacity(2 * m / LEAF + 2);
        nodes.push(Node {
            lo: P::ZERO,
            hi: P::ZERO,
            first: 0,
            count: 0,
        });
        // Explicit stack of (node, start, end) to avoid recursion depth limits.
        let mut stack = vec![(0usize, 0usize, m)];
        while let Some((ni, s, e)) = stack.pop() {
            let mut lo = [f64::INFINITY; D];
            let mut hi = [f64::NEG_INFINITY; D];
            let mut clo = [f64::INFINITY; D];
            let mut chi = [f64::NEG_INFINITY; D];
            for &i in &order[s..e] {
                let (bl, bh) = &boxes[i as usize];
                let c = &centre[i as usize];
                for k in 0..D {
                    lo[k] = lo[k].min(bl[k]);
                    hi[k] = hi[k].max(bh[k]);
                    clo[k] = clo[k].min(c[k]);
                    chi[k] = chi[k].max(c[k]);
                }
            }
            nodes[ni].lo = P::from_array(lo);
            nodes[ni].hi = P::from_array(hi);
            if e - s <= LEAF {
                nodes[ni].first = s as u32;
                nodes[ni].count = (e - s) as u32;
                continue;
            }
            let axis = (0..D)
                .max_by(|&a, &b| (chi[a] - clo[a]).total_cmp(&(chi[b] - clo[b])))
                .unwrap_or(0);
            let mid = s + (e - s) / 2;
            order[s..e].select_nth_unstable_by(mid - s, |&a, &b| {
                centre[a as usize][axis]
                    .total_cmp(&centre[b as usize][axis])
                    .then(a.cmp(&b))
            });
            let left = nodes.len();
            let blank = nodes[ni];
            nodes.push(blank);
            nodes.push(blank);
            nodes[ni].first = left as u32;
            nodes[ni].count = 0;
            stack.push((left, s, mid));
            stack.push((left + 1, mid, e));
        }
        Bvh { nodes, order }
    }

    /// The primitive nearest to `p` and its distance, given the exact distance `dist(p, i)` to
    /// primitive `i` and a starting guess `hint` (any primitive index, used as the first upper
    /// bound). Ties are broken towards the primitive found first; the returned *distance* is the
    /// minimum over all primitives whatever the hint.
    #[inline]
    pub(crate) fn nearest<const D: usize>(
        &self,
        p: &P,
        hint: u32,
        dist: impl Fn(u32) -> f64,
        stack: &mut Vec<u32>,
    ) -> (u32, f64)
    where
        P: Point<D>,
    {
        let mut best = hint;
        let mut best_d = dist(hint);
        let mut best_d2 = best_d * best_d;
        stack.clear();
        stack.push(0);
        while let Some(ni) = stack.pop() {
            let node = &self.nodes[ni as usize];
            if box_dist2(p, &node.lo, &node.hi) >= best_d2 {
                continue;
            }
            if node.count > 0 {
                let s = node.first as usize;
                for &i in &self.order[s..s + node.count as usize] {
                    let d = dist(i);
                    if d < best_d {
                        best_d = d;
                        best_d2 = d * d;
                        best = i;
                    }
                }
            } else {
                let l = node.first;
                let dl = {
                    let n = &self.nodes[l as usize];
                    box_dist2(p, &n.lo, &n.hi)
                };
                let dr = {
                    let n = &self.nodes[l as usize + 1];
                    box_dist2(p, &n.lo, &n.hi)
                };
                // Push the farther child first so that the nearer one is explored first.
                if dl <= dr {
                    stack.push(l + 1);
                    stack.push(l);
                } else {
                    stack.push(l);
                    stack.push(l + 1);
                }
            }
        }
        (best, best_d)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geom::DVec3;

    #[test]
    fn nearest_matches_brute_force_on_points() {
        // Primitives are points on a spiral; compare with brute force for many queries.
        let pts: Vec<DVec3> = (0..500)
            .map(|i| {
                let t = i as f64 * 0.1;
                DVec3::new(t.cos() * (0.1 + 0.01 * t), t.sin() * (0.1 + 0.01 * t), 0.0)
            })
            .collect();
        let boxes: Vec<_> = pts.iter().map(|p| (*p, *p)).collect();
        let bvh = Bvh::build(&boxes);
        let mut stack = Vec::new();
        for q in 0..400 {
            let p = DVec3::new(
                (q as f64 * 0.37).sin() * 0.8,
                (q as f64 * 0.91).cos() * 0.8,
                0.0,
            );
            let dist = |i: u32| {
                let a = pts[i as usize];
                ((a[0] - p[0]).powi(2) + (a[1] - p[1]).powi(2)).sqrt()
            };
            let (_, d) = bvh.nearest(&p, (q % 500) as u32, dist, &mut stack);
            let brute = (0..500u32).map(dist).fold(f64::INFINITY, f64::min);
            assert_eq!(d, brute);
        }
    }
}
