//! Regenerates the Hertz chapter's tables and figures in
//! `book/src/generated/hertz/` and prints them.
//!
//! ```text
//! cargo run --release --example hertz            # timings on 8², 64², 256²
//! cargo run --release --example hertz -- 8 64    # timings on the meshes given
//! ```
//!
//! The 256² timing run (132 870 DOFs, the default and the paper's
//! full-step BFGS) takes about 25 s and peaks at about 3 GB; pass smaller
//! meshes on a smaller machine.

use iga_contact::studies::{default_dir, hertz};
use std::process::ExitCode;

fn main() -> ExitCode {
    let meshes: Result<Vec<usize>, _> = std::env::args().skip(1).map(|a| a.parse()).collect();
    let meshes = match meshes {
        Ok(m) if m.is_empty() => hertz::TIMING_ELEMENTS.to_vec(),
        Ok(m) => m,
        Err(e) => {
            eprintln!("hertz: the arguments are timing meshes (elements per direction): {e}");
            return ExitCode::FAILURE;
        }
    };
    let out = default_dir("hertz");
    match hertz::run_with(&out, &meshes) {
        Ok(summary) => {
            print!("{summary}");
            println!("written to {}", out.display());
            ExitCode::SUCCESS
        }
        Err(e) => {
            eprintln!("hertz: {e}");
            ExitCode::FAILURE
        }
    }
}
