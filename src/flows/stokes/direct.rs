//! The direct path of [`super::StokesProblem::solve`]: the full condensed MINI saddle-point
//! matrix, symmetric Dirichlet elimination, and one sparse LU factorisation (the reference the
//! Uzawa iteration is tested against).

use super::{DirichletData, StokesReport};
use crate::error::{Error, Result};
use crate::fem::assembly::{assemble_matrix, assemble_vector};
use crate::fem::csr::{norm, Csr};
use crate::fem::dirichlet::apply_dirichlet;
use crate::fem::p1_bubble::MiniElement;
use crate::fem::solve::Lu;

/// Assembles the full condensed saddle-point matrix `K` (dofs `ux = v, uy = n_v + v,
/// p = 2 n_v + v`) of the elements `tris`, eliminates the Dirichlet dofs symmetrically and
/// solves by sparse LU. Returns the solution and a report with the residual `‖K x - F‖/‖F‖`.
pub(super) fn solve(
    nv: usize,
    tris: &[[u32; 3]],
    element: &(impl Fn(usize) -> MiniElement + Sync),
    mut rhs: Vec<f64>,
    bc: &DirichletData,
) -> Result<(Vec<f64>, StokesReport)> {
    let nvu = nv as u32;
    let elems: Vec<[u32; 9]> = tris
        .iter()
        .map(|v| std::array::from_fn(|k| (k as u32 / 3) * nvu + v[k % 3]))
        .collect();
    let mut k = Csr::from_elements(3 * nv, &elems)?;
    assemble_matrix(&mut k, &elems, |e| element(e).k)?;
    assemble_vector(&mut rhs, &elems, |e| element(e).f)?;
    apply_dirichlet(&mut k, &mut rhs, &bc.fixed, &bc.values)?;
    let x = solve_lu(&k, &rhs, nv, bc.all_dirichlet)?;
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
/// the constraint `Σ_i p_i = 0` ([`bordered`]) and the multiplier is dropped from the solution.
fn solve_lu(k: &Csr, rhs: &[f64], nv: usize, all_dirichlet: bool) -> Result<Vec<f64>> {
    if !all_dirichlet {
        let mut x = rhs.to_vec();
        Lu::new(k)?.solve_in_place(&mut x);
        return Ok(x);
    }
    let n = k.n;
    let mut x = rhs.to_vec();
    x.push(0.0);
    Lu::new(&bordered(k, nv))?.solve_in_place(&mut x);
    x.truncate(n);
    if x.iter().any(|v| !v.is_finite()) {
        return Err(Error::InvalidInput(
            "Stokes direct solve: singular saddle-point matrix".into(),
        ));
    }
    Ok(x)
}

/// `k` bordered by one Lagrange-multiplier row and column holding 1 at every pressure dof
/// (`>= 2 n_v`) and 0 on the diagonal. The constraint has unit weights: the kernel of the
/// pressure block is the constant vector, and the zero-mean shift is applied afterwards by the
/// caller.
fn bordered(k: &Csr, nv: usize) -> Csr {
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
    Csr {
        n: n + 1,
        row_ptr,
        col,
        val,
    }
}
