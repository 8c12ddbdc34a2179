//! How a kernel (17)–(18) is factorised: once per problem through the
//! condensation (the default), or each assembled kernel on its own.
//!
//! The default ([`Factorisation::Auto`]) factorises once per problem: the
//! bulk stiffness plus the penalty term of the whole potential contact
//! boundary, A₀, by sparse Cholesky with the contact layer ordered last
//! ([`crate::condense`]). Every kernel, of every θ (θ = 1 included) and
//! every active set, is A₀ plus a matrix on the layer, so it costs one
//! dense factorisation of the layer's Schur complement plus that matrix
//! ([`super::trace`]).
//!
//! The two earlier ways factorise each assembled kernel on its own:
//! sparse LU, or — for θ ≤ 0 — Cholesky of its symmetric positive
//! definite part with a Sherman–Morrison–Woodbury correction of the trace
//! rows ([`Problem::kernel_split`], [`crate::linsolve::LowRankCorrected`]).

use super::history::Event;
use crate::error::Result;
use crate::linsolve::{Factor, FactorError, Factoriser, Method};
use crate::problem::{Kernel, Problem};
use serde::{Deserialize, Serialize};

/// How the solvers factorise their kernels.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Factorisation {
    /// Factorise once: Cholesky of A₀ with the contact layer last, then a
    /// dense factorisation of the layer's Schur complement per kernel.
    /// Falls back to [`Factorisation::LowRank`] when the layer is too
    /// large for dense kernels ([`super::trace::MAX_LAYER`]).
    #[default]
    Auto,
    /// Per kernel: Cholesky plus the low-rank trace correction where it
    /// applies (every point θ ≤ 0, the symmetric part positive definite,
    /// the set-up check passed), sparse LU otherwise.
    LowRank,
    /// Sparse LU of the assembled kernel, always.
    Lu,
}

/// Factorises the assembled full-space kernel `kind` of `problem` on its
/// own, reusing the symbolic analyses kept in `fac`: by LU for
/// [`Factorisation::Lu`], by the low-rank path otherwise (`Auto` has no
/// single-kernel form: it factorises A₀ once for a whole solve). A
/// low-rank factorisation that needed refinement, or was refused in
/// favour of LU, is logged in `events` ([`Event::KernelRefined`],
/// [`Event::KernelLuFallback`]); LU chosen because some θ > 0 is the
/// design, not an event.
pub fn factor_kernel(
    problem: &Problem,
    fac: &mut Factoriser,
    kind: Kernel,
    how: Factorisation,
    events: &mut Vec<Event>,
) -> Result<Factor> {
    if how != Factorisation::Lu {
        if let Some(split) = problem.kernel_split(kind)? {
            let low_rank = fac.factor_low_rank(&split.spd, &split.u, &split.v);
            if let Some(f) = low_rank_or_lu(low_rank, events)? {
                return Ok(f);
            }
        }
    }
    Ok(fac.factor(&problem.kernel(kind)?, Method::Lu)?)
}

/// What the low-rank path's outcome leaves to do: its factor (`Some`), LU
/// (`None`, logged as [`Event::KernelLuFallback`]) where the method rather
/// than the matrix failed ([`FactorError::lu_may_help`]: a non-positive
/// pivot of S, an inaccurate Woodbury solve), or its error, which LU cannot
/// mend (out of memory, a structurally singular or oversized matrix).
fn low_rank_or_lu(
    low_rank: std::result::Result<Factor, FactorError>,
    events: &mut Vec<Event>,
) -> std::result::Result<Option<Factor>, FactorError> {
    match low_rank {
        Ok(f) => {
            if matches!(&f, Factor::LowRank(l) if l.refines()) {
                events.push(Event::KernelRefined);
            }
            Ok(Some(f))
        }
        Err(e) if e.lu_may_help() => {
            events.push(Event::KernelLuFallback);
            Ok(None)
        }
        Err(e) => Err(e),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Only a failure of the method hands the kernel to LU: running out of
    /// memory, or a matrix LU cannot factorise either, is the solve's error
    /// and is logged as no fallback.
    #[test]
    fn lu_takes_over_from_a_non_positive_pivot_only() {
        let hard = [
            FactorError::OutOfMemory { what: "Cholesky" },
            FactorError::SymbolicSingular {
                what: "symbolic LU",
                index: 3,
            },
            FactorError::Faer {
                what: "symbolic Cholesky",
                error: faer::sparse::FaerError::IndexOverflow,
            },
        ];
        for e in hard {
            let mut events = Vec::new();
            let out = low_rank_or_lu(Err(e.clone()), &mut events);
            assert!(matches!(out, Err(ref got) if *got == e), "{e}: not for LU");
            assert!(events.is_empty(), "{e}: {events:?}");
        }
        let soft = [
            FactorError::NotPositiveDefinite {
                what: "Cholesky",
                pivot: 7,
            },
            FactorError::CapacitanceSingular,
            FactorError::LowRankInaccurate {
                plain: 1e-3,
                refined: 1e-5,
            },
        ];
        for e in soft {
            let mut events = Vec::new();
            let out = low_rank_or_lu(Err(e.clone()), &mut events);
            assert!(matches!(out, Ok(None)), "{e}: LU takes over");
            assert!(
                matches!(events[..], [Event::KernelLuFallback]),
                "{e}: {events:?}"
            );
        }
    }
}
