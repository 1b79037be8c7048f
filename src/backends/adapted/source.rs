//! The metric source of a re-adaptation: a new or moved vertex gets the value of the quadratic
//! reconstruction of the level set the mesh carried before the remeshing, built from the
//! least-squares gradients and Hessians of 004 §4.3 (exact for quadratics). Plain P1
//! interpolation would move a curved zero level at every collapse: the interpolant of a convex
//! distance lies above it, so a circle shrinks a little at each re-adaptation.

use crate::adapt::MetricSource;
use crate::error::Result;
use crate::geom::DVec2;
use crate::mesh::{Location, Mesh2};
use crate::metric::Sym2;
use crate::recovery::{recover_ls, Recovered};

/// Above this ratio `max ‖H_j − H_k‖ / max ‖H_k‖` between the vertex Hessians of a triangle the
/// reconstruction falls back to P1 there (kinks of the distance, corners of the zero level).
const DISAGREEMENT: f64 = 0.5;

/// The quadratic reconstruction of a P1 field on a frozen copy of its mesh: in triangle
/// `(x_0, x_1, x_2)` with barycentric coordinates `λ_k`,
/// `q(p) = Σ λ_k [u_k + g_k·(p − x_k) + ½ (p − x_k)ᵀ H_k (p − x_k)]`. The metric is left to
/// interpolation.
pub(crate) struct QuadraticSource {
    mesh: Mesh2,
    u: Vec<f64>,
    rec: Recovered,
}

fn frobenius(h: &Sym2) -> f64 {
    (h.xx * h.xx + 2.0 * h.xy * h.xy + h.yy * h.yy).sqrt()
}

impl QuadraticSource {
    /// The reconstruction of `u` on `mesh`. Errors: those of the recovery.
    pub(crate) fn new(mesh: &Mesh2, u: &[f64]) -> Result<QuadraticSource> {
        Ok(QuadraticSource {
            mesh: mesh.clone(),
            u: u.to_vec(),
            rec: recover_ls(mesh, u)?,
        })
    }

    /// The reconstructed value at `p`.
    pub(crate) fn value(&self, p: DVec2) -> f64 {
        let start = self.mesh.live_tris().next().unwrap_or(0) as u32;
        let (Location::Inside { tri, bary } | Location::Outside { tri, bary }) =
            self.mesh.locate(p, start);
        let t = self.mesh.tris[tri as usize].map(|v| v as usize);
        let linear: f64 = (0..3).map(|k| bary[k] * self.u[t[k]]).sum();
        let h = t.map(|v| self.rec.hessian[v]);
        let size = h.iter().map(frobenius).fold(0.0, f64::max);
        let spread = (0..3)
            .map(|k| {
                let (a, b) = (h[k], h[(k + 1) % 3]);
                frobenius(&Sym2::new(a.xx - b.xx, a.xy - b.xy, a.yy - b.yy))
            })
            .fold(0.0, f64::max);
        if spread > DISAGREEMENT * size {
            return linear;
        }
        (0..3)
            .map(|k| {
                let v = t[k];
                let d = p - self.mesh.points[v];
                let hd = DVec2::new(h[k].xx * d.x + h[k].xy * d.y, h[k].xy * d.x + h[k].yy * d.y);
                bary[k] * (self.u[v] + self.rec.gradient[v].dot(d) + 0.5 * d.dot(hd))
            })
            .sum()
    }
}

impl MetricSource for QuadraticSource {
    fn metric_at(&self, _p: DVec2) -> Option<Sym2> {
        None
    }
    fn fields_at(&self, p: DVec2, out: &mut [f64]) -> bool {
        if out.len() == 1 {
            out[0] = self.value(p);
            true
        } else {
            false
        }
    }
}

/// The area-weighted mean of `||∇u_h| − 1|` over the triangles cut by the zero level (0 when
/// none is cut): how far the P1 field is from a signed distance at the interface.
pub(crate) fn distance_defect(mesh: &Mesh2, u: &[f64]) -> f64 {
    let (mut sum, mut area) = (0.0, 0.0);
    for t in mesh.live_tris() {
        let tri = mesh.tris[t].map(|v| v as usize);
        let neg = tri.iter().filter(|&&v| u[v] < 0.0).count();
        if neg == 0 || neg == 3 {
            continue;
        }
        let [p0, p1, p2] = mesh.tri_points(t);
        let (e1, e2) = (p1 - p0, p2 - p0);
        let det = e1.perp_dot(e2);
        let (d1, d2) = (u[tri[1]] - u[tri[0]], u[tri[2]] - u[tri[0]]);
        let g = DVec2::new(d1 * e2.y - d2 * e1.y, e1.x * d2 - e2.x * d1) / det;
        let a = 0.5 * det.abs();
        sum += a * (g.length() - 1.0).abs();
        area += a;
    }
    if area > 0.0 {
        sum / area
    } else {
        0.0
    }
}
