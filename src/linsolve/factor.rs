//! Numeric factorisations of one pattern's matrices, reusing their
//! symbolic analyses: Cholesky, LU, and the low-rank corrected Cholesky.

use super::low_rank::LowRankCorrected;
use crate::error::{FactorError, Result, SingularError};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu, SymbolicLlt, SymbolicLu};
use faer::sparse::SparseColMat;

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
    LowRank(Box<LowRankCorrected>),
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
                Factor::LowRank(f) => f.solve_in_place(&mut x),
            }
        }
        if x.iter().all(|v| v.is_finite()) {
            Ok(x)
        } else {
            Err(SingularError::NonFiniteSolution.into())
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
    pub fn factor(
        &mut self,
        a: &SparseColMat<usize, f64>,
        method: Method,
    ) -> std::result::Result<Factor, FactorError> {
        match method {
            Method::Cholesky => {
                if self.llt.is_none() {
                    self.llt = Some(
                        SymbolicLlt::try_new(a.symbolic(), faer::Side::Lower)
                            .map_err(|e| FactorError::of_faer("symbolic Cholesky", e))?,
                    );
                }
                let sym = self.llt.clone().expect("set above");
                Llt::try_new_with_symbolic(sym, a.as_ref(), faer::Side::Lower)
                    .map(Factor::Llt)
                    .map_err(|e| FactorError::of_llt("Cholesky", e))
            }
            Method::Lu => {
                if self.lu.is_none() {
                    self.lu = Some(
                        SymbolicLu::try_new(a.symbolic())
                            .map_err(|e| FactorError::of_faer("symbolic LU", e))?,
                    );
                }
                let sym = self.lu.clone().expect("set above");
                Lu::try_new_with_symbolic(sym, a.as_ref())
                    .map(|f| Factor::Lu(Box::new(f)))
                    .map_err(|e| FactorError::of_lu("LU", e))
            }
        }
    }

    /// The [`LowRankCorrected`] factorisation of A = S + U Vᵀ, where `s`
    /// (n × n, symmetric positive definite, of this factoriser's pattern)
    /// is factorised by Cholesky and `u`, `v` are n × k. Fails with
    /// [`FactorError::NotPositiveDefinite`] if S is not positive definite,
    /// and [`FactorError::LowRankInaccurate`] if I + Vᵀ Z is singular or
    /// the set-up check fails even with refinement (S nearly singular): in
    /// each case LU is the safe choice.
    pub fn factor_low_rank(
        &mut self,
        s: &SparseColMat<usize, f64>,
        u: &SparseColMat<usize, f64>,
        v: &SparseColMat<usize, f64>,
    ) -> std::result::Result<Factor, FactorError> {
        let n = s.nrows();
        let k = u.ncols();
        assert_eq!(
            (u.nrows(), v.nrows(), v.ncols()),
            (n, n, k),
            "U and V must be n × k"
        );
        let Factor::Llt(llt) = self.factor(s, Method::Cholesky)? else {
            unreachable!("Method::Cholesky gives Factor::Llt")
        };
        LowRankCorrected::new(s, u, v, llt).map(|f| Factor::LowRank(Box::new(f)))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::linsolve::{mul, mul_transpose};
    use faer::sparse::Triplet;
    use nalgebra::{DMatrix, DVector};

    fn csc(n: usize, m: usize, entries: &[(usize, usize, f64)]) -> SparseColMat<usize, f64> {
        let t: Vec<_> = entries
            .iter()
            .map(|&(i, j, v)| Triplet::new(i, j, v))
            .collect();
        SparseColMat::try_new_from_triplets(n, m, &t).unwrap()
    }

    /// S: the 1D Laplacian with a diagonal shift, last diagonal `last`;
    /// U: unit columns on `rows`; V: dense pseudo-random columns. So
    /// U Vᵀ changes only the rows `rows`, like the θ = 0 kernels.
    fn case(n: usize, last: f64, rows: &[usize]) -> [SparseColMat<usize, f64>; 3] {
        let mut s = Vec::new();
        for i in 0..n {
            s.push((i, i, if i + 1 == n { last } else { 2.5 }));
            if i + 1 < n - 1 {
                s.push((i, i + 1, -1.0));
                s.push((i + 1, i, -1.0));
            }
        }
        let u: Vec<_> = rows.iter().enumerate().map(|(c, &i)| (i, c, 1.0)).collect();
        let mut v = Vec::new();
        for c in 0..rows.len() {
            for j in 0..n {
                v.push((j, c, ((c * 31 + j * 17) % 13) as f64 / 13.0 - 0.4));
            }
        }
        [
            csc(n, n, &s),
            csc(n, rows.len(), &u),
            csc(n, rows.len(), &v),
        ]
    }

    fn dense(m: &[SparseColMat<usize, f64>; 3]) -> DMatrix<f64> {
        let n = m[0].nrows();
        DMatrix::from_fn(n, n, |i, j| {
            let e = DVector::from_fn(n, |k, _| if k == j { 1.0 } else { 0.0 });
            let mut col = mul(&m[0], e.as_slice());
            for (ci, ui) in col
                .iter_mut()
                .zip(mul(&m[1], &mul_transpose(&m[2], e.as_slice())))
            {
                *ci += ui;
            }
            col[i]
        })
    }

    fn check_against_dense(last: f64) -> (bool, f64) {
        let n = 40;
        let m = case(n, last, &[3, 17, 39]);
        let f = Factoriser::default()
            .factor_low_rank(&m[0], &m[1], &m[2])
            .unwrap();
        let Factor::LowRank(lr) = &f else {
            panic!("low-rank factor expected")
        };
        assert_eq!(lr.rank(), 3);
        let b: Vec<f64> = (0..n).map(|i| (i as f64).sin()).collect();
        let x = f.solve(&b).unwrap();
        let want = dense(&m).lu().solve(&DVector::from_vec(b)).unwrap();
        let err = (DVector::from_vec(x) - &want).norm() / want.norm();
        (lr.refines(), err)
    }

    #[test]
    fn woodbury_matches_a_dense_solve() {
        let (refines, err) = check_against_dense(2.5);
        assert!(!refines);
        assert!(err <= 1e-13, "{err:.2e}");
    }

    #[test]
    fn a_nearly_singular_symmetric_part_is_refined() {
        // S's last pivot is 1e-12, A's is O(1): Z = S⁻¹E is huge and the
        // identity cancels about 12 digits; refinement recovers them
        let (refines, err) = check_against_dense(1e-12);
        assert!(refines, "the set-up check should have asked for refinement");
        assert!(err <= 1e-10, "{err:.2e}");
    }

    #[test]
    fn a_singular_symmetric_part_is_refused() {
        let m = case(20, 0.0, &[3, 17]);
        let err = Factoriser::default()
            .factor_low_rank(&m[0], &m[1], &m[2])
            .err()
            .expect("S is singular");
        assert!(
            matches!(err, FactorError::NotPositiveDefinite { .. }),
            "{err}"
        );
        assert!(err.lu_may_help());
    }
}
