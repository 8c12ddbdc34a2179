//! Sparse linear algebra on top of faer: a fixed sparsity pattern whose
//! values are refilled cheaply, factorisations that reuse their symbolic
//! analysis, and the exact Cholesky-plus-low-rank solve of a matrix that
//! is symmetric positive definite up to a correction of low rank.

use crate::assembly::Triplets;
use crate::error::{Error, Result};
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Llt, Lu, SymbolicLlt, SymbolicLu};
use faer::sparse::linalg::{LltError, LuError};
use faer::sparse::{FaerError, SparseColMat, SymbolicSparseColMat};

/// Why a factorisation failed: what decides whether another method can
/// take over ([`crate::solver::kernel`] falls back to LU on the first and
/// the last only) and what the user is told.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FactorError {
    /// Cholesky met a pivot that is not positive: the matrix is not
    /// symmetric positive definite (LU may still factorise it).
    #[error("{what}: pivot {pivot} is not positive, so the matrix is not positive definite")]
    NotPositiveDefinite { what: &'static str, pivot: usize },
    /// No usable pivot: the matrix is singular.
    #[error("{what}: {detail}")]
    Singular { what: &'static str, detail: String },
    /// The factorisation could not allocate its storage.
    #[error("{what}: out of memory")]
    OutOfMemory { what: &'static str },
    /// The Woodbury solve of a [`LowRankCorrected`] factorisation is
    /// singular or inaccurate (S nearly singular): LU is the safe choice.
    #[error("{0}")]
    LowRankInaccurate(String),
}

impl FactorError {
    fn of_faer(what: &'static str, e: FaerError) -> Self {
        match e {
            FaerError::OutOfMemory => FactorError::OutOfMemory { what },
            other => FactorError::Singular {
                what,
                detail: format!("{other:?}"),
            },
        }
    }

    fn of_llt(what: &'static str, e: LltError) -> Self {
        match e {
            LltError::Numeric(
                faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index },
            ) => FactorError::NotPositiveDefinite { what, pivot: index },
            LltError::Generic(g) => Self::of_faer(what, g),
        }
    }

    fn of_lu(what: &'static str, e: LuError) -> Self {
        match e {
            LuError::SymbolicSingular { index } => FactorError::Singular {
                what,
                detail: format!("no pivot in column {index}"),
            },
            LuError::Generic(g) => Self::of_faer(what, g),
        }
    }

    /// Whether another factorisation of the same matrix may succeed (LU
    /// where Cholesky or the low-rank path failed); running out of memory
    /// or a singular matrix is not helped by that.
    pub fn lu_may_help(&self) -> bool {
        matches!(
            self,
            FactorError::NotPositiveDefinite { .. } | FactorError::LowRankInaccurate(_)
        )
    }
}

impl From<FactorError> for Error {
    fn from(e: FactorError) -> Self {
        match e {
            FactorError::OutOfMemory { .. } => Error::OutOfMemory(e.to_string()),
            other => Error::Singular(other.to_string()),
        }
    }
}

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
            return Err(Error::Singular(format!(
                "cannot build the sparsity pattern: entry ({i}, {j}) outside {n} × {n}"
            )));
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
            Err(Error::Singular(
                "the solve produced non-finite values".into(),
            ))
        }
    }
}

/// A = S + U Vᵀ, with S sparse symmetric positive definite and U, V
/// sparse n × k with k ≪ n, solved exactly by the Sherman–Morrison–Woodbury
/// identity
///
///   A⁻¹ b = y − Z (I + Vᵀ Z)⁻¹ Vᵀ y,   y = S⁻¹ b,   Z = S⁻¹ U.
///
/// Setting up costs one Cholesky factorisation and k triangular solves
/// (blocked, for Z); a solve costs one triangular solve, a product with
/// the n × k block Z and a k × k dense solve. It pays when k ≪ n, which
/// is the case of the θ ≤ 0 Nitsche kernels: their non-symmetric part
/// lives in the rows (and, for θ ≠ 0, the columns) of the contact trace,
/// k ~ √n.
///
/// The identity loses accuracy when S is much worse conditioned than A.
/// The set-up therefore solves A x = A v for a rough v and measures the
/// forward error; if it exceeds [`LOW_RANK_CHECK_TOL`], every solve adds
/// iterative refinement, and if that does not bring it under the
/// tolerance either, the factorisation is refused.
pub struct LowRankCorrected {
    s: SparseColMat<usize, f64>,
    u: SparseColMat<usize, f64>,
    v: SparseColMat<usize, f64>,
    llt: Llt<usize, f64>,
    /// S⁻¹ U, n × k.
    z: faer::Mat<f64>,
    capacitance: nalgebra::LU<f64, nalgebra::Dyn, nalgebra::Dyn>,
    /// Refinement steps per solve (0 when the set-up check passed without).
    refine: usize,
}

/// The largest relative forward error ‖x − v‖/‖v‖ the set-up check of a
/// [`LowRankCorrected`] factorisation accepts.
pub const LOW_RANK_CHECK_TOL: f64 = 1e-8;

/// Refinement steps per solve when the plain Woodbury solve fails the check.
const LOW_RANK_REFINE: usize = 2;

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

impl LowRankCorrected {
    /// A x = S x + U (Vᵀ x).
    pub fn apply(&self, x: &[f64]) -> Vec<f64> {
        let mut y = mul(&self.s, x);
        for (yi, ui) in y.iter_mut().zip(mul(&self.u, &mul_transpose(&self.v, x))) {
            *yi += ui;
        }
        y
    }

    /// Rank of the correction, k.
    pub fn rank(&self) -> usize {
        self.u.ncols()
    }

    /// Whether solves refine iteratively (the plain identity failed the check).
    pub fn refines(&self) -> bool {
        self.refine > 0
    }

    fn woodbury(&self, x: &mut [f64]) {
        self.llt
            .solve_in_place(faer::ColMut::from_slice_mut(x).as_mat_mut());
        if self.rank() == 0 {
            return; // A = S
        }
        let vy = nalgebra::DVector::from_vec(mul_transpose(&self.v, x));
        let t = self
            .capacitance
            .solve(&vy)
            .expect("the capacitance LU was checked invertible at set-up");
        for (c, tc) in t.iter().enumerate() {
            for (xi, zi) in x.iter_mut().zip(self.z.col_as_slice(c)) {
                *xi -= tc * zi;
            }
        }
    }

    fn solve_in_place(&self, x: &mut [f64]) {
        let b = (self.refine > 0).then(|| x.to_vec());
        self.woodbury(x);
        if let Some(b) = b {
            for _ in 0..self.refine {
                let mut d: Vec<f64> = b.iter().zip(self.apply(x)).map(|(p, q)| p - q).collect();
                self.woodbury(&mut d);
                for (xi, di) in x.iter_mut().zip(&d) {
                    *xi += di;
                }
            }
        }
    }

    /// ‖x − v‖/‖v‖ for the solve of A x = A v with a fixed rough v, which
    /// excites every mode.
    fn check(&self) -> f64 {
        let mut seed = 0x9e37_79b9_7f4a_7c15_u64;
        let v: Vec<f64> = (0..self.s.nrows())
            .map(|_| {
                seed ^= seed << 13;
                seed ^= seed >> 7;
                seed ^= seed << 17;
                (seed >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect();
        let mut x = self.apply(&v);
        self.solve_in_place(&mut x);
        let err: Vec<f64> = x.iter().zip(&v).map(|(a, c)| a - c).collect();
        let e = norm2(&err) / norm2(&v).max(f64::MIN_POSITIVE);
        if e.is_finite() {
            e
        } else {
            f64::INFINITY
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
        let mut z = faer::Mat::<f64>::zeros(n, k);
        let su = u.symbolic();
        for c in 0..k {
            for p in su.col_ptr()[c]..su.col_ptr()[c + 1] {
                z[(su.row_idx()[p], c)] = u.val()[p];
            }
        }
        llt.solve_in_place(z.as_mut());
        // I + Vᵀ Z: row c is column c of V against Z
        let mut cap = nalgebra::DMatrix::<f64>::identity(k, k);
        let sv = v.symbolic();
        for c in 0..k {
            for p in sv.col_ptr()[c]..sv.col_ptr()[c + 1] {
                let (i, vi) = (sv.row_idx()[p], v.val()[p]);
                for d in 0..k {
                    cap[(c, d)] += vi * z[(i, d)];
                }
            }
        }
        let capacitance = cap.lu();
        if !capacitance.is_invertible() {
            return Err(FactorError::LowRankInaccurate(
                "the low-rank capacitance matrix I + Vᵀ S⁻¹ U is singular".into(),
            ));
        }
        let mut f = LowRankCorrected {
            s: s.clone(),
            u: u.clone(),
            v: v.clone(),
            llt,
            z,
            capacitance,
            refine: 0,
        };
        let plain = f.check();
        if plain <= LOW_RANK_CHECK_TOL {
            return Ok(Factor::LowRank(Box::new(f)));
        }
        f.refine = LOW_RANK_REFINE;
        let refined = f.check();
        if refined <= LOW_RANK_CHECK_TOL {
            return Ok(Factor::LowRank(Box::new(f)));
        }
        Err(FactorError::LowRankInaccurate(format!(
            "the low-rank solve is inaccurate: forward error {plain:.1e} on the set-up check, {refined:.1e} with refinement (S nearly singular?)"
        )))
    }
}

fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;
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
