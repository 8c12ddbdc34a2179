//! The studies behind the book's chapters. Each `run` regenerates one
//! chapter's tables (CSV + Markdown) and figures (SVG) from scratch in the
//! directory it is given; the chapter examples and `iga-contact reproduce`
//! are thin wrappers around them.
//!
//! Timing columns live in files of their own (`*timings*.csv`), so that two
//! runs produce identical tables everywhere else.

pub mod error_vs_time;
pub mod hertz;
pub mod iga_vs_fem;
pub mod solvers;
pub mod stability;
pub mod taylor;

use std::path::{Path, PathBuf};

/// `book/src/generated/<chapter>` below the current directory.
pub fn default_dir(chapter: &str) -> PathBuf {
    Path::new("book")
        .join("src")
        .join("generated")
        .join(chapter)
}

/// One chapter's study: its name (also its output directory) and how to run it.
pub struct Study {
    pub name: &'static str,
    pub run: fn(&Path) -> crate::Result<()>,
}

/// Every study, in the order of the book.
pub fn registry() -> Vec<Study> {
    vec![
        Study {
            name: "taylor",
            run: |p| taylor::run(p).map(|_| ()),
        },
        Study {
            name: "hertz",
            run: |p| hertz::run(p).map(|_| ()),
        },
        Study {
            name: "iga_vs_fem",
            run: iga_vs_fem::run,
        },
        Study {
            name: "error_vs_time",
            run: error_vs_time::run,
        },
        Study {
            name: "solvers",
            run: solvers::run,
        },
        Study {
            name: "stability",
            run: stability::run,
        },
    ]
}
