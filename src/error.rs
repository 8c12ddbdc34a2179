//! One error type for the whole crate.
//!
//! Every variant says *what* went wrong in words a user can act on: invalid
//! input names the field path and the offending value, a solver failure
//! carries its full iteration history.

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
    Geometry(String),
    /// A linear system could not be factorised.
    #[error("singular kernel: {0}")]
    Singular(String),
    /// A factorisation or kernel could not allocate its storage: the
    /// problem is too large for the memory left.
    #[error("out of memory: {0}")]
    OutOfMemory(String),
    /// Every potential contact point is open and the secant matrix lost the
    /// rigid-body support that contact provided.
    #[error("active set empty: the body floats ({0})")]
    Floating(String),
    /// The nonlinear iteration stopped without meeting its tolerances.
    #[error("{reason} after {} iterations (last relative residual {:.3e})", history.len(), history.last_relative_residual())]
    NotConverged { reason: String, history: History },
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

    /// What kind of failure this is, for a program that acts on it (a
    /// study that tabulates failures, a test that expects one).
    pub fn kind(&self) -> ErrorKind {
        match self {
            Error::InvalidInput { .. } => ErrorKind::InvalidInput,
            Error::Geometry(_) => ErrorKind::Geometry,
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

pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite, naming `field` otherwise.
pub fn finite(field: &str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(field, value, "must be a finite number"))
    }
}
