//! Which storage could not be allocated, as data.

use faer::dyn_stack::mem::AllocError;
use faer::sparse::{CreationError, FaerError};
use std::collections::TryReserveError;

/// The storage `what` (the Cholesky factor, a kernel's pattern, ...) could
/// not be allocated, and the allocator's refusal.
#[derive(Clone, Debug, PartialEq, Eq, thiserror::Error)]
#[error("{what}: {refusal}")]
pub struct OutOfMemory {
    pub what: &'static str,
    pub refusal: Refusal,
}

/// An allocator's refusal, as the library that allocated reports it.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Refusal {
    Faer(FaerError),
    Creation(CreationError),
    Reserve(TryReserveError),
    Workspace(AllocError),
}

// faer renders its errors by their Debug form (a type name): say what happened.
impl std::fmt::Display for Refusal {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Refusal::Faer(e) => write!(f, "{}", super::faer_text::faer(e)),
            Refusal::Creation(e) => write!(f, "{}", super::faer_text::creation(e)),
            Refusal::Reserve(e) => write!(f, "{e}"),
            Refusal::Workspace(_) => write!(f, "the solver's workspace could not be allocated"),
        }
    }
}

impl From<FaerError> for Refusal {
    fn from(e: FaerError) -> Self {
        Refusal::Faer(e)
    }
}

impl From<CreationError> for Refusal {
    fn from(e: CreationError) -> Self {
        Refusal::Creation(e)
    }
}

impl From<TryReserveError> for Refusal {
    fn from(e: TryReserveError) -> Self {
        Refusal::Reserve(e)
    }
}

impl From<AllocError> for Refusal {
    fn from(e: AllocError) -> Self {
        Refusal::Workspace(e)
    }
}
