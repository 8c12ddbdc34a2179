//! A fixed sparsity pattern whose values are refilled cheaply, and the
//! products with its matrices.

use crate::error::{Result, SingularError};
use crate::sparse::Triplets;
use faer::sparse::{SparseColMat, SymbolicSparseColMat};

/// A square sparsity pattern built once from the (row, col) lists of one
/// or more triplet sets; triplet sets with the same (row, col) lists, in
/// the same order, then become a matrix in O(nnz) (duplicates summed).
///
/// The pattern is built by bucketing the triplets by column (a counting
/// sort) and sorting each column's few distinct rows, which is several
/// times faster than sorting all (row, col) pairs for the million-entry
/// triplet sets of element assembly.
pub struct Pattern {
    symbolic: SymbolicSparseColMat<usize>,
    /// The CSC slot of every triplet, the parts one after the other.
    slot: Vec<usize>,
}

impl Pattern {
    pub fn new(n: usize, parts: &[&Triplets]) -> Result<Self> {
        let len: usize = parts.iter().map(|t| t.len()).sum();
        let entries = || {
            parts
                .iter()
                .flat_map(|t| t.rows.iter().copied().zip(t.cols.iter().copied()))
        };
        if let Some((i, j)) = entries().find(|&(i, j)| i >= n || j >= n) {
            return Err(SingularError::OutsideMatrix { row: i, col: j, n }.into());
        }
        // bucket the triplets by column
        let mut start = vec![0usize; n + 1];
        for (_, j) in entries() {
            start[j + 1] += 1;
        }
        for j in 0..n {
            start[j + 1] += start[j];
        }
        let mut fill = start.clone();
        let (mut id, mut row) = (vec![0usize; len], vec![0usize; len]);
        for (t, (i, j)) in entries().enumerate() {
            id[fill[j]] = t;
            row[fill[j]] = i;
            fill[j] += 1;
        }
        // per column: distinct rows, sorted, and every triplet's slot
        const FREE: usize = usize::MAX;
        let mut at = vec![FREE; n];
        let mut col_ptr = vec![0usize; n + 1];
        let mut row_idx = Vec::with_capacity(len / 4);
        let mut slot = vec![0usize; len];
        for j in 0..n {
            let bucket = start[j]..start[j + 1];
            let first = row_idx.len();
            for &i in &row[bucket.clone()] {
                if at[i] == FREE {
                    at[i] = 0;
                    row_idx.push(i);
                }
            }
            row_idx[first..].sort_unstable();
            for (k, &i) in row_idx[first..].iter().enumerate() {
                at[i] = first + k;
            }
            for p in bucket {
                slot[id[p]] = at[row[p]];
            }
            for &i in &row_idx[first..] {
                at[i] = FREE;
            }
            col_ptr[j + 1] = row_idx.len();
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Ok(Self { symbolic, slot })
    }

    pub fn n(&self) -> usize {
        self.symbolic.nrows()
    }

    /// Stored entries.
    pub fn nnz(&self) -> usize {
        self.symbolic.row_idx().len()
    }

    /// The matrix whose triplet values are `parts` (the same parts, in the
    /// same order, as the triplet sets that made the pattern).
    pub fn matrix(&self, parts: &[&[f64]]) -> Result<SparseColMat<usize, f64>> {
        let len: usize = parts.iter().map(|v| v.len()).sum();
        assert_eq!(len, self.slot.len(), "values do not match the pattern");
        let mut val = vec![0.0; self.nnz()];
        for (&k, v) in self.slot.iter().zip(parts.iter().flat_map(|p| p.iter())) {
            val[k] += v;
        }
        Ok(SparseColMat::new(self.symbolic.clone(), val))
    }
}

/// y = A x for a faer CSC matrix.
pub fn mul(a: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let mut y = vec![0.0; a.nrows()];
    let s = a.symbolic();
    let (ptr, idx, val) = (s.col_ptr(), s.row_idx(), a.val());
    for j in 0..a.ncols() {
        for k in ptr[j]..ptr[j + 1] {
            y[idx[k]] += val[k] * x[j];
        }
    }
    y
}

/// y = Aᵀ x for a faer CSC matrix (a dot product per column).
pub fn mul_transpose(a: &SparseColMat<usize, f64>, x: &[f64]) -> Vec<f64> {
    let s = a.symbolic();
    (0..a.ncols())
        .map(|j| {
            (s.col_ptr()[j]..s.col_ptr()[j + 1])
                .map(|k| a.val()[k] * x[s.row_idx()[k]])
                .sum()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    #[test]
    fn a_pattern_sums_duplicates_across_parts() {
        let n = 7;
        let mut seed = 99u64;
        let mut next = |m: usize| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (seed >> 33) as usize % m
        };
        let mut parts = [Triplets::default(), Triplets::default()];
        let mut want = DMatrix::<f64>::zeros(n, n);
        for t in 0..60 {
            let (i, j, v) = (next(n), next(n), next(1000) as f64 - 500.0);
            let part = &mut parts[t % 2];
            part.rows.push(i);
            part.cols.push(j);
            part.vals.push(v);
            want[(i, j)] += v;
        }
        let pattern = Pattern::new(n, &[&parts[0], &parts[1]]).unwrap();
        let a = pattern.matrix(&[&parts[0].vals, &parts[1].vals]).unwrap();
        let s = a.symbolic();
        for j in 0..n {
            let rows = &s.row_idx()[s.col_ptr()[j]..s.col_ptr()[j + 1]];
            assert!(
                rows.windows(2).all(|w| w[0] < w[1]),
                "column {j} sorted, distinct"
            );
        }
        assert_eq!(
            a.to_dense().as_ref(),
            faer::Mat::from_fn(n, n, |i, j| want[(i, j)])
        );
        let mut bad = Triplets::default();
        bad.rows.push(n);
        bad.cols.push(0);
        bad.vals.push(1.0);
        assert!(Pattern::new(n, &[&bad]).is_err());
    }
}
