//! Reconstruction of a planar band field between its nodes: the bicubic Hermite interpolant
//! with fourth-order central-difference slopes (exact for cubics, interpolation error `O(h⁴)`,
//! continuously differentiable across cells) where the `6 × 6` nodes around a cell are band
//! nodes, else the bicubic Catmull–Rom interpolant (exact for quadratics, `O(h³)`) where the
//! `4 × 4` nodes are, else the bilinear (Q1) interpolant. A [`Patch`] holds one cell's reconstruction and gives the value, gradient and Hessian
//! ([`Jet`]) at any point near the cell (a cell's polynomial continued a little outside it).
//!
//! The bicubic zero level is what the band's zero level, distance extension and curvature read
//! (000 §2.4: the extension must be second order for `j ≥ 2`; reading the chords or the bilinear
//! zero level instead moves a convex zero level inwards by `O(h²κ)` at every redistancing; with
//! the `O(h³)` Catmull–Rom level the nodal curvature of the distance is only first order, with
//! the `O(h⁴)` Hermite level second order).

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

/// The weights of the nodes at offsets −2 … 3 for `t ∈ [0, 1]` (with their first and second
/// derivatives in `t`) of the cubic Hermite interpolant whose end slopes are the fourth-order
/// central differences `(f₋₂ − 8f₋₁ + 8f₁ − f₂)/12h`: interpolation error `O(h⁴)`, exact for
/// cubics, continuously differentiable across cells.
fn hermite6(t: f64) -> [[f64; 6]; 3] {
    let (t2, t3) = (t * t, t * t * t);
    // H00, H01, H10, H11 and their first and second derivatives.
    let h = [
        [
            2.0 * t3 - 3.0 * t2 + 1.0,
            -2.0 * t3 + 3.0 * t2,
            t3 - 2.0 * t2 + t,
            t3 - t2,
        ],
        [
            6.0 * t2 - 6.0 * t,
            -6.0 * t2 + 6.0 * t,
            3.0 * t2 - 4.0 * t + 1.0,
            3.0 * t2 - 2.0 * t,
        ],
        [
            12.0 * t - 6.0,
            -12.0 * t + 6.0,
            6.0 * t - 4.0,
            6.0 * t - 2.0,
        ],
    ];
    // The slopes at offsets 0 and 1 (times h) from the six nodes.
    const D0: [f64; 6] = [1.0, -8.0, 0.0, 8.0, -1.0, 0.0];
    const D1: [f64; 6] = [0.0, 1.0, -8.0, 0.0, 8.0, -1.0];
    h.map(|b| {
        std::array::from_fn(|k| {
            let node = if k == 2 {
                b[0]
            } else if k == 3 {
                b[1]
            } else {
                0.0
            };
            node + (b[2] * D0[k] + b[3] * D1[k]) / 12.0
        })
    })
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
    /// The `6 × 6` node values, `v[6 dy + dx]` at offset `(dx − 2, dy − 2)` from the cell.
    Hermite([f64; 36]),
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
    /// The bicubic Hermite patch of `cell` (fourth-order slopes, `O(h⁴)`) where its `6 × 6`
    /// nodes are band nodes, else the Catmull–Rom patch where its `4 × 4` nodes are, else the
    /// bilinear one where its corners are, else `None`.
    pub fn of(f: &Field<'_>, cell: C2) -> Option<Patch> {
        let mut w = [0.0; 36];
        let wide = w.iter_mut().enumerate().all(|(k, wk)| {
            f.at([cell[0] + (k % 6) as i32 - 2, cell[1] + (k / 6) as i32 - 2])
                .map(|x| *wk = x)
                .is_some()
        });
        if wide {
            return Some(Patch {
                cell,
                origin: f.plane.pos(cell),
                h: f.plane.h,
                kind: Kind::Hermite(w),
            });
        }
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

    /// Whether the patch is bicubic (Hermite or Catmull–Rom).
    pub fn is_cubic(&self) -> bool {
        !matches!(self.kind, Kind::Linear(_))
    }

    /// The value, gradient and Hessian at `x` (the cell's polynomial, also outside the cell).
    pub fn jet(&self, x: DVec2) -> Jet {
        let h = self.h;
        let (tx, ty) = ((x.x - self.origin.x) / h, (x.y - self.origin.y) / h);
        match &self.kind {
            Kind::Hermite(v) => {
                let (wx, wy) = (hermite6(tx), hermite6(ty));
                let mut s = [0.0; 6];
                for dy in 0..6 {
                    let mut r = [0.0; 3];
                    for dx in 0..6 {
                        let vk = v[6 * dy + dx];
                        r[0] += vk * wx[0][dx];
                        r[1] += vk * wx[1][dx];
                        r[2] += vk * wx[2][dx];
                    }
                    s[0] += wy[0][dy] * r[0];
                    s[1] += wy[0][dy] * r[1];
                    s[2] += wy[1][dy] * r[0];
                    s[3] += wy[0][dy] * r[2];
                    s[4] += wy[1][dy] * r[1];
                    s[5] += wy[2][dy] * r[0];
                }
                Jet {
                    value: s[0],
                    grad: DVec2::new(s[1], s[2]) / h,
                    hess: [s[3] / (h * h), s[4] / (h * h), s[5] / (h * h)],
                }
            }
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

    /// The closest point to `p` on the patch's zero level, from a guess `q` near it, and
    /// whether it is the converged critical point of the distance (else the last iterate).
    ///
    /// Newton's method on the optimality system `q − p + λ∇u(q) = 0`, `u(q) = 0` (3 × 3, with
    /// the patch's Hessian), started from `q` projected onto the level; it stops when the level
    /// residual `|u|/|∇u|` and the tangential residual `|(q − p) × ∇u|/|∇u|` are both below
    /// `1e-11 h`, usually after 2–4 steps. Steps are limited to half a cell and the point stays
    /// within one cell of the patch's cell. Where Newton does not converge in 20 steps, the
    /// alternating iteration (tangential moves towards the foot of `p`, projections onto the
    /// level; linearly convergent) takes over from the guess.
    pub fn closest(&self, p: DVec2, q: DVec2) -> (DVec2, bool) {
        let lo = self.origin - DVec2::splat(self.h);
        let hi = self.origin + DVec2::splat(2.0 * self.h);
        let tol = 1e-11 * self.h;
        let start = self.project(q.clamp(lo, hi), 4);
        let mut x = start;
        let mut lam = {
            let g = self.jet(x).grad;
            let g2 = g.length_squared();
            if !(g2 > 1e-300 && g2.is_finite()) {
                return (x, false);
            }
            (p - x).dot(g) / g2
        };
        for _ in 0..20 {
            let j = self.jet(x);
            let g = j.grad;
            let gl = g.length();
            if !(gl > 1e-150 && gl.is_finite()) {
                break;
            }
            let r = x - p + lam * g;
            let (lev, tang) = (j.value.abs() / gl, (x - p).perp_dot(g).abs() / gl);
            if lev <= tol && tang <= tol {
                return (x, true);
            }
            // [[1 + λHxx, λHxy, gx], [λHxy, 1 + λHyy, gy], [gx, gy, 0]] (dx, dy, dλ) = −(r, u).
            let (a, b, c) = (
                1.0 + lam * j.hess[0],
                lam * j.hess[1],
                1.0 + lam * j.hess[2],
            );
            let det = -(a * g.y * g.y - 2.0 * b * g.x * g.y + c * g.x * g.x);
            if det.is_nan() || det.abs() <= 1e-300 {
                break;
            }
            let rhs = [-r.x, -r.y, -j.value];
            // Cramer's rule on the symmetric 3 × 3 system.
            let m = [[a, b, g.x], [b, c, g.y], [g.x, g.y, 0.0]];
            let solve = |col: usize| {
                let mut k = m;
                for (row, rv) in k.iter_mut().zip(rhs) {
                    row[col] = rv;
                }
                (k[0][0] * (k[1][1] * k[2][2] - k[1][2] * k[2][1])
                    - k[0][1] * (k[1][0] * k[2][2] - k[1][2] * k[2][0])
                    + k[0][2] * (k[1][0] * k[2][1] - k[1][1] * k[2][0]))
                    / det
            };
            let (dx, dl) = (DVec2::new(solve(0), solve(1)), solve(2));
            let len = dx.length();
            if !len.is_finite() || !dl.is_finite() {
                break;
            }
            let s = if len > 0.5 * self.h {
                0.5 * self.h / len
            } else {
                1.0
            };
            x = (x + s * dx).clamp(lo, hi);
            lam += s * dl;
        }
        (self.closest_alternating(p, start), false)
    }

    /// The alternating iteration of [`Patch::closest`]'s fallback: 12 tangential moves towards
    /// the foot of `p`, each followed by a projection onto the level.
    fn closest_alternating(&self, p: DVec2, mut q: DVec2) -> DVec2 {
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

    /// Whether `x` lies in the patch's cell, within `tol` cells.
    pub fn contains(&self, x: DVec2, tol: f64) -> bool {
        let t = (x - self.origin) / self.h;
        t.min_element() >= -tol && t.max_element() <= 1.0 + tol
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
    // The six-node Hermite cubic where the nodes at −2 and 3 are band nodes (what a Hermite
    // patch of a cell on this edge gives along it), else Catmull–Rom.
    let wide = match (f.at(a.offset(axis, -2)), f.at(a.offset(axis, 3))) {
        (Some(vmm), Some(vpp)) => Some([vmm, vm, va, vb, vp, vpp]),
        _ => None,
    };
    let v = [vm, va, vb, vp];
    let eval = |t: f64| match wide {
        Some(u) => {
            let w = hermite6(t);
            (
                (0..6).map(|k| u[k] * w[0][k]).sum::<f64>(),
                (0..6).map(|k| u[k] * w[1][k]).sum::<f64>(),
            )
        }
        None => {
            let w = catmull_rom(t);
            (
                (0..4).map(|k| v[k] * w[0][k]).sum::<f64>(),
                (0..4).map(|k| v[k] * w[1][k]).sum::<f64>(),
            )
        }
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
        // The six-node Hermite patches reproduce cubics (interpolation error O(h⁴)).
        let cub = |p: DVec2| q(p) + 0.7 * p.x * p.x * p.x - 0.4 * p.x * p.y * p.y;
        let u: Vec<f64> = band.coords().map(|c| cub(plane.pos(c))).collect();
        let f3 = Field {
            plane: &plane,
            band: &band,
            u: &u,
        };
        let x = DVec2::new(0.43, 0.61);
        let p = Patch::of(&f3, locate(&plane, x).unwrap()).unwrap();
        assert!(matches!(p.kind, Kind::Hermite(_)));
        let j = p.jet(x);
        let g = DVec2::new(
            1.0 - 2.0 * x.y + 3.0 * x.x + 2.1 * x.x * x.x - 0.4 * x.y * x.y,
            -2.0 * x.x - 2.0 * x.y - 0.8 * x.x * x.y,
        );
        assert!((j.value - cub(x)).abs() < 1e-12 && (j.grad - g).length() < 1e-10);
        assert!((j.hess[0] - (3.0 + 4.2 * x.x)).abs() < 1e-8);
        assert!((j.hess[1] + 2.0 + 0.8 * x.y).abs() < 1e-8);
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
