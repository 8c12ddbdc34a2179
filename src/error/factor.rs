//! Why a factorisation fails, as data.

use faer::sparse::FaerError;

/// Why a factorisation failed, as data: what decides whether another
/// method can take over ([`FactorError::lu_may_help`]) and what the user
/// is told (rendered once, by `Display`, when the crate error prints it).
///
/// The sparse factorisations of [`crate::linsolve`] raise it; it lives
/// with the crate error, which carries it, because that error sits below
/// every layer that fails.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
pub enum FactorError {
    /// Cholesky met a pivot that is not positive: the matrix is not
    /// symmetric positive definite (LU may still factorise it).
    #[error("{what}: pivot {pivot} is not positive, so the matrix is not positive definite")]
    NotPositiveDefinite { what: &'static str, pivot: usize },
    /// LU found no pivot in column `index`: the matrix is structurally
    /// singular.
    #[error("{what}: no pivot in column {index}")]
    SymbolicSingular { what: &'static str, index: usize },
    /// The factorisation could not allocate its storage.
    #[error("{what}: out of memory")]
    OutOfMemory { what: &'static str },
    /// Any other refusal of faer's (an index overflow: the matrix is too
    /// large for its index type).
    #[error("{what}: {}", super::faer_text::faer(error))]
    Faer {
        what: &'static str,
        error: FaerError,
    },
    /// The capacitance matrix I + Vᵀ S⁻¹ U of a
    /// [`LowRankCorrected`](crate::linsolve::LowRankCorrected)
    /// factorisation is singular: the Woodbury identity does not apply.
    #[error("the low-rank capacitance matrix I + Vᵀ S⁻¹ U is singular")]
    CapacitanceSingular,
    /// The set-up check of a
    /// [`LowRankCorrected`](crate::linsolve::LowRankCorrected)
    /// factorisation failed, plain and refined: its relative forward errors
    /// (S nearly singular).
    #[error("the low-rank solve is inaccurate: forward error {plain:.1e} on the set-up check, {refined:.1e} with refinement (S nearly singular?)")]
    LowRankInaccurate { plain: f64, refined: f64 },
}

impl FactorError {
    /// Whether LU may factorise the matrix where this method failed: a
    /// non-positive Cholesky pivot says the matrix is not positive
    /// definite, a failed Woodbury solve that the low-rank identity lost
    /// accuracy; neither says LU fails. Running out of memory, a
    /// structurally singular matrix or an index overflow would not be
    /// helped by LU, which needs more memory and the same pattern.
    pub fn lu_may_help(&self) -> bool {
        matches!(
            self,
            FactorError::NotPositiveDefinite { .. }
                | FactorError::CapacitanceSingular
                | FactorError::LowRankInaccurate { .. }
        )
    }

    /// Whether the factorisation ran out of memory (kind
    /// [`ErrorKind::OutOfMemory`](super::ErrorKind::OutOfMemory); every
    /// other failure is a singular kernel).
    pub fn is_out_of_memory(&self) -> bool {
        matches!(self, FactorError::OutOfMemory { .. })
    }
}
