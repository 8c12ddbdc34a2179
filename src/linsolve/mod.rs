//! Sparse linear algebra on top of faer: a fixed sparsity pattern whose
//! values are refilled cheaply, factorisations that reuse their symbolic
//! analysis, and the exact Cholesky-plus-low-rank solve of a matrix that
//! is symmetric positive definite up to a correction of low rank.

mod error;
mod factor;
mod low_rank;
mod pattern;

pub use crate::error::FactorError;
pub use factor::{Factor, Factoriser, Method};
pub use low_rank::{LowRankCorrected, LOW_RANK_CHECK_TOL};
pub use pattern::{mul, mul_transpose, Pattern};
