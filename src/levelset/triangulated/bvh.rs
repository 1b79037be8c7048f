//! A bounding-volume hierarchy of axis-aligned boxes over triangles, in flat arrays, for the
//! nearest-triangle query.
//!
//! Built top-down: a node's triangles are split at the median of their centroids along the
//! longest axis of the centroids' box (`select_nth_unstable`, so the build is `O(n log n)`),
//! down to leaves of at most [`LEAF`] triangles. The query descends the nearer child first and
//! prunes every box farther than the best distance found so far, so it returns the exact
//! nearest triangle.

use super::closest::{closest_point, Feature};
use crate::geom::DVec3;

/// The largest number of triangles in a leaf.
pub const LEAF: usize = 4;

#[derive(Debug, Clone, Copy)]
struct Node {
    lo: DVec3,
    hi: DVec3,
    /// Leaf: first index into `order`; inner: index of the left child (right is `left + 1`).
    start: u32,
    /// Leaf: number of triangles (> 0); inner: 0.
    count: u32,
}

/// The hierarchy: nodes (root first), the triangle permutation the leaves index into and the
/// triangles' corners in that order (contiguous per leaf, for cache locality).
#[derive(Debug, Clone)]
pub struct Bvh {
    nodes: Vec<Node>,
    order: Vec<u32>,
    corners: Vec<[DVec3; 3]>,
}

/// The result of [`Bvh::nearest`].
#[derive(Debug, Clone, Copy)]
pub struct Nearest {
    /// The triangle.
    pub triangle: u32,
    /// The closest point on it.
    pub point: DVec3,
    /// The feature of the triangle the closest point lies on.
    pub feature: Feature,
    /// The squared distance.
    pub distance_squared: f64,
}

fn bounds(points: impl Iterator<Item = DVec3>) -> (DVec3, DVec3) {
    points.fold(
        (DVec3::splat(f64::INFINITY), DVec3::splat(f64::NEG_INFINITY)),
        |(lo, hi), p| (lo.min(p), hi.max(p)),
    )
}

impl Bvh {
    /// Builds the hierarchy over `triangles` (at least one).
    pub fn new(points: &[DVec3], triangles: &[[u32; 3]]) -> Bvh {
        let centroids: Vec<DVec3> = triangles
            .iter()
            .map(|t| t.iter().map(|&v| points[v as usize]).sum::<DVec3>() / 3.0)
            .collect();
        let mut order: Vec<u32> = (0..triangles.len() as u32).collect();
        let mut nodes = Vec::with_capacity(2 * triangles.len() / LEAF + 1);
        let root_box = |range: &[u32]| {
            bounds(
                range
                    .iter()
                    .flat_map(|&t| triangles[t as usize].map(|v| points[v as usize])),
            )
        };
        let (lo, hi) = root_box(&order);
        nodes.push(Node {
            lo,
            hi,
            start: 0,
            count: order.len() as u32,
        });
        // Explicit stack of nodes to split.
        let mut stack = vec![0usize];
        while let Some(ni) = stack.pop() {
            let Node { start, count, .. } = nodes[ni];
            if count as usize <= LEAF {
                continue;
            }
            let (s, c) = (start as usize, count as usize);
            let range = &mut order[s..s + c];
            let (clo, chi) = bounds(range.iter().map(|&t| centroids[t as usize]));
            let ext = chi - clo;
            let axis = if ext.x >= ext.y && ext.x >= ext.z {
                0
            } else if ext.y >= ext.z {
                1
            } else {
                2
            };
            let mid = c / 2;
            range.select_nth_unstable_by(mid, |&a, &b| {
                let (ca, cb) = (centroids[a as usize][axis], centroids[b as usize][axis]);
                ca.total_cmp(&cb).then(a.cmp(&b))
            });
            let left = nodes.len();
            for (off, len) in [(s, mid), (s + mid, c - mid)] {
                let (lo, hi) = root_box(&order[off..off + len]);
                nodes.push(Node {
                    lo,
                    hi,
                    start: off as u32,
                    count: len as u32,
                });
            }
            nodes[ni].start = left as u32;
            nodes[ni].count = 0;
            stack.push(left);
            stack.push(left + 1);
        }
        let corners = order
            .iter()
            .map(|&t| triangles[t as usize].map(|v| points[v as usize]))
            .collect();
        Bvh {
            nodes,
            order,
            corners,
        }
    }

    /// The number of nodes.
    pub fn n_nodes(&self) -> usize {
        self.nodes.len()
    }

    /// The nearest triangle to `p` and the closest point on it (ties go to the triangle met
    /// first in the deterministic traversal).
    pub fn nearest(&self, p: DVec3) -> Nearest {
        let box_d2 = |n: &Node| {
            let d = (n.lo - p).max(p - n.hi).max(DVec3::ZERO);
            d.length_squared()
        };
        let mut best = Nearest {
            triangle: u32::MAX,
            point: p,
            feature: Feature::Face,
            distance_squared: f64::INFINITY,
        };
        let mut stack: Vec<(u32, f64)> = Vec::with_capacity(64);
        stack.push((0, box_d2(&self.nodes[0])));
        while let Some((ni, d2)) = stack.pop() {
            if d2 >= best.distance_squared {
                continue;
            }
            let node = &self.nodes[ni as usize];
            if node.count > 0 {
                let s = node.start as usize;
                let e = s + node.count as usize;
                for (&t, &[a, b, c]) in self.order[s..e].iter().zip(&self.corners[s..e]) {
                    let (q, feature) = closest_point(p, a, b, c);
                    let dq = (p - q).length_squared();
                    if dq < best.distance_squared {
                        best = Nearest {
                            triangle: t,
                            point: q,
                            feature,
                            distance_squared: dq,
                        };
                    }
                }
            } else {
                let (l, r) = (node.start, node.start + 1);
                let (dl, dr) = (
                    box_d2(&self.nodes[l as usize]),
                    box_d2(&self.nodes[r as usize]),
                );
                // Push the farther first so the nearer is visited first.
                if dl <= dr {
                    stack.push((r, dr));
                    stack.push((l, dl));
                } else {
                    stack.push((l, dl));
                    stack.push((r, dr));
                }
            }
        }
        best
    }
}
