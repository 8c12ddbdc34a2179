//! `iga-contact`: run scene files, check them, and reproduce the book.
//!
//! Exit codes: 0 success, 1 a failure while computing or writing (solver
//! not converged, singular kernel, i/o, ...), 2 invalid input (a scene that
//! does not parse or validate, an unknown study, bad command-line usage).
//! Every error is one line on stderr starting with `error:`.

use clap::{Parser, Subcommand};
use iga_contact::report::chapter::PROGRAMS;
use iga_contact::scene::Scene;
use iga_contact::Error;
use std::path::{Path, PathBuf};
use std::process::ExitCode;
use std::time::Instant;

/// Isogeometric frictionless contact with Nitsche's method and BFGS
/// (a companion to Hu 2021).
#[derive(Parser, Debug)]
#[command(name = "iga-contact", version, about)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand, Debug)]
enum Command {
    /// Solve a scene and write the outputs it asks for.
    Run {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Output directory [default: out/<scene file stem>].
        #[arg(long)]
        out: Option<PathBuf>,
    },
    /// Parse, validate and build a scene without solving it.
    Check {
        /// The scene file (TOML).
        scene: PathBuf,
    },
    /// Regenerate the book's tables and figures: run every chapter program
    /// (`cargo run --release --example NAME` in this source tree).
    Reproduce {
        /// Run only the chapter program of this name.
        #[arg(long)]
        only: Option<String>,
    },
}

/// A failure and the exit code it maps to.
struct Failure {
    message: String,
    code: u8,
}

impl Failure {
    fn from_error(context: Option<&Path>, e: &Error) -> Self {
        let code = match e {
            Error::InvalidInput { .. } => 2,
            _ => 1,
        };
        let message = match context {
            Some(p) => format!("{}: {e}", p.display()),
            None => e.to_string(),
        };
        Failure { message, code }
    }
}

/// Keeps the one-line promise even if a message carries line breaks.
fn one_line(s: &str) -> String {
    s.split_whitespace().collect::<Vec<_>>().join(" ")
}

fn run(scene_path: &Path, out: Option<PathBuf>) -> Result<(), Failure> {
    let fail = |e: Error| Failure::from_error(Some(scene_path), &e);
    let scene = Scene::load(scene_path).map_err(fail)?;
    let out = out.unwrap_or_else(|| {
        let stem = scene_path
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        Path::new("out").join(stem)
    });
    let report = scene.run(&out).map_err(fail)?;
    let place = if report.files.is_empty() {
        String::new()
    } else {
        format!(" to {}", out.display())
    };
    println!("{}: {report}{place}", scene_path.display());
    Ok(())
}

fn check(scene_path: &Path) -> Result<(), Failure> {
    let fail = |e: Error| Failure::from_error(Some(scene_path), &e);
    let scene = Scene::load(scene_path).map_err(fail)?;
    let problem = scene.build().map_err(fail)?;
    println!(
        "{}: ok ({} bodies, {} free DOFs, {} contact points)",
        scene_path.display(),
        problem.bodies.len(),
        problem.n(),
        problem.points.len()
    );
    Ok(())
}

fn reproduce(only: Option<String>) -> Result<(), Failure> {
    let mut all: Vec<_> = PROGRAMS.to_vec();
    if let Some(name) = &only {
        let names: Vec<&str> = all.iter().map(|p| p.example).collect();
        if !names.contains(&name.as_str()) {
            let e = Error::invalid(
                "--only",
                name,
                format!("no such chapter program (programs: {})", names.join(", ")),
            );
            return Err(Failure::from_error(None, &e));
        }
        all.retain(|p| p.example == name);
    }
    let manifest = Path::new(env!("CARGO_MANIFEST_DIR")).join("Cargo.toml");
    let cargo = std::env::var_os("CARGO").unwrap_or_else(|| "cargo".into());
    // One build of every example first, so that the progress below is the
    // programs' own running time.
    let status = std::process::Command::new(&cargo)
        .args(["build", "--release", "--examples", "--manifest-path"])
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
            .args(["run", "--quiet", "--release", "--manifest-path"])
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
    let cli = Cli::parse();
    // A panic is a bug, but the user still gets one `error:` line and exit
    // code 1 rather than a backtrace and 101.
    std::panic::set_hook(Box::new(|info| {
        let msg = info
            .payload()
            .downcast_ref::<&str>()
            .map(|s| s.to_string())
            .or_else(|| info.payload().downcast_ref::<String>().cloned())
            .unwrap_or_else(|| "unknown panic".into());
        let at = info
            .location()
            .map(|l| format!(" at {}:{}", l.file(), l.line()))
            .unwrap_or_default();
        eprintln!(
            "error: internal error (please report): {}{at}",
            one_line(&msg)
        );
    }));
    let outcome = std::panic::catch_unwind(|| match cli.command {
        Command::Run { scene, out } => run(&scene, out),
        Command::Check { scene } => check(&scene),
        Command::Reproduce { only } => reproduce(only),
    });
    match outcome {
        Ok(Ok(())) => ExitCode::SUCCESS,
        Ok(Err(f)) => {
            eprintln!("error: {}", one_line(&f.message));
            ExitCode::from(f.code)
        }
        Err(_) => ExitCode::from(1),
    }
}
