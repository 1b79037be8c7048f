//! The Kuhn (Freudenthal) subdivision of a box: every cube of an `nx x ny x nz` grid is cut into
//! the six tetrahedra along its main diagonal, `(v, v + e_a, v + e_a + e_b, v + 1)` for the six
//! permutations `(a, b, c)` of the axes. All cubes are cut the same way, so the mesh is conforming
//! and compatible with newest-vertex bisection (tag 3, refinement edge = the main diagonal).

use super::Mesh3;
use crate::error::{Error, Result};
use crate::geom::DVec3;

const PERMS: [[usize; 3]; 6] = [
    [0, 1, 2],
    [0, 2, 1],
    [1, 0, 2],
    [1, 2, 0],
    [2, 0, 1],
    [2, 1, 0],
];

impl Mesh3 {
    /// The Kuhn mesh of the box `[lo, hi]` with `n = [nx, ny, nz]` cubes (cells) per direction.
    /// Boundary faces are labelled by box side: `x = lo` 1, `x = hi` 2, `y` 3, 4, `z` 5, 6.
    pub fn kuhn_box(lo: DVec3, hi: DVec3, n: [usize; 3]) -> Result<Mesh3> {
        if n.contains(&0) {
            return Err(Error::InvalidInput(format!(
                "a box mesh needs at least one cell per direction (got {n:?})"
            )));
        }
        if !(lo.is_finite() && hi.is_finite() && hi.cmpgt(lo).all()) {
            return Err(Error::InvalidInput(format!(
                "bad box [{lo}, {hi}]: need finite corners with hi > lo"
            )));
        }
        let nv = (n[0] + 1) * (n[1] + 1) * (n[2] + 1);
        if nv >= (u32::MAX / 4) as usize {
            return Err(Error::InvalidInput(format!("box mesh {n:?} is too large")));
        }
        let id = |i: usize, j: usize, k: usize| ((k * (n[1] + 1) + j) * (n[0] + 1) + i) as u32;
        let mut points = Vec::with_capacity(nv);
        for k in 0..=n[2] {
            for j in 0..=n[1] {
                for i in 0..=n[0] {
                    let c = |idx: usize, m: usize, a: usize| {
                        if idx == m {
                            hi[a]
                        } else {
                            lo[a] + (hi[a] - lo[a]) * idx as f64 / m as f64
                        }
                    };
                    points.push(DVec3::new(c(i, n[0], 0), c(j, n[1], 1), c(k, n[2], 2)));
                }
            }
        }
        let mut maubach = Vec::with_capacity(6 * n[0] * n[1] * n[2]);
        for k in 0..n[2] {
            for j in 0..n[1] {
                for i in 0..n[0] {
                    for p in PERMS {
                        let mut c = [i, j, k];
                        let mut t = [id(i, j, k); 4];
                        for (s, &axis) in p.iter().enumerate() {
                            c[axis] += 1;
                            t[s + 1] = id(c[0], c[1], c[2]);
                        }
                        maubach.push((t, 3u8));
                    }
                }
            }
        }
        let g = vec![0u8; maubach.len()];
        let mut m = Mesh3::from_maubach(points, maubach, g);
        // Box sides: x = lo 1, x = hi 2, y = lo 3, y = hi 4, z = lo 5, z = hi 6 (exact: the
        // side coordinates are stored exactly).
        m.label_boundary(|m, f| {
            let p = f.map(|v| m.points[v as usize]);
            (0..3)
                .find_map(|a| {
                    if p.iter().all(|q| q[a] == lo[a]) {
                        Some(2 * a as i32 + 1)
                    } else if p.iter().all(|q| q[a] == hi[a]) {
                        Some(2 * a as i32 + 2)
                    } else {
                        None
                    }
                })
                .unwrap_or(1)
        });
        Ok(m)
    }
}
