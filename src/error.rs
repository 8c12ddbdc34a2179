//! One error type for the whole crate.
//!
//! Every variant says *what* went wrong in words a user can act on: invalid
//! input names the field path and the offending value, a solver failure
//! carries its full iteration history. The failures of a layer are typed
//! data of their own ([`GeometryError`], [`FactorError`], [`SingularError`],
//! [`OutOfMemory`], [`FloatingBody`], [`Diagnosis`]) that the crate error only wraps: the
//! message is rendered once, by `Display`, where the error is shown.
//!
//! They live here, below every layer that raises them, so that the crate
//! error can name them without depending on a layer above it.

mod diagnosis;
mod factor;
mod faer_text;
mod geometry;
mod kernel;
mod memory;

pub use diagnosis::{Diagnosis, Finding, Halt};
pub use factor::FactorError;
pub use geometry::{ContactPart, GeometryError};
pub use kernel::{FloatingBody, SingularError};
pub use memory::{OutOfMemory, Refusal};

use crate::history::History;

/// Errors raised anywhere in the pipeline geometry → space → assembly →
/// contact → solver → report.
#[derive(Debug, thiserror::Error)]
pub enum Error {
    /// A user-provided value is out of its admissible range.
    #[error("invalid input: `{field}` = {value}: {reason}")]
    InvalidInput {
        field: String,
        value: String,
        reason: String,
    },
    /// A geometric query failed (projection, degenerate Jacobian, ...).
    #[error("geometry: {0}")]
    Geometry(GeometryError),
    /// A sparse factorisation failed. Running out of memory is kind
    /// [`ErrorKind::OutOfMemory`] and says so; every other failure is a
    /// singular kernel, which is how the tables of failures tag it.
    #[error("{}: {}", if .0.is_out_of_memory() { "out of memory" } else { "singular kernel" }, .0)]
    Factor(FactorError),
    /// A linear system could not be built or solved.
    #[error("singular kernel: {0}")]
    Singular(SingularError),
    /// A factorisation or kernel could not allocate its storage: the
    /// problem is too large for the memory left.
    #[error("out of memory: {0}")]
    OutOfMemory(OutOfMemory),
    /// The load pulls a body along a rigid mode that neither a support nor
    /// contact can hold.
    #[error("active set empty: the body floats ({0})")]
    Floating(FloatingBody),
    /// The nonlinear iteration stopped without meeting its tolerances.
    // the count first: the reason ends with the diagnosis, whose last part
    // (a count of failed curvature conditions, say) must not read as if it
    // were what happened after that many iterations
    #[error("not converged after {} iteration{} (last relative residual {:.3e}): {diagnosis}", history.len(), if history.len() == 1 { "" } else { "s" }, history.last_relative_residual())]
    NotConverged {
        diagnosis: Diagnosis,
        history: History,
    },
    /// The output location cannot take the outputs (a file where a
    /// directory should be, no permission, foreign content): found before
    /// any work is done.
    #[error("output directory `{path}` {reason}")]
    Output { path: String, reason: String },
    /// File output failed.
    #[error("i/o on `{path}`: {source}")]
    Io {
        path: String,
        #[source]
        source: std::io::Error,
    },
}

impl Error {
    /// Shorthand for [`Error::InvalidInput`].
    pub fn invalid(
        field: impl Into<String>,
        value: impl std::fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Error::InvalidInput {
            field: field.into(),
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// Shorthand for [`Error::OutOfMemory`]: the storage `what` could not
    /// be allocated.
    pub fn out_of_memory(what: &'static str, refusal: impl Into<Refusal>) -> Self {
        Error::OutOfMemory(OutOfMemory {
            what,
            refusal: refusal.into(),
        })
    }

    /// A [`Error::Geometry`] with the context `f` adds (the body, the
    /// contact pair it happened on); any other error unchanged.
    pub fn map_geometry(self, f: impl FnOnce(GeometryError) -> GeometryError) -> Self {
        match self {
            Error::Geometry(g) => Error::Geometry(f(g)),
            other => other,
        }
    }

    /// What kind of failure this is, for a program that acts on it (a
    /// study that tabulates failures, a test that expects one).
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::InvalidInput { .. } => ErrorKind::InvalidInput,
            Error::Geometry(_) => ErrorKind::Geometry,
            Error::Factor(e) if e.is_out_of_memory() => ErrorKind::OutOfMemory,
            Error::Factor(_) => ErrorKind::SingularKernel,
            Error::Singular(_) => ErrorKind::SingularKernel,
            Error::OutOfMemory(_) => ErrorKind::OutOfMemory,
            Error::Floating(_) => ErrorKind::FloatingBody,
            Error::NotConverged { .. } => ErrorKind::NotConverged,
            Error::Output { .. } => ErrorKind::Output,
            Error::Io { .. } => ErrorKind::Io,
        }
    }
}

/// The variant of an [`Error`] without its data: comparable, copyable, and
/// written into tables by its [`tag`](ErrorKind::tag).
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub enum ErrorKind {
    InvalidInput,
    Geometry,
    SingularKernel,
    OutOfMemory,
    FloatingBody,
    NotConverged,
    Output,
    Io,
}

impl ErrorKind {
    /// The snake-case tag of the kind, as the stability atlas's
    /// `error_kind` column holds it.
    pub fn tag(self) -> &'static str {
        match self {
            ErrorKind::InvalidInput => "invalid_input",
            ErrorKind::Geometry => "geometry",
            ErrorKind::SingularKernel => "singular_kernel",
            ErrorKind::OutOfMemory => "out_of_memory",
            ErrorKind::FloatingBody => "floating_body",
            ErrorKind::NotConverged => "not_converged",
            ErrorKind::Output => "output",
            ErrorKind::Io => "io",
        }
    }
}

impl std::fmt::Display for ErrorKind {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.write_str(self.tag())
    }
}

impl From<GeometryError> for Error {
    fn from(e: GeometryError) -> Self {
        Error::Geometry(e)
    }
}

impl From<FactorError> for Error {
    fn from(e: FactorError) -> Self {
        Error::Factor(e)
    }
}

impl From<SingularError> for Error {
    fn from(e: SingularError) -> Self {
        Error::Singular(e)
    }
}

impl From<FloatingBody> for Error {
    fn from(e: FloatingBody) -> Self {
        Error::Floating(e)
    }
}

pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite, naming `field` otherwise.
pub fn finite(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "must be a finite number"))
    }
}
