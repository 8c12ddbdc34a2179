//! [`FactorError`]s from faer's errors: which of faer's refusals means
//! what for the matrix.

use crate::error::FactorError;
use faer::sparse::linalg::{LltError, LuError};
use faer::sparse::FaerError;

impl FactorError {
    /// The failure of step `what` (a symbolic analysis, say) that faer
    /// reports as a generic error: out of memory, or an index overflow.
    pub fn of_faer(what: &'static str, e: FaerError) -> Self {
        match e {
            FaerError::OutOfMemory => FactorError::OutOfMemory { what },
            error => FactorError::Faer { what, error },
        }
    }

    /// The failure of the sparse Cholesky factorisation `what`.
    pub fn of_llt(what: &'static str, e: LltError) -> Self {
        match e {
            LltError::Numeric(
                faer::linalg::cholesky::llt::factor::LltError::NonPositivePivot { index },
            ) => FactorError::NotPositiveDefinite { what, pivot: index },
            LltError::Generic(g) => Self::of_faer(what, g),
        }
    }

    /// The failure of the sparse LU factorisation `what`.
    pub fn of_lu(what: &'static str, e: LuError) -> Self {
        match e {
            LuError::SymbolicSingular { index } => FactorError::SymbolicSingular { what, index },
            LuError::Generic(g) => Self::of_faer(what, g),
        }
    }
}
