//! `Csr`: a square sparse matrix in compressed sparse row storage, with sorted columns and the
//! diagonal always present, built from element-to-dof maps and filled by element assembly.
//!
//! Every parallel operation here is deterministic: a row is always summed by one thread in
//! storage order, and reductions ([`dot`]) sum fixed-size chunks and then the chunk sums in
//! order, so results do not depend on the number of rayon threads.

use crate::error::{Error, Result};
use crate::mesh::Mesh2;
use rayon::prelude::*;
use std::ops::Range;

/// Chunk length of deterministic parallel reductions.
const CHUNK: usize = 4096;

/// Square sparse matrix in CSR form: row `i` holds columns `col[row_ptr[i]..row_ptr[i+1]]`
/// (strictly increasing) and values `val[..]` at the same positions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Csr {
    /// Number of rows and columns.
    pub n: usize,
    /// Start of each row in `col` and `val` (`n + 1` entries).
    pub row_ptr: Vec<usize>,
    /// Column index of each stored entry.
    pub col: Vec<u32>,
    /// Value of each stored entry.
    pub val: Vec<f64>,
}

impl Csr {
    /// The pattern (values zero) of the P1 vertex–vertex coupling of the live triangles of
    /// `mesh`, plus every diagonal entry (so unreferenced vertices get a diagonal too).
    pub fn p1_pattern(mesh: &Mesh2) -> Result<Csr> {
        let elems: Vec<[u32; 3]> = mesh.live_tris().map(|t| mesh.tris[t]).collect();
        Csr::from_elements(mesh.n_points(), &elems)
    }

    /// The pattern of all couplings `(a, b)` with `a` and `b` in the same element, plus the
    /// diagonal. `elems[e]` lists the global dofs of element `e` (P1, P2, MINI, a block of a
    /// saddle-point system ...); dofs must be `< n`.
    pub fn from_elements<const K: usize>(n: usize, elems: &[[u32; K]]) -> Result<Csr> {
        Csr::from_element_iter(n, elems.iter().map(|e| &e[..]))
    }

    /// As [`Csr::from_elements`] for elements given as slices of any length.
    pub fn from_element_iter<'a>(
        n: usize,
        elems: impl Iterator<Item = &'a [u32]> + Clone,
    ) -> Result<Csr> {
        if n >= u32::MAX as usize {
            return Err(Error::InvalidInput(format!(
                "matrix size {n} too large for u32 columns"
            )));
        }
        // Dof -> elements (counting sort), then each row is the sorted union of its elements.
        let mut count = vec![0usize; n + 1];
        for (e, dofs) in elems.clone().enumerate() {
            for &d in dofs {
                if d as usize >= n {
                    return Err(Error::InvalidInput(format!(
                        "element {e} refers to dof {d}, but the matrix has {n} rows"
                    )));
                }
                count[d as usize + 1] += 1;
            }
        }
        for i in 0..n {
            count[i + 1] += count[i];
        }
        let mut fill = count.clone();
        let elem_list: Vec<&[u32]> = elems.collect();
        let mut d2e = vec![0u32; count[n]];
        for (e, dofs) in elem_list.iter().enumerate() {
            for &d in dofs.iter() {
                d2e[fill[d as usize]] = e as u32;
                fill[d as usize] += 1;
            }
        }
        let rows: Vec<Vec<u32>> = (0..n)
            .into_par_iter()
            .map(|i| {
                let mut row = vec![i as u32];
                for &e in &d2e[count[i]..count[i + 1]] {
                    row.extend_from_slice(elem_list[e as usize]);
                }
                row.sort_unstable();
                row.dedup();
                row
            })
            .collect();
        let mut row_ptr = Vec::with_capacity(n + 1);
        row_ptr.push(0);
        let mut col = Vec::with_capacity(rows.iter().map(Vec::len).sum());
        for r in rows {
            col.extend_from_slice(&r);
            row_ptr.push(col.len());
        }
        let val = vec![0.0; col.len()];
        Ok(Csr {
            n,
            row_ptr,
            col,
            val,
        })
    }

    /// Builds a matrix from `(row, col, value)` triplets (duplicates are summed); the diagonal
    /// is always stored.
    pub fn from_triplets(n: usize, triplets: &[(u32, u32, f64)]) -> Result<Csr> {
        let mut rows: Vec<Vec<u32>> = (0..n as u32).map(|i| vec![i]).collect();
        for &(i, j, _) in triplets {
            if i as usize >= n || j as usize >= n {
                return Err(Error::InvalidInput(format!(
                    "triplet ({i}, {j}) out of range for a {n} x {n} matrix"
                )));
            }
            rows[i as usize].push(j);
        }
        let mut row_ptr = vec![0];
        let mut col = Vec::new();
        for mut r in rows {
            r.sort_unstable();
            r.dedup();
            col.extend_from_slice(&r);
            row_ptr.push(col.len());
        }
        let mut a = Csr {
            n,
            val: vec![0.0; col.len()],
            row_ptr,
            col,
        };
        for &(i, j, v) in triplets {
            a.add(i as usize, j as usize, v)?;
        }
        Ok(a)
    }

    /// Number of stored entries.
    pub fn nnz(&self) -> usize {
        self.col.len()
    }

    /// Storage position of entry `(i, j)`, or `None` if it is not in the pattern.
    #[inline]
    pub fn find(&self, i: usize, j: usize) -> Option<usize> {
        let r = self.row_ptr[i]..self.row_ptr[i + 1];
        self.col[r.clone()]
            .binary_search(&(j as u32))
            .ok()
            .map(|k| r.start + k)
    }

    /// Value of entry `(i, j)` (0 outside the pattern).
    pub fn get(&self, i: usize, j: usize) -> f64 {
        if i >= self.n || j >= self.n {
            return 0.0;
        }
        self.find(i, j).map_or(0.0, |k| self.val[k])
    }

    /// `A[i][j] += v`. Errors if `(i, j)` is not in the pattern.
    #[inline]
    pub fn add(&mut self, i: usize, j: usize, v: f64) -> Result<()> {
        match (i < self.n && j < self.n)
            .then(|| self.find(i, j))
            .flatten()
        {
            Some(k) => {
                self.val[k] += v;
                Ok(())
            }
            None => Err(Error::InvalidInput(format!(
                "entry ({i}, {j}) is not in the sparsity pattern"
            ))),
        }
    }

    /// Sets all values to zero (keeps the pattern).
    pub fn clear_values(&mut self) {
        self.val.iter_mut().for_each(|v| *v = 0.0);
    }

    /// Adds the dense element matrix `ke` at the dofs `dofs`.
    pub fn add_element<const K: usize>(
        &mut self,
        dofs: &[u32; K],
        ke: &[[f64; K]; K],
    ) -> Result<()> {
        for a in 0..K {
            for b in 0..K {
                self.add(dofs[a] as usize, dofs[b] as usize, ke[a][b])?;
            }
        }
        Ok(())
    }

    /// `y = A x`, rows in parallel.
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

    /// `A x` as a new vector.
    pub fn mul(&self, x: &[f64]) -> Vec<f64> {
        let mut y = vec![0.0; self.n];
        self.matvec(x, &mut y);
        y
    }

    /// `y[i - rows.start] = Σ_{j in cols} A[i][j] x[j - cols.start]` for `i` in `rows`: the
    /// product with the block `(rows, cols)` (used for the blocks of a saddle-point matrix).
    pub fn block_matvec(&self, rows: Range<usize>, cols: Range<usize>, x: &[f64], y: &mut [f64]) {
        let (c0, c1) = (cols.start as u32, cols.end as u32);
        y.par_iter_mut().enumerate().for_each(|(k, yi)| {
            let i = rows.start + k;
            let r = self.row_ptr[i]..self.row_ptr[i + 1];
            let cs = &self.col[r.clone()];
            let lo = cs.partition_point(|&j| j < c0);
            let hi = cs.partition_point(|&j| j < c1);
            *yi = (lo..hi)
                .map(|q| self.val[r.start + q] * x[(cs[q] - c0) as usize])
                .sum();
        });
    }

    /// The diagonal.
    pub fn diagonal(&self) -> Vec<f64> {
        (0..self.n).map(|i| self.get(i, i)).collect()
    }

    /// Row sums `A 1`.
    pub fn row_sums(&self) -> Vec<f64> {
        (0..self.n)
            .map(|i| self.val[self.row_ptr[i]..self.row_ptr[i + 1]].iter().sum())
            .collect()
    }

    /// The transpose.
    pub fn transpose(&self) -> Csr {
        let (row_ptr, col, val) =
            super::rect_csr::transpose_arrays(self.n, &self.row_ptr, &self.col, &self.val);
        Csr {
            n: self.n,
            row_ptr,
            col,
            val,
        }
    }

    /// The square diagonal block `A[range, range]` as a new matrix (indices shifted to 0).
    pub fn sub_block(&self, range: Range<usize>) -> Csr {
        let (c0, c1) = (range.start as u32, range.end as u32);
        let mut row_ptr = vec![0];
        let mut col = Vec::new();
        let mut val = Vec::new();
        for i in range.clone() {
            for k in self.row_ptr[i]..self.row_ptr[i + 1] {
                let j = self.col[k];
                if j >= c0 && j < c1 {
                    col.push(j - c0);
                    val.push(self.val[k]);
                }
            }
            row_ptr.push(col.len());
        }
        Csr {
            n: range.len(),
            row_ptr,
            col,
            val,
        }
    }

    /// Largest `|A[i][j] - A[j][i]|` over the stored entries (0 for a symmetric matrix).
    pub fn asymmetry(&self) -> f64 {
        (0..self.n)
            .flat_map(|i| {
                (self.row_ptr[i]..self.row_ptr[i + 1]).map(move |k| (i, self.col[k] as usize, k))
            })
            .map(|(i, j, k)| (self.val[k] - self.get(j, i)).abs())
            .fold(0.0, f64::max)
    }
}

/// Deterministic parallel dot product (fixed chunks, chunk sums added in order).
pub fn dot(a: &[f64], b: &[f64]) -> f64 {
    let partial: Vec<f64> = a
        .par_chunks(CHUNK)
        .zip(b.par_chunks(CHUNK))
        .map(|(x, y)| x.iter().zip(y).map(|(p, q)| p * q).sum::<f64>())
        .collect();
    partial.iter().sum()
}

/// Euclidean norm, deterministic.
pub fn norm(a: &[f64]) -> f64 {
    dot(a, a).sqrt()
}

/// `y += alpha x`, in parallel.
pub fn axpy(alpha: f64, x: &[f64], y: &mut [f64]) {
    y.par_iter_mut()
        .zip(x)
        .for_each(|(yi, xi)| *yi += alpha * xi);
}
