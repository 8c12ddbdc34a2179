//! The book's build system, kept out of the library: what the chapter
//! programs (`examples/`) share, where they write (`book/src/generated/`),
//! the facts the chapters quote, the registry that `reproduce` runs, and
//! the chapters themselves as doc-tests.
//!
//! The library `iga_contact` knows nothing of the book: it compiles without
//! the book's files, picks no allocator for the programs that link it, and
//! installs no signal handler unless asked. This crate does all three for
//! the chapter programs.

#[cfg(feature = "allocator")]
mod allocator;
#[doc(hidden)]
pub mod book;
pub mod canary;
pub mod chapter;
pub mod facts;
pub mod figures;
pub mod timing;

// The set-ups and measures that several chapter programs (and the tests
// of their results) share.
pub mod getfem;
pub mod harness;
pub mod hertz;
pub mod lame;
pub mod penalty;
pub mod solvers;
pub mod taylor;

pub use chapter::{cli_binary, generated_root, source_root, Chapter, Cost, Program, PROGRAMS};
pub use facts::Facts;
pub use solvers::Solver;

use iga_contact::scene::Scene;
use iga_contact::Result;
use std::path::PathBuf;

/// The facts the program of `chapter` wrote (`book/src/generated/<chapter>/facts.txt`),
/// for the doc-tests that check what the chapter's prose says about them.
pub fn facts(chapter: &str) -> Result<Facts> {
    Facts::load(generated_root().join(chapter))
}

/// The path of a scene file shipped in `data/scenes/` of the source tree
/// (`""` for the folder itself).
pub fn shipped_path(file: &str) -> PathBuf {
    source_root().join("data/scenes").join(file)
}

/// A scene file shipped in `data/scenes/`, loaded: the paper's set-ups are
/// these files, and the chapter programs start from them.
pub fn shipped(file: &str) -> Result<Scene> {
    Scene::load(shipped_path(file))
}
