//! One mean curvature step `u_t = |∇u| div(∇u/|∇u|)` (000 eq. (2.4)) of a P1 level set on a
//! fixed mesh, by the schemes of [`McfScheme`] (documented in the parent module).

use super::curvature;
use super::{AdaptedOptions, McfScheme};
use crate::error::Result;
use crate::fem::p1::{add_mass, add_stiffness, mass, Coef};
use crate::fem::solve::cg;
use crate::fem::Csr;
use crate::mesh::Mesh2;
use crate::metric::Sym2;
use crate::DVec2;
use std::time::Instant;

/// What a step cost.
#[derive(Debug, Default)]
pub(crate) struct StepCost {
    pub assembly: f64,
    pub solve: f64,
    pub iterations: usize,
    pub converged: bool,
}

/// The regularisation `|x|_ε = √(ε² + |x|²)` of the semi-implicit scheme (000 §2.2).
const GRAD_EPS: f64 = 1e-3;

/// `u` after one step of length `dt`; `width` is the distance from the zero level within which
/// the speed is taken from the cubic fit (`cubic.rs`).
pub(crate) fn step(
    mesh: &Mesh2,
    u: &[f64],
    dt: f64,
    width: f64,
    opts: &AdaptedOptions,
    cost: &mut StepCost,
) -> Result<Vec<f64>> {
    cost.converged = true;
    match opts.mcf {
        McfScheme::Heat => {
            let t = Instant::now();
            let m = mass(mesh)?;
            let mut a = Csr::p1_pattern(mesh)?;
            add_mass(&mut a, mesh, 1.0)?;
            add_stiffness(&mut a, mesh, &Coef::Const(dt))?;
            let rhs = m.mul(u);
            cost.assembly += t.elapsed().as_secs_f64();
            solve(&a, &rhs, u.to_vec(), opts, cost)
        }
        McfScheme::SemiImplicit => semi_implicit(mesh, u, dt, opts, cost),
        McfScheme::RecoveredCurvature => {
            let t = Instant::now();
            let m = mass(mesh)?;
            let mut a = Csr::p1_pattern(mesh)?;
            add_mass(&mut a, mesh, 1.0)?;
            if opts.smoothing > 0.0 {
                if opts.tangential_smoothing {
                    let tensors = tangential_tensors(mesh, u, opts.smoothing * dt);
                    add_stiffness(&mut a, mesh, &Coef::Tensor(&tensors))?;
                } else {
                    add_stiffness(&mut a, mesh, &Coef::Const(opts.smoothing * dt))?;
                }
            }
            cost.assembly += t.elapsed().as_secs_f64();
            let increment = |u: &[f64], cost: &mut StepCost| -> Result<Vec<f64>> {
                let t = Instant::now();
                let f = curvature::mean_curvature_speed(mesh, u, width, opts.cubic)?;
                let b: Vec<f64> = f.iter().map(|v| dt * v).collect();
                let rhs = m.mul(&b);
                cost.assembly += t.elapsed().as_secs_f64();
                solve(&a, &rhs, b, opts, cost)
            };
            let d1 = increment(u, cost)?;
            if !opts.heun {
                return Ok(u.iter().zip(&d1).map(|(u, d)| u + d).collect());
            }
            let mid: Vec<f64> = u.iter().zip(&d1).map(|(u, d)| u + d).collect();
            let d2 = increment(&mid, cost)?;
            Ok(u.iter()
                .zip(d1.iter().zip(&d2))
                .map(|(u, (a, b))| u + 0.5 * (a + b))
                .collect())
        }
    }
}

/// The P1 gradient of `u` on live triangle `t`.
fn element_gradient(mesh: &Mesh2, u: &[f64], t: usize) -> DVec2 {
    let tri = mesh.tris[t].map(|v| v as usize);
    let [p0, p1, p2] = mesh.tri_points(t);
    let (e1, e2) = (p1 - p0, p2 - p0);
    let det = e1.perp_dot(e2);
    let (d1, d2) = (u[tri[1]] - u[tri[0]], u[tri[2]] - u[tri[0]]);
    DVec2::new(d1 * e2.y - d2 * e1.y, e1.x * d2 - e2.x * d1) / det
}

/// `c (I − n nᵀ)` on each triangle, `n` the unit P1 gradient of `u` there (`c I` where it
/// vanishes): diffusion along the level lines only, the stiff part of the linearised
/// `|∇u| div(∇u/|∇u|)`.
fn tangential_tensors(mesh: &Mesh2, u: &[f64], c: f64) -> Vec<Sym2> {
    let mut out = vec![Sym2::scalar(c); mesh.tris.len()];
    for t in mesh.live_tris() {
        let g = element_gradient(mesh, u, t);
        let len = g.length();
        if len > 0.0 && len.is_finite() {
            let n = g / len;
            out[t] = Sym2::new(c * (1.0 - n.x * n.x), -c * n.x * n.y, c * (1.0 - n.y * n.y));
        }
    }
    out
}

fn solve(
    a: &Csr,
    rhs: &[f64],
    mut x: Vec<f64>,
    opts: &AdaptedOptions,
    cost: &mut StepCost,
) -> Result<Vec<f64>> {
    let t = Instant::now();
    let r = cg(a, rhs, &mut x, &opts.cg)?;
    cost.solve += t.elapsed().as_secs_f64();
    cost.iterations += r.iterations;
    cost.converged &= r.converged;
    Ok(x)
}

/// 000 eq. (2.5): `(M[uⁿ] + dt L[uⁿ]) uⁿ⁺¹ = M[uⁿ] uⁿ` with the lumped mass weighted by the
/// element value of `|∇uⁿ|_ε⁻¹` (eq. (2.6)) and the stiffness `∫ |∇uⁿ|_ε⁻¹ ∇φ_i·∇φ_j`
/// (eq. (2.7)); natural conditions on the box.
fn semi_implicit(
    mesh: &Mesh2,
    u: &[f64],
    dt: f64,
    opts: &AdaptedOptions,
    cost: &mut StepCost,
) -> Result<Vec<f64>> {
    let t = Instant::now();
    let mut w = vec![0.0; mesh.tris.len()];
    let mut lumped = vec![0.0; mesh.n_points()];
    for tr in mesh.live_tris() {
        let tri = mesh.tris[tr].map(|v| v as usize);
        let g = element_gradient(mesh, u, tr);
        w[tr] = 1.0 / (GRAD_EPS * GRAD_EPS + g.length_squared()).sqrt();
        for &v in &tri {
            lumped[v] += w[tr] * mesh.tri_area(tr) / 3.0;
        }
    }
    let mut a = Csr::p1_pattern(mesh)?;
    let wdt: Vec<f64> = w.iter().map(|w| w * dt).collect();
    add_stiffness(&mut a, mesh, &Coef::PerElement(&wdt))?;
    for (i, &m) in lumped.iter().enumerate() {
        a.add(i, i, m)?;
    }
    let rhs: Vec<f64> = lumped.iter().zip(u).map(|(m, u)| m * u).collect();
    cost.assembly += t.elapsed().as_secs_f64();
    solve(&a, &rhs, u.to_vec(), opts, cost)
}
