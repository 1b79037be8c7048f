//! The Uzawa path of [`super::StokesProblem::solve`]: block assembly of the condensed MINI
//! system with the Dirichlet velocity dofs eliminated, one sparse Cholesky factorisation of the
//! velocity block, and CG on the pressure Schur complement (004 §5.1).
//!
//! **Assembly.** Every block lives on the P1 vertex pattern: the element matrices (computed in
//! parallel) are scattered sequentially in element order through precomputed storage positions
//! into one array of 8 values per pattern entry (`A_xx, A_xy, A_yx, A_yy, B_x, B_y, C` and the
//! weighted pressure mass), so the sums do not depend on the thread count.
//!
//! **Reduced system.** With `f` the free (non-Dirichlet) vertices and velocity unknowns
//! interleaved (`2k + c` for free vertex `k`, component `c`):
//! `A_ff u + B_fᵀ p = F_f - A_fD g`, `B_f u - C p = G - B_D g`. The divergence block `B_f` and
//! its transpose are [`RectCsr`] matrices.
//!
//! **Solver.** `A_ff` is factorised once by sparse Cholesky with an AMD ordering of the vertex
//! graph expanded to the 2x2 vertex blocks. The Schur complement `S = B A⁻¹ Bᵀ + C` is solved by
//! CG preconditioned by the pressure mass matrix weighted by `1/μ̄_T` (`μ̄_T` the mean viscosity
//! of the element, also Cholesky-factorised): `S` is spectrally equivalent to it uniformly in
//! `h` and in the viscosity ratio on shape-regular meshes (the weighted-mass Schur
//! preconditioner for variable viscosity, e.g. Grinevich & Olshanskii 2009).

use super::{DirichletData, StokesReport};
use crate::error::{Error, Result};
use crate::fem::csr::{dot, Csr};
use crate::fem::p1_bubble::BubbleRecovery;
use crate::fem::rect_csr::RectCsr;
use crate::fem::solve::{amd_order, expand_ordering, pcg, CgOptions, CgReport, Cholesky};
use rayon::prelude::*;
use std::time::Instant;

/// Elements per parallel chunk of the assembly.
const CHUNK: usize = 1 << 14;

/// Marks a constrained vertex in the free-vertex numbering.
const FIXED: u32 = u32::MAX;

/// What one element contributes: the condensed 9x9 matrix on `[ux0..2, uy0..2, p0..2]`, its
/// right-hand side, and the element's mean viscosity and area (for the pressure mass).
pub(super) struct ElementData {
    /// Condensed element matrix.
    pub k: [[f64; 9]; 9],
    /// Condensed element load.
    pub f: [f64; 9],
    /// Mean viscosity `μ̄_T` over the element.
    pub mu_mean: f64,
    /// Element area.
    pub area: f64,
    /// What recovers the element's bubble after the solve.
    pub bubble: BubbleRecovery,
}

/// Inputs of [`solve`].
pub(super) struct UzawaInput<'a> {
    /// Number of vertices.
    pub nv: usize,
    /// Vertices of the live triangles (element order).
    pub tris: &'a [[u32; 3]],
    /// The full right-hand side without the element terms (Neumann, surface tension), in the
    /// layout `ux = v, uy = n_v + v, p = 2 n_v + v`; the element loads are added here.
    pub rhs_extra: &'a [f64],
    /// Dirichlet mask and values in the same layout.
    pub bc: &'a DirichletData,
    /// Relative tolerance of the Schur-complement CG.
    pub rtol: f64,
    /// Iteration limit of the Schur-complement CG.
    pub max_iter: usize,
}

/// The element contributions summed on the P1 vertex pattern.
struct Assembled {
    /// The vertex–vertex pattern of the elements.
    pattern: Csr,
    /// Per pattern entry: `A_xx, A_xy, A_yx, A_yy, B_x, B_y, -C` and the weighted pressure mass.
    vals: Vec<[f64; 8]>,
    /// The full right-hand side with the element loads.
    rhs: Vec<f64>,
    /// Bubble-recovery data per element.
    bubbles: Vec<BubbleRecovery>,
}

/// The reduced saddle-point system on the free velocity dofs.
struct Reduced {
    /// Free index of each vertex, [`FIXED`] for a Dirichlet vertex.
    free: Vec<u32>,
    /// `A_ff`, velocity components interleaved.
    a: Csr,
    /// `F_f - A_fD g`.
    f: Vec<f64>,
    /// `B_f` (pressure rows, free velocity columns) and its transpose.
    b: RectCsr,
    bt: RectCsr,
    /// `G - B_D g`.
    gp: Vec<f64>,
    /// The pressure stabilisation `C` and the `1/μ̄_T`-weighted pressure mass.
    c: Csr,
    m: Csr,
}

/// Assembles the blocks and solves by Schur-complement CG. Returns the solution in the full
/// layout (Dirichlet values included), the bubble-recovery data of every element, and the
/// report (iterations, residual of the full system, timings).
pub(super) fn solve(
    inp: &UzawaInput,
    element: impl Fn(usize) -> ElementData + Sync,
) -> Result<(Vec<f64>, Vec<BubbleRecovery>, StokesReport)> {
    let t0 = Instant::now();
    let asm = assemble(inp, element)?;
    let red = reduce(inp, &asm);
    let assembly = t0.elapsed().as_secs_f64();

    let t1 = Instant::now();
    let (chol, mchol) = factor(&asm.pattern, &red)?;
    let factor = t1.elapsed().as_secs_f64();

    let t2 = Instant::now();
    let (u, p, cg, inner) = schur_cg(inp, &red, &chol, &mchol);
    let uzawa = t2.elapsed().as_secs_f64();

    let report = StokesReport {
        uzawa_iterations: cg.iterations,
        inner_iterations: inner,
        residual: relative_residual(inp, &red, &u, &p),
        converged: cg.converged,
        assembly_seconds: assembly,
        factor_seconds: factor,
        uzawa_seconds: uzawa,
        factor_nnz: chol.factor_nnz(),
        ..Default::default()
    };
    Ok((full_solution(inp, &red, &u, &p), asm.bubbles, report))
}

/// Computes the element data in parallel chunks and scatters it in element order.
fn assemble(inp: &UzawaInput, element: impl Fn(usize) -> ElementData + Sync) -> Result<Assembled> {
    let pattern = Csr::from_elements(inp.nv, inp.tris)?;
    let pos = storage_positions(&pattern, inp.tris)?;
    let mut vals = vec![[0.0f64; 8]; pattern.nnz()];
    let mut rhs = inp.rhs_extra.to_vec();
    let mut bubbles = Vec::with_capacity(inp.tris.len());
    for start in (0..inp.tris.len()).step_by(CHUNK) {
        let end = (start + CHUNK).min(inp.tris.len());
        let els: Vec<ElementData> = (start..end).into_par_iter().map(&element).collect();
        bubbles.extend(els.iter().map(|el| el.bubble));
        for (e, el) in (start..end).zip(&els) {
            scatter(el, &pos[e], inp.tris[e], inp.nv, &mut vals, &mut rhs);
        }
    }
    Ok(Assembled {
        pattern,
        vals,
        rhs,
        bubbles,
    })
}

/// Storage positions in `pattern` of the 9 vertex pairs of each element (always in the
/// pattern, which is built from the same elements).
fn storage_positions(pattern: &Csr, tris: &[[u32; 3]]) -> Result<Vec<[u32; 9]>> {
    let pos: Vec<[u32; 9]> = tris
        .par_iter()
        .map(|v| {
            std::array::from_fn(|ab| {
                let (a, b) = (v[ab / 3] as usize, v[ab % 3] as usize);
                pattern.find(a, b).map_or(u32::MAX, |q| q as u32)
            })
        })
        .collect();
    if let Some(e) = pos.iter().position(|p| p.contains(&u32::MAX)) {
        return Err(Error::InvalidInput(format!(
            "Stokes assembly: element {e} has a vertex pair missing from the pattern"
        )));
    }
    Ok(pos)
}

/// Adds one element's blocks (and the `1/μ̄_T`-weighted P1 mass) at the positions `pos` and
/// its load at the vertices `tri`.
fn scatter(
    el: &ElementData,
    pos: &[u32; 9],
    tri: [u32; 3],
    nv: usize,
    vals: &mut [[f64; 8]],
    rhs: &mut [f64],
) {
    let k = &el.k;
    let (d, o) = (el.area / (6.0 * el.mu_mean), el.area / (12.0 * el.mu_mean));
    for a in 0..3 {
        for b in 0..3 {
            let w = &mut vals[pos[3 * a + b] as usize];
            w[0] += k[a][b];
            w[1] += k[a][3 + b];
            w[2] += k[3 + a][b];
            w[3] += k[3 + a][3 + b];
            w[4] += k[6 + a][b];
            w[5] += k[6 + a][3 + b];
            w[6] -= k[6 + a][6 + b];
            w[7] += if a == b { d } else { o };
        }
        let v = tri[a] as usize;
        rhs[v] += el.f[a];
        rhs[nv + v] += el.f[3 + a];
        rhs[2 * nv + v] += el.f[6 + a];
    }
}

/// Eliminates the Dirichlet vertices: the free numbering, `A_ff` with `F_f - A_fD g`, `B_f`
/// with `G - B_D g`, `C` and the weighted pressure mass.
fn reduce(inp: &UzawaInput, asm: &Assembled) -> Reduced {
    let free = free_numbering(&inp.bc.fixed[..inp.nv]);
    let (a, f) = velocity_block(inp, asm, &free);
    let (b, gp) = divergence_block(inp, asm, &free);
    let bt = b.transpose();
    let with_vals = |k: usize| Csr {
        n: inp.nv,
        row_ptr: asm.pattern.row_ptr.clone(),
        col: asm.pattern.col.clone(),
        val: asm.vals.iter().map(|w| w[k]).collect(),
    };
    Reduced {
        free,
        a,
        f,
        b,
        bt,
        gp,
        c: with_vals(6),
        m: with_vals(7),
    }
}

/// Consecutive numbers for the vertices that are not fixed, [`FIXED`] for the others.
fn free_numbering(fixed: &[bool]) -> Vec<u32> {
    let mut nf = 0u32;
    fixed
        .iter()
        .map(|&x| {
            if x {
                FIXED
            } else {
                nf += 1;
                nf - 1
            }
        })
        .collect()
}

/// The prescribed velocity at vertex `j`.
fn g(inp: &UzawaInput, j: usize) -> [f64; 2] {
    [inp.bc.values[j], inp.bc.values[inp.nv + j]]
}

/// `A_ff` (rows and columns `2k + c` for free vertex `k`) and `F_f - A_fD g`.
fn velocity_block(inp: &UzawaInput, asm: &Assembled, free: &[u32]) -> (Csr, Vec<f64>) {
    let (nv, pat) = (inp.nv, &asm.pattern);
    let nf = free.iter().filter(|&&k| k != FIXED).count();
    let mut a = Csr {
        n: 2 * nf,
        row_ptr: vec![0],
        col: Vec::new(),
        val: Vec::new(),
    };
    let mut f = vec![0.0; 2 * nf];
    for i in (0..nv).filter(|&i| free[i] != FIXED) {
        let k = free[i] as usize;
        for c in 0..2 {
            let mut fi = asm.rhs[c * nv + i];
            for q in pat.row_ptr[i]..pat.row_ptr[i + 1] {
                let j = pat.col[q] as usize;
                let (w0, w1) = (asm.vals[q][2 * c], asm.vals[q][2 * c + 1]);
                if free[j] == FIXED {
                    let gj = g(inp, j);
                    fi -= w0 * gj[0] + w1 * gj[1];
                } else {
                    let l = free[j];
                    a.col.extend([2 * l, 2 * l + 1]);
                    a.val.extend([w0, w1]);
                }
            }
            f[2 * k + c] = fi;
            a.row_ptr.push(a.col.len());
        }
    }
    (a, f)
}

/// `B_f` (one row per pressure dof, columns `2k + c` for free vertex `k`) and `G - B_D g`.
fn divergence_block(inp: &UzawaInput, asm: &Assembled, free: &[u32]) -> (RectCsr, Vec<f64>) {
    let (nv, pat) = (inp.nv, &asm.pattern);
    let nf = free.iter().filter(|&&k| k != FIXED).count();
    let mut b = RectCsr::new(2 * nf);
    let mut gp = asm.rhs[2 * nv..].to_vec();
    for (i, gi) in gp.iter_mut().enumerate() {
        for q in pat.row_ptr[i]..pat.row_ptr[i + 1] {
            let j = pat.col[q] as usize;
            let (w0, w1) = (asm.vals[q][4], asm.vals[q][5]);
            if free[j] == FIXED {
                let gj = g(inp, j);
                *gi -= w0 * gj[0] + w1 * gj[1];
            } else {
                let l = free[j];
                b.push(2 * l, w0);
                b.push(2 * l + 1, w1);
            }
        }
        b.end_row();
    }
    (b, gp)
}

/// Cholesky factors of `A_ff` and of the weighted pressure mass, with one AMD ordering of the
/// vertex graph: used as is for the pressure mass and, restricted to the free vertices and
/// expanded to the 2x2 vertex blocks, for the velocity block (AMD on the scalar graph is 4x
/// cheaper than on the interleaved matrix and gives the same fill).
fn factor(pattern: &Csr, red: &Reduced) -> Result<(Cholesky, Cholesky)> {
    let vperm = amd_order(pattern)?;
    let free_perm: Vec<usize> = vperm
        .iter()
        .filter(|&&v| red.free[v] != FIXED)
        .map(|&v| red.free[v] as usize)
        .collect();
    let perm = expand_ordering(&free_perm, 2);
    let chol = Cholesky::with_ordering(&red.a, Some(&perm))?;
    let mchol = Cholesky::with_ordering(&red.m, Some(&vperm))?;
    Ok((chol, mchol))
}

/// CG on `S p = B A⁻¹ F - G` with `S = B A⁻¹ Bᵀ + C`, preconditioned by the weighted pressure
/// mass (kept orthogonal to constants when every boundary is Dirichlet), then the velocity
/// `u = A⁻¹ (F - Bᵀ p)`. Returns `u`, `p`, the CG report and the number of `A⁻¹` solves.
fn schur_cg(
    inp: &UzawaInput,
    red: &Reduced,
    chol: &Cholesky,
    mchol: &Cholesky,
) -> (Vec<f64>, Vec<f64>, CgReport, usize) {
    let nv = inp.nv;
    let nu = red.f.len();
    let project = |v: &mut [f64]| {
        if inp.bc.all_dirichlet {
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            v.iter_mut().for_each(|x| *x -= mean);
        }
    };
    let mut af = red.f.clone();
    chol.solve_in_place(&mut af);
    let mut rhs_p = vec![0.0; nv];
    red.b.matvec(&af, &mut rhs_p);
    rhs_p.iter_mut().zip(&red.gp).for_each(|(r, gi)| *r -= gi);
    project(&mut rhs_p);
    let mut p = vec![0.0; nv];
    let mut tmp_u = vec![0.0; nu];
    let mut tmp_p = vec![0.0; nv];
    let mut inner = 1usize;
    let opts = CgOptions {
        rtol: inp.rtol,
        atol: 0.0,
        max_iter: inp.max_iter,
        ..Default::default()
    };
    let rep = pcg(
        |q, y| {
            red.bt.matvec(q, &mut tmp_u);
            chol.solve_in_place(&mut tmp_u);
            inner += 1;
            red.b.matvec(&tmp_u, y);
            red.c.matvec(q, &mut tmp_p);
            y.iter_mut().zip(&tmp_p).for_each(|(yi, ci)| *yi += ci);
            project(y);
        },
        |r, z| {
            z.copy_from_slice(r);
            mchol.solve_in_place(z);
            project(z);
        },
        &rhs_p,
        &mut p,
        &opts,
    );
    let mut u = vec![0.0; nu];
    red.bt.matvec(&p, &mut u);
    u.iter_mut().zip(&red.f).for_each(|(ui, fi)| *ui = fi - *ui);
    chol.solve_in_place(&mut u);
    inner += 1;
    (u, p, rep, inner)
}

/// Residual of the reduced system relative to the full right-hand side (Dirichlet rows hold
/// their values and are satisfied exactly).
fn relative_residual(inp: &UzawaInput, red: &Reduced, u: &[f64], p: &[f64]) -> f64 {
    let nv = inp.nv;
    let mut ru = vec![0.0; u.len()];
    let mut tmp_u = vec![0.0; u.len()];
    red.a.matvec(u, &mut ru);
    red.bt.matvec(p, &mut tmp_u);
    let mut rnorm2 = 0.0;
    for ((r, t), fi) in ru.iter().zip(&tmp_u).zip(&red.f) {
        rnorm2 += (r + t - fi).powi(2);
    }
    let mut rp = vec![0.0; nv];
    let mut tmp_p = vec![0.0; nv];
    red.b.matvec(u, &mut rp);
    red.c.matvec(p, &mut tmp_p);
    for ((r, t), gi) in rp.iter().zip(&tmp_p).zip(&red.gp) {
        rnorm2 += (r - t - gi).powi(2);
    }
    let fixed_norm2: f64 = (0..2 * nv)
        .filter(|&d| inp.bc.fixed[d])
        .map(|d| inp.bc.values[d].powi(2))
        .sum();
    let bnorm = (dot(&red.f, &red.f) + dot(&red.gp, &red.gp) + fixed_norm2).sqrt();
    rnorm2.sqrt() / bnorm.max(f64::MIN_POSITIVE)
}

/// The solution in the full layout `ux = v, uy = n_v + v, p = 2 n_v + v`, with the Dirichlet
/// values at the fixed vertices.
fn full_solution(inp: &UzawaInput, red: &Reduced, u: &[f64], p: &[f64]) -> Vec<f64> {
    let nv = inp.nv;
    let mut x = vec![0.0; 3 * nv];
    for v in 0..nv {
        for cc in 0..2 {
            x[cc * nv + v] = if red.free[v] == FIXED {
                inp.bc.values[cc * nv + v]
            } else {
                u[2 * red.free[v] as usize + cc]
            };
        }
    }
    x[2 * nv..].copy_from_slice(p);
    x
}
