//! Level-set relaxation of the solute–solvent interface by steepest descent of the free energy
//! 001 (7.1), as the algorithm of 001 §7 (steps 1–8) on the uniform base grid:
//!
//! 1. the base grid (right diagonals) and the initial wrap, redistanced;
//! 2. the curvature `κ_h` of the level set at the base vertices by local averaging
//!    (001 (5.2), [`vertex_curvature`]; boundary vertices 0);
//! 3. the zero level fitted into the base grid ([`fit`]);
//! 4. the potential term `ρ_w Σ_i U_i` of 001 (7.3) at the interface vertices of the fitted
//!    mesh;
//! 5. its extension off Γ by the velocity extension of 001 §3 ([`extend_velocity`], on a band
//!    of half-width [`RelaxOptions::band`] cells; harmonic by default), so the steep potential
//!    near the particles never enters the velocity directly;
//! 6. the level-set step `φ ← φ − Δt V` at the base vertices of the band with
//!    `V = −P − γκ_h + (extended potential term)` (001 (7.3); the 2D first variation, see
//!    [`super::model`]);
//! 7. reinitialisation: the exact distance to the P1 zero level
//!    ([`redistance_geometric`]) at every base vertex except the ends of the cut edges, whose
//!    values are kept so that reinitialising does not move Γ.
//!
//! **Time step** (adaptive): `Δt = c · min(h / max|V|, h²/(4γ), 1/max_Γ |∇(ρ_w ΣU)|)` with the
//! Courant number `c` ([`RelaxOptions::cfl`]): the advective limit, the limit of the explicit
//! curvature term (diffusion-like, `γκ ≈ −γΔφ`; with `h²/(2γ)` and `c = 0.5` the surface
//! oscillated from step to step on a 64² grid, with `h²/(4γ)` it settles), and the stiffness of
//! the potential (a displacement `δ` along `n` changes `V` by `∂_n(ρ_w ΣU) δ`).
//!
//! **Semi-implicit stabilisation** ([`RelaxOptions::stabilise`] `= s > 0`, the default): the
//! step solves `(M_L + Δt sγ K) δ = −Δt M_L V`, `φ ← φ + δ`, with the P1 stiffness `K` and
//! lumped mass `M_L` of the base grid — the explicit step plus `Δt sγ Δ_h(φ^{n+1} − φ^n)`, the
//! linear stabilisation of stiff curvature flows (Smereka 2003, J. Sci. Comput. 19). Its steady
//! states are the explicit scheme's (`δ = 0` exactly when `V = 0`), high-frequency modes of the
//! curvature term are damped instead of amplified, and the limit `h²/(4γ)` is lifted to
//! [`RelaxOptions::curvature_steps`]` · h²/(4γ)`; the advective and potential limits stay.
//!
//! The free energy ([`free_energy`]) is evaluated on every fitted mesh, so the record holds `G`
//! at every step. The relaxation stops at a steady state — the length-weighted mean `|V_n|` on Γ
//! below [`RelaxOptions::tol`], or `G` changed by less than [`RelaxOptions::energy_rtol`]` · |G|`
//! over the last [`RelaxOptions::window`] steps (the discrete `V_n` keeps an `O(h)` residual on
//! a settled surface) — or after [`RelaxOptions::max_steps`].

use super::energy::{free_energy, Energy};
use super::model::System;
use super::systems::{initial_level_set, Wrap};
use crate::backends::fitted::{
    extend_velocity, fit, vertex_curvature, ExtensionKind, ExtensionOptions, FitOptions, FittedMesh,
};
use crate::error::{Error, Result};
use crate::fem::solve::cg;
use crate::fem::{p1, p1::Coef, CgOptions, Csr, PrecondKind};
use crate::levelset::redistance::redistance_geometric;
use crate::mesh::{check_p1_field, GridPattern, Mesh2};
use serde::Serialize;

/// Options of [`relax`].
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RelaxOptions {
    /// Courant number `c` of the time step (module documentation).
    pub cfl: f64,
    /// Half-width of the band in which the velocity is extended and `φ` moved, in cells.
    pub band: f64,
    /// The velocity extension of 001 §3.
    pub extension: ExtensionKind,
    /// Cuts within this many cells of a base vertex are snapped to it.
    pub snap: f64,
    /// Stop when the length-weighted mean `|V_n|` on Γ is below this.
    pub tol: f64,
    /// Stop when `G` changed by less than this times `|G|` over the last `window` steps.
    pub energy_rtol: f64,
    /// The number of steps of the energy test.
    pub window: usize,
    /// Stop after this many steps.
    pub max_steps: usize,
    /// Semi-implicit stabilisation factor `s` (module documentation); 0 for the explicit step.
    pub stabilise: f64,
    /// With `stabilise > 0`: the curvature limit of the time step is this many times the
    /// explicit one, `h²/(4γ)`.
    pub curvature_steps: f64,
}

impl Default for RelaxOptions {
    fn default() -> Self {
        RelaxOptions {
            cfl: 0.5,
            band: 3.0,
            extension: ExtensionKind::Harmonic,
            snap: 0.01,
            tol: 2e-5,
            energy_rtol: 1e-6,
            window: 50,
            max_steps: 4000,
            stabilise: 1.0,
            curvature_steps: 16.0,
        }
    }
}

/// The state before one step.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct StepRecord {
    /// Steps done.
    pub step: usize,
    /// Pseudo-time of the relaxation.
    pub time: f64,
    /// The next time step (0 after the last).
    pub dt: f64,
    /// The free energy of the current surface.
    pub energy: Energy,
    /// Largest `|V_n|` on Γ.
    pub max_vn: f64,
    /// Length-weighted mean `|V_n|` on Γ.
    pub mean_vn: f64,
}

/// A relaxation: the record per step and the final level set.
#[derive(Debug, Clone)]
pub struct Relaxation {
    /// The records of the states 0, 1, ..., steps.
    pub records: Vec<StepRecord>,
    /// The initial level set (base vertices).
    pub phi_initial: Vec<f64>,
    /// The final level set.
    pub phi: Vec<f64>,
    /// Whether a steady state was reached (module documentation).
    pub converged: bool,
}

impl Relaxation {
    /// The free energy of the final surface.
    pub fn final_energy(&self) -> Energy {
        self.records[self.records.len() - 1].energy
    }
}

/// The base grid of `n × n` cells on the system's box and the initial level set of `wrap`
/// (`ring`: the annulus for a tight wrap), redistanced. Errors: `n` outside `8..=2048`, a wrap
/// that leaves the box or has no zero level on the grid.
pub fn setup(sys: &System, wrap: Wrap, ring: bool, n: usize) -> Result<(Mesh2, Vec<f64>)> {
    sys.check()?;
    if !(8..=2048).contains(&n) {
        return Err(Error::InvalidInput(format!(
            "solvation: the grid must have 8 to 2048 cells per side (got {n})"
        )));
    }
    let (lo, hi) = sys.domain;
    let base = Mesh2::rectangle(lo, hi, n, n, GridPattern::Right)?;
    let phi0 = initial_level_set(sys, wrap, ring, &base.points);
    let flags = base.boundary_vertex_flags();
    if let Some(v) = (0..phi0.len()).find(|&v| flags[v] && phi0[v] <= 0.0) {
        return Err(Error::InvalidInput(format!(
            "solvation: the {wrap:?} wrap reaches the boundary of the box at {}",
            base.points[v]
        )));
    }
    if !phi0.iter().any(|&f| f < 0.0) {
        return Err(Error::EmptyLevelSet(format!(
            "solvation: the {wrap:?} wrap encloses no vertex of the {n} x {n} grid"
        )));
    }
    let phi = redistance_geometric(&base, &phi0)?;
    Ok((base, phi))
}

fn check_options(o: &RelaxOptions) -> Result<()> {
    let ok = o.cfl.is_finite()
        && o.cfl > 0.0
        && o.cfl <= 1.0
        && o.band.is_finite()
        && o.band >= 1.0
        && o.snap.is_finite()
        && (0.0..0.5).contains(&o.snap)
        && o.tol.is_finite()
        && o.tol >= 0.0
        && o.energy_rtol.is_finite()
        && o.energy_rtol >= 0.0
        && o.window >= 1
        && o.stabilise.is_finite()
        && o.stabilise >= 0.0
        && o.curvature_steps.is_finite()
        && o.curvature_steps >= 1.0;
    if ok {
        Ok(())
    } else {
        Err(Error::InvalidInput(format!(
            "solvation: need 0 < cfl <= 1, band >= 1 cell, 0 <= snap < 0.5 cell, tol >= 0, \
             energy_rtol >= 0, window >= 1, stabilise >= 0, curvature_steps >= 1, all finite \
             (got {o:?})"
        )))
    }
}

/// What one evaluation at the current surface gives: its record (without `dt`) and the base
/// velocity.
fn evaluate(
    base: &Mesh2,
    h: f64,
    sys: &System,
    phi: &[f64],
    o: &RelaxOptions,
) -> Result<(StepRecord, Vec<f64>)> {
    let max_phi = phi.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let fm: FittedMesh = fit(
        base,
        phi,
        &FitOptions {
            iso: 0.0,
            snap: ((o.snap * h) / max_phi.max(f64::MIN_POSITIVE)).max(1e-12),
        },
    )?;
    let energy = free_energy(&fm, sys)?;
    let m = &fm.mesh;
    let n = m.n_points();
    let mut on = vec![false; n];
    let mut weight = vec![0.0; n];
    for [a, b] in fm.interface_edges() {
        let l = 0.5 * (m.points[a as usize] - m.points[b as usize]).length();
        for v in [a as usize, b as usize] {
            on[v] = true;
            weight[v] += l;
        }
    }
    for (flag, &u) in on.iter_mut().zip(&fm.u) {
        if u == 0.0 {
            *flag = true;
        }
    }
    // Steps 4–5: the potential term on Γ, extended.
    let mut w = vec![0.0; n];
    let mut stiff = 0.0f64;
    for v in (0..n).filter(|&v| on[v]) {
        w[v] = sys.potential(m.points[v]);
        stiff = stiff.max(sys.potential_gradient(m.points[v]).length());
    }
    let band = o.band * h;
    let ext = extend_velocity(
        &fm,
        &w,
        &on,
        &ExtensionOptions {
            kind: o.extension,
            band: Some(band),
        },
    )?;
    // Step 2: curvature at the base vertices.
    let kappa: Vec<f64> = vertex_curvature(base, phi)?
        .kappa
        .into_iter()
        .map(|k| k.unwrap_or(0.0))
        .collect();
    let q = &sys.params;
    let nb = fm.n_base_vertices;
    let velocity: Vec<f64> = (0..nb)
        .map(|v| {
            if phi[v].abs() <= band {
                -q.pressure - q.gamma * kappa[v] + ext.values[v]
            } else {
                0.0
            }
        })
        .collect();
    // V_n on Γ (κ interpolated along the cut edges) for the record and the stopping test.
    let kappa_fit = fm.extend_from_base(&kappa)?;
    let (mut max_vn, mut sum, mut len) = (0.0f64, 0.0, 0.0);
    for v in (0..n).filter(|&v| on[v]) {
        let vn = (-q.pressure - q.gamma * kappa_fit[v] + w[v]).abs();
        max_vn = max_vn.max(vn);
        sum += weight[v] * vn;
        len += weight[v];
    }
    let mean_vn = if len > 0.0 { sum / len } else { 0.0 };
    let vmax = velocity.iter().fold(0.0f64, |a, &b| a.max(b.abs()));
    let mut dt = f64::INFINITY;
    if vmax > 0.0 {
        dt = dt.min(h / vmax);
    }
    if q.gamma > 0.0 {
        let steps = if o.stabilise > 0.0 {
            o.curvature_steps
        } else {
            1.0
        };
        dt = dt.min(steps * h * h / (4.0 * q.gamma));
    }
    if stiff > 0.0 {
        dt = dt.min(1.0 / stiff);
    }
    if !dt.is_finite() {
        dt = 0.0;
    }
    Ok((
        StepRecord {
            step: 0,
            time: 0.0,
            dt: o.cfl * dt,
            energy,
            max_vn,
            mean_vn,
        },
        velocity,
    ))
}

/// Relaxes the level set `phi` (negative in the solute, on `base`, a uniform grid of cell size
/// `h` over the system's box) by the loop of the module documentation.
///
/// Errors: invalid options or system, a field of the wrong size or with non-finite values, a
/// solute region that vanishes ([`Error::EmptyLevelSet`]), a particle that ends up in the
/// solvent, the extension's solver errors.
pub fn relax(
    base: &Mesh2,
    h: f64,
    sys: &System,
    phi: Vec<f64>,
    o: &RelaxOptions,
) -> Result<Relaxation> {
    check_options(o)?;
    sys.check()?;
    check_p1_field(base.n_points(), &phi, "level set")?;
    if !(h.is_finite() && h > 0.0) {
        return Err(Error::InvalidInput(format!(
            "solvation: the cell size must be finite and positive (got {h})"
        )));
    }
    let phi_initial = phi.clone();
    let mut phi = phi;
    let mut records: Vec<StepRecord> = Vec::new();
    let mut time = 0.0;
    let mut converged = false;
    let mut implicit = if o.stabilise > 0.0 && sys.params.gamma > 0.0 {
        Some(Stabiliser::new(base, o.stabilise * sys.params.gamma)?)
    } else {
        None
    };
    for step in 0..=o.max_steps {
        let (mut rec, velocity) = evaluate(base, h, sys, &phi, o)?;
        rec.step = step;
        rec.time = time;
        let settled = step >= o.window && {
            let g0 = records[step - o.window].energy.total;
            (rec.energy.total - g0).abs() <= o.energy_rtol * rec.energy.total.abs()
        };
        if rec.mean_vn < o.tol || settled || step == o.max_steps || rec.dt == 0.0 {
            converged = rec.mean_vn < o.tol || settled || rec.dt == 0.0;
            rec.dt = 0.0;
            records.push(rec);
            break;
        }
        records.push(rec);
        let dt = rec.dt;
        match implicit.as_mut() {
            Some(st) => st.step(&mut phi, &velocity, dt)?,
            None => {
                for (p, &v) in phi.iter_mut().zip(&velocity) {
                    *p -= dt * v;
                }
            }
        }
        phi = reinitialise(base, &phi)?;
        time += dt;
    }
    Ok(Relaxation {
        records,
        phi_initial,
        phi,
        converged,
    })
}

/// The semi-implicit step `(M_L + Δt β K) δ = −Δt M_L V` (module documentation).
struct Stabiliser {
    k: Csr,
    m: Vec<f64>,
    a: Csr,
    delta: Vec<f64>,
    beta: f64,
}

impl Stabiliser {
    fn new(base: &Mesh2, beta: f64) -> Result<Self> {
        let k = p1::stiffness(base, &Coef::Const(1.0))?;
        let m = p1::lumped_mass(base)?;
        let a = k.clone();
        let delta = vec![0.0; m.len()];
        Ok(Stabiliser {
            k,
            m,
            a,
            delta,
            beta,
        })
    }

    /// `φ ← φ + δ`; the previous increment is the initial guess of CG.
    fn step(&mut self, phi: &mut [f64], velocity: &[f64], dt: f64) -> Result<()> {
        let n = self.m.len();
        for (a, &k) in self.a.val.iter_mut().zip(&self.k.val) {
            *a = dt * self.beta * k;
        }
        for i in 0..n {
            if let Some(p) = self.a.find(i, i) {
                self.a.val[p] += self.m[i];
            }
        }
        let rhs: Vec<f64> = (0..n).map(|i| -dt * self.m[i] * velocity[i]).collect();
        let rep = cg(
            &self.a,
            &rhs,
            &mut self.delta,
            &CgOptions {
                rtol: 1e-10,
                atol: 0.0,
                max_iter: 2000,
                precond: PrecondKind::Ic0,
            },
        )?;
        if !rep.converged {
            return Err(Error::NotConverged(format!(
                "solvation: the semi-implicit step did not converge (residual {:.1e} after {} \
                 iterations)",
                rep.residual, rep.iterations
            )));
        }
        for (p, &d) in phi.iter_mut().zip(&self.delta) {
            *p += d;
        }
        Ok(())
    }
}

/// Step 7: the distance to the P1 zero level except at the ends of the cut base edges.
fn reinitialise(base: &Mesh2, phi: &[f64]) -> Result<Vec<f64>> {
    let mut out = redistance_geometric(base, phi)?;
    for t in base.live_tris() {
        for i in 0..3 {
            let [a, b] = base.edge_vertices(t, i);
            let (a, b) = (a as usize, b as usize);
            if phi[a] * phi[b] <= 0.0 {
                out[a] = phi[a];
                out[b] = phi[b];
            }
        }
    }
    Ok(out)
}
