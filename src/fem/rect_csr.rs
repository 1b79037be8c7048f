//! `RectCsr`: a rectangular `m x n` sparse matrix in compressed sparse row storage, for the
//! off-diagonal blocks of saddle-point systems (the discrete divergence `B` of a Stokes problem
//! and its transpose `Bᵀ`).
//!
//! Rows are built one after the other ([`RectCsr::push`], [`RectCsr::end_row`]); columns within a
//! row keep the order in which they were pushed. Products are deterministic: each row is summed
//! by one thread in storage order, and [`RectCsr::transpose`] is a counting sort, so results do
//! not depend on the number of rayon threads.

use crate::error::{Error, Result};
use rayon::prelude::*;

/// Rectangular sparse matrix in CSR form: row `i` holds the columns `col[row_ptr[i]..row_ptr[i+1]]`
/// and the values `val[..]` at the same positions; every column index is `< ncols`.
#[derive(Debug, Clone, PartialEq)]
pub struct RectCsr {
    ncols: usize,
    row_ptr: Vec<usize>,
    col: Vec<u32>,
    val: Vec<f64>,
}

impl RectCsr {
    /// An empty matrix with no rows and `ncols` columns; add rows with [`RectCsr::push`] and
    /// [`RectCsr::end_row`].
    pub fn new(ncols: usize) -> Self {
        RectCsr {
            ncols,
            row_ptr: vec![0],
            col: Vec::new(),
            val: Vec::new(),
        }
    }

    /// Builds a matrix from its rows, each a list of `(column, value)` entries in storage order.
    /// Errors if a column is out of range.
    pub fn from_rows(ncols: usize, rows: &[Vec<(u32, f64)>]) -> Result<Self> {
        let mut m = RectCsr::new(ncols);
        for (i, row) in rows.iter().enumerate() {
            for &(j, v) in row {
                if j as usize >= ncols {
                    return Err(Error::InvalidInput(format!(
                        "row {i} refers to column {j}, but the matrix has {ncols} columns"
                    )));
                }
                m.push(j, v);
            }
            m.end_row();
        }
        Ok(m)
    }

    /// Appends the entry `(j, v)` to the row being built. The caller keeps `j < ncols`
    /// (checked in debug builds).
    #[inline]
    pub fn push(&mut self, j: u32, v: f64) {
        debug_assert!((j as usize) < self.ncols);
        self.col.push(j);
        self.val.push(v);
    }

    /// Closes the row being built (a row with no entries is a zero row).
    #[inline]
    pub fn end_row(&mut self) {
        self.row_ptr.push(self.col.len());
    }

    /// Number of rows.
    pub fn nrows(&self) -> usize {
        self.row_ptr.len() - 1
    }

    /// Number of columns.
    pub fn ncols(&self) -> usize {
        self.ncols
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.col.len()
    }

    /// The stored entries `(column, value)` of row `i`, in storage order.
    pub fn row(&self, i: usize) -> impl Iterator<Item = (usize, f64)> + '_ {
        let r = self.row_ptr[i]..self.row_ptr[i + 1];
        self.col[r.clone()]
            .iter()
            .zip(&self.val[r])
            .map(|(&j, &v)| (j as usize, v))
    }

    /// `y = M x` (`x` of length `ncols`, `y` of length `nrows`), rows in parallel, each row
    /// summed in storage order.
    pub fn matvec(&self, x: &[f64], y: &mut [f64]) {
        y.par_iter_mut().enumerate().for_each(|(i, yi)| {
            let r = self.row_ptr[i]..self.row_ptr[i + 1];
            *yi = self.col[r.clone()]
                .iter()
                .zip(&self.val[r])
                .map(|(&j, &a)| a * x[j as usize])
                .sum();
        });
    }

    /// The transpose `Mᵀ` (`ncols x nrows`), by a counting sort over the columns: within a row
    /// of `Mᵀ` the entries are in increasing column order.
    pub fn transpose(&self) -> RectCsr {
        let (row_ptr, col, val) = transpose_arrays(self.ncols, &self.row_ptr, &self.col, &self.val);
        RectCsr {
            ncols: self.nrows(),
            row_ptr,
            col,
            val,
        }
    }

    /// The dense matrix, row by row (repeated entries are summed); for tests and small cases.
    pub fn to_dense(&self) -> Vec<Vec<f64>> {
        (0..self.nrows())
            .map(|i| {
                let mut row = vec![0.0; self.ncols];
                for (j, v) in self.row(i) {
                    row[j] += v;
                }
                row
            })
            .collect()
    }
}

/// The arrays of the transpose of a CSR matrix with `ncols` columns (counting sort by column;
/// within a row of the transpose the entries keep their original row order).
pub(crate) fn transpose_arrays(
    ncols: usize,
    row_ptr: &[usize],
    col: &[u32],
    val: &[f64],
) -> (Vec<usize>, Vec<u32>, Vec<f64>) {
    let mut ptr = vec![0usize; ncols + 1];
    for &j in col {
        ptr[j as usize + 1] += 1;
    }
    for j in 0..ncols {
        ptr[j + 1] += ptr[j];
    }
    let mut fill = ptr.clone();
    let mut tcol = vec![0u32; col.len()];
    let mut tval = vec![0.0; col.len()];
    for i in 0..row_ptr.len().saturating_sub(1) {
        for q in row_ptr[i]..row_ptr[i + 1] {
            let j = col[q] as usize;
            tcol[fill[j]] = i as u32;
            tval[fill[j]] = val[q];
            fill[j] += 1;
        }
    }
    (ptr, tcol, tval)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A 3 x 4 matrix with an empty row and an empty column.
    fn sample() -> RectCsr {
        RectCsr::from_rows(
            4,
            &[
                vec![(0, 1.0), (2, -2.0)],
                vec![],
                vec![(3, 0.5), (0, 4.0), (2, 3.0)],
            ],
        )
        .unwrap()
    }

    fn dense_mul(d: &[Vec<f64>], x: &[f64]) -> Vec<f64> {
        d.iter()
            .map(|r| r.iter().zip(x).map(|(a, b)| a * b).sum())
            .collect()
    }

    #[test]
    fn shape_and_products_match_the_dense_matrix() {
        let b = sample();
        assert_eq!((b.nrows(), b.ncols(), b.nnz()), (3, 4, 5));
        let d = b.to_dense();
        assert_eq!(d[2], vec![4.0, 0.0, 3.0, 0.5]);
        let x = [1.0, -1.0, 2.0, 4.0];
        let mut y = vec![f64::NAN; 3];
        b.matvec(&x, &mut y);
        assert_eq!(y, dense_mul(&d, &x));
        assert_eq!(y, vec![-3.0, 0.0, 12.0]);
    }

    #[test]
    fn transpose_applied_equals_the_dense_transpose() {
        let b = sample();
        let bt = b.transpose();
        assert_eq!((bt.nrows(), bt.ncols(), bt.nnz()), (4, 3, 5));
        let d = b.to_dense();
        let dt: Vec<Vec<f64>> = (0..4).map(|j| (0..3).map(|i| d[i][j]).collect()).collect();
        assert_eq!(bt.to_dense(), dt);
        let q = [2.0, 7.0, -1.0];
        let mut z = vec![f64::NAN; 4];
        bt.matvec(&q, &mut z);
        assert_eq!(z, dense_mul(&dt, &q));
        assert_eq!(z, vec![-2.0, 0.0, -7.0, -0.5]);
        // Rows of the transpose are sorted by column; transposing twice gives the same dense
        // matrix (storage order within a row may differ from the input).
        assert!((0..4).all(|j| bt.row(j).map(|(i, _)| i).is_sorted()));
        assert_eq!(bt.transpose().to_dense(), d);
    }

    #[test]
    fn out_of_range_column_is_an_error() {
        let e = RectCsr::from_rows(2, &[vec![(2, 1.0)]]).unwrap_err();
        assert!(e.to_string().contains("column 2"), "{e}");
    }
}
