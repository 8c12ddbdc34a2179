//! SIGINT and SIGTERM: remove this process's staging directories and exit.

use super::set::{active, discard};
use crate::error::{Error, Result};

/// Installs handlers so that SIGINT and SIGTERM remove this process's
/// staging directories (after any commit in progress) and exit with
/// 128 + the signal number, printing one `error:` line. Call it once, at
/// the start of a program that writes output sets.
///
/// The work a clean exit needs (deleting directories) is not allowed in a
/// signal handler, so the `signal-hook` crate forwards the signals to a
/// thread that does it.
#[cfg(unix)]
pub fn install_signal_cleanup() -> Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    use std::io::Write;
    let mut signals =
        signal_hook::iterator::Signals::new([SIGINT, SIGTERM]).map_err(|e| Error::Io {
            path: "signal handlers".into(),
            source: e,
        })?;
    std::thread::Builder::new()
        .name("output-cleanup".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                let registry = active();
                for (staging, lock) in registry.iter() {
                    discard(staging, lock);
                }
                let name = if sig == SIGINT { "SIGINT" } else { "SIGTERM" };
                // Holding stderr until the exit keeps the main thread from
                // printing a warning after the error line: the error is the
                // run's last word.
                let mut err = std::io::stderr().lock();
                let _ = writeln!(err, "error: interrupted by {name}; no output was written");
                std::process::exit(128 + sig);
            }
        })
        .map_err(|e| Error::Io {
            path: "signal handler thread".into(),
            source: e,
        })?;
    Ok(())
}

#[cfg(not(unix))]
pub fn install_signal_cleanup() -> Result<()> {
    Ok(())
}
