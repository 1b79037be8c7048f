//! Dirichlet conditions by symmetric elimination: the known values are moved to the right-hand
//! side, their rows and columns are zeroed and the diagonal set to 1, so a symmetric matrix stays
//! symmetric (and SPD) and CG still applies.

use super::csr::Csr;
use crate::error::{Error, Result};
use crate::mesh::{Mesh2, NONE};
use rayon::prelude::*;

/// Applies `x[i] = values[i]` for every `i` with `fixed[i]`: for a free row `i`,
/// `b[i] -= Σ_{j fixed} A[i][j] values[j]` and `A[i][j] = 0`; a fixed row becomes the unit row
/// and `b[i] = values[i]`. `values` is only read where `fixed` is true.
pub fn apply_dirichlet(a: &mut Csr, b: &mut [f64], fixed: &[bool], values: &[f64]) -> Result<()> {
    let n = a.n;
    if b.len() != n || fixed.len() != n || values.len() != n {
        return Err(Error::InvalidInput(format!(
            "Dirichlet elimination: matrix has {n} rows but rhs, mask and values have {}, {}, {}",
            b.len(),
            fixed.len(),
            values.len()
        )));
    }
    let row_ptr = &a.row_ptr;
    let col = &a.col;
    // Split the values by rows so each row is edited by one thread.
    let mut rows: Vec<&mut [f64]> = Vec::with_capacity(n);
    let mut rest: &mut [f64] = &mut a.val;
    for i in 0..n {
        let (head, tail) = rest.split_at_mut(row_ptr[i + 1] - row_ptr[i]);
        rows.push(head);
        rest = tail;
    }
    rows.par_iter_mut()
        .zip(b.par_iter_mut())
        .enumerate()
        .for_each(|(i, (vals, bi))| {
            let cols = &col[row_ptr[i]..row_ptr[i + 1]];
            if fixed[i] {
                for (v, &j) in vals.iter_mut().zip(cols) {
                    *v = if j as usize == i { 1.0 } else { 0.0 };
                }
                *bi = values[i];
            } else {
                for (v, &j) in vals.iter_mut().zip(cols) {
                    if fixed[j as usize] {
                        *bi -= *v * values[j as usize];
                        *v = 0.0;
                    }
                }
            }
        });
    Ok(())
}

/// Vertices on boundary (or interface) edges whose label is in `labels` (all labelled boundary
/// edges when `labels` is empty): the P1 Dirichlet mask.
pub fn boundary_mask(mesh: &Mesh2, labels: &[i32]) -> Vec<bool> {
    let mut mask = vec![false; mesh.n_points()];
    for t in mesh.live_tris() {
        for i in 0..3 {
            let r = mesh.edge_ref[t][i];
            let on = if labels.is_empty() {
                mesh.neighbours[t][i] == NONE
            } else {
                r != 0 && labels.contains(&r)
            };
            if on {
                for v in mesh.edge_vertices(t, i) {
                    mask[v as usize] = true;
                }
            }
        }
    }
    mask
}
