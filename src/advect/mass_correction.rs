//! Mass correction by a constant shift of the level set (004 §5.1: "assuming that the error is
//! constant over the domain, we use an optimization scheme to determine a constant value by which
//! the level set is normalized so as to preserve the total mass").
//!
//! Finds `c` with `A(c) = |{u + c < 0}| = target`, where `A` is the exact area (volume on
//! tetrahedra) of the negative part of the P1 field. `A` is continuous and non-increasing in
//! `c`, equal to the whole mesh's for `c ≤ -max u` and to 0 for `c ≥ -min u`, so a root is
//! bracketed; it is found by the Illinois variant of regula falsi with bisection as safeguard.

use crate::error::{Error, Result};
use crate::geom::{simplex, DVec3};
use crate::levelset::enclosed_measure;
use crate::levelset::interface::enclosed_area;
use crate::mesh::{check_p1_field, Mesh2};

/// Outcome of a mass correction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MassCorrection {
    /// The shift added to every nodal value.
    pub shift: f64,
    /// The area (volume on tetrahedra) of `{u < 0}` before the shift.
    pub area_before: f64,
    /// The area (volume on tetrahedra) of `{u < 0}` after the shift.
    pub area_after: f64,
    /// Evaluations of the area function.
    pub iterations: usize,
}

/// The exact area of `{u + c < 0}` for a P1 field.
pub fn shifted_area(mesh: &Mesh2, u: &[f64], c: f64) -> Result<f64> {
    let s: Vec<f64> = u.iter().map(|v| v + c).collect();
    enclosed_area(mesh, &s)
}

/// Shifts `u` in place by the constant `c` such that the area of `{u < 0}` equals `target`
/// (relative tolerance `rel_tol`, e.g. 1e-13).
pub fn correct_mass(
    mesh: &Mesh2,
    u: &mut [f64],
    target: f64,
    rel_tol: f64,
) -> Result<MassCorrection> {
    check_p1_field(mesh.n_points(), u, "level set")?;
    correct_measure(|s| enclosed_area(mesh, s), mesh.area(), u, target, rel_tol)
}

/// Shifts the P1 field `u` on the tetrahedra `tets` over `points` in place by the constant `c`
/// such that the volume of `{u < 0}` equals `target` (relative tolerance `rel_tol`): the 3D
/// form of [`correct_mass`]. Errors: a bad field or cell, a target outside `(0, |mesh|)`.
pub fn correct_volume(
    points: &[DVec3],
    tets: &[[u32; 4]],
    u: &mut [f64],
    target: f64,
    rel_tol: f64,
) -> Result<MassCorrection> {
    enclosed_measure(points, tets, u)?;
    let total = tets
        .iter()
        .map(|t| simplex::volume(&t.map(|v| points[v as usize])).abs())
        .sum();
    correct_measure(
        |s| enclosed_measure(points, tets, s),
        total,
        u,
        target,
        rel_tol,
    )
}

/// The shift of `u` making `measure(u + c) = target` (module documentation), for a measure of
/// the negative part that is `total` for `c ≤ -max u` and 0 for `c ≥ -min u`.
fn correct_measure(
    measure: impl Fn(&[f64]) -> Result<f64>,
    total: f64,
    u: &mut [f64],
    target: f64,
    rel_tol: f64,
) -> Result<MassCorrection> {
    if !(target > 0.0 && target < total) {
        return Err(Error::InvalidInput(format!(
            "mass correction: target measure {target} is not in (0, {total})"
        )));
    }
    if rel_tol.is_nan() || rel_tol <= 0.0 {
        return Err(Error::InvalidInput(format!(
            "mass correction: tolerance must be positive (got {rel_tol})"
        )));
    }
    let (umin, umax) = u
        .iter()
        .fold((f64::INFINITY, f64::NEG_INFINITY), |(a, b), &v| {
            (a.min(v), b.max(v))
        });
    let area_before = measure(u)?;
    let f = |c: f64| {
        let s: Vec<f64> = u.iter().map(|v| v + c).collect();
        measure(&s).map(|a| a - target)
    };
    // Bracket: f(a) >= 0 >= f(b).
    let span = (umax - umin).max(1e-300);
    let (a, b) = (-umax - 1e-9 * span, -umin + 1e-9 * span);
    let mut br = Bracket {
        a,
        b,
        fa: f(a)?,
        fb: f(b)?,
    };
    // Narrow the bracket to c = 0 on the side where f(0) lies, to save evaluations.
    let f0 = area_before - target;
    if f0 >= 0.0 {
        br.a = 0.0;
        br.fa = f0;
    } else {
        br.b = 0.0;
        br.fb = f0;
    }
    let (c, fc, evals) = illinois(f, br, f0, rel_tol * target, 3)?;
    for v in u.iter_mut() {
        *v += c;
    }
    Ok(MassCorrection {
        shift: c,
        area_before,
        area_after: fc + target,
        iterations: evals,
    })
}

/// A bracket `[a, b]` of a root of a non-increasing function: `f(a) >= 0 >= f(b)`.
struct Bracket {
    a: f64,
    b: f64,
    fa: f64,
    fb: f64,
}

/// The root `c` of `f` in the bracket with `|f(c)| <= tol`, by the Illinois variant of regula
/// falsi (the retained end's value is halved when the same end moves twice), with a bisection
/// step every eighth evaluation or when the secant leaves the bracket. `0` is the starting
/// iterate with value `f0`; `evals` counts the evaluations made so far. Returns `c`, `f(c)` and
/// the evaluation count; errors after 200 evaluations.
fn illinois(
    f: impl Fn(f64) -> Result<f64>,
    br: Bracket,
    f0: f64,
    tol: f64,
    mut evals: usize,
) -> Result<(f64, f64, usize)> {
    let Bracket {
        mut a,
        mut b,
        mut fa,
        mut fb,
    } = br;
    let mut c = if f0.abs() <= tol { 0.0 } else { f64::NAN };
    let mut side = 0i8;
    let mut fc = f0;
    while c.is_nan() || fc.abs() > tol {
        if evals > 200 {
            return Err(Error::NotConverged(format!(
                "mass correction: |A(c) - target| = {:e} after {evals} evaluations",
                fc.abs()
            )));
        }
        let mut x = if fa != fb {
            (a * fb - b * fa) / (fb - fa)
        } else {
            0.5 * (a + b)
        };
        if !(x > a && x < b) || evals % 8 == 7 {
            x = 0.5 * (a + b);
        }
        if x == a || x == b || (b - a) <= 4.0 * f64::EPSILON * (a.abs().max(b.abs()) + 1e-300) {
            c = x;
            fc = f(x)?;
            evals += 1;
            break;
        }
        let fx = f(x)?;
        evals += 1;
        c = x;
        fc = fx;
        if fx > 0.0 {
            a = x;
            fa = fx;
            if side == 1 {
                fb *= 0.5;
            }
            side = 1;
        } else {
            b = x;
            fb = fx;
            if side == -1 {
                fa *= 0.5;
            }
            side = -1;
        }
    }
    Ok((c, fc, evals))
}
