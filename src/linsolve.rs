//! Sparse linear algebra on top of faer: a fixed sparsity pattern whose
//! values are refilled cheaply, and factorisations that reuse their
//! symbolic analysis.

use crate::assembly::Triplets;
use crate::error::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu, SymbolicLlt, SymbolicLu};
use faer::sparse::{Argsort, Pair, SparseColMat, SymbolicSparseColMat};

/// A square sparsity pattern built once from the (row, col) list of a
/// triplet set; any triplet set with the same (row, col) list, in the same
/// order, can then be turned into a matrix in O(nnz).
pub struct Pattern {
    n: usize,
    symbolic: SymbolicSparseColMat<usize>,
    argsort: Argsort<usize>,
    len: usize,
}

impl Pattern {
    pub fn new(n: usize, t: &Triplets) -> Result<Self> {
        let pairs: Vec<Pair<usize, usize>> = t
            .rows
            .iter()
            .zip(&t.cols)
            .map(|(&row, &col)| Pair { row, col })
            .collect();
        let (symbolic, argsort) = SymbolicSparseColMat::try_new_from_indices(n, n, &pairs)
            .map_err(|e| Error::Singular(format!("cannot build the sparsity pattern: {e:?}")))?;
        Ok(Self {
            n,
            symbolic,
            argsort,
            len: t.len(),
        })
    }

    pub fn n(&self) -> usize {
        self.n
    }

    /// The matrix with values `vals` (same order as the triplets that made the pattern).
    pub fn matrix(&self, vals: &[f64]) -> Result<SparseColMat<usize, f64>> {
        assert_eq!(vals.len(), self.len, "values do not match the pattern");
        SparseColMat::new_from_argsort(self.symbolic.clone(), &self.argsort, vals)
            .map_err(|e| Error::Singular(format!("cannot fill the sparse matrix: {e:?}")))
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

/// Which factorisation a kernel uses.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Method {
    /// Symmetric positive definite: LLᵀ.
    Cholesky,
    /// General: LU with partial pivoting.
    Lu,
}

/// A numeric factorisation ready to solve many right-hand sides.
pub enum Factor {
    Llt(Llt<usize, f64>),
    Lu(Box<Lu<usize, f64>>),
}

impl Factor {
    /// Solves A x = b, checking the result is finite.
    pub fn solve(&self, b: &[f64]) -> Result<Vec<f64>> {
        let mut x = b.to_vec();
        {
            let col = faer::ColMut::from_slice_mut(&mut x);
            let mat = col.as_mat_mut();
            match self {
                Factor::Llt(f) => f.solve_in_place(mat),
                Factor::Lu(f) => f.solve_in_place(mat),
            }
        }
        if x.iter().all(|v| v.is_finite()) {
            Ok(x)
        } else {
            Err(Error::Singular(
                "the solve produced non-finite values".into(),
            ))
        }
    }
}

/// Factorises matrices of one pattern, keeping the symbolic analysis of
/// each method after its first use.
#[derive(Default)]
pub struct Factoriser {
    llt: Option<SymbolicLlt<usize>>,
    lu: Option<SymbolicLu<usize>>,
}

impl Factoriser {
    pub fn factor(&mut self, a: &SparseColMat<usize, f64>, method: Method) -> Result<Factor> {
        let sing =
            |what: &str, e: &dyn std::fmt::Debug| Error::Singular(format!("{what} failed: {e:?}"));
        match method {
            Method::Cholesky => {
                if self.llt.is_none() {
                    self.llt = Some(
                        SymbolicLlt::try_new(a.symbolic(), faer::Side::Lower)
                            .map_err(|e| sing("symbolic Cholesky", &e))?,
                    );
                }
                let sym = self.llt.clone().expect("set above");
                Llt::try_new_with_symbolic(sym, a.as_ref(), faer::Side::Lower)
                    .map(Factor::Llt)
                    .map_err(|e| sing("Cholesky (matrix not positive definite?)", &e))
            }
            Method::Lu => {
                if self.lu.is_none() {
                    self.lu = Some(
                        SymbolicLu::try_new(a.symbolic()).map_err(|e| sing("symbolic LU", &e))?,
                    );
                }
                let sym = self.lu.clone().expect("set above");
                Lu::try_new_with_symbolic(sym, a.as_ref())
                    .map(|f| Factor::Lu(Box::new(f)))
                    .map_err(|e| sing("LU", &e))
            }
        }
    }
}
