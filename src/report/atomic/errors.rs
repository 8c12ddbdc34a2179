//! The errors of the output steps, naming the path.

use crate::error::Error;
use std::path::Path;

pub(super) fn io_error(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.display().to_string(),
        source,
    }
}

pub(super) fn output_error(path: &Path, reason: impl Into<String>) -> Error {
    Error::Output {
        path: path.display().to_string(),
        reason: reason.into(),
    }
}
