//! `iga-contact`: run scene files and check them. (The book's chapter
//! programs are run by the companion's `reproduce`, not by this binary.)
//!
//! Exit codes: 0 success, 1 a failure while computing or writing (solver
//! not converged, singular kernel, i/o, out of memory, ...), 2 invalid
//! input (a scene that does not parse or validate, is ill-posed or too
//! large for the memory budget, an output directory that cannot take the
//! outputs, bad command-line usage), 130 / 143 interrupted
//! by SIGINT / SIGTERM (no output written). Every error is one line on
//! stderr starting with `error:`, command-line usage included. A run or check whose answer may be
//! doubtful (a penalty outside its stable range, the stiffer body as slave,
//! locking, a contact zone cut off by the end of its slave side, ...)
//! succeeds, with one `warning:` line on stderr per cause.

use clap::{Parser, Subcommand};
use iga_contact::report::atomic;
use iga_contact::resources::{parse_size, Budget};
use iga_contact::scene::Scene;
use iga_contact::solver::Warning;
use iga_contact::timing::Stopwatch;
use iga_contact::{Error, ErrorKind};
use std::path::{Path, PathBuf};
use std::process::ExitCode;

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
        /// 8G, 512M) [default: 80% of the available memory (MemAvailable), or 80% of ulimit -v].
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
                e.kind(),
                ErrorKind::NotConverged | ErrorKind::SingularKernel | ErrorKind::FloatingBody
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
        format!("a command is required (usage: {usage}; commands: run, check; see --help)")
    } else if e.kind() == ErrorKind::InvalidSubcommand
        && std::env::args().nth(1).as_deref() == Some("reproduce")
    {
        // Earlier versions had this command; the book's programs moved to
        // the companion crate, so say where rather than only refusing.
        "unrecognized subcommand 'reproduce': the book's results are regenerated by \
         `cargo run --release --bin reproduce` from the repository's root"
            .to_string()
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

/// The global allocator of this binary (feature `allocator`, on by
/// default); the library declares none, so a program built on it keeps its
/// own, and the chapter programs get theirs from the book's companion crate.
///
/// Two reasons. Speed: the whole run still pays for the allocator. The
/// per-point vectors that made glibc's malloc twice as slow in assembly
/// are gone (`space::ElementValues`, reused per thread), so assembly alone
/// now gains little: the CSC stiffness of Hertz p = 2 took 0.33–0.38 s
/// with mimalloc against 0.34–0.36 s with the system allocator at 256²,
/// and 1.16–1.37 s against 1.35–1.44 s at 512² (two medians of five runs
/// each of `examples/assembly_bench.rs -- buffers 5 256 512`, 2026-12-06,
/// two cores; in the same runs the reused buffers made the element matrices
/// 1.01–1.24× faster than buffers made per element). But the whole
/// `iga-contact run` of Hertz p = 2 on 256² (summary only) took 2.66–2.95 s
/// with mimalloc against 3.35–3.41 s with the system allocator (three
/// alternating runs each, the same day), at 9 % more peak memory. Safety: a failed allocation ends the process with one `error:`
/// line and exit code 1 instead of Rust's abort.
#[cfg(feature = "allocator")]
mod allocator {
    use std::alloc::{GlobalAlloc, Layout};
    use std::io::Write;

    /// The allocator the guard forwards to.
    static INNER: mimalloc::MiMalloc = mimalloc::MiMalloc;

    /// The allocator, except that a failed allocation ends the process
    /// with one `error:` line and exit code 1 instead of Rust's abort (SIGABRT,
    /// "memory allocation of … bytes failed"). The resource estimate refuses
    /// runs that would not fit before they start; this is the last line of
    /// defence when the estimate is exceeded (another process took the memory,
    /// a `ulimit -v` tighter than the budget).
    struct Guarded;

    // SAFETY: every call is forwarded to the inner allocator unchanged; only
    // a null result is intercepted, and then the process ends.
    unsafe impl GlobalAlloc for Guarded {
        unsafe fn alloc(&self, layout: Layout) -> *mut u8 {
            let p = INNER.alloc(layout);
            if p.is_null() {
                out_of_memory(layout.size());
            }
            p
        }

        unsafe fn alloc_zeroed(&self, layout: Layout) -> *mut u8 {
            let p = INNER.alloc_zeroed(layout);
            if p.is_null() {
                out_of_memory(layout.size());
            }
            p
        }

        unsafe fn realloc(&self, ptr: *mut u8, layout: Layout, new_size: usize) -> *mut u8 {
            let p = INNER.realloc(ptr, layout, new_size);
            if p.is_null() {
                out_of_memory(new_size);
            }
            p
        }

        unsafe fn dealloc(&self, ptr: *mut u8, layout: Layout) {
            INNER.dealloc(ptr, layout)
        }
    }

    /// Reports a failed allocation and exits, allocating nothing: the message
    /// is formatted into a stack buffer and written with `write(2)`.
    fn out_of_memory(size: usize) -> ! {
        let mut buf = [0u8; 320];
        let mut cur = std::io::Cursor::new(&mut buf[..]);
        let _ = writeln!(
            cur,
            "error: out of memory: allocating {size} bytes failed; the run needs more memory than is \
             available (lower --max-memory to have such runs refused before they start)"
        );
        let n = cur.position() as usize;
        // SAFETY: writes n initialised bytes of `buf` to stderr, then exits
        // without running destructors or allocating.
        unsafe {
            libc::write(2, buf.as_ptr().cast(), n);
            libc::_exit(1)
        }
    }

    #[global_allocator]
    static ALLOCATOR: Guarded = Guarded;
}
