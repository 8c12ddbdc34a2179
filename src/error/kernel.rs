//! Why a kernel cannot be solved, as data: it is singular, or it would be
//! if the solve went on (the body floats).

use faer::linalg::cholesky::llt::factor::LltError;
use faer::sparse::{CreationError, FaerError};

/// Why a linear system of the solve is singular, outside the sparse
/// factorisations (which fail with a [`FactorError`](super::FactorError)):
/// each variant names the module that raises it.
#[derive(Clone, Debug, thiserror::Error)]
pub enum SingularError {
    /// A triplet summed into an `n` × `n` matrix lies outside it
    /// ([`crate::linsolve::Pattern`]).
    #[error("cannot build the sparsity pattern: entry ({row}, {col}) outside {n} × {n}")]
    OutsideMatrix { row: usize, col: usize, n: usize },
    /// A contact point's entry is not in the pattern the kernels share
    /// ([`crate::problem`]).
    #[error("entry ({row}, {col}) outside the kernels' pattern")]
    OutsidePattern { row: usize, col: usize },
    /// faer refused the sparse factors of the low-rank correction
    /// ([`crate::problem`]).
    #[error("cannot build the low-rank factors: {}", super::faer_text::creation(.0))]
    LowRankFactors(CreationError),
    /// A solve with a factor gave non-finite values
    /// ([`crate::linsolve::Factor`], the dense trace kernel).
    #[error("the solve produced non-finite values")]
    NonFiniteSolution,
    /// The step `what` (the ordering, the symbolic analysis) of the
    /// condensation onto the contact layer failed ([`crate::condense`]).
    #[error("{what}: {}", super::faer_text::faer(error))]
    Condensation {
        what: &'static str,
        error: FaerError,
    },
    /// The bulk stiffness plus the penalty on the whole contact layer has
    /// no Cholesky factor ([`crate::condense`]).
    #[error("the bulk stiffness plus the penalty over the whole contact boundary is not positive definite ({}): contact everywhere would not hold the bodies", super::faer_text::llt(.0))]
    BulkNotPositiveDefinite(LltError),
    /// The contact layer has `dofs` DOFs, above the `max` that a dense
    /// trace kernel may have (the solver's trace problem).
    #[error("the contact layer has {dofs} DOFs, more than the {max} a dense trace kernel allows")]
    LayerTooLarge { dofs: usize, max: usize },
    /// A pivot of the dense LU of the trace kernel vanishes against the
    /// largest: the moduli of the pivots range from `smallest` to
    /// `largest`.
    #[error("the trace kernel is singular (pivots from {smallest:.2e} to {largest:.2e})")]
    TraceKernel { smallest: f64, largest: f64 },
}

/// The load cannot be balanced along a rigid mode that no support holds:
/// [`floating_modes`](crate::problem::Problem::floating_modes)`[mode]`,
/// along which the load does the work `load_work`, and along which none of
/// the `contact_points` contact points can push back.
#[derive(Clone, Debug, PartialEq, thiserror::Error)]
#[error("the load pulls a body away from every contact point and no support holds it, so no equilibrium exists")]
pub struct FloatingBody {
    pub mode: usize,
    pub load_work: f64,
    pub contact_points: usize,
}
