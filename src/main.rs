//! `iga-contact`: run scene files, check them, and reproduce the book.
//!
//! Exit codes: 0 success, 1 a failure while computing or writing (solver
//! not converged, singular kernel, i/o, out of memory, ...), 2 invalid
//! input (a scene that does not parse or validate, is ill-posed or too
//! large for the memory budget, an output directory that cannot take the
//! outputs, an unknown study, bad command-line usage), 130 / 143 interrupted
//! by SIGINT / SIGTERM (no output written). Every error is one line on
//! stderr starting with `error:`, command-line usage included. A run or check whose answer may be
//! doubtful (a penalty outside its stable range, the stiffer body as slave,
//! locking, a contact zone cut off by the end of its slave side, ...)
//! succeeds, with one `warning:` line on stderr per cause.

use clap::{Parser, Subcommand};
use iga_contact::report::atomic::{self, OutputSet};
use iga_contact::report::chapter::{generated_root, Cost, PROGRAMS};
use iga_contact::resources::{parse_size, Budget};
use iga_contact::scene::Scene;
use iga_contact::solver::Warning;
use iga_contact::timing::Stopwatch;
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
        /// Output directory [default: out/<scene file stem>]. Its content
        /// is replaced as a whole by the run's outputs.
        #[arg(long)]
        out: Option<PathBuf>,
        /// Refuse the run if its estimated peak memory exceeds this (e.g.
        /// 8G, 512M) [default: all of the available memory (MemAvailable), or 80% of ulimit -v].
        #[arg(long, value_name = "SIZE")]
        max_memory: Option<String>,
    },
    /// Validate a scene, estimate its memory, and check its geometry,
    /// contact points (element stiffnesses for C_T) and supports, without assembling the global system or solving.
    Check {
        /// The scene file (TOML).
        scene: PathBuf,
        /// Report a scene whose estimated peak memory exceeds this as too large.
        #[arg(long, value_name = "SIZE")]
        max_memory: Option<String>,
    },
    /// Regenerate the book's tables and figures: run every chapter program
    /// (`cargo run --release --example NAME` in this source tree).
    Reproduce {
        /// Run only the chapter program of this name.
        #[arg(long)]
        only: Option<String>,
        /// Run the heavy programs too (getfem_peer, solver_scaling,
        /// penalty_contrast, reliability, answers, memory_table: many minutes
        /// and gigabytes).
        #[arg(long)]
        all: bool,
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
            Error::InvalidInput { .. } | Error::Output { .. } => 2,
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

/// The memory budget: `--max-memory`, or the machine's default.
fn budget(max_memory: Option<String>) -> Result<Budget, Failure> {
    match max_memory {
        Some(s) => parse_size(&s)
            .map(Budget::explicit)
            .map_err(|e| Failure::from_error(None, &e)),
        None => Ok(Budget::from_machine()),
    }
}

fn run(scene_path: &Path, out: Option<PathBuf>, max_memory: Option<String>) -> Result<(), Failure> {
    // the run's clock starts before the scene is read: `[timing]` of
    // summary.toml charges the parse to its first phase
    let clock = Stopwatch::start();
    let fail = |e: Error| Failure::from_error(Some(scene_path), &e);
    let budget = budget(max_memory)?;
    let scene = Scene::load(scene_path).map_err(fail)?;
    let out = out.unwrap_or_else(|| {
        let stem = scene_path
            .file_stem()
            .map_or_else(|| "scene".into(), |s| s.to_string_lossy().into_owned());
        Path::new("out").join(stem)
    });
    let report = match scene.run_timed(&out, &budget, clock) {
        Ok(report) => report,
        Err(e) => {
            // A failed solve has no active set to judge; where the bodies
            // first touch tells whether a penalty below its bound may be why.
            if matches!(
                e,
                Error::NotConverged { .. } | Error::Singular(_) | Error::Floating(_)
            ) {
                if let Ok(c) = scene.check(&budget) {
                    warn(scene_path, &c.warnings);
                }
            }
            return Err(fail(e));
        }
    };
    warn(scene_path, &report.warnings);
    let place = if report.files.is_empty() {
        String::new()
    } else {
        format!(" to {}", out.display())
    };
    println!("{}: {report}{place}", scene_path.display());
    Ok(())
}

fn check(scene_path: &Path, max_memory: Option<String>) -> Result<(), Failure> {
    let fail = |e: Error| Failure::from_error(Some(scene_path), &e);
    let budget = budget(max_memory)?;
    let scene = Scene::load(scene_path).map_err(fail)?;
    let report = scene.check(&budget).map_err(fail)?;
    warn(scene_path, &report.warnings);
    println!("{}: {report}", scene_path.display());
    Ok(())
}

/// One `warning:` line on stderr per cause that makes the answer doubtful
/// ([`Warning`]): the run goes on (the solution may still be right), but
/// the user is told, with the one change that fixes it.
fn warn(scene_path: &Path, warnings: &[Warning]) {
    for w in warnings {
        eprintln!(
            "warning: {}: {}",
            scene_path.display(),
            one_line(&w.to_string())
        );
    }
}

fn reproduce(only: Option<String>, heavy: bool) -> Result<(), Failure> {
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
    } else if !heavy {
        all.retain(|p| p.cost == Cost::Quick);
    }
    // Fail fast: every chapter folder must be able to take a new set of
    // outputs before any program runs (each program then replaces its folder
    // as one set, or leaves it as it was).
    for program in &all {
        OutputSet::begin(generated_root().join(program.chapter))
            .map_err(|e| Failure::from_error(None, &e))?
            .abort();
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

/// clap's usage error as one line: its message, the argument it names
/// (clap puts lists such as the missing arguments on lines of their own),
/// its tip and the usage, joined; `--help` and `--version` print as usual.
fn parse_args() -> Result<Cli, ExitCode> {
    use clap::error::ErrorKind;
    let e = match Cli::try_parse() {
        Ok(cli) => return Ok(cli),
        Err(e) => e,
    };
    if matches!(e.kind(), ErrorKind::DisplayHelp | ErrorKind::DisplayVersion) {
        let _ = e.print();
        return Err(ExitCode::SUCCESS);
    }
    let text = e.render().to_string();
    let line = if e.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
        let usage = text
            .lines()
            .find_map(|l| l.trim().strip_prefix("Usage: "))
            .unwrap_or("iga-contact <COMMAND>");
        format!(
            "a command is required (usage: {usage}; commands: run, check, reproduce; see --help)"
        )
    } else {
        usage_line(&text)
    };
    eprintln!("error: {line}");
    Err(ExitCode::from(2))
}

/// Joins the parts of clap's rendered usage error into one line.
fn usage_line(text: &str) -> String {
    let mut parts: Vec<String> = Vec::new();
    let mut usage = None;
    for l in text.lines().map(str::trim).filter(|l| !l.is_empty()) {
        if let Some(u) = l.strip_prefix("Usage: ") {
            usage = Some(u.to_string());
        } else if l.starts_with("For more information") {
            continue;
        } else if let Some(m) = l.strip_prefix("error: ") {
            parts.push(m.to_string());
        } else if let Some(t) = l.strip_prefix("tip: ") {
            parts.push(format!("; {t}"));
        } else {
            // A continuation: the arguments a message lists.
            parts.push(format!(" {l}"));
        }
    }
    let mut line: String = parts.concat();
    if let Some(u) = usage {
        line.push_str(&format!(" (usage: {u}; see --help)"));
    } else {
        line.push_str(" (see --help)");
    }
    one_line(&line)
}

fn main() -> ExitCode {
    // First, so that the window in which SIGINT or SIGTERM still has its
    // default action is the process's start-up before `main` only, when
    // nothing is staged yet.
    if let Err(e) = atomic::install_signal_cleanup() {
        eprintln!("error: {}", one_line(&e.to_string()));
        return ExitCode::from(1);
    }
    let cli = match parse_args() {
        Ok(cli) => cli,
        Err(code) => return code,
    };
    // A file-size limit (`ulimit -f`) makes writes fail with EFBIG, reported
    // as an i/o error, instead of killing the process with SIGXFSZ.
    // SAFETY: setting a signal's disposition to "ignore" has no preconditions.
    unsafe {
        libc::signal(libc::SIGXFSZ, libc::SIG_IGN);
    }
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
        Command::Run {
            scene,
            out,
            max_memory,
        } => run(&scene, out, max_memory),
        Command::Check { scene, max_memory } => check(&scene, max_memory),
        Command::Reproduce { only, all } => reproduce(only, all),
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
