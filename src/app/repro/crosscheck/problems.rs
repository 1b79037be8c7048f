//! The cross-check problems: each returns a [`Problem`] with one row per back end and level.

use super::{Build2, Build3, Problem, Resolution, Row};
use crate::app::repro::surface_mcf::{self, SurfaceMcfOptions};
use anisomesh::backends::surface::ParametricCurve;
use anisomesh::backends::{BuildSpec, CurvatureSamples, FnShape, D2};
use anisomesh::error::Result;
use anisomesh::geom::DVec2;
use anisomesh::levelset::{Circle, Shape};
use std::f64::consts::PI;
use std::time::Instant;

/// Circle flow: centre, initial radius, final time.
const CENTRE: DVec2 = DVec2::new(0.1, -0.05);
const R0: f64 = 0.5;
const T_END: f64 = 0.06;
/// The box of the level-set back ends.
const DOMAIN: (DVec2, DVec2) = (DVec2::new(-1.0, -1.0), DVec2::new(1.0, 1.0));
/// The coarsest level-set resolution (halved per level).
const H0: f64 = 0.02;
/// The coarsest polygon (vertices, doubled per level).
const N0: usize = 16;
/// The ellipse's half axes.
const AXES: (f64, f64) = (0.5, 0.3);

fn spec<'a>(shape: &'a dyn Shape, h: f64) -> BuildSpec<'a, D2> {
    BuildSpec {
        function: shape,
        domain: DOMAIN,
        resolution: h,
    }
}

/// The circle shrinking by curvature from `R0 = 0.5` to `T = 0.06`: the error of the radius
/// `√(A/π)` of the enclosed area `A` against `√(R0² − 2T)`. Level-set back ends at
/// `h = h0 / 2^k` ([`super::circle_h0`]: 0.02, the band 0.04; [`super::circle_levels`]) with
/// `dt ≈ 0.4h`; parametric curves with `16·2^k` vertices and `τ ∝ h²`.
pub fn circle_mcf(
    res: Resolution,
    backends: &[(&'static str, Build2)],
    progress: &mut dyn FnMut(&str),
) -> Result<Problem> {
    let exact = (R0 * R0 - 2.0 * T_END).sqrt();
    let mut rows = Vec::new();
    let circle = Circle {
        centre: CENTRE,
        radius: R0,
    };
    for (name, build) in backends {
        for k in 0..super::circle_levels(res, name) {
            let h = super::circle_h0(name) / 2f64.powi(k as i32);
            let start = Instant::now();
            let mut b = build(&spec(&circle, h))?;
            let steps = (T_END / (0.4 * h)).round().max(1.0) as usize;
            for _ in 0..steps {
                b.advance_mean_curvature(T_END / steps as f64)?;
            }
            let r = (b.enclosed_measure()? / PI).sqrt();
            rows.push(Row {
                backend: name.to_string(),
                resolution: h,
                dof: b.dof(),
                error: (r - exact).abs(),
                value: Some(r),
                order: None,
                seconds: start.elapsed().as_secs_f64(),
            });
            progress(&format!(
                "circle_mcf {name} h {h}: error {:.2e}",
                (r - exact).abs()
            ));
        }
    }
    for order in [1, 2] {
        let name = format!("parametric P{order}");
        for k in 0..res.levels() {
            let n = N0 << k;
            let start = Instant::now();
            let mut c = ParametricCurve::circle(CENTRE, R0, n, order)?;
            let steps = 8 << (2 * k);
            for _ in 0..steps {
                c.theta_step(T_END / steps as f64, 0.5)?;
            }
            let r = (c.enclosed_area() / PI).sqrt();
            rows.push(Row {
                backend: name.clone(),
                resolution: 2.0 * PI * R0 / n as f64,
                dof: c.nodes.len(),
                error: (r - exact).abs(),
                value: Some(r),
                order: None,
                seconds: start.elapsed().as_secs_f64(),
            });
            progress(&format!(
                "circle_mcf {name} n {n}: error {:.2e}",
                (r - exact).abs()
            ));
        }
    }
    let mut p = Problem {
        name: "circle_mcf".into(),
        error_measure: "|sqrt(area/pi) - sqrt(R0^2 - 2T)|, R0 0.5, T 0.06".into(),
        rows,
    };
    p.fill_orders();
    Ok(p)
}

/// The sphere shrinking by mean curvature from `R0 = 2` to `T = 0.1` (002): the error of the
/// averaged radius, parametric P1 and P2 from icosahedral level 2, `τ = 0.02` divided by 4 per
/// level; the 3D level-set back ends in `[−2.5, 2.5]³` at the resolutions of
/// [`super::sphere_resolutions`] with `τ ≈ h²`, the error of the radius `(3V/4π)^{1/3}` of the
/// enclosed volume.
pub fn sphere_mcf(
    res: Resolution,
    backends: &[(&'static str, Build3)],
    progress: &mut dyn FnMut(&str),
) -> Result<Problem> {
    let mut rows = Vec::new();
    let (r0, t_end): (f64, f64) = (2.0, 0.1);
    let exact = (r0 * r0 - 4.0 * t_end).sqrt();
    let sphere = move |p: anisomesh::geom::DVec3| p.length() - r0;
    for (name, build) in backends {
        for h in super::sphere_resolutions(res, name) {
            let start = Instant::now();
            let mut b = build(&BuildSpec {
                function: &sphere,
                domain: (
                    anisomesh::geom::DVec3::splat(-2.5),
                    anisomesh::geom::DVec3::splat(2.5),
                ),
                resolution: h,
            })?;
            let steps = (t_end / super::sphere_tau(name, h)).round().max(1.0) as usize;
            for _ in 0..steps {
                b.advance_mean_curvature(t_end / steps as f64)?;
            }
            let r = (3.0 * b.enclosed_measure()? / (4.0 * PI)).cbrt();
            let error = (r - exact).abs();
            progress(&format!("sphere_mcf {name} h {h}: error {error:.2e}"));
            rows.push(Row {
                backend: name.to_string(),
                resolution: h,
                dof: b.dof(),
                error,
                value: Some(r),
                order: None,
                seconds: start.elapsed().as_secs_f64(),
            });
        }
    }
    let opts = SurfaceMcfOptions::default();
    for order in [1, 2] {
        for k in 0..res.levels() {
            let tau = opts.tau0 / opts.tau_factor.powi(k as i32);
            let r = surface_mcf::run_one(&opts, order, opts.first_level + k, tau)?;
            progress(&format!(
                "sphere_mcf P{order} {} vertices: error {:.2e}",
                r.vertices, r.error
            ));
            rows.push(Row {
                backend: format!("parametric P{order}"),
                resolution: 1.0 / (r.vertices as f64).sqrt(),
                dof: r.dofs,
                error: r.error,
                value: Some(r.mean_radius),
                order: None,
                seconds: r.seconds,
            });
        }
    }
    let mut p = Problem {
        name: "sphere_mcf".into(),
        error_measure: "|mean radius - sqrt(R0^2 - 4T)|, R0 2, T 0.1 (002)".into(),
        rows,
    };
    p.fill_orders();
    Ok(p)
}

/// The curvature of the level set of `φ = x²/a² + y²/b² − 1` through `p`:
/// `div(∇φ/|∇φ|)`, the ellipse's curvature on the ellipse.
fn ellipse_level_curvature(p: DVec2) -> f64 {
    let (a2, b2) = (AXES.0 * AXES.0, AXES.1 * AXES.1);
    let (fx, fy) = (2.0 * p.x / a2, 2.0 * p.y / b2);
    let g = (fx * fx + fy * fy).sqrt();
    (2.0 / a2 * fy * fy + 2.0 / b2 * fx * fx) / (g * g * g)
}

/// The mean relative error of curvature samples against `exact(p)`.
fn mean_rel_error(points: &[DVec2], values: &[f64], exact: impl Fn(DVec2) -> f64) -> f64 {
    let s: f64 = points
        .iter()
        .zip(values)
        .map(|(&p, &k)| ((k - exact(p)) / exact(p)).abs())
        .sum();
    s / values.len().max(1) as f64
}

/// The interface curvature of a circle (`R = 0.5`, a distance function) or of the ellipse with
/// half axes 0.5, 0.3 given by `x²/a² + y²/b² − 1` (not a distance function): the mean
/// relative error of the samples of the level-set back ends, and of the vertex curvature of
/// parametric curves through points of the exact curve (equally spaced in angle on the circle,
/// in the parameter on the ellipse).
pub fn curvature(
    res: Resolution,
    ellipse: bool,
    backends: &[(&'static str, Build2)],
    progress: &mut dyn FnMut(&str),
) -> Result<Problem> {
    let (a, b) = AXES;
    let circle = Circle {
        centre: DVec2::ZERO,
        radius: R0,
    };
    let ell = FnShape::new("ellipse", move |p: DVec2| {
        p.x * p.x / (a * a) + p.y * p.y / (b * b) - 1.0
    });
    let shape: &dyn Shape = if ellipse { &ell } else { &circle };
    let exact = |p: DVec2| {
        if ellipse {
            ellipse_level_curvature(p)
        } else {
            1.0 / p.length()
        }
    };
    let name = if ellipse {
        "curvature_ellipse"
    } else {
        "curvature_circle"
    };
    let mut rows = Vec::new();
    for (bname, build) in backends {
        for k in 0..res.levels() {
            let h = H0 / 2f64.powi(k as i32);
            let start = Instant::now();
            let backend = build(&spec(shape, h))?;
            let s: CurvatureSamples<D2> = backend.interface_curvature()?;
            let e = mean_rel_error(&s.points, &s.values, exact);
            progress(&format!("{name} {bname} h {h}: error {e:.2e}"));
            rows.push(Row {
                backend: bname.to_string(),
                resolution: h,
                dof: backend.dof(),
                error: e,
                value: None,
                order: None,
                seconds: start.elapsed().as_secs_f64(),
            });
        }
    }
    for order in [1, 2] {
        let bname = format!("parametric P{order}");
        for k in 0..res.levels() {
            let n = N0 << k;
            let start = Instant::now();
            let at = |t: f64| {
                if ellipse {
                    DVec2::new(a * t.cos(), b * t.sin())
                } else {
                    R0 * DVec2::new(t.cos(), t.sin())
                }
            };
            let dt = 2.0 * PI / n as f64;
            let vertices = (0..n).map(|i| at(i as f64 * dt)).collect();
            // The inner node of arc i at the parameter midpoint.
            let mid = |p: DVec2| {
                let t = (p.y / b).atan2(p.x / a);
                if ellipse {
                    at(t)
                } else {
                    R0 * p.normalize()
                }
            };
            let c = ParametricCurve::new(vertices, order, mid)?;
            let kappa = c.vertex_curvature()?;
            let e = mean_rel_error(&c.nodes[..n], &kappa, exact);
            progress(&format!("{name} {bname} n {n}: error {e:.2e}"));
            rows.push(Row {
                backend: bname.clone(),
                resolution: c.length() / n as f64,
                dof: c.nodes.len(),
                error: e,
                value: None,
                order: None,
                seconds: start.elapsed().as_secs_f64(),
            });
        }
    }
    let mut p = Problem {
        name: name.into(),
        error_measure: "mean |kappa_h - kappa| / |kappa| over the samples".into(),
        rows,
    };
    p.fill_orders();
    Ok(p)
}

/// Zalesak's slotted disk (004 §5.1) rotated by `v = (−y, x)` for one revolution in 16 steps
/// through the level-set back ends at `h = 0.02 / 2^k` in `[−2, 2]²`: two problems, the
/// relative area error and the relative perimeter error of the zero level after the
/// revolution (no redistancing, no mass correction).
pub fn zalesak(
    res: Resolution,
    backends: &[(&'static str, Build2)],
    progress: &mut dyn FnMut(&str),
) -> Result<[Problem; 2]> {
    use crate::app::repro::zalesak::exact::{EXACT_AREA, EXACT_PERIMETER};
    let shape = anisomesh::levelset::Zalesak::default();
    let (mut area_rows, mut perimeter_rows) = (Vec::new(), Vec::new());
    let steps = 16;
    let v = |_t: f64, x: DVec2| DVec2::new(-x.y, x.x);
    // The tiny resolution stops one level short of the others: a revolution is the costliest run.
    for k in 0..res.levels().min(3) {
        for (name, build) in backends {
            if k >= super::zalesak_levels(res, name) {
                continue;
            }
            let h = H0 / 2f64.powi(k as i32);
            let start = Instant::now();
            let mut b = build(&BuildSpec {
                function: &shape,
                domain: (DVec2::new(-2.0, -2.0), DVec2::new(2.0, 2.0)),
                resolution: h,
            })?;
            for _ in 0..steps {
                b.advect(&v, 2.0 * PI / steps as f64)?;
            }
            let seconds = start.elapsed().as_secs_f64();
            let area = (b.enclosed_measure()? / EXACT_AREA - 1.0).abs();
            let perimeter = (b.interface_measure()? / EXACT_PERIMETER - 1.0).abs();
            progress(&format!(
                "zalesak {name} h {h}: area {area:.2e}, perimeter {perimeter:.2e}"
            ));
            let row = |error| Row {
                backend: name.to_string(),
                resolution: h,
                dof: b.dof(),
                error,
                value: None,
                order: None,
                seconds,
            };
            area_rows.push(row(area));
            perimeter_rows.push(row(perimeter));
        }
    }
    let sort = |rows: &mut Vec<Row>| rows.sort_by(|a, b| a.backend.cmp(&b.backend));
    sort(&mut area_rows);
    sort(&mut perimeter_rows);
    let mut a = Problem {
        name: "zalesak_area".into(),
        error_measure: "|area / exact - 1| after one revolution (16 steps)".into(),
        rows: area_rows,
    };
    let mut p = Problem {
        name: "zalesak_perimeter".into(),
        error_measure: "|perimeter / exact - 1| after one revolution (16 steps)".into(),
        rows: perimeter_rows,
    };
    a.fill_orders();
    p.fill_orders();
    Ok([a, p])
}
