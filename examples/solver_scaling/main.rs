//! The cost of a whole Hertz solve against one Cholesky factorisation of
//! the bulk, on growing meshes, in one run: in-process and through the
//! command line.
//!
//! Each case (degree p, N² elements) runs in one process of its own
//! ([`case::case`]), which measures, in this order:
//!
//! - **assembly**: `Scene::build` (discretisation, contact points, stiffness
//!   pattern and values, load);
//! - **one Cholesky**: faer's symbolic (AMD) plus numeric Cholesky of
//!   A₀ = K + Σ w γ jn jnᵀ, the bulk stiffness plus the contact penalty
//!   (the Hertz disk floats without contact, so K alone is singular): the
//!   **first** factorisation of the process, on memory it has never
//!   touched, and the **fastest** of the repeats, on memory the allocator
//!   kept; both also as processor time;
//! - the other route to the layer operator, for the record: blocked
//!   multi-right-hand-side solves with the factor of A₀ for the ℓ layer
//!   columns of A₀⁻¹ (route B), timed on one block of 64 columns and
//!   scaled to ℓ;
//! - the default solve (up to [`IN_PROCESS_UP_TO`]), split into
//!   **condensation** (Cholesky of A₀ with the contact layer last, the
//!   Schur complement S₀ and the condensed load), **iterations** (count
//!   and time, on the layer) and **back-substitution** (the body from the
//!   layer); **total** (assembly + solve), **total / one Cholesky**, and
//!   the peak resident memory (VmHWM, restarted before the solve);
//! - then, with all of that freed, **the command line**: `iga-contact run`
//!   of the same scene (the default solver, `summary = true`, the default
//!   memory budget) as a child of the case's process: its wall time from
//!   spawn to exit, its processor time and peak resident memory (`wait4`),
//!   and the `[timing]` table of its `summary.toml`, whose parts must add up
//!   to that wall time within [`PARTS_WITHIN`].
//!
//! Each phase is timed 7 times on the smallest mesh, 3 times up to 256²
//! and once above (the reference Cholesky at least twice): the median is
//! kept for the solve's phases and the command line, the fastest for the
//! reference Cholesky. A case above [`IN_PROCESS_UP_TO`] that cannot run
//! (killed, or refused by the memory budget) is recorded as not run, with
//! the reason, in the fact `p<p>_<N>_status`.
//!
//! Writes `book/src/generated/solver_scaling/` (the tables `scaling`, the
//! totals, `phases`, the split of the in-process time, and `cli`, the
//! split of the command-line run) and prints them.
//! `cargo run --release --example solver_scaling [-- p:N ...]` (default
//! 2:64 2:256 2:512 3:256 4:256 2:1024; builds on `cargo build --release`
//! for the binary; tens of minutes, about 15 GB at 1024²).
//!
//! The parts: the measurements of one case in its own process (`case.rs`,
//! with the process's clocks and memory in `process.rs`), the command-line
//! runs (`cli.rs`), the parent reading a case back (`measure.rs`), and the
//! tables and facts it writes (`tables.rs`, `facts.rs`).

mod case;
mod cli;
mod facts;
mod measure;
mod process;
mod tables;

use measure::{measure, NotRun};
use std::process::ExitCode;

const CASES: [(usize, usize); 6] = [(2, 64), (2, 256), (2, 512), (3, 256), (4, 256), (2, 1024)];
/// The largest mesh also solved in-process (above it, the command line only).
const IN_PROCESS_UP_TO: usize = 512;
/// How far the sum of the command line's `[timing]` parts may lie from its
/// wall time measured from outside (process start and exit included).
const PARTS_WITHIN: f64 = 0.05;
/// The smallest mesh (elements per direction) [`PARTS_WITHIN`] is
/// required of: on smaller ones what the summary cannot time — the start
/// of the process, the commit of the outputs (a rename and a sync) and the
/// exit, tenths of a second on a loaded machine — can be more than 5 % of
/// the run.
const PARTS_CHECKED_FROM: usize = 256;
/// Right-hand sides per block of route B.
const BLOCK: usize = 64;

/// The cost of a Hertz solve against one Cholesky factorisation, case by
/// case (or, with `--case p N`, one case in this process).
fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [mode, p, n] = args.as_slice() {
        if mode.starts_with("--") {
            return child(mode, p, n);
        }
    }
    let cases = match parse_cases(&args) {
        Ok(c) => c,
        Err(e) => {
            eprintln!("solver_scaling: the arguments are cases p:N ({e})");
            return ExitCode::FAILURE;
        }
    };
    let mut rows = Vec::new();
    // cases above IN_PROCESS_UP_TO that could not run, with the reason
    let mut not_run = Vec::new();
    for (p, n) in cases {
        eprintln!("p = {p}, {n}² …");
        match measure(p, n) {
            Ok(r) => rows.push(r),
            Err(reason) if n > IN_PROCESS_UP_TO => {
                eprintln!("solver_scaling: not run: {reason}");
                not_run.push(NotRun { p, n, reason });
            }
            Err(e) => {
                eprintln!("solver_scaling: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    if let Err(e) = facts::write_chapter(&rows, &not_run) {
        eprintln!("solver_scaling: {e}");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}

/// The process of one case, `--case p N`: prints its measurements, or
/// `failed` and the reason.
fn child(mode: &str, p: &str, n: &str) -> ExitCode {
    let (Ok(p), Ok(n)) = (p.parse(), n.parse()) else {
        eprintln!("solver_scaling: {mode} wants a degree and a mesh");
        return ExitCode::FAILURE;
    };
    let r = match mode {
        "--case" => case::case(p, n),
        _ => {
            eprintln!("solver_scaling: unknown mode {mode}");
            return ExitCode::FAILURE;
        }
    };
    match r {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            // the parent records the reason of a case not run
            println!("failed {e}");
            ExitCode::FAILURE
        }
    }
}

/// The cases of the command line, `p:N` each ([`CASES`] without any).
fn parse_cases(args: &[String]) -> Result<Vec<(usize, usize)>, String> {
    if args.is_empty() {
        return Ok(CASES.to_vec());
    }
    args.iter()
        .map(|a| {
            let (p, n) = a.split_once(':').ok_or(format!("`{a}` is not p:N"))?;
            Ok((
                p.parse().map_err(|e| format!("`{a}`: {e}"))?,
                n.parse().map_err(|e| format!("`{a}`: {e}"))?,
            ))
        })
        .collect()
}
