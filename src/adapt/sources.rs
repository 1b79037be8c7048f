//! Metric sources: where the metric (and optionally the P1 fields) at a new vertex come from.
//!
//! A [`MetricSource`] is queried by the operators whenever they create or move a vertex: an
//! analytic source (a shape with exact derivatives) re-evaluates the metric and the level set
//! exactly there, which keeps the adapted mesh consistent with the geometry instead of with an
//! interpolation of it.

use crate::error::{Error, Result};
use crate::geom::DVec2;
use crate::levelset::shapes::Shape;
use crate::mesh::Mesh2;
use crate::metric::{geometric_metric, MetricBounds, Sym2};
use rayon::prelude::*;

/// Where the metric at a point comes from. `metric_at` returning `None` means "interpolate from
/// the surrounding vertices"; `fields_at` returning `false` means the same for the P1 fields.
pub trait MetricSource: Sync {
    /// The metric at `p`, or `None` to interpolate.
    fn metric_at(&self, p: DVec2) -> Option<Sym2>;
    /// Writes the values of the carried P1 fields at `p` into `out` and returns `true`, or
    /// returns `false` to interpolate them.
    fn fields_at(&self, _p: DVec2, _out: &mut [f64]) -> bool {
        false
    }
}

/// The source that always interpolates (a given metric field, e.g. read from a `.sol`).
#[derive(Debug, Clone, Copy, Default)]
pub struct NoSource;

impl MetricSource for NoSource {
    fn metric_at(&self, _p: DVec2) -> Option<Sym2> {
        None
    }
}

/// The geometric level-set metric of 004 eq. (6), `M = ∇u ∇uᵀ / hmin² + |D²u| / ε`, applied in
/// the band `|u| < band` around the zero level and bounded by `hmin`, `hmax`, `max_aniso`
/// ([`crate::metric::MetricBounds`]). Outside the band the sizes of the band metric grow linearly with
/// the distance, `h ← min(hmax, h + grade (|u| - band))` (an analytic gradation that keeps the
/// field continuous and can be re-evaluated anywhere; `grade = inf` gives the plain "hmax
/// outside the band" rule). `isotropic` replaces the metric by `λ_max I` (the smallest size of
/// eq. (6) in every direction: the isotropic mesh with the same resolution across the
/// interface, the reference of the "anisotropy pays" comparison).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct LevelSetMetric {
    /// Interface error bound ε of eq. (6).
    pub eps: f64,
    /// Smallest edge size allowed (`h_min` of eq. (6)).
    pub hmin: f64,
    /// Largest edge size allowed.
    pub hmax: f64,
    /// Largest ratio of the two sizes of one metric.
    pub max_aniso: f64,
    /// Half-width of the band around the zero level where eq. (6) applies.
    pub band: f64,
    /// Growth rate of the sizes outside the band (`inf`: `hmax` right outside the band).
    pub grade: f64,
    /// Whether derivatives come from the exact shape (`true`) or from recovery on the P1 field.
    pub analytic: bool,
    /// Isotropic variant.
    pub isotropic: bool,
}

impl Default for LevelSetMetric {
    fn default() -> Self {
        LevelSetMetric {
            eps: 1e-4,
            hmin: 1e-3,
            hmax: 0.2,
            max_aniso: 1e4,
            band: 5e-4,
            grade: 1.0,
            analytic: true,
            isotropic: false,
        }
    }
}

impl LevelSetMetric {
    /// An error unless `eps > 0`, the bounds are valid, `band > 0` and `grade > 0`.
    pub fn validate(&self) -> Result<()> {
        self.bounds().validate()?;
        if !(self.eps > 0.0 && self.band > 0.0 && self.grade > 0.0) {
            return Err(Error::InvalidInput(format!(
                "level-set metric: need eps > 0, band > 0, grade > 0 (got {}, {}, {})",
                self.eps, self.band, self.grade
            )));
        }
        Ok(())
    }

    /// The size bounds.
    pub fn bounds(&self) -> MetricBounds {
        MetricBounds {
            hmin: self.hmin,
            hmax: self.hmax,
            max_aniso: self.max_aniso,
        }
    }

    /// The metric at a point where the level set has value `u`, gradient `grad` and Hessian
    /// `hess` (see the type documentation; 004 eq. (6)).
    pub fn metric(&self, u: f64, grad: DVec2, hess: &Sym2) -> Sym2 {
        let b = self.bounds();
        let mut m = b.apply(&geometric_metric(grad, hess, self.hmin, self.eps));
        if self.isotropic {
            // The smallest size of eq. (6) in every direction.
            let (l, _) = m.eigen();
            m = Sym2::scalar(l[1]);
        }
        let d = u.abs() - self.band;
        if d > 0.0 {
            if !self.grade.is_finite() {
                m = Sym2::iso(self.hmax);
            } else {
                let (l, v) = m.eigen();
                let grow = |l: f64| {
                    let h = (1.0 / l.sqrt() + self.grade * d).min(self.hmax);
                    1.0 / (h * h)
                };
                m = Sym2::from_eigen([grow(l[0]), grow(l[1])], v);
            }
        }
        m
    }
}

/// An analytic level-set source: `f(p) = (u, ∇u, D²u)` exactly (e.g. a shape's signed distance),
/// turned into the metric by a [`LevelSetMetric`]. It re-evaluates the metric at every new or
/// moved vertex and, as field 0, the level set itself (further fields are interpolated).
pub struct AnalyticLevelSetSource<F> {
    /// The level set and its derivatives at a point: `(u, ∇u, D²u)`.
    pub f: F,
    /// How the derivatives become a metric.
    pub metric: LevelSetMetric,
}

impl<F: Fn(DVec2) -> (f64, DVec2, Sym2) + Sync> AnalyticLevelSetSource<F> {
    /// The source for `f` with metric parameters `metric`.
    pub fn new(f: F, metric: LevelSetMetric) -> Self {
        AnalyticLevelSetSource { f, metric }
    }

    /// The metric at every vertex of `mesh` and the level set there.
    pub fn evaluate(&self, mesh: &Mesh2) -> (Vec<Sym2>, Vec<f64>) {
        let vals: Vec<(Sym2, f64)> = mesh
            .points
            .par_iter()
            .map(|&p| {
                let (u, g, h) = (self.f)(p);
                (self.metric.metric(u, g, &h), u)
            })
            .collect();
        vals.into_iter().unzip()
    }
}

impl<F: Fn(DVec2) -> (f64, DVec2, Sym2) + Sync> MetricSource for AnalyticLevelSetSource<F> {
    fn metric_at(&self, p: DVec2) -> Option<Sym2> {
        let (u, g, h) = (self.f)(p);
        Some(self.metric.metric(u, g, &h))
    }
    fn fields_at(&self, p: DVec2, out: &mut [f64]) -> bool {
        // Only field 0 is known; the others would need interpolation, so only claim the fields
        // when there is exactly one.
        if out.len() == 1 {
            out[0] = (self.f)(p).0;
            true
        } else {
            false
        }
    }
}

impl LevelSetMetric {
    /// The metric at every vertex from the P1 level set `u` alone: gradient and Hessian by the
    /// least-squares recovery of 004 §4.3 ([`crate::recovery::recover_ls`]), then
    /// [`LevelSetMetric::metric`]. Errors: those of the recovery (bad field, tiny components).
    pub fn field_from_p1(&self, mesh: &Mesh2, u: &[f64]) -> Result<Vec<Sym2>> {
        self.validate()?;
        let rec = crate::recovery::recover_ls(mesh, u)?;
        Ok((0..mesh.n_points())
            .into_par_iter()
            .map(|v| self.metric(u[v], rec.gradient[v], &rec.hessian[v]))
            .collect())
    }
}

/// The interpolation-error metric of a P1 field: recovered Hessian (004 §4.3) turned into the
/// multiscale `L^p` metric with a target vertex count ([`crate::metric::multiscale_lp`]), or its
/// isotropic variant.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct HessianMetric {
    /// The `L^p` norm exponent (`f64::INFINITY` allowed).
    pub p: f64,
    /// The vertex count the metric's complexity is scaled to.
    pub target_vertices: usize,
    /// Smallest edge size allowed.
    pub hmin: f64,
    /// Largest edge size allowed.
    pub hmax: f64,
    /// Largest ratio of the two sizes of one metric.
    pub max_aniso: f64,
    /// Use the isotropic variant (the smaller size in every direction).
    pub isotropic: bool,
}

impl Default for HessianMetric {
    fn default() -> Self {
        HessianMetric {
            p: 2.0,
            target_vertices: 5000,
            hmin: 1e-4,
            hmax: 0.5,
            max_aniso: 1e4,
            isotropic: false,
        }
    }
}

impl HessianMetric {
    /// The metric field for the P1 field `u` on `mesh`.
    pub fn field(&self, mesh: &Mesh2, u: &[f64]) -> Result<Vec<Sym2>> {
        let bounds = MetricBounds::new(self.hmin, self.hmax, self.max_aniso)?;
        let h = crate::recovery::hessian_ls(mesh, u)?;
        if self.isotropic {
            crate::metric::interpolation_error_metric_iso(
                mesh,
                &h,
                self.p,
                self.target_vertices,
                &bounds,
            )
        } else {
            crate::metric::multiscale_lp(mesh, &h, self.p, self.target_vertices, &bounds)
        }
    }
}

/// Largest absolute eigenvalue of a symmetric 2x2 matrix.
fn spectral_norm(h: &Sym2) -> f64 {
    let (l, _) = h.eigen();
    l[0].abs().max(l[1].abs())
}

/// `(u, ∇u, H)` at `p` for the eq. (6) metric (004 §4.2) with kinks resolved at scale `delta`:
/// `H` is the shape's exact Hessian or, when its spectral norm is more than twice as large, the
/// Hessian seen at scale `delta`, the symmetrised central differences of the exact gradient
/// `H_δ e_i = (∇u(p + δ e_i) - ∇u(p - δ e_i)) / 2δ`.
///
/// Where `u` is smooth on the scale `δ`, `H_δ = D²u + O(δ²)` and the exact Hessian is kept
/// exactly (the factor 2 keeps round-off from switching). On
/// the medial axis through a corner of the shape the gradient jumps by `[∇u]` (up to `√2` at a
/// right-angle slot corner) and the pointwise Hessian is zero on both sides — the hypothesis of
/// 004 Theorem 1 (Lipschitz derivatives) fails there and eq. (6) would let the elements stretch
/// across the kink. `|H_δ| ≈ |[∇u]| / 2δ` within `δ` of the kink instead, which eq. (6) bounds
/// to `hmin` across it when `δ ≈ hmin`: the P1 interpolant sees the kink at the scale of its
/// elements.
pub fn derivatives_at_scale(shape: &dyn Shape, p: DVec2, delta: f64) -> (f64, DVec2, Sym2) {
    let (u, g, h) = (shape.distance(p), shape.gradient(p), shape.hessian(p));
    let dx = DVec2::new(delta, 0.0);
    let dy = DVec2::new(0.0, delta);
    let gx = (shape.gradient(p + dx) - shape.gradient(p - dx)) / (2.0 * delta);
    let gy = (shape.gradient(p + dy) - shape.gradient(p - dy)) / (2.0 * delta);
    let hd = Sym2::new(gx.x, 0.5 * (gx.y + gy.x), gy.y);
    if spectral_norm(&hd) > 2.0 * spectral_norm(&h) {
        (u, g, hd)
    } else {
        (u, g, h)
    }
}
