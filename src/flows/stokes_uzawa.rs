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
//! `A_ff u + B_fᵀ p = F_f - A_fD g`, `B_f u - C p = G - B_D g`.
//!
//! **Solver.** `A_ff` is factorised once by sparse Cholesky with an AMD ordering of the vertex
//! graph expanded to the 2x2 vertex blocks. The Schur complement `S = B A⁻¹ Bᵀ + C` is solved by
//! CG preconditioned by the pressure mass matrix weighted by `1/μ̄_T` (`μ̄_T` the mean viscosity
//! of the element, also Cholesky-factorised): `S` is spectrally equivalent to it uniformly in
//! `h` and in the viscosity ratio on shape-regular meshes (the weighted-mass Schur
//! preconditioner for variable viscosity, e.g. Grinevich & Olshanskii 2009).

use super::stokes::StokesReport;
use crate::error::{Error, Result};
use crate::fem::csr::{dot, Csr};
use crate::fem::p1_bubble::BubbleRecovery;
use crate::fem::solve::{amd_order, expand_ordering, pcg, CgOptions, Cholesky};
use rayon::prelude::*;
use std::time::Instant;

/// Elements per parallel chunk of the assembly.
const CHUNK: usize = 1 << 14;

/// What one element contributes: the condensed 9x9 matrix on `[ux0..2, uy0..2, p0..2]`, its
/// right-hand side, and the element's mean viscosity and area (for the pressure mass).
pub(super) struct ElementData {
    pub k: [[f64; 9]; 9],
    pub f: [f64; 9],
    pub mu_mean: f64,
    pub area: f64,
    /// What recovers the element's bubble after the solve.
    pub bubble: BubbleRecovery,
}

/// A rectangular CSR matrix (the divergence block and its transpose).
struct Rect {
    ncols: usize,
    row_ptr: Vec<usize>,
    col: Vec<u32>,
    val: Vec<f64>,
}

impl Rect {
    fn nrows(&self) -> usize {
        self.row_ptr.len() - 1
    }

    /// `y = M x`, rows in parallel (each row summed by one thread, in storage order).
    fn matvec(&self, x: &[f64], y: &mut [f64]) {
        y.par_iter_mut().enumerate().for_each(|(i, yi)| {
            let r = self.row_ptr[i]..self.row_ptr[i + 1];
            *yi = self.col[r.clone()]
                .iter()
                .zip(&self.val[r])
                .map(|(&j, &a)| a * x[j as usize])
                .sum();
        });
    }

    /// The transpose (counting sort: deterministic).
    fn transpose(&self) -> Rect {
        let (m, n) = (self.nrows(), self.ncols);
        let mut ptr = vec![0usize; n + 1];
        for &j in &self.col {
            ptr[j as usize + 1] += 1;
        }
        for j in 0..n {
            ptr[j + 1] += ptr[j];
        }
        let mut fill = ptr.clone();
        let mut col = vec![0u32; self.col.len()];
        let mut val = vec![0.0; self.col.len()];
        for i in 0..m {
            for q in self.row_ptr[i]..self.row_ptr[i + 1] {
                let j = self.col[q] as usize;
                col[fill[j]] = i as u32;
                val[fill[j]] = self.val[q];
                fill[j] += 1;
            }
        }
        Rect {
            ncols: m,
            row_ptr: ptr,
            col,
            val,
        }
    }
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
    /// Per-dof Dirichlet mask and values in the same layout (both components of a vertex are
    /// fixed together).
    pub fixed: &'a [bool],
    pub values: &'a [f64],
    /// Every boundary edge Dirichlet: the pressure is determined up to a constant.
    pub all_dirichlet: bool,
    pub rtol: f64,
    pub max_iter: usize,
}

/// Assembles the blocks and solves by Schur-complement CG. Returns the solution in the full
/// layout (Dirichlet values included), the bubble-recovery data of every element, and the
/// report (iterations, residual of the full system, timings).
pub(super) fn solve(
    inp: &UzawaInput,
    element: impl Fn(usize) -> ElementData + Sync,
) -> Result<(Vec<f64>, Vec<BubbleRecovery>, StokesReport)> {
    let t0 = Instant::now();
    let nv = inp.nv;
    let pattern = Csr::from_elements(nv, inp.tris)?;
    // Storage positions of the 9 vertex pairs of each element (always in the pattern, which is
    // built from the same elements).
    let pos: Vec<[u32; 9]> = inp
        .tris
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
    let mut vals = vec![[0.0f64; 8]; pattern.nnz()];
    let mut rhs = inp.rhs_extra.to_vec();
    let mut bubbles = Vec::with_capacity(inp.tris.len());
    for start in (0..inp.tris.len()).step_by(CHUNK) {
        let end = (start + CHUNK).min(inp.tris.len());
        let els: Vec<ElementData> = (start..end).into_par_iter().map(&element).collect();
        bubbles.extend(els.iter().map(|el| el.bubble));
        for (e, el) in (start..end).zip(&els) {
            let k = &el.k;
            let (d, o) = (el.area / (6.0 * el.mu_mean), el.area / (12.0 * el.mu_mean));
            for a in 0..3 {
                for b in 0..3 {
                    let q = pos[e][3 * a + b] as usize;
                    let w = &mut vals[q];
                    w[0] += k[a][b];
                    w[1] += k[a][3 + b];
                    w[2] += k[3 + a][b];
                    w[3] += k[3 + a][3 + b];
                    w[4] += k[6 + a][b];
                    w[5] += k[6 + a][3 + b];
                    w[6] -= k[6 + a][6 + b];
                    w[7] += if a == b { d } else { o };
                }
                let v = inp.tris[e][a] as usize;
                rhs[v] += el.f[a];
                rhs[nv + v] += el.f[3 + a];
                rhs[2 * nv + v] += el.f[6 + a];
            }
        }
    }
    drop(pos);
    // Free-vertex numbering.
    let mut free = vec![u32::MAX; nv];
    let mut nf = 0usize;
    for (fv, &fixed) in free.iter_mut().zip(inp.fixed) {
        if !fixed {
            *fv = nf as u32;
            nf += 1;
        }
    }
    let g = |j: usize| [inp.values[j], inp.values[nv + j]];
    let rows = |i: usize| pattern.row_ptr[i]..pattern.row_ptr[i + 1];
    // A_ff (interleaved), and F_f - A_fD g.
    let mut a = Csr {
        n: 2 * nf,
        row_ptr: vec![0],
        col: Vec::new(),
        val: Vec::new(),
    };
    let mut f = vec![0.0; 2 * nf];
    for i in (0..nv).filter(|&i| !inp.fixed[i]) {
        let k = free[i] as usize;
        for c in 0..2 {
            let mut fi = rhs[c * nv + i];
            for q in rows(i) {
                let j = pattern.col[q] as usize;
                let (w0, w1) = (vals[q][2 * c], vals[q][2 * c + 1]);
                if inp.fixed[j] {
                    let gj = g(j);
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
    // B_f, G - B_D g, C and the weighted pressure mass (on the vertex pattern).
    let mut b = Rect {
        ncols: 2 * nf,
        row_ptr: vec![0],
        col: Vec::new(),
        val: Vec::new(),
    };
    let mut gp = rhs[2 * nv..].to_vec();
    for (i, gi) in gp.iter_mut().enumerate() {
        for q in rows(i) {
            let j = pattern.col[q] as usize;
            let (w0, w1) = (vals[q][4], vals[q][5]);
            if inp.fixed[j] {
                let gj = g(j);
                *gi -= w0 * gj[0] + w1 * gj[1];
            } else {
                let l = free[j];
                b.col.extend([2 * l, 2 * l + 1]);
                b.val.extend([w0, w1]);
            }
        }
        b.row_ptr.push(b.col.len());
    }
    let bt = b.transpose();
    let with_vals = |k: usize| Csr {
        n: nv,
        row_ptr: pattern.row_ptr.clone(),
        col: pattern.col.clone(),
        val: vals.iter().map(|w| w[k]).collect(),
    };
    let c = with_vals(6);
    let m = with_vals(7);
    drop(vals);
    let assembly = t0.elapsed().as_secs_f64();

    // Factorisations: one AMD ordering of the vertex graph, used for the pressure mass and,
    // restricted to the free vertices and expanded to the 2x2 vertex blocks, for the velocity
    // block (AMD on the scalar graph is 4x cheaper than on the interleaved matrix and gives
    // the same fill; a geometric nested dissection tried here gave 10% more fill).
    let t1 = Instant::now();
    let vperm = amd_order(&pattern)?;
    let free_perm: Vec<usize> = vperm
        .iter()
        .filter(|&&v| free[v] != u32::MAX)
        .map(|&v| free[v] as usize)
        .collect();
    let perm = expand_ordering(&free_perm, 2);
    let chol = Cholesky::with_ordering(&a, Some(&perm))?;
    let mchol = Cholesky::with_ordering(&m, Some(&vperm))?;
    let factor = t1.elapsed().as_secs_f64();

    // Schur-complement CG.
    let t2 = Instant::now();
    let project = |v: &mut [f64]| {
        if inp.all_dirichlet {
            let mean = v.iter().sum::<f64>() / v.len() as f64;
            v.iter_mut().for_each(|x| *x -= mean);
        }
    };
    let mut af = f.clone();
    chol.solve_in_place(&mut af);
    let mut rhs_p = vec![0.0; nv];
    b.matvec(&af, &mut rhs_p);
    rhs_p.iter_mut().zip(&gp).for_each(|(r, gi)| *r -= gi);
    project(&mut rhs_p);
    let mut p = vec![0.0; nv];
    let mut tmp_u = vec![0.0; 2 * nf];
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
            bt.matvec(q, &mut tmp_u);
            chol.solve_in_place(&mut tmp_u);
            inner += 1;
            b.matvec(&tmp_u, y);
            c.matvec(q, &mut tmp_p);
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
    let mut u = vec![0.0; 2 * nf];
    bt.matvec(&p, &mut u);
    u.iter_mut().zip(&f).for_each(|(ui, fi)| *ui = fi - *ui);
    chol.solve_in_place(&mut u);
    inner += 1;
    let uzawa = t2.elapsed().as_secs_f64();

    // Residual of the reduced system, relative to the full right-hand side (Dirichlet rows
    // hold their values and are satisfied exactly).
    let mut ru = vec![0.0; 2 * nf];
    a.matvec(&u, &mut ru);
    bt.matvec(&p, &mut tmp_u);
    let mut rnorm2 = 0.0;
    for ((r, t), fi) in ru.iter().zip(&tmp_u).zip(&f) {
        rnorm2 += (r + t - fi).powi(2);
    }
    let mut rp = vec![0.0; nv];
    b.matvec(&u, &mut rp);
    c.matvec(&p, &mut tmp_p);
    for ((r, t), gi) in rp.iter().zip(&tmp_p).zip(&gp) {
        rnorm2 += (r - t - gi).powi(2);
    }
    let fixed_norm2: f64 = (0..2 * nv)
        .filter(|&d| inp.fixed[d])
        .map(|d| inp.values[d].powi(2))
        .sum();
    let bnorm = (dot(&f, &f) + dot(&gp, &gp) + fixed_norm2).sqrt();

    let mut x = vec![0.0; 3 * nv];
    for v in 0..nv {
        for cc in 0..2 {
            x[cc * nv + v] = if inp.fixed[v] {
                inp.values[cc * nv + v]
            } else {
                u[2 * free[v] as usize + cc]
            };
        }
    }
    x[2 * nv..].copy_from_slice(&p);
    let report = StokesReport {
        uzawa_iterations: rep.iterations,
        inner_iterations: inner,
        residual: rnorm2.sqrt() / bnorm.max(f64::MIN_POSITIVE),
        converged: rep.converged,
        assembly_seconds: assembly,
        factor_seconds: factor,
        uzawa_seconds: uzawa,
        factor_nnz: chol.factor_nnz(),
        ..Default::default()
    };
    Ok((x, bubbles, report))
}
