//! The exact Cholesky-plus-low-rank solve of a matrix that is symmetric
//! positive definite up to a correction of low rank.

use super::pattern::{mul, mul_transpose};
use crate::error::FactorError;
use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::Llt;
use faer::sparse::SparseColMat;

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

impl LowRankCorrected {
    /// Completes the Cholesky factor `llt` of `s` (n × n) into the
    /// factorisation of S + U Vᵀ (`u`, `v` n × k), checked as the type's
    /// documentation says.
    pub(super) fn new(
        s: &SparseColMat<usize, f64>,
        u: &SparseColMat<usize, f64>,
        v: &SparseColMat<usize, f64>,
        llt: Llt<usize, f64>,
    ) -> Result<Self, FactorError> {
        let (n, k) = (s.nrows(), u.ncols());
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
            return Err(FactorError::CapacitanceSingular);
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
            return Ok(f);
        }
        f.refine = LOW_RANK_REFINE;
        let refined = f.check();
        if refined <= LOW_RANK_CHECK_TOL {
            return Ok(f);
        }
        Err(FactorError::LowRankInaccurate { plain, refined })
    }

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

    pub(super) fn solve_in_place(&self, x: &mut [f64]) {
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

fn norm2(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}
