//! Generic element-by-element assembly into a pre-built [`Csr`] pattern and into vectors.
//!
//! Element matrices are computed in parallel, a chunk of elements at a time, and scattered
//! sequentially in element order, so the assembled values do not depend on the thread count.

use super::csr::Csr;
use crate::error::{Error, Result};
use rayon::prelude::*;

/// Elements per parallel chunk (bounds the memory of buffered element matrices).
const CHUNK: usize = 1 << 14;

/// `A += Σ_e P_e^T K_e P_e` where element `e` has dofs `elems[e]` and local matrix `local(e)`.
/// Errors if a dof pair is missing from the pattern of `a`.
pub fn assemble_matrix<const K: usize>(
    a: &mut Csr,
    elems: &[[u32; K]],
    local: impl Fn(usize) -> [[f64; K]; K] + Sync,
) -> Result<()> {
    for start in (0..elems.len()).step_by(CHUNK) {
        let end = (start + CHUNK).min(elems.len());
        let mats: Vec<[[f64; K]; K]> = (start..end).into_par_iter().map(&local).collect();
        for (e, ke) in (start..end).zip(&mats) {
            a.add_element(&elems[e], ke)?;
        }
    }
    Ok(())
}

/// `b += Σ_e P_e^T f_e` where element `e` has dofs `elems[e]` and local vector `local(e)`.
/// Errors if a dof is `>= b.len()`.
pub fn assemble_vector<const K: usize>(
    b: &mut [f64],
    elems: &[[u32; K]],
    local: impl Fn(usize) -> [f64; K] + Sync,
) -> Result<()> {
    let n = b.len();
    for start in (0..elems.len()).step_by(CHUNK) {
        let end = (start + CHUNK).min(elems.len());
        let vecs: Vec<[f64; K]> = (start..end).into_par_iter().map(&local).collect();
        for (e, fe) in (start..end).zip(&vecs) {
            for (k, &d) in elems[e].iter().enumerate() {
                match b.get_mut(d as usize) {
                    Some(bi) => *bi += fe[k],
                    None => {
                        return Err(Error::InvalidInput(format!(
                            "element {e} refers to dof {d}, but the vector has length {n}"
                        )))
                    }
                }
            }
        }
    }
    Ok(())
}
