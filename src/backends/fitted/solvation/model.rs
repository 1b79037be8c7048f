//! The variational implicit-solvent model of 001 §7 in the plane: solute particles with
//! Lennard-Jones solute–solvent potentials (001 (7.2)), the model parameters, and the pieces of
//! the free energy (001 (7.1)) that are plain functions of position.
//!
//! **The functional** (001 (7.1), with the pressure and Tolman terms of the variational
//! implicit-solvent model, ref. [3] of 001; both 0 in 001's runs):
//! `G[Γ] = P |Ω_s| + γ ∫_Γ (1 − 2τκ) ds + ρ_w Σ_i ∫_{Ω_w} U_i(|x − x_i|) dx`,
//! `Ω_s` the solute region (inside Γ), `Ω_w` the solvent region (the rest of the box), `κ` the
//! curvature of Γ (positive where `Ω_s` is convex).
//!
//! **Its first variation in 2D.** Moving Γ along its unit normal `n` (out of `Ω_s`) with speed
//! `V`: `d|Ω_s|/dt = ∫_Γ V`, `d|Γ|/dt = ∫_Γ κ V`, `d/dt ∫_{Ω_w} U = −∫_Γ U V`, and
//! `∫_Γ κ ds = 2π χ(Ω_s)` (the turning number: components minus holes) does not change under a
//! smooth motion, so the Tolman term, which in 3D gives the Gaussian curvature `K`, has no
//! first variation in the plane. Hence `δG/δΓ = P + γκ − ρ_w Σ_i U_i`, and the steepest descent
//! moves Γ with the normal velocity
//! `V_n = −δG/δΓ = −P − γκ + ρ_w Σ_i U_i(|x − x_i|)` (001 (7.3) with `P = 0`), along which
//! `dG/dt = −∫_Γ V_n² ds ≤ 0`. The Tolman term changes only when the topology of `Ω_s` does
//! (by `−4πγτ` per new component).
//!
//! **The van der Waals term as a boundary integral.** `U(r) = div F` for the radial field
//! `F = f(r) x̂`, `f(r) = (1/r) ∫^r s U(s) ds = 4ε [σ⁶/(4 r⁵) − σ¹²/(10 r¹¹)]` (vanishing at
//! infinity). When no particle lies in `Ω_w`, `∫_{Ω_w} U_i = ∮_{∂Ω_w} F_i · ν ds` (`ν` out of
//! `Ω_w`), so the term is exact for a polygonal Γ up to the quadrature on its edges, with no
//! quadrature of the `r⁻¹²` singularity over areas.

use crate::error::{Error, Result};
use crate::geom::DVec2;

/// A solute particle: position and Lennard-Jones parameters (001 (7.2)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Particle {
    /// Position `x_i`.
    pub x: DVec2,
    /// Length parameter `σ` (`U(σ) = 0`).
    pub sigma: f64,
    /// Energy parameter `ε` (the depth of the well, at `r = 2^{1/6} σ`).
    pub epsilon: f64,
}

impl Particle {
    /// The Lennard-Jones potential 001 (7.2), `U(r) = 4ε[(σ/r)¹² − (σ/r)⁶]`, at distance `r`.
    pub fn potential(&self, r: f64) -> f64 {
        let s6 = (self.sigma / r).powi(6);
        4.0 * self.epsilon * (s6 * s6 - s6)
    }

    /// `dU/dr` at distance `r`.
    pub fn potential_derivative(&self, r: f64) -> f64 {
        let s6 = (self.sigma / r).powi(6);
        4.0 * self.epsilon * (-12.0 * s6 * s6 + 6.0 * s6) / r
    }

    /// The radial field `F(x) = f(r) (x − x_i)/r` with `div F = U` (module documentation).
    pub fn flux_field(&self, p: DVec2) -> DVec2 {
        let d = p - self.x;
        let r = d.length();
        let s6 = (self.sigma / r).powi(6);
        // F = (f(r)/r) (x − x_i) with f(r)/r = 4ε [σ⁶/(4 r⁶) − σ¹²/(10 r¹²)].
        d * (4.0 * self.epsilon * (0.25 * s6 - 0.1 * s6 * s6))
    }
}

/// The model parameters of 001 (7.1): surface tension, solvent density, and the pressure and
/// Tolman length of the full model (0 in 001).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Parameters {
    /// Surface tension `γ` (001 writes `γ` or `γ₀`).
    pub gamma: f64,
    /// Solvent density `ρ_w`.
    pub rho_w: f64,
    /// Pressure difference `P` (the term `P |Ω_s|`).
    pub pressure: f64,
    /// Tolman length `τ` (the term `−2γτ ∫_Γ κ ds`).
    pub tolman: f64,
}

/// A solvation system: particles in a box and the model parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct System {
    /// The particles (fixed).
    pub particles: Vec<Particle>,
    /// The parameters.
    pub params: Parameters,
    /// The box `(lo, hi)` (001: the unit square).
    pub domain: (DVec2, DVec2),
}

impl System {
    /// Checks the system: at least one particle, every particle strictly inside the box with a
    /// positive finite `σ` and a non-negative finite `ε`, `γ ≥ 0`, `ρ_w ≥ 0`, finite `P` and `τ`.
    pub fn check(&self) -> Result<()> {
        let (lo, hi) = self.domain;
        if !(lo.is_finite() && hi.is_finite() && lo.x < hi.x && lo.y < hi.y) {
            return Err(Error::InvalidInput(format!(
                "solvation: the domain ({lo}, {hi}) is not a box"
            )));
        }
        if self.particles.is_empty() {
            return Err(Error::InvalidInput(
                "solvation: the system has no particle".into(),
            ));
        }
        for (i, p) in self.particles.iter().enumerate() {
            let inside =
                p.x.is_finite() && p.x.x > lo.x && p.x.x < hi.x && p.x.y > lo.y && p.x.y < hi.y;
            let valid = inside
                && p.sigma.is_finite()
                && p.sigma > 0.0
                && p.epsilon.is_finite()
                && p.epsilon >= 0.0;
            if !valid {
                return Err(Error::InvalidInput(format!(
                    "solvation: particle {i} at {} (sigma {}, epsilon {}) must lie inside the box \
                     with sigma > 0 and epsilon >= 0, finite",
                    p.x, p.sigma, p.epsilon
                )));
            }
        }
        let q = &self.params;
        let valid = q.gamma.is_finite()
            && q.gamma >= 0.0
            && q.rho_w.is_finite()
            && q.rho_w >= 0.0
            && q.pressure.is_finite()
            && q.tolman.is_finite();
        if !valid {
            return Err(Error::InvalidInput(format!(
                "solvation: need gamma >= 0, rho_w >= 0 and finite pressure and Tolman length \
                 (got {q:?})"
            )));
        }
        Ok(())
    }

    /// `ρ_w Σ_i U_i(|x − x_i|)`, the potential term of the normal velocity 001 (7.3).
    pub fn potential(&self, x: DVec2) -> f64 {
        self.params.rho_w
            * self
                .particles
                .iter()
                .map(|p| p.potential((x - p.x).length()))
                .sum::<f64>()
    }

    /// The gradient of [`System::potential`] at `x`.
    pub fn potential_gradient(&self, x: DVec2) -> DVec2 {
        let mut g = DVec2::ZERO;
        for p in &self.particles {
            let d = x - p.x;
            let r = d.length();
            g += d * (p.potential_derivative(r) / r);
        }
        g * self.params.rho_w
    }

    /// `ρ_w Σ_i ∫_seg F_i · ν ds` over the segment `a → b` with `ν` its right-hand unit normal
    /// (outward when the region lies on the left): Gauss–Legendre with 5 points on pieces no
    /// longer than a fifth of their distance to each particle, so the `r⁻¹¹` field is
    /// integrated to round-off.
    pub fn segment_flux(&self, a: DVec2, b: DVec2) -> f64 {
        const X: [f64; 5] = [
            -0.906_179_845_938_664,
            -0.538_469_310_105_683,
            0.0,
            0.538_469_310_105_683,
            0.906_179_845_938_664,
        ];
        const W: [f64; 5] = [
            0.236_926_885_056_189,
            0.478_628_670_499_366,
            0.568_888_888_888_889,
            0.478_628_670_499_366,
            0.236_926_885_056_189,
        ];
        let t = b - a;
        let len = t.length();
        if len == 0.0 {
            return 0.0;
        }
        let nu = DVec2::new(t.y, -t.x) / len;
        let mut total = 0.0;
        for p in &self.particles {
            let dist = segment_distance(p.x, a, b);
            let pieces = ((5.0 * len / dist.max(1e-300)).ceil() as usize).clamp(1, 4096);
            let step = 1.0 / pieces as f64;
            let mut s = 0.0;
            for k in 0..pieces {
                let (s0, s1) = (k as f64 * step, (k + 1) as f64 * step);
                for (x, w) in X.iter().zip(W) {
                    let u = 0.5 * (s0 + s1) + 0.5 * (s1 - s0) * x;
                    s += w * 0.5 * (s1 - s0) * p.flux_field(a + t * u).dot(nu);
                }
            }
            total += s * len;
        }
        self.params.rho_w * total
    }
}

/// Distance from `p` to the segment `[a, b]`.
pub fn segment_distance(p: DVec2, a: DVec2, b: DVec2) -> f64 {
    let t = b - a;
    let l2 = t.length_squared();
    let s = if l2 > 0.0 {
        ((p - a).dot(t) / l2).clamp(0.0, 1.0)
    } else {
        0.0
    };
    (a + t * s - p).length()
}
