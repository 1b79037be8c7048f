//! Fast marching on unstructured simplicial meshes (2D and 3D): the extension phase of
//! redistancing, from a frozen band of known distances to every node. Each tentative value solves
//! the local eikonal equation `Σ_i |∇φ_i u_i|² = 1` (004 eq. (5)) on a simplex with the known
//! vertices; in an obtuse simplex the characteristic may miss the known face, so the update is the
//! exact Hopf–Lax minimum over every face of known vertices (an edge, a triangle, ...), where a face
//! solution only counts when its characteristic passes through that face (the acute-angle caveat),
//! and edge updates `u_j + |x_j - x_0|` are always admissible.

use std::cmp::{Ordering, Reverse};
use std::collections::BinaryHeap;

use nalgebra::{Matrix2, Matrix3};

use crate::geom::DVec3;

#[derive(Debug, Clone, Copy, PartialEq)]
struct Key(f64, u32);
impl Eq for Key {}
impl PartialOrd for Key {
    fn partial_cmp(&self, o: &Self) -> Option<Ordering> {
        Some(self.cmp(o))
    }
}
impl Ord for Key {
    fn cmp(&self, o: &Self) -> Ordering {
        self.0.total_cmp(&o.0).then(self.1.cmp(&o.1))
    }
}

/// The face solution from the known vertices `sel` (2 or 3 of them): the `u_0` with
/// `(u - u_0 1)^T Q^{-1} (u - u_0 1) = 1`, `Q = E^T E`, `E = [x_i - x_0]`, if its characteristic
/// passes through the face (`μ = Q^{-1}(u - u_0 1) <= 0`).
fn face_solution(x0: &DVec3, sel: &[(DVec3, f64)]) -> Option<f64> {
    let k = sel.len();
    let mut e = [DVec3::ZERO; 3];
    let mut u = [0.0; 3];
    for (i, (x, v)) in sel.iter().enumerate() {
        e[i] = *x - *x0;
        u[i] = *v;
    }
    let q = |i: usize, j: usize| e[i][0] * e[j][0] + e[i][1] * e[j][1] + e[i][2] * e[j][2];
    // Q^{-1} applied through an explicit inverse (k = 2 or 3).
    let inv: [[f64; 3]; 3] = if k == 2 {
        let m = Matrix2::new(q(0, 0), q(0, 1), q(1, 0), q(1, 1)).try_inverse()?;
        [
            [m[(0, 0)], m[(0, 1)], 0.0],
            [m[(1, 0)], m[(1, 1)], 0.0],
            [0.0; 3],
        ]
    } else {
        let m = Matrix3::from_fn(q).try_inverse()?;
        std::array::from_fn(|i| std::array::from_fn(|j| m[(i, j)]))
    };
    let apply = |v: &[f64; 3]| -> [f64; 3] {
        std::array::from_fn(|i| (0..k).map(|j| inv[i][j] * v[j]).sum())
    };
    let one = [1.0, 1.0, if k == 3 { 1.0 } else { 0.0 }];
    let qo = apply(&one);
    let qu = apply(&u);
    let a: f64 = (0..k).map(|i| qo[i]).sum();
    let b: f64 = (0..k).map(|i| qu[i]).sum();
    let c: f64 = (0..k).map(|i| u[i] * qu[i]).sum::<f64>() - 1.0;
    let disc = b * b - a * c;
    if a.is_nan() || a <= 0.0 || disc < 0.0 {
        return None;
    }
    let u0 = (b + disc.sqrt()) / a;
    let tol = 1e-12 * u0.abs().max(1.0);
    (0..k).all(|i| qu[i] - u0 * qo[i] <= tol).then_some(u0)
}

/// The eikonal update of `x0` from the known vertices `known = [(x_i, u_i)]` of one simplex:
/// the minimum over every non-empty subset (vertex, edge or face) of its admissible solution.
pub(crate) fn local_update(x0: &DVec3, known: &[(DVec3, f64)]) -> f64 {
    let m = known.len();
    let mut best = f64::INFINITY;
    let mut sel = [(DVec3::ZERO, 0.0); 3];
    for mask in 1u32..(1 << m) {
        let mut k = 0;
        for (i, kn) in known.iter().enumerate() {
            if mask & (1 << i) != 0 {
                sel[k] = *kn;
                k += 1;
            }
        }
        if k == 1 {
            best = best.min(sel[0].1 + (sel[0].0 - *x0).length());
        } else if let Some(u0) = face_solution(x0, &sel[..k]) {
            best = best.min(u0);
        }
    }
    best
}

/// Unsigned distances at every node of the simplicial mesh `(points, cells)` (stride `nv`), given
/// the frozen values `known[i] = Some(|d_i|)` of the initial band. Nodes not connected to the band
/// get `f64::INFINITY`.
pub(crate) fn fast_marching(
    points: &[DVec3],
    cells: &[u32],
    nv: usize,
    known: &[Option<f64>],
) -> Vec<f64> {
    let n = points.len();
    let mut off = vec![0usize; n + 1];
    for &v in cells {
        off[v as usize + 1] += 1;
    }
    for i in 0..n {
        off[i + 1] += off[i];
    }
    let mut fill = off.clone();
    let mut v2c = vec![0u32; cells.len()];
    for (c, cell) in cells.chunks(nv).enumerate() {
        for &v in cell {
            v2c[fill[v as usize]] = c as u32;
            fill[v as usize] += 1;
        }
    }
    let mut val = vec![f64::INFINITY; n];
    let mut done = vec![false; n];
    let mut heap = BinaryHeap::new();
    for (i, k) in known.iter().enumerate() {
        if let Some(d) = k {
            val[i] = *d;
            done[i] = true;
        }
    }
    // The update of node `b` from the accepted nodes of one cell `c`.
    let cell_update = |b: usize, c: usize, val: &[f64], done: &[bool]| -> f64 {
        let cell = &cells[c * nv..(c + 1) * nv];
        let mut kn = [(DVec3::ZERO, 0.0); 3];
        let mut k = 0;
        for &w in cell {
            if w as usize != b && done[w as usize] && k < 3 {
                kn[k] = (points[w as usize], val[w as usize]);
                k += 1;
            }
        }
        if k > 0 {
            local_update(&points[b], &kn[..k])
        } else {
            f64::INFINITY
        }
    };
    let update = |b: usize, val: &[f64], done: &[bool]| -> f64 {
        v2c[off[b]..off[b + 1]]
            .iter()
            .map(|&c| cell_update(b, c as usize, val, done))
            .fold(f64::INFINITY, f64::min)
    };
    // Seed: every non-frozen neighbour of the band.
    let mut seeds: Vec<usize> = Vec::new();
    for (i, &d) in done.iter().enumerate() {
        if d {
            for &c in &v2c[off[i]..off[i + 1]] {
                for &w in &cells[c as usize * nv..(c as usize + 1) * nv] {
                    if !done[w as usize] {
                        seeds.push(w as usize);
                    }
                }
            }
        }
    }
    seeds.sort_unstable();
    seeds.dedup();
    for b in seeds {
        let t = update(b, &val, &done);
        if t < val[b] {
            val[b] = t;
            heap.push(Reverse(Key(t, b as u32)));
        }
    }
    while let Some(Reverse(Key(t, a))) = heap.pop() {
        let a = a as usize;
        if done[a] || t > val[a] {
            continue;
        }
        done[a] = true;
        // Only the cells around `a` gained an accepted node: update their other nodes from them.
        for &c in &v2c[off[a]..off[a + 1]] {
            let c = c as usize;
            for j in 0..nv {
                let b = cells[c * nv + j] as usize;
                if done[b] {
                    continue;
                }
                let t = cell_update(b, c, &val, &done);
                if t < val[b] {
                    val[b] = t;
                    heap.push(Reverse(Key(t, b as u32)));
                }
            }
        }
    }
    val
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn face_update_reproduces_plane_distance() {
        // Known values of the distance to the plane x = 0 at three points; the update at x0 must
        // give x0.x exactly when the characteristic passes through the face.
        let pts = [
            DVec3::new(1.0, 0.0, 0.0),
            DVec3::new(1.0, 1.0, 0.0),
            DVec3::new(1.0, 0.0, 1.0),
        ];
        let kn: Vec<_> = pts.iter().map(|p| (*p, p[0])).collect();
        let x0 = DVec3::new(1.7, 0.2, 0.3);
        assert!((local_update(&x0, &kn) - 1.7).abs() < 1e-14);
        // Obtuse case: the foot point is outside the face, so the face solution is rejected and
        // the answer is an edge/vertex update (>= the true distance 1.7).
        let x1 = DVec3::new(1.7, 3.0, 3.0);
        let u = local_update(&x1, &kn);
        assert!(u >= 1.7 - 1e-14 && u.is_finite());
    }
}
