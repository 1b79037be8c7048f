//! Reconstruction of a planar band field between its nodes: the bilinear (Q1) interpolant, and
//! the bicubic Catmull–Rom interpolant (exact for quadratics, interpolation error `O(h³)`,
//! continuously differentiable across cells) where the `4 × 4` nodes around a cell are band
//! nodes. A [`Patch`] holds one cell's reconstruction and gives the value, gradient and Hessian
//! ([`Jet`]) at any point near the cell (a cell's polynomial continued a little outside it).
//!
//! The bicubic zero level is what the band's zero level, distance extension and curvature read
//! (000 §2.4: the extension must be second order for `j ≥ 2`; reading the chords or the bilinear
//! zero level instead moves a convex zero level inwards by `O(h²κ)` at every redistancing).

use super::{Grid2, Plane, C2};
use crate::backends::dtgrid::band::{Band, GridCoord};
use crate::geom::DVec2;

/// A band field: the grid, the band and one value per band node.
#[derive(Debug, Clone, Copy)]
pub struct Field<'a> {
    /// The grid.
    pub plane: &'a Plane,
    /// The band nodes.
    pub band: &'a Grid2,
    /// The values, in band order.
    pub u: &'a [f64],
}

impl Field<'_> {
    /// The value at node `c`, `None` outside the band.
    #[inline]
    pub fn at(&self, c: C2) -> Option<f64> {
        self.band.index(c).map(|i| self.u[i])
    }
}

/// Value, gradient and Hessian `[∂xx, ∂xy, ∂yy]` of a reconstruction at a point.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Jet {
    /// The value.
    pub value: f64,
    /// The gradient.
    pub grad: DVec2,
    /// The second derivatives `[∂xx, ∂xy, ∂yy]`.
    pub hess: [f64; 3],
}

impl Jet {
    /// `div(∇u/|∇u|) = (u_xx u_y² − 2 u_x u_y u_xy + u_yy u_x²) / |∇u|³`, `None` where the
    /// gradient vanishes.
    pub fn curvature(&self) -> Option<f64> {
        curvature(self.grad, self.hess)
    }
}

/// The curvature of the level line through a point with gradient `g` and Hessian `hs`.
fn curvature(g: DVec2, hs: [f64; 3]) -> Option<f64> {
    let g2 = g.length_squared();
    if !(g2 > 0.0 && g2.is_finite()) {
        return None;
    }
    let num = hs[0] * g.y * g.y - 2.0 * g.x * g.y * hs[1] + hs[2] * g.x * g.x;
    Some(num / (g2 * g2.sqrt()))
}

/// The Catmull–Rom weights of the nodes at offsets −1, 0, 1, 2 for `t ∈ [0, 1]`, with their
/// first and second derivatives in `t`.
fn catmull_rom(t: f64) -> [[f64; 4]; 3] {
    let (t2, t3) = (t * t, t * t * t);
    [
        [
            0.5 * (-t3 + 2.0 * t2 - t),
            0.5 * (3.0 * t3 - 5.0 * t2 + 2.0),
            0.5 * (-3.0 * t3 + 4.0 * t2 + t),
            0.5 * (t3 - t2),
        ],
        [
            0.5 * (-3.0 * t2 + 4.0 * t - 1.0),
            0.5 * (9.0 * t2 - 10.0 * t),
            0.5 * (-9.0 * t2 + 8.0 * t + 1.0),
            0.5 * (3.0 * t2 - 2.0 * t),
        ],
        [
            0.5 * (-6.0 * t + 4.0),
            0.5 * (18.0 * t - 10.0),
            0.5 * (-18.0 * t + 8.0),
            0.5 * (6.0 * t - 2.0),
        ],
    ]
}

/// The cell holding the point `x` (clamped to the grid's cells) and whether `x` is inside the
/// grid (within `1e-9` cells).
pub fn locate(plane: &Plane, x: DVec2) -> Option<C2> {
    let top = (plane.n - 1) as f64;
    let s = [x.x / plane.h, x.y / plane.h];
    if s.iter()
        .any(|v| !v.is_finite() || *v < -1e-9 || *v > top + 1e-9)
    {
        return None;
    }
    Some(s.map(|v| (v.floor() as i32).clamp(0, plane.n as i32 - 2)))
}

#[derive(Debug, Clone, Copy, PartialEq)]
enum Kind {
    /// The `4 × 4` node values, `v[4 dy + dx]` at offset `(dx − 1, dy − 1)` from the cell.
    Cubic([f64; 16]),
    /// The corner values (corner `k`: bit 0 along x, bit 1 along y).
    Linear([f64; 4]),
}

/// The reconstruction of a band field on one cell (see the module documentation).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Patch {
    /// The cell's lowest corner.
    pub cell: C2,
    origin: DVec2,
    h: f64,
    kind: Kind,
}

impl Patch {
    /// The bicubic patch of `cell` where its `4 × 4` nodes are band nodes, else the bilinear
    /// one where its corners are, else `None`.
    pub fn of(f: &Field<'_>, cell: C2) -> Option<Patch> {
        let mut v = [0.0; 16];
        let mut cubic = true;
        for (k, vk) in v.iter_mut().enumerate() {
            match f.at([cell[0] + (k % 4) as i32 - 1, cell[1] + (k / 4) as i32 - 1]) {
                Some(x) => *vk = x,
                None => {
                    cubic = false;
                    break;
                }
            }
        }
        let kind = if cubic {
            Kind::Cubic(v)
        } else {
            let mut c = [0.0; 4];
            for (k, ck) in c.iter_mut().enumerate() {
                *ck = f.at(cell.corner(k))?;
            }
            Kind::Linear(c)
        };
        Some(Patch {
            cell,
            origin: f.plane.pos(cell),
            h: f.plane.h,
            kind,
        })
    }

    /// The bilinear patch of `cell` from its corner values.
    pub fn linear(plane: &Plane, cell: C2, corners: [f64; 4]) -> Patch {
        Patch {
            cell,
            origin: plane.pos(cell),
            h: plane.h,
            kind: Kind::Linear(corners),
        }
    }

    /// Whether the patch is bicubic.
    pub fn is_cubic(&self) -> bool {
        matches!(self.kind, Kind::Cubic(_))
    }

    /// The value, gradient and Hessian at `x` (the cell's polynomial, also outside the cell).
    pub fn jet(&self, x: DVec2) -> Jet {
        let h = self.h;
        let (tx, ty) = ((x.x - self.origin.x) / h, (x.y - self.origin.y) / h);
        match &self.kind {
            Kind::Cubic(v) => {
                let (wx, wy) = (catmull_rom(tx), catmull_rom(ty));
                let mut s = [0.0; 6];
                for dy in 0..4 {
                    for dx in 0..4 {
                        let vk = v[4 * dy + dx];
                        s[0] += vk * wy[0][dy] * wx[0][dx];
                        s[1] += vk * wy[0][dy] * wx[1][dx];
                        s[2] += vk * wy[1][dy] * wx[0][dx];
                        s[3] += vk * wy[0][dy] * wx[2][dx];
                        s[4] += vk * wy[1][dy] * wx[1][dx];
                        s[5] += vk * wy[2][dy] * wx[0][dx];
                    }
                }
                Jet {
                    value: s[0],
                    grad: DVec2::new(s[1], s[2]) / h,
                    hess: [s[3] / (h * h), s[4] / (h * h), s[5] / (h * h)],
                }
            }
            Kind::Linear(c) => {
                let value = c[0] * (1.0 - tx) * (1.0 - ty)
                    + c[1] * tx * (1.0 - ty)
                    + c[2] * (1.0 - tx) * ty
                    + c[3] * tx * ty;
                let gx = (c[1] - c[0]) * (1.0 - ty) + (c[3] - c[2]) * ty;
                let gy = (c[2] - c[0]) * (1.0 - tx) + (c[3] - c[1]) * tx;
                let hxy = (c[0] - c[1] - c[2] + c[3]) / (h * h);
                Jet {
                    value,
                    grad: DVec2::new(gx, gy) / h,
                    hess: [0.0, hxy, 0.0],
                }
            }
        }
    }

    /// `x` moved onto the patch's zero level by Newton steps along the gradient (at most
    /// `iters`, each at most half a cell).
    pub fn project(&self, mut x: DVec2, iters: usize) -> DVec2 {
        for _ in 0..iters {
            let j = self.jet(x);
            let g2 = j.grad.length_squared();
            if g2.is_nan() || g2 <= 1e-300 {
                break;
            }
            let step = j.grad * (j.value / g2);
            if step.length().is_nan() || step.length() > 0.5 * self.h {
                break;
            }
            x -= step;
            if step.length() < 1e-13 * self.h {
                break;
            }
        }
        x
    }

    /// The closest point to `p` on the patch's zero level, from the guess `q` on it: alternate
    /// tangential moves towards the foot of `p` and projections onto the level. The point stays
    /// within one cell of the patch's cell.
    pub fn closest(&self, p: DVec2, mut q: DVec2) -> DVec2 {
        let lo = self.origin - DVec2::splat(self.h);
        let hi = self.origin + DVec2::splat(2.0 * self.h);
        for _ in 0..12 {
            let g = self.jet(q).grad;
            if g.length_squared().is_nan() || g.length_squared() <= 1e-300 {
                break;
            }
            let t = DVec2::new(-g.y, g.x).normalize();
            let moved = (q + t * (p - q).dot(t)).clamp(lo, hi);
            q = self.project(moved, 3);
        }
        q
    }
}

/// The root in `[0, 1]` of the 1D Catmull–Rom interpolant along the grid line through `a` in
/// direction `axis`, between nodes `a` and `a + e_axis` whose values `va`, `vb` differ in sign
/// (the linear root where a node of the 4-node stencil is missing). Edges shared by two cells
/// get the same root from both.
pub fn edge_root(f: &Field<'_>, a: C2, axis: usize, va: f64, vb: f64) -> f64 {
    let lin = (va / (va - vb)).clamp(0.0, 1.0);
    let (Some(vm), Some(vp)) = (f.at(a.offset(axis, -1)), f.at(a.offset(axis, 2))) else {
        return lin;
    };
    let v = [vm, va, vb, vp];
    let eval = |t: f64| {
        let w = catmull_rom(t);
        (
            (0..4).map(|k| v[k] * w[0][k]).sum::<f64>(),
            (0..4).map(|k| v[k] * w[1][k]).sum::<f64>(),
        )
    };
    // Newton safeguarded by bisection on the bracket [lo, hi] where the sign changes.
    let (mut lo, mut hi) = (0.0, 1.0);
    let neg_lo = va < 0.0;
    let mut t = lin;
    for _ in 0..30 {
        let (ft, dt) = eval(t);
        if ft == 0.0 {
            return t;
        }
        if (ft < 0.0) == neg_lo {
            lo = t;
        } else {
            hi = t;
        }
        let newton = t - ft / dt;
        let next = if dt != 0.0 && newton > lo && newton < hi {
            newton
        } else {
            0.5 * (lo + hi)
        };
        if (next - t).abs() < 1e-14 {
            return next;
        }
        t = next;
    }
    t
}

/// `div(∇u/|∇u|)` at the band node `c` by second-order central differences over its `3 × 3`
/// neighbourhood, `None` where a neighbour is missing or the gradient vanishes.
pub fn node_curvature(f: &Field<'_>, c: C2) -> Option<f64> {
    let mut u = [0.0; 9];
    for (k, uk) in u.iter_mut().enumerate() {
        *uk = f.at([c[0] + k as i32 % 3 - 1, c[1] + k as i32 / 3 - 1])?;
    }
    let h = f.plane.h;
    let g = DVec2::new(u[5] - u[3], u[7] - u[1]) / (2.0 * h);
    let hxx = (u[5] - 2.0 * u[4] + u[3]) / (h * h);
    let hyy = (u[7] - 2.0 * u[4] + u[1]) / (h * h);
    let hxy = (u[8] - u[6] - u[2] + u[0]) / (4.0 * h * h);
    curvature(g, [hxx, hxy, hyy])
}

#[cfg(test)]
mod tests {
    use super::*;

    fn full(n: usize) -> (Plane, Grid2) {
        let plane = Plane::new(n, 1.0 / (n - 1) as f64).unwrap();
        let m = n as i32;
        let band = Grid2::from_sorted((0..m * m).map(|k| [k / m, k % m])).unwrap();
        (plane, band)
    }

    #[test]
    fn bicubic_reproduces_quadratics_and_their_curvature() {
        let (plane, band) = full(17);
        let q = |p: DVec2| 0.3 + p.x - 2.0 * p.x * p.y + 1.5 * p.x * p.x - p.y * p.y;
        let u: Vec<f64> = band.coords().map(|c| q(plane.pos(c))).collect();
        let f = Field {
            plane: &plane,
            band: &band,
            u: &u,
        };
        for i in 0..40 {
            let s = i as f64;
            let x = DVec2::new(0.5 + 0.35 * (1.3 * s).sin(), 0.5 + 0.35 * (2.1 * s).cos());
            let p = Patch::of(&f, locate(&plane, x).unwrap()).unwrap();
            assert!(p.is_cubic());
            let j = p.jet(x);
            assert!((j.value - q(x)).abs() < 1e-12);
            let g = DVec2::new(1.0 - 2.0 * x.y + 3.0 * x.x, -2.0 * x.x - 2.0 * x.y);
            assert!((j.grad - g).length() < 1e-10);
            assert!((j.hess[0] - 3.0).abs() < 1e-8 && (j.hess[1] + 2.0).abs() < 1e-8);
            assert!((j.hess[2] + 2.0).abs() < 1e-8);
        }
        // The zero level of the distance to a circle: curvature 1/r at points projected on it.
        let r = 0.3;
        let d: Vec<f64> = band
            .coords()
            .map(|c| (plane.pos(c) - DVec2::splat(0.5)).length() - r)
            .collect();
        let f = Field {
            plane: &plane,
            band: &band,
            u: &d,
        };
        let x = DVec2::new(0.5 + r * 0.6, 0.5 + r * 0.8) + DVec2::splat(0.01);
        let p = Patch::of(&f, locate(&plane, x).unwrap()).unwrap();
        let y = p.project(x, 5);
        // Catmull–Rom interpolation error O(h³) at h = 1/16.
        assert!(((y - DVec2::splat(0.5)).length() - r).abs() < 5e-4);
        // The patch's second derivatives are first order (radius 4.8 cells here); the nodal
        // central differences below are second order.
        assert!((p.jet(y).curvature().unwrap() * r - 1.0).abs() < 0.5);
        let c = [8, 12];
        let k = node_curvature(&f, c).unwrap();
        assert!((k * (plane.pos(c) - DVec2::splat(0.5)).length() - 1.0).abs() < 0.02);
        // The edge root of the 1D cubic.
        let a = [12, 8];
        let t = edge_root(&f, a, 0, f.at(a).unwrap(), f.at([13, 8]).unwrap());
        let x = plane.pos(a) + DVec2::new(t * plane.h, 0.0);
        assert!(((x - DVec2::splat(0.5)).length() - r).abs() < 1e-4, "{t}");
    }
}
