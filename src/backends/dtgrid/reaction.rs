//! Reaction–diffusion on a fixed implicit surface solved on a narrow band (000 §2.1, §4.1):
//! each species `u` takes the semi-implicit step
//! `(M[Φ] + τ c L[Φ]) U^{k+1} = M[Φ] (U^k + τ F[U^k]) (+ τ c Γ[U^k])` (000 §2.1, the system
//! after (2.2)), diffusion implicit (CG), reaction explicit, with the weighted lumped mass and
//! the tangential stiffness of the surface heat problem ([`Weight::Heat`]) and natural or
//! transparent Neumann conditions (000 (2.9)–(2.10), `U_approx = U^k`).
//!
//! [`Turing`] is the two-species system of 000 §4.1 (Turing's model as Turk uses it for
//! textures): `∂ₜa = c_s(α − ab) + c_a Δ_M a`, `∂ₜb = c_s(ab − b − β) + c_b Δ_M b` with a random
//! `β = β̄ ± δβ` per band node. Its homogeneous state is `a = α/(α − β̄)`, `b = α − β̄`.

use super::band::Band;
use super::fem::{assemble, elements, transparent_vector, BandMatrices, Element, Weight};
use super::lattice::{Lattice, NarrowBand, C3};
use super::scheme::{solve_all, system_matrix, Bc};
use crate::error::{Error, Result};
use crate::fem::Csr;

/// The band discretisation of `Δ_M` on the zero level of a fixed band field `Φ`.
#[derive(Debug, Clone)]
pub struct SurfaceOperator {
    lat: Lattice,
    elems: Vec<Element>,
    phi: Vec<f64>,
    /// The weighted lumped mass `M[Φ]` and tangential stiffness `L[Φ]` (000 §2.1).
    pub mats: BandMatrices,
    bc: Bc,
}

impl SurfaceOperator {
    /// Assembles the surface heat matrices on the band `nb` for the band field `phi`.
    /// Errors: [`Error::InvalidInput`] for Dirichlet or extrapolated conditions (the surface stays fixed; use
    /// natural or transparent ones) or a field of the wrong length.
    pub fn new<B: Band<Coord = C3>>(
        lat: Lattice,
        nb: &NarrowBand<B>,
        phi: &[f64],
        bc: Bc,
    ) -> Result<SurfaceOperator> {
        if matches!(bc, Bc::Dirichlet | Bc::Extrapolated) {
            return Err(Error::InvalidInput(
                "reaction–diffusion on a fixed surface takes natural or transparent conditions"
                    .into(),
            ));
        }
        let n = nb.band.len();
        if phi.len() != n {
            return Err(Error::InvalidInput(format!(
                "level-set field of {} values on a band of {n} nodes",
                phi.len()
            )));
        }
        let elems = elements(nb);
        let mats = assemble(&lat, &elems, n, phi, Weight::Heat)?;
        Ok(SurfaceOperator {
            lat,
            elems,
            phi: phi.to_vec(),
            mats,
            bc,
        })
    }

    /// The number of band nodes.
    pub fn len(&self) -> usize {
        self.mats.mass.len()
    }

    /// Whether the band is empty.
    pub fn is_empty(&self) -> bool {
        self.mats.mass.is_empty()
    }

    /// `M + τ c L`, the matrix of one step of a species diffusing with coefficient `c`.
    pub fn system(&self, c: f64, tau: f64) -> Result<Csr> {
        system_matrix(&self.mats, c * tau)
    }

    /// One step of `∂ₜu = c Δ_M u + f` with the matrix `a = self.system(c, tau)` and the
    /// explicit reaction values `f` per band node; returns the CG iterations.
    /// Errors: [`Error::InvalidInput`] for fields of the wrong length, solver errors
    /// ([`Error::NotConverged`], [`Error::InvalidField`] for a non-finite result).
    pub fn step(&self, a: &Csr, c: f64, tau: f64, u: &mut [f64], f: &[f64]) -> Result<usize> {
        let n = self.len();
        if u.len() != n || f.len() != n {
            return Err(Error::InvalidInput(format!(
                "fields of {} and {} values on a band of {n} nodes",
                u.len(),
                f.len()
            )));
        }
        let mut b: Vec<f64> = self
            .mats
            .mass
            .iter()
            .zip(u.iter().zip(f))
            .map(|(m, (u, f))| m * (u + tau * f))
            .collect();
        if self.bc == Bc::Transparent {
            let g = transparent_vector(&self.lat, &self.elems, n, &self.phi, u, Weight::Heat);
            b.iter_mut().zip(&g).for_each(|(b, g)| *b += tau * c * g);
        }
        solve_all(a, &b, u)
    }

    /// The mass-weighted mean `Σ Mᵢ uᵢ / Σ Mᵢ` (an approximation of the surface mean of `u`).
    pub fn mean(&self, u: &[f64]) -> f64 {
        let m: f64 = self.mats.mass.iter().sum();
        self.total(u) / m
    }

    /// The discrete total `Σ Mᵢ uᵢ`, conserved by pure diffusion under natural conditions.
    pub fn total(&self, u: &[f64]) -> f64 {
        self.mats.mass.iter().zip(u).map(|(m, u)| m * u).sum()
    }

    /// The mass-weighted variance of `u` about its mean.
    pub fn variance(&self, u: &[f64]) -> f64 {
        let mean = self.mean(u);
        let m: f64 = self.mats.mass.iter().sum();
        self.mats
            .mass
            .iter()
            .zip(u)
            .map(|(w, u)| w * (u - mean).powi(2))
            .sum::<f64>()
            / m
    }
}

/// The parameters of Turing's two-species system (000 §4.1).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Turing {
    /// The reaction rate `c_s`.
    pub cs: f64,
    /// The diffusion coefficient `c_a` of `a`.
    pub ca: f64,
    /// The diffusion coefficient `c_b` of `b`.
    pub cb: f64,
    /// `α`.
    pub alpha: f64,
    /// The mean of the random `β`.
    pub beta: f64,
    /// The half-width of the uniform random spread of `β`.
    pub beta_spread: f64,
    /// The seed of the random `β` (a hash of the seed and the node's grid coordinates, so the
    /// field does not depend on the storage or the thread count).
    pub seed: u64,
}

/// The grid spacing of the paper's dragon run (000 Fig. 4.1).
pub const PAPER_H: f64 = 0.00102;

impl Turing {
    /// The parameters of 000 Fig. 4.1: `c_s = 0.05`, `c_a = 2.5·10⁻⁷`, `c_b = 6.3·10⁻⁸`,
    /// `α = 16`, `β = 12 ± 0.4` at the grid spacing [`PAPER_H`].
    pub fn paper() -> Turing {
        Turing {
            cs: 0.05,
            ca: 2.5e-7,
            cb: 6.3e-8,
            alpha: 16.0,
            beta: 12.0,
            beta_spread: 0.4,
            seed: 1,
        }
    }

    /// The paper's parameters with `c_a`, `c_b` scaled by `(h / PAPER_H)²`: the same pattern
    /// measured in grid cells on a grid of spacing `h`.
    pub fn paper_at(h: f64) -> Turing {
        let s = (h / PAPER_H).powi(2);
        let p = Turing::paper();
        Turing {
            ca: p.ca * s,
            cb: p.cb * s,
            ..p
        }
    }

    /// The homogeneous steady state `(a, b) = (α/(α − β̄), α − β̄)`.
    pub fn steady_state(&self) -> (f64, f64) {
        let b = self.alpha - self.beta;
        (self.alpha / b, b)
    }

    /// `β` at the grid node `c`: `β̄ + δβ·(2ξ − 1)` with `ξ ∈ [0, 1)` hashed from the seed and `c`.
    pub fn beta_at(&self, c: C3) -> f64 {
        let xi = unit_hash(self.seed, c);
        self.beta + self.beta_spread * (2.0 * xi - 1.0)
    }

    /// Checks that the parameters are finite, the rates and coefficients positive and
    /// `α > β̄ + δβ` (a positive steady state everywhere).
    pub fn check(&self) -> Result<()> {
        let v = [
            self.cs,
            self.ca,
            self.cb,
            self.alpha,
            self.beta,
            self.beta_spread,
        ];
        if v.iter().any(|x| !x.is_finite())
            || self.cs <= 0.0
            || self.ca <= 0.0
            || self.cb <= 0.0
            || self.beta_spread < 0.0
            || self.alpha <= self.beta + self.beta_spread
        {
            return Err(Error::InvalidInput(format!(
                "Turing parameters c_s = {}, c_a = {}, c_b = {}, α = {}, β = {} ± {} (rates and \
                 coefficients positive, α > β + spread)",
                self.cs, self.ca, self.cb, self.alpha, self.beta, self.beta_spread
            )));
        }
        Ok(())
    }
}

/// A uniform number in `[0, 1)` from `seed` and a grid coordinate (SplitMix64 finaliser).
pub fn unit_hash(seed: u64, c: C3) -> f64 {
    let mut x = seed ^ 0x9e37_79b9_7f4a_7c15;
    for v in c {
        x = x
            .wrapping_add(v as u32 as u64)
            .wrapping_mul(0xbf58_476d_1ce4_e5b9);
        x ^= x >> 31;
        x = x.wrapping_mul(0x94d0_49bb_1331_11eb);
        x ^= x >> 29;
    }
    (x >> 11) as f64 / (1u64 << 53) as f64
}

/// Turing's system on a band: both species, the random `β`, the operator and the two step
/// matrices.
#[derive(Debug, Clone)]
pub struct TuringState {
    /// The species `a` per band node.
    pub a: Vec<f64>,
    /// The species `b` per band node.
    pub b: Vec<f64>,
    /// `β` per band node.
    pub beta: Vec<f64>,
    /// The surface operator.
    pub op: SurfaceOperator,
    params: Turing,
    tau: f64,
    sys_a: Csr,
    sys_b: Csr,
}

impl TuringState {
    /// Starts from the homogeneous steady state on the band `nb` around the zero level of
    /// `phi`, with time step `tau`.
    /// Errors: invalid parameters or `tau`, as [`SurfaceOperator::new`].
    pub fn new<B: Band<Coord = C3>>(
        lat: Lattice,
        nb: &NarrowBand<B>,
        phi: &[f64],
        params: Turing,
        tau: f64,
        bc: Bc,
    ) -> Result<TuringState> {
        params.check()?;
        if !(tau.is_finite() && tau > 0.0) {
            return Err(Error::InvalidInput(format!(
                "time step {tau} (must be positive)"
            )));
        }
        let op = SurfaceOperator::new(lat, nb, phi, bc)?;
        let (a0, b0) = params.steady_state();
        let n = op.len();
        let beta = nb.band.coords().map(|c| params.beta_at(c)).collect();
        let sys_a = op.system(params.ca, tau)?;
        let sys_b = op.system(params.cb, tau)?;
        Ok(TuringState {
            a: vec![a0; n],
            b: vec![b0; n],
            beta,
            op,
            params,
            tau,
            sys_a,
            sys_b,
        })
    }

    /// The time step.
    pub fn tau(&self) -> f64 {
        self.tau
    }

    /// One step of both species; returns the CG iterations.
    /// Errors: solver errors, [`Error::InvalidField`] when a concentration stops being finite.
    pub fn step(&mut self) -> Result<usize> {
        let p = self.params;
        let fa: Vec<f64> = self
            .a
            .iter()
            .zip(&self.b)
            .map(|(a, b)| p.cs * (p.alpha - a * b))
            .collect();
        let fb: Vec<f64> = self
            .a
            .iter()
            .zip(&self.b)
            .zip(&self.beta)
            .map(|((a, b), beta)| p.cs * (a * b - b - beta))
            .collect();
        let mut it = self
            .op
            .step(&self.sys_a, p.ca, self.tau, &mut self.a, &fa)?;
        it += self
            .op
            .step(&self.sys_b, p.cb, self.tau, &mut self.b, &fb)?;
        // The reaction keeps b ≥ 0 in the continuous problem; clamp the explicit step's
        // undershoot so the product ab stays meaningful.
        self.b.iter_mut().for_each(|b| *b = b.max(0.0));
        Ok(it)
    }
}
