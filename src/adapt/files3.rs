//! Adapting a user's tetrahedral mesh (004 §5) to what comes with it, and the metric gradation in
//! 3D: the pieces between [`super::run3`], which adapts to a metric given as a function of
//! position, and fields given at the vertices of a mesh.
//!
//! - [`MetricField3`]: a vertex metric field on a tetrahedral (background) mesh as a function of
//!   position: the point is located in the background mesh (an R-tree,
//!   [`crate::levelset::compare3::TetLocator`]) and the four vertex metrics are interpolated with
//!   the barycentric weights `λ_i` by one of two rules ([`FieldInterpolation3`]):
//!   - *linear sizes* (metric files): the size tensors `H_i = M_i^{-1/2}` are interpolated
//!     linearly, `M = (Σ λ_i H_i)^{-2}`. When the vertex metrics share their eigenvectors (as
//!     every axis-aligned field does) every size `h` is the P1 interpolant of the vertex sizes,
//!     so a field linear in `h` on each background tetrahedron is reproduced exactly (the 2D
//!     adaptation of metric files interpolates sizes linearly too,
//!     [`crate::metric::lerp_sizes`]). With rotating eigenvectors the interpolated size tensor is
//!     still SPD (a convex combination of SPD tensors), does not depend on the order of the
//!     vertices (unlike a pairwise simultaneous reduction), and its sizes lie between the
//!     smallest and the largest size of the four vertex metrics (the eigenvalues of a convex
//!     combination of symmetric matrices lie between the extreme eigenvalues of the terms).
//!   - *log-Euclidean* (fields built inside the library, [`run3_graded`]): `exp(Σ λ_i log M_i)`;
//!     sizes vary geometrically, so between a fine and a coarse vertex the field is finer than
//!     the linear one.
//! - [`DiscreteLevelSet3`]: a P1 level set on a tetrahedral mesh as a 3D shape (as the 2D
//!   `DiscreteLevelSet`): the distance is the exact distance to the P1 zero level (its
//!   triangles in an R-tree) with the sign of the P1 interpolant, the gradient the unit vector
//!   from the closest point, the Hessian the shape operator `P H P` with `H` recovered by least
//!   squares from the redistanced field (004 §2.2, §4.3) and interpolated P1.
//! - [`shape_metric3`]: the metric [`super::run3`] adapts to for a shape, at given vertices
//!   (004 eq. (6), [`super::level_set_metric3`]), optionally graded over the tetrahedra
//!   ([`crate::metric::gradate_tets`]) — what `anisomesh metric` writes for a 3D mesh.
//! - [`run3_graded`]: adapting with a graded metric: rounds of (metric at the vertices of the
//!   current mesh, graded over its tetrahedra; adapt to the exact metric intersected with the
//!   graded field interpolated from that mesh) until the vertex count changes by less than 5 %.
//!   The intersection keeps every size of the exact metric (a band of eq. (6) narrower than
//!   the previous mesh's elements is never missed), and adds the gradation's smaller sizes.

use super::tet::run::Seen3;
use super::{level_set_metric3, run3, Adapted3, LevelSetMetric, Run3Options, Target3};
use crate::error::{Error, Result};
use crate::geom::DVec3;
use crate::levelset::compare3::{Facet, TetLocator};
use crate::levelset::compare_radial::zero_level_triangles;
use crate::levelset::redistance::redistance_geometric_cells;
use crate::levelset::triangulated::closest::closest_point;
use crate::levelset::{enclosed_measure, interface_measure, Shape};
use crate::mesh3::Mesh3;
use crate::metric::{gradate_tets, Sym3, SymTensor};
use crate::recovery::recover_ls3;
use rayon::prelude::*;
use rstar::RTree;

/// How [`MetricField3`] interpolates the vertex metrics inside a background tetrahedron (module
/// documentation).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum FieldInterpolation3 {
    /// `exp(Σ λ_i log M_i)`: sizes vary geometrically.
    #[default]
    LogEuclidean,
    /// `(Σ λ_i M_i^{-1/2})^{-2}`: sizes vary linearly (exactly so along common eigenvectors).
    LinearSizes,
}

/// A vertex metric field on a tetrahedral mesh as a function of position (module
/// documentation).
pub struct MetricField3<'a> {
    tets: &'a [[u32; 4]],
    loc: TetLocator<'a>,
    /// Per vertex: `log M` (log-Euclidean) or `M^{-1/2}` (linear sizes).
    stored: Vec<Sym3>,
    rule: FieldInterpolation3,
}

impl<'a> MetricField3<'a> {
    /// The field `metric` (one SPD tensor per vertex) on `tets` over `points`, interpolated
    /// log-Euclidean. Errors: a length mismatch, a tensor that is not SPD (its vertex named,
    /// 0-based), no tetrahedra.
    pub fn new(points: &'a [DVec3], tets: &'a [[u32; 4]], metric: &[Sym3]) -> Result<Self> {
        Self::with_rule(points, tets, metric, FieldInterpolation3::LogEuclidean)
    }

    /// The field `metric` on `tets` over `points`, interpolated by `rule`. Errors as
    /// [`MetricField3::new`].
    pub fn with_rule(
        points: &'a [DVec3],
        tets: &'a [[u32; 4]],
        metric: &[Sym3],
        rule: FieldInterpolation3,
    ) -> Result<Self> {
        if metric.len() != points.len() {
            return Err(Error::InvalidField {
                name: "metric".into(),
                msg: format!(
                    "{} tensors for {} vertices (need one per vertex)",
                    metric.len(),
                    points.len()
                ),
            });
        }
        for (v, m) in metric.iter().enumerate() {
            SymTensor::validate(m, v)?;
        }
        let stored = match rule {
            FieldInterpolation3::LogEuclidean => metric.par_iter().map(SymTensor::log).collect(),
            FieldInterpolation3::LinearSizes => metric.par_iter().map(|m| m.powf(-0.5)).collect(),
        };
        Ok(MetricField3 {
            tets,
            loc: TetLocator::new(points, tets)?,
            stored,
            rule,
        })
    }

    /// The metric at `p`: interpolated by the field's rule in the tetrahedron containing `p`
    /// (the nearest one, weights clipped, for a point just outside).
    pub fn at(&self, p: DVec3) -> Sym3 {
        let (t, w) = self.loc.locate(p);
        let v = self.tets[t as usize];
        let mut s = Sym3::default();
        for k in 0..4 {
            s = s.add(&self.stored[v[k] as usize].scale(w[k]));
        }
        match self.rule {
            FieldInterpolation3::LogEuclidean => SymTensor::exp(&s),
            FieldInterpolation3::LinearSizes => s.map_eigen(|h| 1.0 / (h * h)),
        }
    }
}

/// A P1 level set on a tetrahedral mesh as a 3D shape (module documentation).
pub struct DiscreteLevelSet3<'a> {
    points: &'a [DVec3],
    tets: &'a [[u32; 4]],
    u: &'a [f64],
    loc: TetLocator<'a>,
    hessian: Vec<Sym3>,
    facets: RTree<Facet>,
    volume: f64,
    area: f64,
}

impl<'a> DiscreteLevelSet3<'a> {
    /// The zero level of `u` on `tets` over `points`. Errors: an invalid field or cells, no
    /// zero level.
    pub fn new(points: &'a [DVec3], tets: &'a [[u32; 4]], u: &'a [f64]) -> Result<Self> {
        let (tris, volume) = zero_level_triangles(points, tets, u)?;
        if tris.is_empty() {
            let (lo, hi) = u
                .iter()
                .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &x| {
                    (a.min(x), b.max(x))
                });
            return Err(Error::EmptyLevelSet(format!(
                "the level set has no zero level on its mesh (values in [{lo:.3e}, {hi:.3e}])"
            )));
        }
        let d = redistance_geometric_cells(points, tets, u)?;
        let hessian = recover_ls3(points, tets, &d)?.hessian;
        Ok(DiscreteLevelSet3 {
            points,
            tets,
            u,
            loc: TetLocator::new(points, tets)?,
            hessian,
            area: interface_measure(points, tets, u)?,
            facets: RTree::bulk_load(tris.into_iter().map(Facet).collect()),
            volume,
        })
    }

    /// The closest point of the zero level to `p`.
    fn closest(&self, p: DVec3) -> DVec3 {
        let f = self
            .facets
            .nearest_neighbor(p.to_array())
            .expect("a zero level has triangles");
        let [a, b, c] = f.0;
        closest_point(p, a, b, c).0
    }

    /// The P1 gradient direction of the containing tetrahedron (for points on the zero level).
    fn p1_normal(&self, p: DVec3) -> DVec3 {
        let (t, _) = self.loc.locate(p);
        let v = self.tets[t as usize];
        let x = v.map(|i| self.points[i as usize]);
        let g = crate::geom::simplex::p1_gradient(&x, &v.map(|i| self.u[i as usize]));
        g.try_normalize().unwrap_or(DVec3::X)
    }
}

impl Shape<DVec3> for DiscreteLevelSet3<'_> {
    fn distance(&self, p: DVec3) -> f64 {
        let d = (p - self.closest(p)).length();
        if self.loc.interpolate(self.u, p) < 0.0 {
            -d
        } else {
            d
        }
    }
    fn gradient(&self, p: DVec3) -> DVec3 {
        let q = self.closest(p);
        match (p - q).try_normalize() {
            Some(n) if self.loc.interpolate(self.u, p) < 0.0 => -n,
            Some(n) => n,
            None => self.p1_normal(p),
        }
    }
    fn hessian(&self, p: DVec3) -> Sym3 {
        let (t, w) = self.loc.locate(p);
        let v = self.tets[t as usize];
        let mut h = Sym3::default();
        for k in 0..4 {
            h = h.add(&self.hessian[v[k] as usize].scale(w[k]));
        }
        let n = self.gradient(p);
        let proj = Sym3::IDENTITY.sub(&Sym3::outer(n));
        // P H P.
        let ph = |e: DVec3| proj.mul_vec(h.mul_vec(proj.mul_vec(e)));
        let (c0, c1, c2) = (ph(DVec3::X), ph(DVec3::Y), ph(DVec3::Z));
        Sym3::new(
            c0.x,
            0.5 * (c1.x + c0.y),
            0.5 * (c2.x + c0.z),
            c1.y,
            0.5 * (c2.y + c1.z),
            c2.z,
        )
    }
    fn exact_area(&self) -> Option<f64> {
        Some(self.volume)
    }
    fn exact_perimeter(&self) -> Option<f64> {
        Some(self.area)
    }
    fn name(&self) -> String {
        "the input's P1 zero level".into()
    }
}

/// 004 eq. (6) of `shape` with the setting `lm` ([`level_set_metric3`]) at `points`, graded over
/// `tets` with the factor `hgrad` when given ([`gradate_tets`]): the metric [`run3_graded`] (or
/// [`run3`] without gradation) adapts to, at those vertices. Errors: invalid options, a metric
/// that is not SPD at a vertex, an invalid `hgrad`.
pub fn shape_metric3(
    shape: &dyn Shape<DVec3>,
    lm: &LevelSetMetric,
    points: &[DVec3],
    tets: &[[u32; 4]],
    hgrad: Option<f64>,
) -> Result<Vec<Sym3>> {
    lm.validate()?;
    let seen = Seen3::new(shape, bounding_diameter(points));
    let mut m: Vec<Sym3> = points
        .par_iter()
        .map(|&p| {
            let (u, g, h) = seen.jet(p);
            level_set_metric3(lm, u, g, &h)
        })
        .collect();
    for (v, x) in m.iter().enumerate() {
        SymTensor::validate(x, v)?;
    }
    if let Some(beta) = hgrad {
        gradate_tets(points, tets, &mut m, beta)?;
    }
    Ok(m)
}

/// The length of the diagonal of the bounding box of `points` (1 for fewer than two points).
fn bounding_diameter(points: &[DVec3]) -> f64 {
    let lo = points
        .iter()
        .fold(DVec3::splat(f64::INFINITY), |a, &p| a.min(p));
    let hi = points
        .iter()
        .fold(DVec3::splat(f64::NEG_INFINITY), |a, &p| a.max(p));
    let d = (hi - lo).length();
    if d.is_finite() && d > 0.0 {
        d
    } else {
        1.0
    }
}

/// Rounds of at most this many adaptations in [`run3_graded`].
pub const GRADED_ROUNDS: usize = 4;

/// Adapts to `shape` (004 eq. (6) of `opts.metric`) with the metric graded with factor `beta`
/// (module documentation), from `start` or the Kuhn mesh of `opts`' box. The report's
/// volume, area and level set are the shape's, as [`run3`] gives them; its `adapt` counts
/// add up the rounds. Errors: those of [`run3`], `beta <= 1`.
pub fn run3_graded(
    shape: &dyn Shape<DVec3>,
    start: Option<&Mesh3>,
    opts: &Run3Options,
    beta: f64,
) -> Result<Adapted3> {
    let clock = std::time::Instant::now();
    let lm = opts.metric;
    lm.validate()?;
    let seen = Seen3::new(shape, (opts.hi - opts.lo).length());
    let exact = |p: DVec3| {
        let (u, g, h) = seen.jet(p);
        level_set_metric3(&lm, u, g, &h)
    };
    let shape = seen.shape();
    let mut mesh = match start {
        Some(m) => m.clone(),
        None => Mesh3::kuhn_box(opts.lo, opts.hi, [opts.cells; 3])?,
    };
    let mut total = super::AdaptReport::default();
    let mut last = None;
    for _ in 0..GRADED_ROUNDS {
        let graded = shape_metric3(shape, &lm, &mesh.points, &mesh.tets, Some(beta))?;
        let field = MetricField3::new(&mesh.points, &mesh.tets, &graded)?;
        let f = |p: DVec3| exact(p).intersect(&field.at(p));
        let a = run3(Target3::Metric(&f), Some(&mesh), opts)?;
        total.absorb(&a.report.adapt);
        total.converged = a.report.adapt.converged;
        let (before, after) = (mesh.n_points() as f64, a.mesh.n_points() as f64);
        let settled = (after - before).abs() < 0.05 * after;
        mesh = a.mesh.clone();
        last = Some(a);
        if settled {
            break;
        }
    }
    let mut a = last.ok_or_else(|| Error::InvalidInput("no adaptation round ran".into()))?;
    let u: Vec<f64> = a.mesh.points.iter().map(|&p| shape.distance(p)).collect();
    a.report.volume = Some(enclosed_measure(&a.mesh.points, &a.mesh.tets, &u)?);
    a.report.surface_area = Some(interface_measure(&a.mesh.points, &a.mesh.tets, &u)?);
    a.report.exact_volume = shape.exact_area();
    total.seconds = clock.elapsed().as_secs_f64();
    a.report.adapt = total;
    a.report.seconds = clock.elapsed().as_secs_f64();
    a.level_set = Some(u);
    Ok(a)
}

/// Adapts `mesh` to the vertex metric field `metric` given on it ([`MetricField3`]: new
/// vertices take the linear-size interpolation in the input mesh,
/// [`FieldInterpolation3::LinearSizes`]), the field first graded
/// over the input's tetrahedra with factor `hgrad` when given. Errors: those of [`run3`] and
/// [`MetricField3::new`].
pub fn run3_to_field(
    mesh: &Mesh3,
    mut metric: Vec<Sym3>,
    opts: &Run3Options,
    hgrad: Option<f64>,
) -> Result<Adapted3> {
    if let Some(beta) = hgrad {
        gradate_tets(&mesh.points, &mesh.tets, &mut metric, beta)?;
    }
    let field = MetricField3::with_rule(
        &mesh.points,
        &mesh.tets,
        &metric,
        FieldInterpolation3::LinearSizes,
    )?;
    let f = |p: DVec3| field.at(p);
    run3(Target3::Metric(&f), Some(mesh), opts)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::levelset::Sphere;

    #[test]
    fn metric_field_reproduces_vertex_values_and_constant_fields() {
        let m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [3, 3, 3]).unwrap();
        let f = |p: DVec3| Sym3::iso(0.01 + 0.1 * p.x).add(&Sym3::outer(DVec3::new(1.0, p.y, 0.0)));
        let metric: Vec<Sym3> = m.points.iter().map(|&p| f(p)).collect();
        let field = MetricField3::new(&m.points, &m.tets, &metric).unwrap();
        for (p, x) in m.points.iter().zip(&metric) {
            let y = field.at(*p);
            assert!(y.sub(x).norm() < 1e-9 * x.norm(), "{p}");
        }
        // A constant field anywhere; a determinant interpolated geometrically.
        let c = Sym3::new(4.0, 1.0, 0.5, 3.0, 0.2, 2.0);
        let field = MetricField3::new(&m.points, &m.tets, &vec![c; m.n_points()]).unwrap();
        let y = field.at(DVec3::new(0.31, 0.77, 0.52));
        assert!(y.sub(&c).norm() < 1e-12 * c.norm());
        let mut bad = vec![c; m.n_points()];
        bad[5] = Sym3::new(f64::NAN, 0.0, 0.0, 1.0, 0.0, 1.0);
        assert!(matches!(
            MetricField3::new(&m.points, &m.tets, &bad),
            Err(Error::InvalidMetric { vertex: 5, .. })
        ));
    }

    /// Linear sizes reproduce a field whose sizes are affine on each background tetrahedron
    /// exactly: the UGAWG cube-linear field (its kink at z = 0.5 is a plane of the mesh) and an
    /// anisotropic field with a fixed rotated frame and sizes affine in x, y, z; with rotating
    /// frames the result stays SPD with sizes between the vertices' extremes. Log-Euclidean
    /// interpolation misses the affine sizes by far more.
    #[test]
    fn linear_sizes_reproduce_affine_size_fields() {
        use crate::metric::ugawg::UgawgCase;
        let m = Mesh3::kuhn_box(DVec3::ZERO, DVec3::ONE, [4, 4, 4]).unwrap();
        let case = UgawgCase::CubeLinear;
        let r = {
            let (c, s) = (0.3f64.cos(), 0.3f64.sin());
            let (ca, sa) = (0.7f64.cos(), 0.7f64.sin());
            [
                DVec3::new(c, s, 0.0),
                DVec3::new(-s * ca, c * ca, sa),
                DVec3::new(s * sa, -c * sa, ca),
            ]
        };
        let sizes = |p: DVec3| {
            [
                0.01 + 0.2 * p.x + 0.05 * p.y,
                0.002 + 0.1 * p.z,
                0.3 - 0.1 * p.x + 0.2 * p.z,
            ]
        };
        let rotated = move |p: DVec3| Sym3::from_eigen(sizes(p).map(|h| 1.0 / (h * h)), r);
        let fields: [(&dyn Fn(DVec3) -> Sym3, &str); 2] =
            [(&|p| case.metric(p), "cube-linear"), (&rotated, "rotated")];
        let pts: Vec<DVec3> = (0..400)
            .map(|k| {
                let f = |a: f64| (a * (k as f64 + 0.5)).fract();
                DVec3::new(f(0.618_034), f(0.414_214), f(0.732_051))
            })
            .collect();
        for (f, name) in fields {
            let vm: Vec<Sym3> = m.points.iter().map(|&p| f(p)).collect();
            let lin =
                MetricField3::with_rule(&m.points, &m.tets, &vm, FieldInterpolation3::LinearSizes)
                    .unwrap();
            let log = MetricField3::new(&m.points, &m.tets, &vm).unwrap();
            let (mut worst_lin, mut worst_log) = (0.0f64, 0.0f64);
            for &p in &pts {
                let want = f(p);
                let rel = |x: Sym3| x.sub(&want).norm() / want.norm();
                worst_lin = worst_lin.max(rel(lin.at(p)));
                worst_log = worst_log.max(rel(log.at(p)));
            }
            assert!(
                worst_lin < 1e-9,
                "{name}: linear sizes off by {worst_lin:.2e}"
            );
            assert!(
                worst_log > 1e-2,
                "{name}: log-Euclidean off by {worst_log:.2e}"
            );
        }
        // Rotating frames: SPD, sizes within the vertices' extremes.
        let spin = |p: DVec3| {
            let a = 3.0 * p.x + 2.0 * p.z;
            let v = [
                DVec3::new(a.cos(), a.sin(), 0.0),
                DVec3::new(-a.sin(), a.cos(), 0.0),
                DVec3::Z,
            ];
            Sym3::from_eigen([1e4, 25.0, 1.0 + p.y], v)
        };
        let vm: Vec<Sym3> = m.points.iter().map(|&p| spin(p)).collect();
        let lin =
            MetricField3::with_rule(&m.points, &m.tets, &vm, FieldInterpolation3::LinearSizes)
                .unwrap();
        let (hmin, hmax) = (0.01, 1.0);
        for &p in &pts {
            let x = lin.at(p);
            assert!(x.is_spd(), "{p}");
            let (l, _) = x.eigen();
            for li in l {
                let h = 1.0 / li.sqrt();
                assert!(
                    h >= hmin * (1.0 - 1e-9) && h <= hmax * (1.0 + 1e-9),
                    "{p}: {h}"
                );
            }
        }
    }

    #[test]
    fn discrete_sphere_distance_and_normal() {
        let m = Mesh3::kuhn_box(DVec3::splat(-1.0), DVec3::ONE, [12, 12, 12]).unwrap();
        let s = Sphere {
            centre: DVec3::ZERO,
            radius: 0.55,
        };
        let u: Vec<f64> = m.points.iter().map(|&p| s.distance(p)).collect();
        let d = DiscreteLevelSet3::new(&m.points, &m.tets, &u).unwrap();
        // The P1 zero level is within h²/(8r) ≈ 0.008 of the sphere; away from it the
        // distance and the normal follow the sphere's.
        for p in [
            DVec3::new(0.9, 0.1, 0.0),
            DVec3::new(-0.1, 0.2, 0.1),
            DVec3::new(0.3, -0.6, 0.5),
        ] {
            let (got, want) = (d.distance(p), s.distance(p));
            assert!((got - want).abs() < 0.02, "{p}: {got} vs {want}");
            let n = d.gradient(p);
            assert!((n.length() - 1.0).abs() < 1e-12);
            assert!(n.dot(p.normalize()) > 0.98, "{p}: {n}");
        }
        // The shape operator: zero along the normal, about 1/r across it.
        let p = DVec3::new(0.0, 0.0, 0.7);
        let h = d.hessian(p);
        assert!(h.quad(DVec3::Z).abs() < 0.05, "{h:?}");
        // (Recovered on elements of size 1/6: about 20 % off.)
        assert!((h.quad(DVec3::X) - 1.0 / 0.7).abs() < 0.45, "{h:?}");
        let vol = 4.0 / 3.0 * std::f64::consts::PI * 0.55f64.powi(3);
        assert!((d.exact_area().unwrap() / vol - 1.0).abs() < 0.05);
        let none = vec![1.0; m.n_points()];
        assert!(matches!(
            DiscreteLevelSet3::new(&m.points, &m.tets, &none),
            Err(Error::EmptyLevelSet(_))
        ));
    }
}
