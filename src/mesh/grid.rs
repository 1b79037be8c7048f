//! Structured triangulations of a rectangle.

use super::Mesh2;
use crate::error::{Error, Result};
use crate::geom::DVec2;

/// How each grid cell is cut into triangles.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum GridPattern {
    /// One diagonal per cell, from lower-left to upper-right.
    #[default]
    Right,
    /// One diagonal per cell, from lower-right to upper-left.
    Left,
    /// Alternating diagonals in a checkerboard ("union jack").
    UnionJack,
    /// Both diagonals: four triangles per cell around an added centre vertex ("criss-cross").
    CrissCross,
}

impl Mesh2 {
    /// A structured mesh of the rectangle `[lo, hi]` with `nx x ny` cells (so `(nx+1)(ny+1)` grid
    /// vertices, plus one per cell for [`GridPattern::CrissCross`]).
    ///
    /// Boundary edges are labelled as FreeFem++'s `square`: 1 bottom, 2 right, 3 top, 4 left. The
    /// four corners are flagged as corners and required.
    pub fn rectangle(
        lo: DVec2,
        hi: DVec2,
        nx: usize,
        ny: usize,
        pattern: GridPattern,
    ) -> Result<Mesh2> {
        if nx == 0 || ny == 0 {
            return Err(Error::InvalidInput(format!(
                "a grid needs at least one cell in each direction (got {nx} x {ny})"
            )));
        }
        if !(lo.is_finite() && hi.is_finite() && hi.x > lo.x && hi.y > lo.y) {
            return Err(Error::InvalidInput(format!(
                "bad rectangle [{lo}, {hi}]: need finite corners with hi > lo"
            )));
        }
        let n_grid = (nx + 1) * (ny + 1);
        let centres = if pattern == GridPattern::CrissCross {
            nx * ny
        } else {
            0
        };
        if n_grid + centres >= u32::MAX as usize / 2 {
            return Err(Error::InvalidInput(format!(
                "grid {nx} x {ny} is too large"
            )));
        }
        let id = |i: usize, j: usize| (j * (nx + 1) + i) as u32;
        let h = (hi - lo) / DVec2::new(nx as f64, ny as f64);
        let mut points = Vec::with_capacity(n_grid + centres);
        for j in 0..=ny {
            for i in 0..=nx {
                // Exact end coordinates on the far sides.
                let x = if i == nx { hi.x } else { lo.x + i as f64 * h.x };
                let y = if j == ny { hi.y } else { lo.y + j as f64 * h.y };
                points.push(DVec2::new(x, y));
            }
        }
        let mut tris = Vec::with_capacity(4 * nx * ny);
        for j in 0..ny {
            for i in 0..nx {
                let (a, b, c, d) = (id(i, j), id(i + 1, j), id(i + 1, j + 1), id(i, j + 1));
                let right = match pattern {
                    GridPattern::Right => true,
                    GridPattern::Left => false,
                    GridPattern::UnionJack => (i + j) % 2 == 0,
                    GridPattern::CrissCross => {
                        let m = points.len() as u32;
                        points.push(lo + h * DVec2::new(i as f64 + 0.5, j as f64 + 0.5));
                        tris.extend_from_slice(&[[a, b, m], [b, c, m], [c, d, m], [d, a, m]]);
                        continue;
                    }
                };
                if right {
                    tris.push([a, b, c]);
                    tris.push([a, c, d]);
                } else {
                    tris.push([a, b, d]);
                    tris.push([b, c, d]);
                }
            }
        }
        let mut mesh = Mesh2::from_triangles(points, tris)?;
        let eps = 1e-9 * (hi - lo).max_element();
        for t in 0..mesh.tris.len() {
            for i in 0..3 {
                if mesh.neighbours[t][i] != super::NONE {
                    continue;
                }
                let [a, b] = mesh.edge_vertices(t, i);
                let m = 0.5 * (mesh.points[a as usize] + mesh.points[b as usize]);
                mesh.edge_ref[t][i] = if (m.y - lo.y).abs() < eps {
                    1
                } else if (m.x - hi.x).abs() < eps {
                    2
                } else if (m.y - hi.y).abs() < eps {
                    3
                } else {
                    4
                };
            }
        }
        for v in [id(0, 0), id(nx, 0), id(nx, ny), id(0, ny)] {
            mesh.corner[v as usize] = true;
            mesh.required[v as usize] = true;
        }
        Ok(mesh)
    }
}
