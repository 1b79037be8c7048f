//! Streamlines of a P1 velocity field (for figures such as 004 Fig. 4): classical RK4 on the
//! unit direction `u / |u|` (so the step is an arc length), the velocity interpolated in the
//! triangle found by [`Mesh2::locate`] from the previous hit.

use crate::geom::DVec2;
use crate::mesh::{Location, Mesh2};

/// Options of [`streamline`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StreamlineOptions {
    /// Arc-length step.
    pub step: f64,
    /// Maximal arc length in each direction.
    pub max_length: f64,
    /// Stop where `|u|` falls below this (stagnation).
    pub min_speed: f64,
}

impl Default for StreamlineOptions {
    fn default() -> Self {
        StreamlineOptions {
            step: 2e-3,
            max_length: 3.0,
            min_speed: 1e-12,
        }
    }
}

/// The P1 velocity at `p`, `None` outside the mesh.
fn velocity(mesh: &Mesh2, u: &[DVec2], p: DVec2, hint: &mut u32) -> Option<DVec2> {
    match mesh.locate(p, *hint) {
        Location::Inside { tri, bary } => {
            *hint = tri;
            let t = mesh.tris[tri as usize];
            Some(
                bary[0] * u[t[0] as usize]
                    + bary[1] * u[t[1] as usize]
                    + bary[2] * u[t[2] as usize],
            )
        }
        Location::Outside { .. } => None,
    }
}

/// Integrates the streamline through `seed` backward and forward; the polyline runs
/// upstream → downstream. Stops at the boundary, at stagnation, after `max_length`, or when a
/// closed streamline returns to its seed (then only the forward branch is kept). `u` holds one
/// velocity per vertex; a mismatched length gives an empty line.
pub fn streamline(mesh: &Mesh2, u: &[DVec2], seed: DVec2, opts: &StreamlineOptions) -> Vec<DVec2> {
    if u.len() != mesh.n_points() || opts.step.is_nan() || opts.step <= 0.0 {
        return Vec::new();
    }
    let mut hint = 0u32;
    if velocity(mesh, u, seed, &mut hint).is_none() {
        return Vec::new();
    }
    let branch = |sign: f64, hint: &mut u32| -> (Vec<DVec2>, bool) {
        let h = opts.step;
        let dir = |p: DVec2, hint: &mut u32| -> Option<DVec2> {
            let v = velocity(mesh, u, p, hint)?;
            let s = v.length();
            (s > opts.min_speed).then(|| sign * v / s)
        };
        let mut pts = vec![seed];
        let mut p = seed;
        let steps = (opts.max_length / h).ceil() as usize;
        for k in 0..steps {
            let Some(k1) = dir(p, hint) else { break };
            let Some(k2) = dir(p + 0.5 * h * k1, hint) else {
                break;
            };
            let Some(k3) = dir(p + 0.5 * h * k2, hint) else {
                break;
            };
            let Some(k4) = dir(p + h * k3, hint) else {
                break;
            };
            p += h / 6.0 * (k1 + 2.0 * k2 + 2.0 * k3 + k4);
            pts.push(p);
            if k > 10 && (p - seed).length() < h {
                pts.push(seed);
                return (pts, true);
            }
        }
        (pts, false)
    };
    let (fwd, closed) = branch(1.0, &mut hint);
    if closed {
        return fwd;
    }
    let (mut back, _) = branch(-1.0, &mut hint);
    back.reverse();
    back.pop();
    back.extend(fwd);
    back
}
