//! Feet of the characteristics (004 §2.2).
//!
//! For a velocity field `v(t, x)`, the trajectory through `x` at time `t1` solves
//! `dX/dt = v(t, X)`, `X(t1) = x`; its *foot* is `X^n(x) = X(t0)` with `t0 < t1` (004 §2.2: the
//! characteristics-Galerkin scheme evaluates `u^n ∘ X^n`). The foot is found by integrating the
//! trajectory backwards over `[t0, t1]`, split into `substeps` equal sub-steps, with an explicit
//! Runge–Kutta scheme: forward Euler (first order, for tests), the midpoint predictor–corrector
//! (second order, the scheme 004 cites from its reference \[26\]) or classical RK4.

use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::mesh::{Location, Mesh2, NONE};
use rayon::prelude::*;

/// A velocity field `v(t, x)`. Any `Fn(f64, DVec2) -> DVec2 + Sync` is one.
pub trait Velocity: Sync {
    /// The velocity at time `t` and point `x`.
    fn at(&self, t: f64, x: DVec2) -> DVec2;
}

impl<F: Fn(f64, DVec2) -> DVec2 + Sync> Velocity for F {
    #[inline]
    fn at(&self, t: f64, x: DVec2) -> DVec2 {
        self(t, x)
    }
}

/// The rigid rotation `v = omega (-y, x)` around the origin (004 §5.1 with `omega = 1`).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rotation {
    /// Angular velocity (counter-clockwise positive).
    pub omega: f64,
}

impl Velocity for Rotation {
    #[inline]
    fn at(&self, _t: f64, x: DVec2) -> DVec2 {
        self.omega * DVec2::new(-x.y, x.x)
    }
}

/// The time integrator used to trace a characteristic backwards.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FootScheme {
    /// Forward Euler (first order). For tests and comparisons only.
    Euler,
    /// Midpoint predictor–corrector (second order): `x* = x - dt/2 v(t1, x)`,
    /// `X = x - dt v(t1 - dt/2, x*)`.
    Midpoint,
    /// Classical fourth-order Runge–Kutta.
    #[default]
    Rk4,
}

/// How the feet are computed: scheme and number of equal sub-steps over `[t0, t1]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FootOptions {
    /// The time integrator.
    pub scheme: FootScheme,
    /// Number of sub-steps (at least 1).
    pub substeps: usize,
}

impl Default for FootOptions {
    fn default() -> Self {
        FootOptions {
            scheme: FootScheme::Rk4,
            substeps: 4,
        }
    }
}

impl FootOptions {
    /// Validates the options.
    pub fn validate(&self) -> Result<()> {
        if self.substeps == 0 || self.substeps > 1_000_000 {
            return Err(Error::InvalidInput(format!(
                "foot sub-steps must be in 1..=1e6 (got {})",
                self.substeps
            )));
        }
        Ok(())
    }
}

/// The foot `X(t0)` of the characteristic through `x` at time `t1` (004 §2.2), integrated
/// backwards with `opts.scheme` over `opts.substeps` equal sub-steps.
pub fn foot<V: Velocity + ?Sized>(v: &V, x: DVec2, t0: f64, t1: f64, opts: &FootOptions) -> DVec2 {
    let n = opts.substeps.max(1);
    let h = (t1 - t0) / n as f64;
    let mut p = x;
    let mut t = t1;
    for _ in 0..n {
        p = match opts.scheme {
            FootScheme::Euler => p - h * v.at(t, p),
            FootScheme::Midpoint => {
                let mid = p - 0.5 * h * v.at(t, p);
                p - h * v.at(t - 0.5 * h, mid)
            }
            FootScheme::Rk4 => {
                let k1 = v.at(t, p);
                let k2 = v.at(t - 0.5 * h, p - 0.5 * h * k1);
                let k3 = v.at(t - 0.5 * h, p - 0.5 * h * k2);
                let k4 = v.at(t - h, p - h * k3);
                p - h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4)
            }
        };
        t -= h;
    }
    p
}

/// Locates the points `pts` in `mesh` by walking (`Mesh2::locate`). Each point's walk starts
/// from `hints[i]` when given and valid; otherwise the points are visited in Morton (Z-curve)
/// order of their coordinates and each walk starts from the previous hit of the same parallel
/// chunk, so every walk is a few steps long whatever the numbering of the points (adapted
/// meshes are not numbered coherently).
pub fn locate_all(mesh: &Mesh2, pts: &[DVec2], hints: Option<&[u32]>) -> Result<Vec<Location>> {
    if let Some(h) = hints {
        if h.len() != pts.len() {
            return Err(Error::InvalidInput(format!(
                "locate_all: {} hints for {} points",
                h.len(),
                pts.len()
            )));
        }
    }
    if mesh.n_live_tris() == 0 {
        return Err(Error::InvalidInput(
            "locate_all: the mesh has no triangle".into(),
        ));
    }
    let nt = mesh.n_tris() as u32;
    let (lo, hi) = mesh
        .bounding_box()
        .ok_or_else(|| Error::InvalidInput("locate_all: the mesh has no vertex".into()))?;
    let order: Vec<u32> = if hints.is_some() {
        (0..pts.len() as u32).collect()
    } else {
        morton_order(pts, lo, hi)
    };
    let chunk = 512;
    let located: Vec<Location> = order
        .par_chunks(chunk)
        .flat_map_iter(|idx| {
            let mut prev = NONE;
            idx.iter()
                .map(|&i| {
                    let i = i as usize;
                    let mut start = prev;
                    if let Some(h) = hints {
                        if h[i] < nt && !mesh.is_deleted(h[i] as usize) {
                            start = h[i];
                        }
                    }
                    let loc = locate_one(mesh, pts[i], start, lo, hi);
                    prev = loc.tri();
                    loc
                })
                .collect::<Vec<_>>()
        })
        .collect();
    let mut out = vec![
        Location::Outside {
            tri: NONE,
            bary: [0.0; 3]
        };
        pts.len()
    ];
    for (k, &i) in order.iter().enumerate() {
        out[i as usize] = located[k];
    }
    Ok(out)
}

/// One walk; points outside the bounding box `[lo, hi]` are reported outside, with the
/// triangle that holds their clamped position (so the walk does not end in `locate`'s O(n)
/// brute-force confirmation).
fn locate_one(mesh: &Mesh2, p: DVec2, start: u32, lo: DVec2, hi: DVec2) -> Location {
    if p.cmpge(lo).all() && p.cmple(hi).all() {
        return mesh.locate(p, start);
    }
    let tri = mesh.locate(p.clamp(lo, hi), start).tri();
    let bary = if tri == NONE {
        [f64::NAN; 3]
    } else {
        let [a, b, c] = mesh.tri_points(tri as usize);
        crate::geom::barycentric(a, b, c, p)
    };
    Location::Outside { tri, bary }
}

/// The indices of `pts` sorted along a Z-order curve of a 2^16 x 2^16 grid of `[lo, hi]`.
fn morton_order(pts: &[DVec2], lo: DVec2, hi: DVec2) -> Vec<u32> {
    let ext = (hi - lo).max(DVec2::splat(1e-300));
    let spread = |mut x: u64| {
        x &= 0xffff;
        x = (x | (x << 8)) & 0x00ff_00ff;
        x = (x | (x << 4)) & 0x0f0f_0f0f;
        x = (x | (x << 2)) & 0x3333_3333;
        (x | (x << 1)) & 0x5555_5555
    };
    let mut keys: Vec<(u64, u32)> = pts
        .par_iter()
        .enumerate()
        .map(|(i, p)| {
            let q = ((*p - lo) / ext).clamp(DVec2::ZERO, DVec2::ONE) * 65535.0;
            (spread(q.x as u64) | (spread(q.y as u64) << 1), i as u32)
        })
        .collect();
    keys.par_sort_unstable();
    keys.into_iter().map(|(_, i)| i).collect()
}

/// For each vertex of `mesh`, one triangle containing it (its seed `vert_tri`): the natural
/// start of the walk for the vertex's own foot when the old and the new mesh coincide.
pub fn vertex_hints(mesh: &Mesh2) -> Vec<u32> {
    mesh.vert_tri.clone()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn rot_err(scheme: FootScheme, substeps: usize) -> f64 {
        let v = Rotation { omega: 1.0 };
        let x = DVec2::new(0.3, 1.1);
        let dt = std::f64::consts::PI / 8.0;
        let f = foot(&v, x, 0.0, dt, &FootOptions { scheme, substeps });
        let (s, c) = (-dt).sin_cos();
        let exact = DVec2::new(c * x.x - s * x.y, s * x.x + c * x.y);
        (f - exact).length()
    }

    #[test]
    fn orders_of_the_foot_schemes() {
        for (scheme, order) in [
            (FootScheme::Euler, 1.0),
            (FootScheme::Midpoint, 2.0),
            (FootScheme::Rk4, 4.0),
        ] {
            let e1 = rot_err(scheme, 8);
            let e2 = rot_err(scheme, 16);
            let p = (e1 / e2).log2();
            assert!((p - order).abs() < 0.15, "{scheme:?}: order {p}");
        }
        assert!(rot_err(FootScheme::Rk4, 4) < 1e-6);
    }
}
