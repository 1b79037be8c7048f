//! The meshes of the sweep and their measures: the domain and corners of a benchmark shape, the
//! level-set metric of the adapted families (004 eq. (6)), a mesh adapted to it, and the interface
//! errors of the nodal interpolant of the exact distance (Hausdorff distance, split near and away
//! from the corners; relative area and perimeter errors, 004 §5.1).

use std::time::Instant;

use super::types::{ConvergenceRow, Family};
use anisomesh::adapt::{adapt_to_shape, LevelSetMetric, ShapeAdaptOptions};
use anisomesh::error::{Error, Result};
use anisomesh::geom::DVec2;
use anisomesh::levelset::{
    enclosed_area, extract_zero_level, interface_distance, interface_length, nodal_distance,
    shape_by_name, Polyline, Shape,
};
use anisomesh::mesh::Mesh2;

/// The domain `(lo, hi)` of a benchmark shape: `[-2, 2]²` for Zalesak (004 §5.1), `[-1, 1]²`
/// for the circle and the flower.
pub fn domain_of(shape: &str) -> Result<(DVec2, DVec2)> {
    match shape.trim().to_ascii_lowercase().as_str() {
        "zalesak" => Ok((DVec2::splat(-2.0), DVec2::splat(2.0))),
        "circle" | "flower" => Ok((DVec2::splat(-1.0), DVec2::splat(1.0))),
        _ => shape_by_name(shape).map(|_| (DVec2::splat(-1.0), DVec2::splat(1.0))),
    }
}

#[cfg(test)]
/// The level-set metric of the adapted families at `ε`: the default `anisomesh adapt` setting
/// ([`LevelSetMetric::default`]: band `5 ε`, sizes growing at rate 1 outside it, anisotropy at
/// most 1e4, `h_max = 0.2`) with `h_min = 0.1 √ε`, so that `ε = 1e-4` is exactly the default run
/// (004 §5.1: `h_min = 0.001`, `h_max = 0.2`).
pub fn metric_for(eps: f64, isotropic: bool) -> LevelSetMetric {
    metric_with(eps, isotropic, None, None)
}

/// [`metric_for`] with the band half-width `band_hmin h_min` and the growth rate `grade` outside
/// it where given (the "equal settings" variations of the anisotropy-pays comparison).
pub fn metric_with(
    eps: f64,
    isotropic: bool,
    band_hmin: Option<f64>,
    grade: Option<f64>,
) -> LevelSetMetric {
    let d = LevelSetMetric::default();
    let hmin = eps.sqrt() / 10.0;
    LevelSetMetric {
        eps,
        hmin,
        band: band_hmin.map_or(d.band * (eps / d.eps), |k| k * hmin),
        grade: grade.unwrap_or(d.grade),
        isotropic,
        ..d
    }
}

/// A mesh of `domain` adapted to the zero level of `shape` with the metric `lm`, by
/// [`adapt_to_shape`] with its default rounds, tolerance and corner features, kinks resolved at
/// `kink_scale`, the metric graded with the factor `gradation` ([`anisomesh::metric::gradate`];
/// `None`: the default of [`ShapeAdaptOptions::gradation`]). Returns the mesh and whether the
/// rounds settled.
fn adapted_mesh(
    shape: &dyn Shape,
    domain: (DVec2, DVec2),
    lm: LevelSetMetric,
    kink_scale: Option<f64>,
    gradation: Option<f64>,
) -> Result<(Mesh2, bool)> {
    let d = ShapeAdaptOptions::default();
    let opts = ShapeAdaptOptions {
        metric: lm,
        kink_scale,
        gradation: gradation.or(d.gradation),
        ..d
    };
    let (mesh, _u, rep) = adapt_to_shape(shape, domain, &opts)?;
    Ok((mesh, rep.converged))
}

/// A mesh adapted with `lm` ([`adapted_mesh`]) measured as a row of `family` with the sweep
/// parameter `parameter` ([`row`]; `seconds` is the adaptation time).
#[allow(clippy::too_many_arguments)]
pub(super) fn adapted_row(
    family: Family,
    parameter: f64,
    lm: LevelSetMetric,
    shape: &dyn Shape,
    domain: (DVec2, DVec2),
    corners: &[DVec2],
    kink_scale: Option<f64>,
    gradation: Option<f64>,
) -> Result<ConvergenceRow> {
    let t = Instant::now();
    let (mesh, converged) = adapted_mesh(shape, domain, lm, kink_scale, gradation)?;
    let secs = t.elapsed().as_secs_f64();
    row(
        family, parameter, lm.hmin, &mesh, shape, corners, secs, converged,
    )
}

/// Radius of the corner neighbourhoods of [`hausdorff_split`] in the sweep (the slot of the
/// Zalesak disk is 0.12 wide).
pub const CORNER_RADIUS: f64 = 0.02;

/// The corners of a benchmark shape (where its distance has kinks): [`Shape::corners`] of
/// [`shape_by_name`] (the four slot corners of the Zalesak disk, none for the circle and the
/// flower); empty for an unknown name.
pub fn corners_of(shape: &str) -> Vec<DVec2> {
    shape_by_name(shape).map_or_else(|_| Vec::new(), |s| s.corners())
}

/// A shape whose boundary samples are restricted to one side of a corner neighbourhood (the
/// exact → discrete direction of [`interface_distance`] restricted to a region).
struct Restricted<'a> {
    shape: &'a dyn Shape,
    corners: &'a [DVec2],
    radius: f64,
    near: bool,
}

impl Restricted<'_> {
    fn keeps(&self, p: DVec2) -> bool {
        near_corner(p, self.corners, self.radius) == self.near
    }
}

fn near_corner(p: DVec2, corners: &[DVec2], radius: f64) -> bool {
    corners.iter().any(|c| (p - *c).length() < radius)
}

impl Shape for Restricted<'_> {
    fn distance(&self, p: DVec2) -> f64 {
        self.shape.distance(p)
    }
    fn boundary_samples(&self, n: usize) -> Option<Vec<DVec2>> {
        self.shape
            .boundary_samples(n)
            .map(|v| v.into_iter().filter(|&p| self.keeps(p)).collect())
    }
    fn name(&self) -> String {
        self.shape.name()
    }
}

/// The two-sided interface distance of [`interface_distance`] split by region: `(near, rest)`,
/// the largest distance attained within `radius` of one of `corners` and elsewhere (points of
/// `Γ_h` measured by `|d|`, samples of `Γ` by their distance to `Γ_h`; 4 samples per segment).
/// `max(near, rest)` is the Hausdorff distance. With no corners `near` is 0.
pub fn hausdorff_split(
    lines: &[Polyline],
    shape: &dyn Shape,
    corners: &[DVec2],
    radius: f64,
) -> (f64, f64) {
    let (mut near, mut rest): (f64, f64) = (0.0, 0.0);
    let k = 4;
    for pl in lines {
        for (a, b) in pl.segments() {
            for i in 0..k {
                let p = a + (b - a) * (i as f64 / (k - 1) as f64);
                let d = shape.distance(p).abs();
                if near_corner(p, corners, radius) {
                    near = near.max(d);
                } else {
                    rest = rest.max(d);
                }
            }
        }
    }
    for (is_near, acc) in [(true, &mut near), (false, &mut rest)] {
        let r = Restricted {
            shape,
            corners,
            radius,
            near: is_near,
        };
        let from = interface_distance(lines, &r, k).from_exact_max;
        if from.is_finite() {
            *acc = acc.max(from);
        }
    }
    (near, rest)
}

/// The interface measures of the nodal interpolant of `shape`'s distance on `mesh`:
/// `(hausdorff, relative area error, relative perimeter error)`. Errors: a shape without exact
/// area or perimeter, an empty zero level.
pub fn measure(mesh: &Mesh2, shape: &dyn Shape) -> Result<(f64, f64, f64)> {
    let u = nodal_distance(mesh, shape);
    let lines = extract_zero_level(mesh, &u)?;
    let hausdorff = interface_distance(&lines, shape, 4).hausdorff;
    let area = shape.exact_area().ok_or_else(|| {
        Error::InvalidInput(format!(
            "convergence: shape {} has no exact area",
            shape.name()
        ))
    })?;
    let perimeter = shape.exact_perimeter().ok_or_else(|| {
        Error::InvalidInput(format!(
            "convergence: shape {} has no exact perimeter",
            shape.name()
        ))
    })?;
    let a = enclosed_area(mesh, &u)?;
    let l = interface_length(mesh, &u)?;
    Ok((
        hausdorff,
        (a - area).abs() / area,
        (l - perimeter).abs() / perimeter,
    ))
}

#[allow(clippy::too_many_arguments)]
pub(super) fn row(
    family: Family,
    parameter: f64,
    hmin: f64,
    mesh: &Mesh2,
    shape: &dyn Shape,
    corners: &[DVec2],
    seconds: f64,
    converged: bool,
) -> Result<ConvergenceRow> {
    let (hausdorff, area_rel_error, perimeter_rel_error) = measure(mesh, shape)?;
    let u = nodal_distance(mesh, shape);
    let lines = extract_zero_level(mesh, &u)?;
    let (hausdorff_corners, hausdorff_rest) =
        hausdorff_split(&lines, shape, corners, CORNER_RADIUS);
    Ok(ConvergenceRow {
        family,
        parameter,
        hmin,
        vertices: mesh.n_points(),
        triangles: mesh.n_live_tris(),
        hausdorff,
        hausdorff_corners,
        hausdorff_rest,
        area_rel_error,
        perimeter_rel_error,
        seconds,
        converged,
    })
}
