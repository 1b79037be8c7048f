//! Two-phase Stokes flow with the MINI element (004 §5.1, eqs. (7)–(9)):
//! `-div(2 μ ε(u)) + ∇p = f`, `div u = 0` on the mesh, with a viscosity that jumps across the
//! zero level of a level set, Dirichlet data on some boundary labels, natural (traction)
//! conditions `σ n = s_N` on others, and an optional surface-tension force on the interface.
//!
//! After static condensation of the bubbles ([`MiniElement`]) the discrete system is
//! `[[A, Bᵀ], [B, -C]] (u, p) = (F, G)` with global dofs `ux = v`, `uy = n_v + v`,
//! `p = 2 n_v + v`. Two solvers:
//! - [`StokesSolver::Uzawa`]: CG on the pressure Schur complement `S = B A⁻¹ Bᵀ + C` (Uzawa's
//!   method accelerated by CG, 004 §5.1), with the Dirichlet velocity dofs eliminated, `A`
//!   factorised once by sparse Cholesky (AMD ordering of the vertex graph) and `S`
//!   preconditioned by the pressure mass matrix weighted by `1/μ̄_T` (`μ̄_T` the mean viscosity
//!   of the element; also Cholesky): measured 19–21 iterations at rtol 1e-8 on criss-cross
//!   meshes of 545–8,321 vertices for viscosity ratios 1–1e-6 (`tests/stokes_couette.rs`).
//!   The block assembly and the iteration are in `src/flows/stokes_uzawa.rs`.
//! - [`StokesSolver::Direct`]: sparse LU of the whole saddle-point matrix, the reference.
//!
//! When every boundary edge is Dirichlet the pressure is defined up to a constant: the Uzawa
//! iteration is kept orthogonal to constants and the direct solve adds the constraint `∫ p = 0`
//! with a Lagrange multiplier; in both cases the returned pressure has zero mean.

use super::stokes_uzawa::{self, ElementData, UzawaInput};
use crate::error::{Error, Result};
use crate::fem::assembly::{assemble_matrix, assemble_vector};
use crate::fem::csr::{dot, norm, Csr};
use crate::fem::dirichlet::apply_dirichlet;
use crate::fem::p1::{bary_point, check_areas, live_elements, P1Geom};
use crate::fem::p1_bubble::{mini_velocity, MiniElement};
use crate::fem::quadrature::tri_rule;
use crate::fem::solve::Lu;
use crate::geom::DVec2;
use crate::mesh::{Mesh2, NONE};
use rayon::prelude::*;
use std::time::Instant;

/// A vector field `x -> v(x)` usable from several threads.
pub type VecField<'a> = &'a (dyn Fn(DVec2) -> DVec2 + Sync);

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
        phi: Vec<f64>,
        mu_in: f64,
        mu_out: f64,
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
        phi: Vec<f64>,
        mu_in: f64,
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
    fn at(&self, mesh: &Mesh2, t: usize, l: &[f64; 3]) -> f64 {
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
    fn level_set(&self) -> Option<&[f64]> {
        match self {
            Viscosity::TwoPhase { phi, .. } | Viscosity::TwoPhaseHarmonic { phi, .. } => Some(phi),
            _ => None,
        }
    }

    fn validate(&self, mesh: &Mesh2) -> Result<()> {
        let bad = |msg: String| {
            Err(Error::InvalidField {
                name: "viscosity".into(),
                msg,
            })
        };
        match self {
            Viscosity::Constant(m) if !(m.is_finite() && *m > 0.0) => {
                bad(format!("constant viscosity {m} must be positive"))
            }
            Viscosity::PerElement(m) if m.len() != mesh.n_tris() => bad(format!(
                "{} values for {} triangle slots",
                m.len(),
                mesh.n_tris()
            )),
            Viscosity::PerElement(m) => match m.iter().position(|v| !(v.is_finite() && *v > 0.0)) {
                Some(t) => bad(format!(
                    "viscosity {} on triangle {t} must be positive",
                    m[t]
                )),
                None => Ok(()),
            },
            Viscosity::TwoPhaseHarmonic { phi, mu_in, mu_out } => Viscosity::TwoPhase {
                phi: phi.clone(),
                mu_in: *mu_in,
                mu_out: *mu_out,
                width: 0.0,
            }
            .validate(mesh),
            Viscosity::TwoPhase {
                phi,
                mu_in,
                mu_out,
                width,
            } => {
                if phi.len() != mesh.n_points() {
                    return bad(format!(
                        "level set has {} values for {} vertices",
                        phi.len(),
                        mesh.n_points()
                    ));
                }
                if phi.iter().any(|v| !v.is_finite()) {
                    return bad("level set holds NaN or infinite values".into());
                }
                if !(*mu_in > 0.0 && *mu_out > 0.0 && mu_in.is_finite() && mu_out.is_finite()) {
                    return bad(format!("viscosities {mu_in}, {mu_out} must be positive"));
                }
                if !(width.is_finite() && *width >= 0.0) {
                    return bad(format!("smoothing width {width} must be >= 0"));
                }
                Ok(())
            }
            _ => Ok(()),
        }
    }
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

/// Which solver [`StokesProblem::solve`] uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StokesSolver {
    /// Schur-complement CG (Uzawa) to relative residual `rtol` on the pressure equation.
    Uzawa { rtol: f64, max_iter: usize },
    /// Sparse LU of the full system.
    Direct,
}

impl Default for StokesSolver {
    fn default() -> Self {
        StokesSolver::Uzawa {
            rtol: 1e-10,
            max_iter: 500,
        }
    }
}

/// Statistics of a Stokes solve.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct StokesReport {
    /// Outer (pressure Schur-complement CG) iterations; 0 for the direct solver.
    pub uzawa_iterations: usize,
    /// Inner velocity solves `A⁻¹ v` (each one Cholesky forward/backward substitution).
    pub inner_iterations: usize,
    /// `‖K x - F‖ / ‖F‖` of the full condensed saddle-point system.
    pub residual: f64,
    /// Whether the outer iteration reached its tolerance (always true for the direct solver).
    pub converged: bool,
    /// Wall-clock seconds of assembly and solve.
    pub seconds: f64,
    /// Uzawa only: seconds of the block assembly (element matrices, scatter, Dirichlet
    /// elimination), of the two Cholesky factorisations (ordering included), of the
    /// Schur-complement CG (with the final velocity solve).
    pub assembly_seconds: f64,
    pub factor_seconds: f64,
    pub uzawa_seconds: f64,
    /// Uzawa only: entries of the Cholesky factor of the velocity block.
    pub factor_nnz: usize,
}

/// A MINI-element Stokes solution.
#[derive(Debug, Clone, PartialEq)]
pub struct StokesSolution {
    /// P1 part of the velocity (the velocity at the vertices).
    pub velocity: Vec<DVec2>,
    /// Bubble coefficient per triangle slot (zero on tombstones).
    pub bubbles: Vec<DVec2>,
    /// P1 pressure.
    pub pressure: Vec<f64>,
}

impl StokesSolution {
    /// The (P1 + bubble) velocity at barycentric point `l` of triangle slot `t`.
    pub fn velocity_at(&self, mesh: &Mesh2, t: usize, l: &[f64; 3]) -> DVec2 {
        let u = mesh.tris[t].map(|i| self.velocity[i as usize]);
        mini_velocity(&u, self.bubbles[t], l)
    }
}

/// A Stokes problem on a mesh. Build with [`StokesProblem::new`] and the builder methods.
pub struct StokesProblem<'a> {
    mesh: &'a Mesh2,
    viscosity: Viscosity,
    force: Option<VecField<'a>>,
    dirichlet: Vec<(i32, VecField<'a>)>,
    neumann: Vec<(i32, VecField<'a>)>,
    surface_tension: f64,
}

impl<'a> StokesProblem<'a> {
    /// A problem with viscosity 1, no force, and (until set) no boundary conditions: unset
    /// boundary labels are traction-free (natural).
    pub fn new(mesh: &'a Mesh2) -> Self {
        StokesProblem {
            mesh,
            viscosity: Viscosity::Constant(1.0),
            force: None,
            dirichlet: Vec::new(),
            neumann: Vec::new(),
            surface_tension: 0.0,
        }
    }

    /// Sets the viscosity.
    pub fn viscosity(mut self, v: Viscosity) -> Self {
        self.viscosity = v;
        self
    }

    /// Sets the body force `ρ f` of (7).
    pub fn force(mut self, f: VecField<'a>) -> Self {
        self.force = Some(f);
        self
    }

    /// Prescribes `u = g` on the boundary edges labelled `label` (9).
    pub fn dirichlet(mut self, label: i32, g: VecField<'a>) -> Self {
        self.dirichlet.push((label, g));
        self
    }

    /// Prescribes the traction `σ n = s` on the boundary edges labelled `label` (9).
    pub fn neumann(mut self, label: i32, s: VecField<'a>) -> Self {
        self.neumann.push((label, s));
        self
    }

    /// Adds the surface-tension force of coefficient `gamma` on the zero level of the
    /// two-phase viscosity's level set (interface condition (8) with `K = γ κ`), in the
    /// Laplace–Beltrami form `-γ ∫_Γ div_Γ v` on the piecewise linear interface.
    pub fn surface_tension(mut self, gamma: f64) -> Self {
        self.surface_tension = gamma;
        self
    }

    /// Assembles and solves. Errors on invalid input (bad viscosity, field sizes, degenerate
    /// triangles) or a failed factorisation; a Uzawa iteration that does not converge is
    /// reported in [`StokesReport::converged`].
    pub fn solve(&self, solver: StokesSolver) -> Result<(StokesSolution, StokesReport)> {
        let start = Instant::now();
        let mesh = self.mesh;
        check_areas(mesh)?;
        self.viscosity.validate(mesh)?;
        if self.surface_tension != 0.0 && self.viscosity.level_set().is_none() {
            return Err(Error::InvalidInput(
                "surface tension needs a two-phase viscosity (it is applied on its level set)"
                    .into(),
            ));
        }
        let nv = mesh.n_points();
        let (slots, tris) = live_elements(mesh);
        let zero = |_: DVec2| DVec2::ZERO;
        let force: VecField = self.force.unwrap_or(&zero);
        let element = |e: usize| {
            let t = slots[e];
            MiniElement::new(mesh.tri_points(t), |l| self.viscosity.at(mesh, t, l), force)
        };
        let mut rhs = vec![0.0; 3 * nv];
        self.add_neumann(&mut rhs)?;
        if self.surface_tension != 0.0 {
            self.add_surface_tension(&mut rhs)?;
        }
        let (fixed, values, all_dirichlet) = self.dirichlet_data()?;
        let (x, recovery, mut report) = match solver {
            StokesSolver::Direct => {
                let (x, rep) =
                    solve_full_direct(nv, &tris, &element, rhs, &fixed, &values, all_dirichlet)?;
                (x, None, rep)
            }
            StokesSolver::Uzawa { rtol, max_iter } => {
                let rule = tri_rule(5);
                let input = UzawaInput {
                    nv,
                    tris: &tris,
                    rhs_extra: &rhs,
                    fixed: &fixed,
                    values: &values,
                    all_dirichlet,
                    rtol,
                    max_iter,
                };
                stokes_uzawa::solve(&input, |e| {
                    let t = slots[e];
                    let el = element(e);
                    ElementData {
                        k: el.k,
                        f: el.f,
                        // Arithmetic mean of μ over the element: a cut element is as stiff
                        // as its viscous part, so the pressure mass must weight it like it
                        // (a harmonic mean of the sampled μ made the outer iteration count
                        // grow with the viscosity ratio).
                        mu_mean: rule.mean(|l| self.viscosity.at(mesh, t, l)),
                        area: mesh.tri_area(t),
                        bubble: el.bubble_recovery(),
                    }
                })
                .map(|(x, b, rep)| (x, Some(b), rep))?
            }
        };
        let mut x = x;
        if all_dirichlet {
            // Zero-mean pressure: subtract ∫p / |Ω| (∫p = Σ p_i ∫φ_i, ∫φ_i = lumped mass).
            let mut lm = vec![0.0; nv];
            assemble_vector(&mut lm, &tris, |e| [mesh.tri_area(slots[e]) / 3.0; 3])?;
            let mean = dot(&lm, &x[2 * nv..]) / lm.iter().sum::<f64>();
            x[2 * nv..].iter_mut().for_each(|p| *p -= mean);
        }
        let bub: Vec<[f64; 2]> = tris
            .par_iter()
            .enumerate()
            .map(|(e, v)| {
                let xe: [f64; 9] = std::array::from_fn(|k| x[(k / 3) * nv + v[k % 3] as usize]);
                match &recovery {
                    Some(r) => r[e].bubble(&xe),
                    None => element(e).bubble(&xe),
                }
            })
            .collect();
        let mut bubbles = vec![DVec2::ZERO; mesh.n_tris()];
        for (e, b) in bub.iter().enumerate() {
            bubbles[slots[e]] = DVec2::new(b[0], b[1]);
        }
        let sol = StokesSolution {
            velocity: (0..nv).map(|v| DVec2::new(x[v], x[nv + v])).collect(),
            bubbles,
            pressure: x[2 * nv..].to_vec(),
        };
        report.seconds = start.elapsed().as_secs_f64();
        Ok((sol, report))
    }

    /// Dirichlet mask and values on the 3 n_v dofs, and whether every boundary edge is
    /// Dirichlet (pressure defined up to a constant).
    fn dirichlet_data(&self) -> Result<(Vec<bool>, Vec<f64>, bool)> {
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let mut fixed = vec![false; 3 * nv];
        let mut values = vec![0.0; 3 * nv];
        let mut all = true;
        for t in mesh.live_tris() {
            for i in 0..3 {
                if mesh.neighbours[t][i] != NONE {
                    continue;
                }
                let label = mesh.edge_ref[t][i];
                let Some((_, g)) = self.dirichlet.iter().find(|(l, _)| *l == label) else {
                    all = false;
                    continue;
                };
                for v in mesh.edge_vertices(t, i) {
                    let v = v as usize;
                    let gv = g(mesh.points[v]);
                    if !gv.is_finite() {
                        return Err(Error::InvalidField {
                            name: "Dirichlet velocity".into(),
                            msg: format!("non-finite value at vertex {v}"),
                        });
                    }
                    fixed[v] = true;
                    fixed[nv + v] = true;
                    values[v] = gv.x;
                    values[nv + v] = gv.y;
                }
            }
        }
        Ok((fixed, values, all))
    }

    /// `∫_{Γ_N} s · v` on labelled boundary edges (2-point Gauss; the bubble vanishes there).
    fn add_neumann(&self, rhs: &mut [f64]) -> Result<()> {
        if self.neumann.is_empty() {
            return Ok(());
        }
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let g = 0.5 / 3f64.sqrt();
        for t in mesh.live_tris() {
            for i in 0..3 {
                if mesh.neighbours[t][i] != NONE {
                    continue;
                }
                let label = mesh.edge_ref[t][i];
                if self.dirichlet.iter().any(|(l, _)| *l == label) {
                    continue;
                }
                let Some((_, s)) = self.neumann.iter().find(|(l, _)| *l == label) else {
                    continue;
                };
                let [a, b] = mesh.edge_vertices(t, i);
                let (pa, pb) = (mesh.points[a as usize], mesh.points[b as usize]);
                let len = (pb - pa).length();
                for xi in [0.5 - g, 0.5 + g] {
                    let sv = s(pa + xi * (pb - pa)) * (0.5 * len);
                    for (v, phi) in [(a, 1.0 - xi), (b, xi)] {
                        rhs[v as usize] += phi * sv.x;
                        rhs[nv + v as usize] += phi * sv.y;
                    }
                }
            }
        }
        Ok(())
    }

    /// Surface tension `-γ ∫_Γ div_Γ v ds`, `div_Γ v = div v - n·(∇v) n`, on the straight
    /// piece of the zero level of the P1 level set in each cut triangle (P1 velocity part: the
    /// bubble contribution is dropped, it is of higher order).
    fn add_surface_tension(&self, rhs: &mut [f64]) -> Result<()> {
        let Some(phi) = self.viscosity.level_set() else {
            return Ok(());
        };
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let gamma = self.surface_tension;
        for t in mesh.live_tris() {
            let v = mesh.tris[t].map(|i| i as usize);
            let f = v.map(|i| phi[i]);
            let p = mesh.tri_points(t);
            // Zero crossings on the edges.
            let mut cut = Vec::with_capacity(2);
            for i in 0..3 {
                let (a, b) = ((i + 1) % 3, (i + 2) % 3);
                if (f[a] < 0.0) != (f[b] < 0.0) {
                    let s = f[a] / (f[a] - f[b]);
                    cut.push(p[a] + s * (p[b] - p[a]));
                }
            }
            if cut.len() != 2 {
                continue;
            }
            let len = (cut[1] - cut[0]).length();
            let g = P1Geom::new(p);
            let grad_phi: DVec2 = (0..3).map(|k| f[k] * g.grad[k]).sum();
            let nrm = grad_phi.normalize_or_zero();
            for k in 0..3 {
                // div_Γ(φ_k e_c) = ∂_c φ_k - n_c (n · ∇φ_k)
                let gk = g.grad[k];
                let tang = gk - nrm * nrm.dot(gk);
                rhs[v[k]] -= gamma * len * tang.x;
                rhs[nv + v[k]] -= gamma * len * tang.y;
            }
        }
        Ok(())
    }
}

/// The direct reference: assembles the full condensed saddle-point matrix `K` (dofs
/// `ux = v, uy = n_v + v, p = 2 n_v + v`), eliminates the Dirichlet dofs symmetrically and
/// solves by sparse LU. Returns the solution and a report with the residual `‖K x - F‖/‖F‖`.
fn solve_full_direct(
    nv: usize,
    tris: &[[u32; 3]],
    element: &(impl Fn(usize) -> MiniElement + Sync),
    mut rhs: Vec<f64>,
    fixed: &[bool],
    values: &[f64],
    all_dirichlet: bool,
) -> Result<(Vec<f64>, StokesReport)> {
    let nvu = nv as u32;
    let elems: Vec<[u32; 9]> = tris
        .iter()
        .map(|v| std::array::from_fn(|k| (k as u32 / 3) * nvu + v[k % 3]))
        .collect();
    let mut k = Csr::from_elements(3 * nv, &elems)?;
    assemble_matrix(&mut k, &elems, |e| element(e).k)?;
    assemble_vector(&mut rhs, &elems, |e| element(e).f)?;
    apply_dirichlet(&mut k, &mut rhs, fixed, values)?;
    let x = solve_direct(&k, &rhs, nv, all_dirichlet)?;
    let kx = k.mul(&x);
    let r: Vec<f64> = kx.iter().zip(&rhs).map(|(a, b)| a - b).collect();
    let report = StokesReport {
        converged: true,
        residual: norm(&r) / norm(&rhs).max(f64::MIN_POSITIVE),
        ..Default::default()
    };
    Ok((x, report))
}

/// Sparse LU of the condensed system; with all-Dirichlet boundaries the matrix is bordered by
/// the constraint `Σ_i p_i ∫φ_i = 0` (Lagrange multiplier in the last row and column).
fn solve_direct(k: &Csr, rhs: &[f64], nv: usize, all_dirichlet: bool) -> Result<Vec<f64>> {
    if !all_dirichlet {
        let mut x = rhs.to_vec();
        Lu::new(k)?.solve_in_place(&mut x);
        return Ok(x);
    }
    // Constraint with unit weights (the kernel of the pressure block is the constant vector);
    // the zero-mean shift is applied afterwards by the caller.
    let n = k.n;
    let mut row_ptr = Vec::with_capacity(n + 2);
    let mut col = Vec::with_capacity(k.nnz() + 2 * nv + 1);
    let mut val = Vec::with_capacity(k.nnz() + 2 * nv + 1);
    row_ptr.push(0);
    for i in 0..n {
        for q in k.row_ptr[i]..k.row_ptr[i + 1] {
            col.push(k.col[q]);
            val.push(k.val[q]);
        }
        if i >= 2 * nv {
            col.push(n as u32);
            val.push(1.0);
        }
        row_ptr.push(col.len());
    }
    for j in 2 * nv..n {
        col.push(j as u32);
        val.push(1.0);
    }
    col.push(n as u32);
    val.push(0.0);
    row_ptr.push(col.len());
    let kb = Csr {
        n: n + 1,
        row_ptr,
        col,
        val,
    };
    let mut x = rhs.to_vec();
    x.push(0.0);
    Lu::new(&kb)?.solve_in_place(&mut x);
    x.truncate(n);
    if x.iter().any(|v| !v.is_finite()) {
        return Err(Error::InvalidInput(
            "Stokes direct solve: singular saddle-point matrix".into(),
        ));
    }
    Ok(x)
}

/// A least-squares rigid motion `u(x) ≈ t + ω (x - c)^⊥` of a velocity field inside a region.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RigidFit {
    /// Angular velocity `ω` (counter-clockwise positive).
    pub omega: f64,
    /// Velocity of the centroid `c` of the region.
    pub translation: DVec2,
    /// The centroid `c` of the fitted vertices (weighted).
    pub centre: DVec2,
    /// `max_i |u_i - t - ω (x_i - c)^⊥| / max_i |u_i|` over the fitted vertices.
    pub max_deviation_rel: f64,
    /// Number of vertices used.
    pub vertices: usize,
}

/// Fits a rigid motion to the P1 `velocity` at the vertices `x` with `inside(x)`, weighting each
/// vertex by its lumped-mass area (so the fit does not depend on how densely the region is
/// meshed). The measure of rigidity of the Couette disk of 004 §5.1. Errors when fewer than two
/// vertices are inside.
pub fn rigid_motion_fit(
    mesh: &Mesh2,
    velocity: &[DVec2],
    inside: impl Fn(DVec2) -> bool,
) -> Result<RigidFit> {
    if velocity.len() != mesh.n_points() {
        return Err(Error::InvalidField {
            name: "velocity".into(),
            msg: format!("{} values for {} vertices", velocity.len(), mesh.n_points()),
        });
    }
    let mut w = vec![0.0; mesh.n_points()];
    for t in mesh.live_tris() {
        let a = mesh.tri_area(t) / 3.0;
        for v in mesh.tris[t] {
            w[v as usize] += a;
        }
    }
    let ids: Vec<usize> = (0..mesh.n_points())
        .filter(|&v| w[v] > 0.0 && inside(mesh.points[v]))
        .collect();
    if ids.len() < 2 {
        return Err(Error::InvalidInput(format!(
            "rigid-motion fit needs at least 2 vertices inside the region, found {}",
            ids.len()
        )));
    }
    let wsum: f64 = ids.iter().map(|&v| w[v]).sum();
    let c: DVec2 = ids.iter().map(|&v| w[v] * mesh.points[v]).sum::<DVec2>() / wsum;
    let t: DVec2 = ids.iter().map(|&v| w[v] * velocity[v]).sum::<DVec2>() / wsum;
    let (mut num, mut den) = (0.0, 0.0);
    for &v in &ids {
        let r = mesh.points[v] - c;
        num += w[v] * r.perp().dot(velocity[v] - t);
        den += w[v] * r.length_squared();
    }
    let omega = if den > 0.0 { num / den } else { 0.0 };
    let (mut dev, mut umax) = (0.0f64, 0.0f64);
    for &v in &ids {
        let r = mesh.points[v] - c;
        dev = dev.max((velocity[v] - t - omega * r.perp()).length());
        umax = umax.max(velocity[v].length());
    }
    Ok(RigidFit {
        omega,
        translation: t,
        centre: c,
        max_deviation_rel: if umax > 0.0 { dev / umax } else { 0.0 },
        vertices: ids.len(),
    })
}

/// The velocity error `‖u_h - u‖_{L2}` (P1 + bubble) and pressure error `‖p_h - p‖_{L2}` of a
/// solution against exact fields, with the degree-7 rule.
pub fn stokes_errors(
    mesh: &Mesh2,
    sol: &StokesSolution,
    u: impl Fn(DVec2) -> DVec2,
    p: impl Fn(DVec2) -> f64,
) -> (f64, f64) {
    let rule = tri_rule(7);
    let (mut eu, mut ep) = (0.0, 0.0);
    for t in mesh.live_tris() {
        let pts = mesh.tri_points(t);
        let area = mesh.tri_area(t);
        let pv = mesh.tris[t].map(|i| sol.pressure[i as usize]);
        eu += area
            * rule
                .mean(|l| (sol.velocity_at(mesh, t, l) - u(bary_point(&pts, l))).length_squared());
        ep += area
            * rule.mean(|l| {
                let e = l[0] * pv[0] + l[1] * pv[1] + l[2] * pv[2] - p(bary_point(&pts, l));
                e * e
            });
    }
    (eu.sqrt(), ep.sqrt())
}
