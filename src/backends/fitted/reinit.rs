//! Poisson reinitialisation of a level set on the interface-fitted mesh (001 §4): on the mesh
//! fitted to the zero level of `φ`, solve
//!
//! `Δφ = G` in Ω₋, `Δφ = 0` in Ω₊, `φ = 1` on ∂Ω, `φ = 0` on Γ, `[∂φ/∂n]_Γ = 0`,
//!
//! an overdetermined system, by least squares, as 001 §3 does for (3.1)–(3.9): the P1 Galerkin
//! rows of the two Dirichlet problems (the analogues of (3.7), (3.8)) at every fitted vertex off
//! Γ and off the Dirichlet boundary, and one gradient-jump row (3.9) per interface edge γ with
//! its triangles `T₋`, `T₊` and their vertices `x₋`, `x₊` off γ:
//! `∇φ|T₋·∇N₋/|∇N₋| + ∇φ|T₊·∇N₊/|∇N₊| = 0`, which, since `φ = 0` on γ, is
//! `φ(x₋)|∇N₋| + φ(x₊)|∇N₊| = 0`. The normal equations `AᵀA U = AᵀF` are solved by sparse
//! Cholesky (a direct method, as 001 §3). The result restricted to the base vertices is the new
//! level set ("unrefinement", 001 §4): the jump rows keep it smooth across Γ, so the zero level
//! of its base interpolant stays where it was up to the discretisation error.
//!
//! Choices the paper leaves open, made here:
//! - `φ = 1` is imposed on the boundary vertices outside (`φ > 0`); boundary vertices inside
//!   get the natural condition (the paper's interfaces stay away from ∂Ω).
//! - [`PoissonReinit::normalise`] (on by default): the solution is divided by the area-weighted
//!   mean of `|∇φ|` over the fitted triangles touching Γ, one constant for the whole field, so
//!   the sign, the zero level and the gradient continuity are kept and `|∇φ| ≈ 1` on average
//!   at Γ. The method is not a redistancing: `|∇φ|` varies along Γ with the geometry (on a
//!   circle of radius R in a box it is constant; elsewhere it is not); measured in
//!   `docs/fitted.md`.

use super::{fit, FitOptions, FittedMesh, REF_INSIDE, REF_INTERFACE, REF_OUTSIDE};
use crate::error::{Error, Result};
use crate::fem::solve::solve_spd;
use crate::fem::Csr;
use crate::geom::simplex::p1_gradients;
use crate::mesh::{Mesh2, NONE};

/// Options of the Poisson reinitialisation (001 §4).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PoissonReinit {
    /// The source `G ≥ 0` of `Δφ = G` inside (001 §4: "between 1 and 10"; 0 allowed with the
    /// jump rows).
    pub g: f64,
    /// Add the gradient-jump rows (3.9) and solve by least squares; without them the two
    /// Dirichlet problems are solved exactly (001 Fig. 4.1: the zero level then moves when the
    /// mesh is unrefined).
    pub jump: bool,
    /// Divide the result by the mean `|∇φ|` at Γ (module documentation).
    pub normalise: bool,
}

impl Default for PoissonReinit {
    fn default() -> Self {
        PoissonReinit {
            g: 4.0,
            jump: true,
            normalise: true,
        }
    }
}

/// The result of [`poisson_reinit`].
#[derive(Debug, Clone)]
pub struct PoissonOutput {
    /// The reinitialised level set at the base vertices.
    pub values: Vec<f64>,
    /// The fitted mesh the problem was solved on.
    pub fitted: FittedMesh,
    /// The solution at the fitted vertices (0 on Γ).
    pub fitted_values: Vec<f64>,
    /// Unknowns and rows of the least-squares system.
    pub unknowns: usize,
    /// See `unknowns`.
    pub rows: usize,
}

impl PoissonReinit {
    /// The reinitialised level set at the base vertices ([`poisson_reinit`]).
    pub fn reinitialise(&self, base: &Mesh2, u: &[f64]) -> Result<Vec<f64>> {
        poisson_reinit(base, u, self).map(|o| o.values)
    }
}

/// Reinitialises the P1 level set `u` on `base` by 001 §4 (module documentation). Errors: those
/// of [`fit`] (wrong length, non-finite values, no zero level), a negative or non-finite `G`.
pub fn poisson_reinit(base: &Mesh2, u: &[f64], opts: &PoissonReinit) -> Result<PoissonOutput> {
    if !(opts.g.is_finite() && opts.g >= 0.0) {
        return Err(Error::InvalidInput(format!(
            "Poisson reinitialisation: G must be finite and >= 0 (got {})",
            opts.g
        )));
    }
    let fitted = fit(base, u, &FitOptions::default())?;
    let m = &fitted.mesh;
    let s = &fitted.u;
    let n = m.n_points();
    let mut boundary = vec![false; n];
    for t in m.live_tris() {
        for i in 0..3 {
            if m.neighbours[t][i] == NONE {
                for v in m.edge_vertices(t, i) {
                    boundary[v as usize] = true;
                }
            }
        }
    }
    // Known values: 0 on Γ, 1 on the outer boundary outside; the rest are unknowns.
    let mut known: Vec<Option<f64>> = vec![None; n];
    for v in 0..n {
        if s[v] == 0.0 {
            known[v] = Some(0.0);
        } else if boundary[v] && s[v] > 0.0 {
            known[v] = Some(1.0);
        }
    }
    let mut index = vec![u32::MAX; n];
    let mut n_unknowns = 0usize;
    for v in 0..n {
        if known[v].is_none() {
            index[v] = n_unknowns as u32;
            n_unknowns += 1;
        }
    }
    // Rows as (entries over unknowns, right-hand side).
    let mut rows: Vec<(Vec<(u32, f64)>, f64)> = vec![(Vec::new(), 0.0); n_unknowns];
    let mut grads = Vec::with_capacity(m.n_tris());
    for t in m.live_tris() {
        let tri = m.tris[t];
        let g = p1_gradients(&m.tri_points(t));
        let area = m.tri_area(t);
        let inside = m.tri_ref[t] == REF_INSIDE;
        for i in 0..3 {
            let r = index[tri[i] as usize];
            if r == u32::MAX {
                continue;
            }
            let row = &mut rows[r as usize];
            if inside {
                // ∫∇φ·∇N = -G ∫N.
                row.1 -= opts.g * area / 3.0;
            }
            for j in 0..3 {
                let a = area * g[i].dot(g[j]);
                let v = tri[j] as usize;
                match known[v] {
                    Some(val) => row.1 -= a * val,
                    None => row.0.push((index[v], a)),
                }
            }
        }
        grads.push((t, g));
    }
    let galerkin_rows = rows.len();
    if opts.jump {
        for t in m.live_tris() {
            if m.tri_ref[t] != REF_INSIDE {
                continue;
            }
            for i in 0..3 {
                let nb = m.neighbours[t][i];
                if m.edge_ref[t][i] != REF_INTERFACE || nb == NONE {
                    continue;
                }
                let nb = nb as usize;
                if m.tri_ref[nb] != REF_OUTSIDE {
                    continue;
                }
                let j = (0..3)
                    .find(|&j| m.neighbours[nb][j] == t as u32)
                    .unwrap_or(0);
                let gm = p1_gradients(&m.tri_points(t))[i].length();
                let gp = p1_gradients(&m.tri_points(nb))[j].length();
                let mut row = (Vec::new(), 0.0);
                for (v, c) in [(m.tris[t][i], gm), (m.tris[nb][j], gp)] {
                    match known[v as usize] {
                        Some(val) => row.1 -= c * val,
                        None => row.0.push((index[v as usize], c)),
                    }
                }
                if !row.0.is_empty() {
                    rows.push(row);
                }
            }
        }
    }
    let n_rows = rows.len();
    // The normal equations AᵀA U = AᵀF (without jump rows A is the symmetric Galerkin matrix
    // and A U = F is solved directly).
    let mut trip: Vec<(u32, u32, f64)> = Vec::new();
    let mut rhs = vec![0.0; n_unknowns];
    if opts.jump {
        for (entries, b) in &rows {
            for &(i, a) in entries {
                rhs[i as usize] += a * b;
                for &(j, c) in entries {
                    trip.push((i, j, a * c));
                }
            }
        }
    } else {
        for (r, (entries, b)) in rows.iter().enumerate().take(galerkin_rows) {
            rhs[r] = *b;
            trip.extend(entries.iter().map(|&(j, a)| (r as u32, j, a)));
        }
    }
    let a = Csr::from_triplets(n_unknowns, &trip)?;
    let x = solve_spd(&a, &rhs)?;
    let mut phi: Vec<f64> = (0..n)
        .map(|v| known[v].unwrap_or_else(|| x[index[v] as usize]))
        .collect();
    if phi.iter().any(|v| !v.is_finite()) {
        return Err(Error::InvalidInput(
            "Poisson reinitialisation: the least-squares system is singular".into(),
        ));
    }
    if opts.normalise {
        let (mut num, mut den) = (0.0, 0.0);
        for (t, g) in &grads {
            let tri = m.tris[*t];
            if tri.iter().any(|&v| s[v as usize] == 0.0) {
                let grad = g[0] * phi[tri[0] as usize]
                    + g[1] * phi[tri[1] as usize]
                    + g[2] * phi[tri[2] as usize];
                let area = m.tri_area(*t);
                num += area * grad.length();
                den += area;
            }
        }
        if num > 0.0 && den > 0.0 {
            let scale = den / num;
            phi.iter_mut().for_each(|v| *v *= scale);
        }
    }
    Ok(PoissonOutput {
        values: phi[..fitted.n_base_vertices].to_vec(),
        fitted_values: phi,
        unknowns: n_unknowns,
        rows: n_rows,
        fitted,
    })
}
