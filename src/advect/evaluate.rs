//! Evaluation of a P1 field at an arbitrary located point: plain P1 interpolation, or a limited
//! local quadratic reconstruction built from recovered vertex gradients and Hessians.
//!
//! The quadratic value at `p` in triangle `K = (x_0, x_1, x_2)` with barycentric coordinates
//! `λ_k` is the barycentric blend of the three vertex Taylor expansions
//! `q(p) = Σ_k λ_k [u_k + g_k·(p - x_k) + ½ (p - x_k)ᵀ H_k (p - x_k)]`,
//! which reproduces quadratics when `g_k`, `H_k` are exact, and is continuous across edges
//! (on an edge, only the two edge vertices have non-zero `λ`). It is used at the feet of the
//! characteristics so that `u^n ∘ X^n` (004 eq. (2)) keeps the accuracy of the smooth level set
//! instead of the O(h²) P1 interpolation error at every step.
//!
//! Limiter: near kinks (the slot corners of the Zalesak disk, the medial axis of a distance
//! function) the recovered Hessians are large and inconsistent. When the vertex Hessians of `K`
//! disagree by more than `disagreement` times their size, P1 is used; otherwise `q` is clamped
//! into the range of the element values widened by the size of the Taylor corrections.

use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::mesh::{check_p1_field, Location, Mesh2, NONE};
use crate::metric::Sym2;
use std::sync::Arc;

/// How a P1 field is evaluated between vertices.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Interpolation {
    /// Linear interpolation in the containing triangle.
    P1,
    /// Limited quadratic reconstruction (see the module documentation). `disagreement` is the
    /// ratio `max‖H_j − H_k‖ / max‖H_k‖` above which the element falls back to P1.
    Quadratic {
        /// Largest Hessian disagreement ratio for which the quadratic is used.
        disagreement: f64,
    },
}

impl Interpolation {
    /// The quadratic reconstruction with the default limiter threshold (0.5).
    pub const QUADRATIC: Interpolation = Interpolation::Quadratic { disagreement: 0.5 };
}

/// The value given to points outside the mesh (feet of characteristics that leave the domain).
#[derive(Clone, Default)]
pub enum Inflow {
    /// A constant value.
    Constant(f64),
    /// The P1 value at the closest point of the boundary triangle where the walk left the mesh
    /// (barycentric coordinates clamped to the triangle): constant extrapolation.
    #[default]
    Nearest,
    /// A prescribed function of the point.
    Function(Arc<dyn Fn(DVec2) -> f64 + Send + Sync>),
}

impl std::fmt::Debug for Inflow {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Inflow::Constant(c) => write!(f, "Constant({c})"),
            Inflow::Nearest => write!(f, "Nearest"),
            Inflow::Function(_) => write!(f, "Function(..)"),
        }
    }
}

/// Recovered per-vertex derivatives of a P1 field (gradient and Hessian), as computed by
/// [`crate::recovery::recover_ls`] (least-squares Taylor fit, 004 §4.3).
pub type Derivatives = crate::recovery::Recovered;

/// A P1 field on a mesh, ready to be evaluated at located points.
pub struct FieldEvaluator<'a> {
    mesh: &'a Mesh2,
    u: &'a [f64],
    interp: Interpolation,
    deriv: Option<Derivatives>,
    inflow: Inflow,
}

#[inline]
fn frob(h: &Sym2) -> f64 {
    (h.xx * h.xx + 2.0 * h.xy * h.xy + h.yy * h.yy).sqrt()
}

impl<'a> FieldEvaluator<'a> {
    /// Prepares the evaluation of `u` on `mesh`; recovers derivatives for the quadratic option.
    pub fn new(
        mesh: &'a Mesh2,
        u: &'a [f64],
        interp: Interpolation,
        inflow: Inflow,
    ) -> Result<FieldEvaluator<'a>> {
        check_p1_field(mesh.n_points(), u, "u")?;
        let deriv = match interp {
            Interpolation::P1 => None,
            Interpolation::Quadratic { disagreement } => {
                if disagreement.is_nan() || disagreement <= 0.0 {
                    return Err(Error::InvalidInput(format!(
                        "quadratic limiter threshold must be positive (got {disagreement})"
                    )));
                }
                Some(crate::recovery::recover_ls(mesh, u)?)
            }
        };
        Ok(FieldEvaluator {
            mesh,
            u,
            interp,
            deriv,
            inflow,
        })
    }

    /// As [`FieldEvaluator::new`] with derivatives supplied by the caller.
    pub fn with_derivatives(
        mesh: &'a Mesh2,
        u: &'a [f64],
        deriv: Derivatives,
        disagreement: f64,
        inflow: Inflow,
    ) -> Result<FieldEvaluator<'a>> {
        check_p1_field(mesh.n_points(), u, "u")?;
        if deriv.gradient.len() != u.len() || deriv.hessian.len() != u.len() {
            return Err(Error::InvalidInput(
                "derivatives do not match the field length".into(),
            ));
        }
        Ok(FieldEvaluator {
            mesh,
            u,
            interp: Interpolation::Quadratic { disagreement },
            deriv: Some(deriv),
            inflow,
        })
    }

    /// The mesh the field lives on.
    pub fn mesh(&self) -> &Mesh2 {
        self.mesh
    }

    /// The value at `p`, located in the mesh as `loc`.
    pub fn value(&self, p: DVec2, loc: &Location) -> f64 {
        match *loc {
            Location::Inside { tri, bary } => self.inside(tri as usize, bary, p),
            Location::Outside { tri, bary } => match &self.inflow {
                Inflow::Constant(c) => *c,
                Inflow::Function(f) => f(p),
                Inflow::Nearest => {
                    if tri == NONE || !bary.iter().all(|b| b.is_finite()) {
                        return 0.0;
                    }
                    let mut l = bary.map(|b| b.max(0.0));
                    let s: f64 = l.iter().sum();
                    if s <= 0.0 {
                        l = [1.0 / 3.0; 3];
                    } else {
                        l = l.map(|b| b / s);
                    }
                    self.p1(tri as usize, l)
                }
            },
        }
    }

    #[inline]
    fn p1(&self, t: usize, l: [f64; 3]) -> f64 {
        let tri = self.mesh.tris[t];
        l[0] * self.u[tri[0] as usize]
            + l[1] * self.u[tri[1] as usize]
            + l[2] * self.u[tri[2] as usize]
    }

    fn inside(&self, t: usize, l: [f64; 3], p: DVec2) -> f64 {
        let lin = self.p1(t, l);
        let (d, theta) = match (&self.deriv, self.interp) {
            (Some(d), Interpolation::Quadratic { disagreement }) => (d, disagreement),
            _ => return lin,
        };
        let tri = self.mesh.tris[t];
        let h = tri.map(|v| d.hessian[v as usize]);
        let size = h.iter().map(frob).fold(0.0, f64::max);
        let mut spread: f64 = 0.0;
        for j in 0..3 {
            for k in (j + 1)..3 {
                let diff = Sym2::new(h[j].xx - h[k].xx, h[j].xy - h[k].xy, h[j].yy - h[k].yy);
                spread = spread.max(frob(&diff));
            }
        }
        if spread > theta * size {
            return lin;
        }
        let mut q = 0.0;
        let mut corr: f64 = 0.0;
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        for k in 0..3 {
            let v = tri[k] as usize;
            let dx = p - self.mesh.points[v];
            let c2 = 0.5 * h[k].quad(dx);
            let taylor = self.u[v] + d.gradient[v].dot(dx) + c2;
            corr = corr.max(c2.abs());
            q += l[k] * taylor;
            lo = lo.min(self.u[v]);
            hi = hi.max(self.u[v]);
        }
        q.clamp(lo - corr, hi + corr)
    }
}
