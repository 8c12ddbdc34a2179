//! Regenerates the Taylor patch-test chapter's tables and figures in
//! `book/src/generated/taylor/` and prints the summary.
//!
//! ```text
//! cargo run --release --example taylor
//! ```

use iga_contact::studies::{default_dir, taylor};
use std::process::ExitCode;

fn main() -> ExitCode {
    let out = default_dir("taylor");
    match taylor::run(&out) {
        Ok(summary) => {
            print!("{summary}");
            println!("written to {}", out.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("taylor: {e}");
            ExitCode::FAILURE
        }
    }
}
