//! Output as one transaction: a run's files appear together or not at all.
//!
//! [`OutputSet`] stages every file of a run in a fresh directory beside the
//! target (`.NAME.staging-ID` next to `NAME`), then [`OutputSet::commit`]
//! swaps the staged directory and the target in one atomic step
//! (`renameat2(RENAME_EXCHANGE)` on Linux) and deletes the earlier set. At
//! every instant the target holds either the complete earlier set of files
//! or the complete new one:
//!
//! - a failure while staging (full disk, a producer's error) drops the
//!   staging directory; the target is untouched;
//! - SIGINT and SIGTERM, once [`install_signal_cleanup`] is called, remove
//!   the staging directories of the process and exit (130 / 143) — a commit
//!   in progress is finished first;
//! - a SIGKILL leaves a staging directory whose owner is dead; the next
//!   [`OutputSet::begin`] on the same target removes it (each staging
//!   directory is owned through a `flock` on a lock file beside it, which
//!   the kernel releases when its process dies);
//! - concurrent runs into one target each stage privately and commit by an
//!   exchange, so the target ends up holding one of the complete sets.
//!
//! A committed directory holds a manifest, [`MANIFEST`], listing its files.
//! Since a commit replaces the whole directory, an output set only takes
//! over a directory that is absent, empty, holds a manifest (an earlier
//! output set), or holds nothing but regular files whose names the set
//! declares (an earlier run of a version without manifests). Anything else
//! is refused before any work is done, naming the path and the reason.
//!
//! ```
//! use iga_contact::report::atomic::OutputSet;
//! let dir = std::env::temp_dir().join(format!("atomic-doc-{}", std::process::id()));
//! let mut set = OutputSet::begin(&dir)?;
//! set.stage("a.csv", b"x,y\n1,2\n")?;
//! set.stage("figures/b.svg", b"<svg/>")?;
//! let files = set.commit()?;
//! assert_eq!(files.len(), 2);
//! assert_eq!(std::fs::read(dir.join("a.csv")).unwrap(), b"x,y\n1,2\n");
//! # std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), iga_contact::Error>(())
//! ```
//!
//! [`write_atomic`] remains for single files (rename of a temporary sibling).

mod errors;
mod fsops;
mod listing;
mod protect;
mod set;
mod signals;
mod single;
mod target;

pub use listing::MANIFEST;
pub use listing::{read_manifest, snapshot, staging_entries};
pub use set::OutputSet;
pub use signals::install_signal_cleanup;
pub use single::{write_atomic, write_text};
