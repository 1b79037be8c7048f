//! The viscosity of a Stokes problem: constant, per element, or two phases separated by the zero
//! level of a P1 level set (004 §5.1), sampled at quadrature points or averaged per element.

use crate::error::{Error, Result};
use crate::mesh::{check_p1_field, Mesh2};

/// How the viscosity is given.
#[derive(Debug, Clone, PartialEq)]
pub enum Viscosity {
    /// The same viscosity everywhere.
    Constant(f64),
    /// One value per triangle slot.
    PerElement(Vec<f64>),
    /// Two phases separated by the zero level of the P1 level set `phi` (negative inside,
    /// 004 §2.1): `μ = mu_in + (mu_out - mu_in) H(φ)` at each quadrature point, with `H` the sign
    /// step (`width = 0`) or the smoothed Heaviside of half-width `width`:
    /// `H(φ) = (1 + φ/ε + sin(π φ/ε)/π) / 2` for `|φ| < ε`.
    TwoPhase {
        /// The level set, one value per vertex.
        phi: Vec<f64>,
        /// Viscosity where `φ < 0`.
        mu_in: f64,
        /// Viscosity where `φ > 0`.
        mu_out: f64,
        /// Half-width `ε` of the smoothed Heaviside (0: a sharp step).
        width: f64,
    },
    /// Two phases separated by the zero level of the P1 level set `phi`, with one viscosity per
    /// triangle: the harmonic mean `1/μ_T = f/μ_in + (1 - f)/μ_out` over the exact area
    /// fraction `f` of the triangle where `φ_h < 0` ([`negative_fraction`]; the triangle is cut
    /// along the straight zero line of `φ_h`). For a cut triangle sheared along the interface
    /// (the fluid sliding past a rigid inclusion, 004 §5.1) the stresses of the two layers are
    /// equal, so the harmonic mean is the exact effective viscosity of a constant-gradient
    /// element: the interface sits where `φ_h = 0` to within the level-set error, instead of
    /// being rounded to the quadrature points. The element viscosity is constant, which also
    /// keeps the Uzawa iteration count low on anisotropic meshes.
    TwoPhaseHarmonic {
        /// The level set, one value per vertex.
        phi: Vec<f64>,
        /// Viscosity where `φ < 0`.
        mu_in: f64,
        /// Viscosity where `φ > 0`.
        mu_out: f64,
    },
}

/// The exact area fraction of a triangle where the linear interpolant of the vertex values `f`
/// is negative (0 when no value is negative, 1 when all are). With the lone vertex `a` (the one
/// whose sign differs from the other two), the corner triangle cut off by the zero line has the
/// fraction `f_a² / ((f_a - f_b)(f_a - f_c))`.
pub fn negative_fraction(f: [f64; 3]) -> f64 {
    let neg = f.iter().filter(|v| **v < 0.0).count();
    if neg == 0 || neg == 3 {
        return if neg == 3 { 1.0 } else { 0.0 };
    }
    let lone_negative = neg == 1;
    let a = (0..3).find(|&i| (f[i] < 0.0) == lone_negative).unwrap_or(0);
    let (b, c) = ((a + 1) % 3, (a + 2) % 3);
    let corner = (f[a] * f[a] / ((f[a] - f[b]) * (f[a] - f[c]))).clamp(0.0, 1.0);
    if lone_negative {
        corner
    } else {
        1.0 - corner
    }
}

impl Viscosity {
    /// The viscosity at barycentric point `l` of triangle slot `t`.
    pub(super) fn at(&self, mesh: &Mesh2, t: usize, l: &[f64; 3]) -> f64 {
        match self {
            Viscosity::Constant(m) => *m,
            Viscosity::PerElement(m) => m[t],
            Viscosity::TwoPhase {
                phi,
                mu_in,
                mu_out,
                width,
            } => {
                let v = mesh.tris[t].map(|i| phi[i as usize]);
                let f = l[0] * v[0] + l[1] * v[1] + l[2] * v[2];
                mu_in + (mu_out - mu_in) * heaviside(f, *width)
            }
            Viscosity::TwoPhaseHarmonic { phi, mu_in, mu_out } => {
                let fr = negative_fraction(mesh.tris[t].map(|i| phi[i as usize]));
                1.0 / (fr / mu_in + (1.0 - fr) / mu_out)
            }
        }
    }

    /// The level set of a two-phase viscosity.
    pub(super) fn level_set(&self) -> Option<&[f64]> {
        match self {
            Viscosity::TwoPhase { phi, .. } | Viscosity::TwoPhaseHarmonic { phi, .. } => Some(phi),
            _ => None,
        }
    }

    /// Checks the values against `mesh`: positive finite viscosities, one per triangle slot for
    /// [`Viscosity::PerElement`], a finite level set with one value per vertex for the two-phase
    /// forms, a smoothing width `>= 0`.
    pub(super) fn validate(&self, mesh: &Mesh2) -> Result<()> {
        match self {
            Viscosity::Constant(m) if !(m.is_finite() && *m > 0.0) => {
                invalid(format!("constant viscosity {m} must be positive"))
            }
            Viscosity::PerElement(m) => validate_per_element(mesh, m),
            Viscosity::TwoPhaseHarmonic { phi, mu_in, mu_out } => {
                validate_two_phase(mesh, phi, *mu_in, *mu_out, 0.0)
            }
            Viscosity::TwoPhase {
                phi,
                mu_in,
                mu_out,
                width,
            } => validate_two_phase(mesh, phi, *mu_in, *mu_out, *width),
            Viscosity::Constant(_) => Ok(()),
        }
    }
}

/// An [`Error::InvalidField`] on the viscosity.
fn invalid(msg: String) -> Result<()> {
    Err(Error::InvalidField {
        name: "viscosity".into(),
        msg,
    })
}

/// One positive finite value per triangle slot.
fn validate_per_element(mesh: &Mesh2, m: &[f64]) -> Result<()> {
    if m.len() != mesh.n_tris() {
        return invalid(format!(
            "{} values for {} triangle slots",
            m.len(),
            mesh.n_tris()
        ));
    }
    match m.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
        Some(t) => invalid(format!(
            "viscosity {} on triangle {t} must be positive",
            m[t]
        )),
        None => Ok(()),
    }
}

/// A finite P1 level set, two positive finite viscosities, a smoothing width `>= 0`.
fn validate_two_phase(
    mesh: &Mesh2,
    phi: &[f64],
    mu_in: f64,
    mu_out: f64,
    width: f64,
) -> Result<()> {
    check_p1_field(mesh.n_points(), phi, "level set")?;
    if !(mu_in > 0.0 && mu_out > 0.0 && mu_in.is_finite() && mu_out.is_finite()) {
        return invalid(format!("viscosities {mu_in}, {mu_out} must be positive"));
    }
    if !(width.is_finite() && width >= 0.0) {
        return invalid(format!("smoothing width {width} must be >= 0"));
    }
    Ok(())
}

/// Step (`eps = 0`) or smoothed Heaviside of half-width `eps`.
fn heaviside(f: f64, eps: f64) -> f64 {
    if eps == 0.0 {
        return if f < 0.0 { 0.0 } else { 1.0 };
    }
    if f <= -eps {
        0.0
    } else if f >= eps {
        1.0
    } else {
        let s = f / eps;
        0.5 * (1.0 + s + (std::f64::consts::PI * s).sin() / std::f64::consts::PI)
    }
}
