//! faer's errors in words. faer renders its errors by their `Debug` form
//! (`IndexOverflow`, `OutOfBounds { row: 3, col: 9 }`), which names a type,
//! not what happened; the crate's messages say it instead.

use faer::linalg::cholesky::llt::factor::LltError;
use faer::sparse::{CreationError, FaerError};

/// What a generic faer error means for the matrix.
pub(crate) fn faer(e: &FaerError) -> &'static str {
    match e {
        FaerError::IndexOverflow => {
            "an index overflows faer's index type (the matrix is too large to index)"
        }
        FaerError::OutOfMemory => "the allocation failed",
        // faer's enum is non-exhaustive
        _ => "faer refused the operation",
    }
}

/// What a failed creation of a sparse matrix means.
pub(crate) fn creation(e: &CreationError) -> String {
    match e {
        CreationError::Generic(g) => faer(g).to_string(),
        CreationError::OutOfBounds { row, col } => {
            format!("entry ({row}, {col}) lies outside the matrix")
        }
    }
}

/// Where a dense Cholesky factorisation stopped.
pub(crate) fn llt(e: &LltError) -> String {
    match e {
        LltError::NonPositivePivot { index } => format!("pivot {index} is not positive"),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn no_message_is_a_type_name() {
        for text in [
            faer(&FaerError::IndexOverflow).to_string(),
            faer(&FaerError::OutOfMemory).to_string(),
            creation(&CreationError::OutOfBounds { row: 3, col: 9 }),
            creation(&CreationError::Generic(FaerError::IndexOverflow)),
            llt(&LltError::NonPositivePivot { index: 4 }),
        ] {
            assert!(
                text.contains(' ') && !text.contains("Overflow") && !text.contains('{'),
                "{text}"
            );
        }
    }
}
