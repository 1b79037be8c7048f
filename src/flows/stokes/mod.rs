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
//!   of the element; also Cholesky): 19–21 iterations at rtol 1e-8 on criss-cross meshes of
//!   545–8,321 vertices for viscosity ratios 1–1e-6 (`tests/stokes_couette.rs`).
//! - [`StokesSolver::Direct`]: sparse LU of the whole saddle-point matrix, the reference.
//!
//! When every boundary edge is Dirichlet the pressure is defined up to a constant: the Uzawa
//! iteration is kept orthogonal to constants and the direct solve adds the constraint `∫ p = 0`
//! with a Lagrange multiplier; in both cases the returned pressure has zero mean.
//!
//! This module owns the types the solvers share; its children each import only from here and
//! from lower layers:
//! - `viscosity`: [`Viscosity`] and the element viscosity (sampled or harmonic mean);
//! - `boundary`: Dirichlet data, traction and surface-tension loads;
//! - `uzawa`: block assembly and the Schur-complement CG;
//! - `direct`: the full saddle-point matrix and its LU;
//! - `diagnostics`: rigid-motion fit and L2 errors of a solution.

mod boundary;
mod diagnostics;
mod direct;
mod uzawa;
mod viscosity;

pub use diagnostics::{rigid_motion_fit, stokes_errors, RigidFit};
pub use viscosity::{negative_fraction, Viscosity};

use crate::error::{Error, Result};
use crate::fem::assembly::assemble_vector;
use crate::fem::csr::dot;
use crate::fem::p1::{check_areas, live_elements};
use crate::fem::p1_bubble::{mini_velocity, BubbleRecovery, MiniElement};
use crate::fem::quadrature::tri_rule;
use crate::geom::DVec2;
use crate::mesh::Mesh2;
use rayon::prelude::*;
use std::time::Instant;

/// A vector field `x -> v(x)` usable from several threads.
pub type VecField<'a> = &'a (dyn Fn(DVec2) -> DVec2 + Sync);

/// Which solver [`StokesProblem::solve`] uses.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum StokesSolver {
    /// Schur-complement CG (Uzawa) to relative residual `rtol` on the pressure equation.
    Uzawa {
        /// Relative tolerance on the pressure equation.
        rtol: f64,
        /// Iteration limit.
        max_iter: usize,
    },
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
    /// elimination).
    pub assembly_seconds: f64,
    /// Uzawa only: seconds of the two Cholesky factorisations (ordering included).
    pub factor_seconds: f64,
    /// Uzawa only: seconds of the Schur-complement CG (with the final velocity solve).
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

/// Dirichlet data on the `3 n_v` dofs (`ux = v`, `uy = n_v + v`, `p = 2 n_v + v`).
struct DirichletData {
    /// Per-dof mask (both components of a vertex are fixed together; pressures never).
    fixed: Vec<bool>,
    /// Prescribed values at the fixed dofs (0 elsewhere).
    values: Vec<f64>,
    /// Every boundary edge is Dirichlet: the pressure is defined up to a constant.
    all_dirichlet: bool,
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
        self.check_input()?;
        let (slots, tris) = live_elements(self.mesh);
        let mut rhs = vec![0.0; 3 * self.mesh.n_points()];
        self.add_neumann(&mut rhs);
        if self.surface_tension != 0.0 {
            self.add_surface_tension(&mut rhs);
        }
        let bc = self.dirichlet_data()?;
        let (mut x, recovery, mut report) = self.solve_system(solver, &slots, &tris, rhs, &bc)?;
        if bc.all_dirichlet {
            self.shift_pressure_to_zero_mean(&slots, &tris, &mut x)?;
        }
        let sol = self.solution(&slots, &tris, &x, recovery.as_deref());
        report.seconds = start.elapsed().as_secs_f64();
        Ok((sol, report))
    }

    /// Positive triangle areas, a valid viscosity, and a level set for surface tension.
    fn check_input(&self) -> Result<()> {
        check_areas(self.mesh)?;
        self.viscosity.validate(self.mesh)?;
        if self.surface_tension != 0.0 && self.viscosity.level_set().is_none() {
            return Err(Error::InvalidInput(
                "surface tension needs a two-phase viscosity (it is applied on its level set)"
                    .into(),
            ));
        }
        Ok(())
    }

    /// The condensed MINI element of triangle slot `t`.
    fn element(&self, t: usize) -> MiniElement {
        let zero = |_: DVec2| DVec2::ZERO;
        let force: VecField = self.force.unwrap_or(&zero);
        MiniElement::new(
            self.mesh.tri_points(t),
            |l| self.viscosity.at(self.mesh, t, l),
            force,
        )
    }

    /// Solves the condensed system with `solver`: the solution in the full dof layout, the
    /// bubble-recovery data per element (Uzawa only) and the report.
    fn solve_system(
        &self,
        solver: StokesSolver,
        slots: &[usize],
        tris: &[[u32; 3]],
        rhs: Vec<f64>,
        bc: &DirichletData,
    ) -> Result<(Vec<f64>, Option<Vec<BubbleRecovery>>, StokesReport)> {
        let nv = self.mesh.n_points();
        match solver {
            StokesSolver::Direct => {
                let element = |e: usize| self.element(slots[e]);
                let (x, rep) = direct::solve(nv, tris, &element, rhs, bc)?;
                Ok((x, None, rep))
            }
            StokesSolver::Uzawa { rtol, max_iter } => {
                let input = uzawa::UzawaInput {
                    nv,
                    tris,
                    rhs_extra: &rhs,
                    bc,
                    rtol,
                    max_iter,
                };
                let (x, b, rep) = uzawa::solve(&input, |e| self.uzawa_element(slots[e]))?;
                Ok((x, Some(b), rep))
            }
        }
    }

    /// What triangle slot `t` contributes to the Uzawa blocks.
    fn uzawa_element(&self, t: usize) -> uzawa::ElementData {
        let el = self.element(t);
        uzawa::ElementData {
            k: el.k,
            f: el.f,
            // Arithmetic mean of μ over the element: a cut element is as stiff as its viscous
            // part, so the pressure mass weights it like it (with a harmonic mean of the
            // sampled μ the outer iteration count grows with the viscosity ratio).
            mu_mean: tri_rule(5).mean(|l| self.viscosity.at(self.mesh, t, l)),
            area: self.mesh.tri_area(t),
            bubble: el.bubble_recovery(),
        }
    }

    /// Subtracts `∫p / |Ω|` from the pressure part of `x` (`∫p = Σ p_i ∫φ_i`, `∫φ_i` the
    /// lumped mass).
    fn shift_pressure_to_zero_mean(
        &self,
        slots: &[usize],
        tris: &[[u32; 3]],
        x: &mut [f64],
    ) -> Result<()> {
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let mut lm = vec![0.0; nv];
        assemble_vector(&mut lm, tris, |e| [mesh.tri_area(slots[e]) / 3.0; 3])?;
        let mean = dot(&lm, &x[2 * nv..]) / lm.iter().sum::<f64>();
        x[2 * nv..].iter_mut().for_each(|p| *p -= mean);
        Ok(())
    }

    /// The solution from the full dof vector `x`, with the bubbles recovered per element.
    fn solution(
        &self,
        slots: &[usize],
        tris: &[[u32; 3]],
        x: &[f64],
        recovery: Option<&[BubbleRecovery]>,
    ) -> StokesSolution {
        let mesh = self.mesh;
        let nv = mesh.n_points();
        let bub: Vec<[f64; 2]> = tris
            .par_iter()
            .enumerate()
            .map(|(e, v)| {
                let xe: [f64; 9] = std::array::from_fn(|k| x[(k / 3) * nv + v[k % 3] as usize]);
                match recovery {
                    Some(r) => r[e].bubble(&xe),
                    None => self.element(slots[e]).bubble(&xe),
                }
            })
            .collect();
        let mut bubbles = vec![DVec2::ZERO; mesh.n_tris()];
        for (e, b) in bub.iter().enumerate() {
            bubbles[slots[e]] = DVec2::new(b[0], b[1]);
        }
        StokesSolution {
            velocity: (0..nv).map(|v| DVec2::new(x[v], x[nv + v])).collect(),
            bubbles,
            pressure: x[2 * nv..].to_vec(),
        }
    }
}
