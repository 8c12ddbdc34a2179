//! `reproduce`: regenerate the book's tables and figures by running every
//! chapter program (`cargo run --release --example NAME` in the source tree
//! this binary was built from), each replacing its folder
//! `book/src/generated/<chapter>/` as one set of files.
//!
//! Exit codes: 0 success, 1 a program (or the build) failed, 2 invalid
//! usage or a chapter folder that cannot take new outputs.

use clap::Parser;
use companion::{generated_root, source_root, Cost, PROGRAMS};
use iga_contact::report::atomic::OutputSet;
use iga_contact::Error;
use std::process::ExitCode;
use std::time::Instant;

/// Regenerate the book's tables and figures: run the chapter programs.
#[derive(Parser, Debug)]
#[command(name = "reproduce", version, about)]
struct Args {
    /// Run only the chapter program of this name.
    #[arg(long)]
    only: Option<String>,
    /// Run the heavy programs too (getfem_peer, solver_scaling,
    /// penalty_contrast, reliability, answers, memory_table: many minutes
    /// and gigabytes).
    #[arg(long)]
    all: bool,
}

/// A failure and the exit code it maps to.
struct Failure {
    message: String,
    code: u8,
}

impl From<Error> for Failure {
    fn from(e: Error) -> Self {
        let code = match e {
            Error::InvalidInput { .. } | Error::Output { .. } => 2,
            _ => 1,
        };
        Failure {
            message: e.to_string(),
            code,
        }
    }
}

fn reproduce(only: Option<String>, heavy: bool) -> Result<(), Failure> {
    let mut all: Vec<_> = PROGRAMS.to_vec();
    if let Some(name) = &only {
        let names: Vec<&str> = all.iter().map(|p| p.example).collect();
        if !names.contains(&name.as_str()) {
            return Err(Error::invalid(
                "--only",
                name,
                format!("no such chapter program (programs: {})", names.join(", ")),
            )
            .into());
        }
        all.retain(|p| p.example == name);
    } else if !heavy {
        all.retain(|p| p.cost == Cost::Quick);
    }
    // Fail fast: every chapter folder must be able to take a new set of
    // outputs before any program runs (each program then replaces its folder
    // as one set, or leaves it as it was).
    for program in &all {
        OutputSet::begin(generated_root().join(program.chapter))?.abort();
    }
    let manifest = source_root().join("Cargo.toml");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    // The examples are the root package's; naming it keeps `cargo run` from
    // looking for them among the workspace's other members.
    let package = ["--package", "iga-contact", "--manifest-path"];
    // One build of every example first, so that the progress below is the
    // programs' own running time; and of the command line tool, which the
    // chapters that show or probe it run (`cli_binary` refuses a missing or
    // stale one, and `--examples` alone does not build it).
    let status = std::process::Command::new(&cargo)
        .args(["build", "--release", "--examples", "--bins"])
        .args(package)
        .arg(&manifest)
        .status();
    if !status.as_ref().is_ok_and(|s| s.success()) {
        return Err(Failure {
            message: format!("building the chapter programs failed ({status:?})"),
            code: 1,
        });
    }
    let n = all.len();
    let start = Instant::now();
    let mut failed = Vec::new();
    for (k, program) in all.iter().enumerate() {
        eprintln!(
            "[{}/{n}] {} → book/src/generated/{}/",
            k + 1,
            program.example,
            program.chapter
        );
        let t = Instant::now();
        let status = std::process::Command::new(&cargo)
            .args(["run", "--quiet", "--release"])
            .args(package)
            .arg(&manifest)
            .args(["--example", program.example])
            .status();
        match status {
            Ok(s) if s.success() => {
                eprintln!("      done in {:.1} s", t.elapsed().as_secs_f64())
            }
            other => {
                eprintln!(
                    "      FAILED after {:.1} s ({other:?})",
                    t.elapsed().as_secs_f64()
                );
                failed.push(program.example);
            }
        }
    }
    let total = start.elapsed().as_secs_f64();
    eprintln!(
        "reproduced {} of {n} chapters in {total:.1} s",
        n - failed.len()
    );
    if failed.is_empty() {
        Ok(())
    } else {
        Err(Failure {
            message: format!(
                "{} of {n} chapter programs failed: {}",
                failed.len(),
                failed.join(", ")
            ),
            code: 1,
        })
    }
}

fn main() -> ExitCode {
    let args = Args::parse();
    match reproduce(args.only, args.all) {
        Ok(()) => ExitCode::SUCCESS,
        Err(f) => {
            eprintln!(
                "error: {}",
                f.message.split_whitespace().collect::<Vec<_>>().join(" ")
            );
            ExitCode::from(f.code)
        }
    }
}
