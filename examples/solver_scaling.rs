//! The cost of a whole Hertz solve against one Cholesky factorisation of
//! the bulk, on growing meshes, in one run: in-process and through the
//! command line.
//!
//! Each case (degree p, N² elements) runs in one process of its own
//! ([`case`]), which measures, in this order:
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

use companion::chapter::Chapter;
use companion::timing::median_time;
use iga_contact::linsolve::FactorError;
use iga_contact::post;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::{solve, SolverOptions};
use iga_contact::timing::PhaseTimes;
use std::path::Path;
use std::process::{Command, ExitCode, Stdio};
use std::time::Instant;

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

/// Peak resident memory of this process (GB), from /proc/self/status:
/// the largest resident set since the start or since the last
/// [`reset_peak`].
fn peak_gb() -> f64 {
    std::fs::read_to_string("/proc/self/status")
        .ok()
        .and_then(|s| {
            s.lines()
                .find(|l| l.starts_with("VmHWM:"))
                .and_then(|l| l.split_whitespace().nth(1)?.parse::<f64>().ok())
        })
        .map_or(f64::NAN, |kb| kb / 1024.0 / 1024.0)
}

extern "C" {
    /// mimalloc's own: frees the pages it keeps for reuse back to the
    /// system (the chapter programs' allocator is mimalloc, linked statically).
    fn mi_collect(force: bool);
}

/// Returns the memory freed so far to the system and restarts the peak
/// (VmHWM) at the present resident set, so that the next phase's peak is
/// its own: the Cholesky's factor, freed but kept by the allocator, would
/// otherwise count in the solve's peak. Writing 5 to
/// `/proc/self/clear_refs` resets VmHWM (Linux ≥ 4.0).
fn reset_peak() {
    // SAFETY: mi_collect takes no pointer and only releases free pages.
    unsafe { mi_collect(true) };
    let _ = std::fs::write("/proc/self/clear_refs", "5");
}

/// How often a phase is timed (the median is kept): on a shared machine one
/// sample of a phase varies by tens of per cent, and a phase of a few
/// hundredths of a second on the small mesh is mostly timer and scheduler
/// noise.
fn repeats(n: usize) -> usize {
    match n {
        0..=64 => 7,
        65..=256 => 3,
        _ => 1,
    }
}

/// Cholesky factorisations timed per case: the first (on memory the
/// process has never touched, as every factorisation of a command-line run)
/// and at least one more (on memory the allocator kept).
fn cholesky_repeats(n: usize) -> usize {
    repeats(n).max(2)
}

fn scene(p: usize, n: usize) -> iga_contact::Result<Scene> {
    companion::shipped("hertz.toml")?.refined("disk", RefineSpec::iga(p, [n, n]))
}

/// Processor time (user and system, all threads) of a `getrusage` result.
fn cpu_of(u: &libc::rusage) -> f64 {
    let t = |v: libc::timeval| v.tv_sec as f64 + v.tv_usec as f64 * 1e-6;
    t(u.ru_utime) + t(u.ru_stime)
}

/// Processor time this process has used so far (all threads), in seconds:
/// beside the wall time, a measure that other jobs on the machine disturb
/// far less.
fn cpu_seconds() -> f64 {
    // SAFETY: an all-zero rusage is a valid value of the plain C struct.
    let mut u: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: `u` is valid for writes for the duration of the call.
    unsafe { libc::getrusage(libc::RUSAGE_SELF, &mut u) };
    cpu_of(&u)
}

/// One Cholesky factorisation (faer's symbolic analysis with its AMD
/// order, then the numeric factor) of `a`, its wall time and its
/// processor time.
#[allow(clippy::type_complexity)]
fn one_cholesky(
    a: &faer::sparse::SparseColMat<usize, f64>,
) -> iga_contact::Result<(faer::sparse::linalg::solvers::Llt<usize, f64>, f64, f64)> {
    use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
    let (t, cpu) = (Instant::now(), cpu_seconds());
    let symbolic = SymbolicLlt::try_new(a.symbolic(), faer::Side::Lower)
        .map_err(|e| FactorError::of_faer("symbolic Cholesky", e))?;
    let factor = Llt::try_new_with_symbolic(symbolic, a.as_ref(), faer::Side::Lower)
        .map_err(|e| FactorError::of_llt("Cholesky", e))?;
    Ok((factor, t.elapsed().as_secs_f64(), cpu_seconds() - cpu))
}

/// Child: one case in one process — the build, the reference Cholesky of
/// A₀ (first and fastest), route B, the in-process solve (up to
/// [`IN_PROCESS_UP_TO`]), then, with everything freed, the command-line
/// runs as children of this process. Prints one `key value` per line.
fn case(p: usize, n: usize) -> Result<(), String> {
    let e = |e: iga_contact::Error| e.to_string();
    let mut out = Vec::<(String, f64)>::new();
    let scene = scene(p, n).map_err(e)?;
    let cpu = cpu_seconds();
    let timed = median_time(repeats(n), || scene.build()).map_err(e)?;
    let assembly_cpu = (cpu_seconds() - cpu) / timed.repeats as f64;
    let (problem, assembly) = (timed.value, timed.seconds);
    out.push(("dofs".into(), problem.n() as f64));
    out.push(("layer".into(), problem.layer().len() as f64));
    out.push(("assembly".into(), assembly));
    {
        use faer::linalg::solvers::SolveCore;
        let a0 = problem.bulk_plus_penalty().map_err(e)?;
        let layer = problem.layer();
        // The first factorisation runs on memory this process has not
        // touched before; the reference is the fastest of all, so any
        // noise can only make the ratio look worse than it is.
        let (mut llt, first, first_cpu) = one_cholesky(&a0).map_err(e)?;
        let (mut fastest, mut least_cpu) = (first, first_cpu);
        for _ in 1..cholesky_repeats(n) {
            drop(llt);
            let (f, s, c) = one_cholesky(&a0).map_err(e)?;
            llt = f;
            fastest = fastest.min(s);
            least_cpu = least_cpu.min(c);
        }
        out.push(("cholesky_first".into(), first));
        out.push(("cholesky_first_cpu".into(), first_cpu));
        out.push(("cholesky".into(), fastest));
        out.push(("cholesky_cpu".into(), least_cpu));
        let cols = BLOCK.min(layer.len());
        let mut rhs = faer::Mat::<f64>::zeros(problem.n(), cols);
        for (c, &i) in layer.iter().take(cols).enumerate() {
            rhs[(i, c)] = 1.0;
        }
        let t = Instant::now();
        llt.solve_in_place_with_conj(faer::Conj::No, rhs.as_mut());
        let route_b = t.elapsed().as_secs_f64() * layer.len() as f64 / cols as f64;
        out.push(("route_b".into(), route_b));
    }
    if n <= IN_PROCESS_UP_TO {
        reset_peak();
        // the phases printed are those of the last repeat, the total the median
        let cpu = cpu_seconds();
        let timed =
            median_time(repeats(n), || solve(&problem, &SolverOptions::default())).map_err(e)?;
        // the mean processor time of a build and a solve
        let solve_cpu = (cpu_seconds() - cpu) / timed.repeats as f64;
        out.push(("total_cpu".into(), assembly_cpu + solve_cpu));
        let s = timed.value;
        let load = -post::applied_resultant(&problem).map_err(e)?[1];
        let force = post::contact_resultant(&problem, &s.full)[1];
        out.extend([
            ("condensation".into(), s.phases.condensation),
            ("iterations".into(), s.history.len() as f64),
            ("iterations_s".into(), s.phases.iterations),
            ("recovery".into(), s.phases.recovery),
            ("total".into(), assembly + timed.seconds),
            ("force_error".into(), (force - load).abs() / load),
            ("peak".into(), peak_gb()),
        ]);
    }
    drop(problem);
    reset_peak();
    let cli = cli(p, n)?;
    out.extend([
        ("cli_wall".into(), cli.wall),
        ("cli_cpu".into(), cli.cpu),
        ("cli_peak".into(), cli.peak),
        // not `cli_iterations`: that is the [timing] part of that name
        ("cli_iteration_count".into(), cli.iterations as f64),
        (
            "cli_fallback".into(),
            f64::from(u8::from(cli.max_memory.is_some())),
        ),
    ]);
    for (k, v) in cli.timing.parts() {
        out.push((format!("cli_{k}"), v));
    }
    out.push(("cli_timing_wall".into(), cli.timing.wall));
    for (k, v) in out {
        println!("{k} {v}");
    }
    Ok(())
}

/// The scene file the command line runs: `hertz.toml` refined to p, N²,
/// with the default solver and only the summary as output.
fn cli_scene(p: usize, n: usize) -> Result<String, String> {
    let path = companion::shipped_path("hertz.toml");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut doc: toml::Table = toml::from_str(&text).map_err(|e| e.to_string())?;
    doc.insert(
        "title".into(),
        format!("Hertz contact, IGA p = {p}, {n} × {n}").into(),
    );
    let refine = doc
        .get_mut("body")
        .and_then(|b| b.as_array_mut())
        .and_then(|b| b.first_mut())
        .and_then(|b| b.get_mut("refine"))
        .and_then(|r| r.as_table_mut())
        .ok_or("hertz.toml: no body[0].refine")?;
    refine.insert("degree".into(), (p as i64).into());
    refine.insert(
        "elements".into(),
        toml::Value::Array(vec![(n as i64).into(), (n as i64).into()]),
    );
    doc.remove("solver");
    let mut output = toml::Table::new();
    output.insert("summary".into(), true.into());
    doc.insert("output".into(), output.into());
    toml::to_string(&doc).map_err(|e| e.to_string())
}

/// One command-line run: wall time from spawn to exit, peak resident
/// memory (bytes) and the `[timing]` of its summary.
struct CliRun {
    /// `None`: the default memory budget; else the `--max-memory` given
    /// because the default refused the run.
    max_memory: Option<&'static str>,
    wall: f64,
    /// Processor time, user and system, of all its threads.
    cpu: f64,
    peak: f64,
    timing: PhaseTimes,
    iterations: usize,
}

/// Runs `iga-contact run` on the scene of p, N² in `dir` (a fresh folder).
fn cli_run(
    bin: &Path,
    dir: &Path,
    p: usize,
    n: usize,
    max_memory: Option<&'static str>,
) -> Result<CliRun, String> {
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, cli_scene(p, n)?).map_err(|e| e.to_string())?;
    let out = dir.join("out");
    let err = dir.join("stderr.txt");
    let stderr = std::fs::File::create(&err).map_err(|e| e.to_string())?;
    let t = Instant::now();
    let mut command = Command::new(bin);
    command.arg("run").arg(&scene).arg("--out").arg(&out);
    if let Some(m) = max_memory {
        command.args(["--max-memory", m]);
    }
    let child = command
        .stdout(Stdio::null())
        .stderr(stderr)
        .spawn()
        .map_err(|e| format!("{}: {e}", bin.display()))?;
    // wait4, not Child::wait: it reports the child's own peak memory
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value of the plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: the pid is our unwaited child; status and usage are valid
    // for writes for the duration of the call.
    let waited = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    let wall = t.elapsed().as_secs_f64();
    if waited < 0 || !libc::WIFEXITED(status) || libc::WEXITSTATUS(status) != 0 {
        let msg = std::fs::read_to_string(&err).unwrap_or_default();
        let how = if waited >= 0 && libc::WIFSIGNALED(status) {
            // SIGKILL without a message: the kernel's out-of-memory killer
            format!(
                "killed by signal {} at {:.1} GB resident",
                libc::WTERMSIG(status),
                usage.ru_maxrss as f64 * 1024.0 / 1e9
            )
        } else {
            msg.trim().to_string()
        };
        return Err(format!("iga-contact run, p = {p}, {n}²: {how}"));
    }
    let summary = std::fs::read_to_string(out.join("summary.toml")).map_err(|e| e.to_string())?;
    let summary: toml::Table = toml::from_str(&summary).map_err(|e| e.to_string())?;
    let t = summary
        .get("timing")
        .and_then(|t| t.as_table())
        .ok_or("summary.toml has no [timing]")?;
    let timing = PhaseTimes::from_keys(|k| t.get(k)?.as_float())
        .map_err(|k| format!("summary.toml: no timing.{k}"))?;
    let iterations = summary
        .get("iterations")
        .and_then(|v| v.as_integer())
        .ok_or("summary.toml: no iterations")? as usize;
    Ok(CliRun {
        max_memory,
        wall,
        cpu: cpu_of(&usage),
        // ru_maxrss is in kilobytes on Linux
        peak: usage.ru_maxrss as f64 * 1024.0,
        timing,
        iterations,
    })
}

/// The budget given when the default memory budget refuses a run: the
/// estimate is an upper bound (22.9 GiB for p = 2 on 512², whose measured
/// peak is about 3 GB), so the fallback lifts the refusal, and the measured
/// peak in the table is the figure to read.
const FALLBACK_MAX_MEMORY: &str = "256G";

/// The median (by wall time) of `repeats(n)` command-line runs, with the
/// default memory budget, or [`FALLBACK_MAX_MEMORY`] where it refuses.
fn cli(p: usize, n: usize) -> Result<CliRun, String> {
    let bin = companion::chapter::cli_binary().map_err(|e| e.to_string())?;
    let dir = std::env::temp_dir().join(format!("solver_scaling_cli_{}", std::process::id()));
    let mut runs = Vec::new();
    let mut max_memory = None;
    while runs.len() < repeats(n) {
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        let run = cli_run(&bin, &dir, p, n, max_memory);
        let _ = std::fs::remove_dir_all(&dir);
        match run {
            Err(e) if max_memory.is_none() && e.contains("over the memory budget") => {
                eprintln!(
                    "  the default memory budget refuses it: --max-memory {FALLBACK_MAX_MEMORY}"
                );
                max_memory = Some(FALLBACK_MAX_MEMORY);
            }
            run => runs.push(run?),
        }
    }
    runs.sort_by(|a, b| a.wall.total_cmp(&b.wall));
    let k = runs.len() / 2;
    Ok(runs.swap_remove(k))
}

/// The in-process measurements of a case.
struct InProcess {
    condensation: f64,
    iterations: usize,
    iterations_s: f64,
    recovery: f64,
    total: f64,
    /// The mean processor time of a build and a solve.
    total_cpu: f64,
    force_error: f64,
    peak: f64,
}

/// Everything measured of one case, in one process run.
struct Row {
    p: usize,
    n: usize,
    dofs: usize,
    layer: usize,
    assembly: f64,
    /// The fastest of the reference factorisations.
    cholesky: f64,
    /// The first reference factorisation of the process.
    cholesky_first: f64,
    /// Processor times of the first and of the least of the factorisations.
    cholesky_first_cpu: f64,
    cholesky_cpu: f64,
    route_b: f64,
    /// `None` above [`IN_PROCESS_UP_TO`].
    solve: Option<InProcess>,
    cli: CliRun,
}

/// Runs the case in a child process of its own ([`case`]) and reads back
/// what it printed.
fn measure(p: usize, n: usize) -> Result<Row, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let out = Command::new(exe)
        .args(["--case", &p.to_string(), &n.to_string()])
        .stderr(Stdio::inherit())
        .output()
        .map_err(|e| e.to_string())?;
    let text = String::from_utf8_lossy(&out.stdout);
    if let Some(why) = text.lines().find_map(|l| l.strip_prefix("failed ")) {
        return Err(why.to_string());
    }
    if !out.status.success() {
        return Err(format!(
            "p = {p}, {n}²: the process of the case ended with {}",
            out.status
        ));
    }
    let mut values = std::collections::HashMap::new();
    for line in text.lines() {
        let (k, v) = line
            .split_once(' ')
            .ok_or(format!("p = {p}, {n}²: `{line}` is not `key value`"))?;
        let v: f64 = v.parse().map_err(|e| format!("{k}: {e}"))?;
        values.insert(k.to_string(), v);
    }
    let get = |k: &str| -> Result<f64, String> {
        values
            .get(k)
            .copied()
            .ok_or(format!("p = {p}, {n}²: the case printed no {k}"))
    };
    let solve = if values.contains_key("total") {
        Some(InProcess {
            condensation: get("condensation")?,
            iterations: get("iterations")? as usize,
            iterations_s: get("iterations_s")?,
            recovery: get("recovery")?,
            total: get("total")?,
            total_cpu: get("total_cpu")?,
            force_error: get("force_error")?,
            peak: get("peak")?,
        })
    } else {
        None
    };
    let timing = PhaseTimes::from_keys(|k| {
        values
            .get(&format!(
                "cli_{}",
                if k == "wall" { "timing_wall" } else { k }
            ))
            .copied()
    })
    .map_err(|k| format!("p = {p}, {n}²: no cli_{k}"))?;
    let cli = CliRun {
        max_memory: (get("cli_fallback")? != 0.0).then_some(FALLBACK_MAX_MEMORY),
        wall: get("cli_wall")?,
        cpu: get("cli_cpu")?,
        peak: get("cli_peak")?,
        timing,
        iterations: get("cli_iteration_count")? as usize,
    };
    let within = (cli.timing.sum() - cli.wall).abs() / cli.wall;
    if n >= PARTS_CHECKED_FROM && within > PARTS_WITHIN {
        return Err(format!(
            "p = {p}, {n}²: the [timing] parts add up to {:.3} s, the run took {:.3} s",
            cli.timing.sum(),
            cli.wall
        ));
    }
    Ok(Row {
        p,
        n,
        dofs: get("dofs")? as usize,
        layer: get("layer")? as usize,
        assembly: get("assembly")?,
        cholesky: get("cholesky")?,
        cholesky_first: get("cholesky_first")?,
        cholesky_first_cpu: get("cholesky_first_cpu")?,
        cholesky_cpu: get("cholesky_cpu")?,
        route_b: get("route_b")?,
        solve,
        cli,
    })
}

/// A cell of an in-process figure, empty where the case ran only through
/// the command line.
fn cell(row: &Row, f: impl Fn(&InProcess) -> Cell) -> Cell {
    row.solve.as_ref().map_or(Cell::Empty, f)
}

/// The totals (`scaling`), the split of the in-process time (`phases`) and
/// of the command-line run (`cli`).
/// The columns of the tables `scaling`, `phases` and `cli`. C is the
/// fastest reference Cholesky factorisation, C₁ the first of its process;
/// times are in seconds. The page shows eight columns at most (the text
/// column is about 750 px wide); the others are in the CSV files.
fn columns() -> [Table; 3] {
    let seconds = |key, header| Column::new(key, header, Unit::None, Format::Fixed(2));
    let ratio = |key, header| Column::new(key, header, Unit::None, Format::Times(2));
    let scaling = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs").csv_only(),
        Column::plain("layer", "layer ℓ").csv_only(),
        Column::plain("iterations", "its"),
        seconds("total", "total").csv_only(),
        ratio("ratio", "solve ÷ C"),
        ratio("cpu_ratio", "solve ÷ C, CPU").csv_only(),
        Column::new("peak_gb", "peak", Unit::Gigabyte, Format::Fixed(2)).csv_only(),
        seconds("cli_wall", "CLI").csv_only(),
        ratio("cli_ratio", "CLI ÷ C"),
        ratio("cli_ratio_first", "CLI ÷ C₁"),
        ratio("cli_cpu_ratio", "CLI ÷ C, CPU"),
        Column::new("cli_peak_gb", "CLI peak", Unit::Gigabyte, Format::Fixed(2)),
        Column::new("force_error", "force error", Unit::None, Format::Sci(1)).csv_only(),
    ]);
    let phases = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        seconds("assembly", "assemble"),
        seconds("one_cholesky", "C"),
        seconds("first_cholesky", "C₁"),
        seconds("condensation", "condense"),
        seconds("iterations_seconds", "iterate"),
        Column::new("back_substitution", "recover", Unit::None, Format::Fixed(3)).csv_only(),
        Column::new("route_b_estimate", "B", Unit::None, Format::Fixed(1)),
    ]);
    let cli = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        seconds("parse_and_build", "parse, build").csv_only(),
        seconds("contact_setup", "contact").csv_only(),
        seconds("assembly", "assemble"),
        seconds("factorisation", "factorise"),
        seconds("iterations", "iterate"),
        seconds("post_processing", "post"),
        seconds("output", "output").csv_only(),
        seconds("parts", "sum"),
        seconds("wall", "wall"),
        seconds("one_cholesky", "C").csv_only(),
    ]);
    [scaling, phases, cli]
}

fn tables(rows: &[Row]) -> iga_contact::Result<[Table; 3]> {
    let [mut scaling, mut phases, mut cli] = columns();
    for r in rows {
        let t = &r.cli.timing;
        scaling.push(vec![
            r.p.into(),
            r.n.into(),
            r.dofs.into(),
            r.layer.into(),
            r.solve
                .as_ref()
                .map_or(r.cli.iterations, |s| s.iterations)
                .into(),
            cell(r, |s| s.total.into()),
            cell(r, |s| (s.total / r.cholesky).into()),
            cell(r, |s| (s.total_cpu / r.cholesky_cpu).into()),
            cell(r, |s| (s.peak * 1e9).into()),
            r.cli.wall.into(),
            (r.cli.wall / r.cholesky).into(),
            (r.cli.wall / r.cholesky_first).into(),
            (r.cli.cpu / r.cholesky_cpu).into(),
            r.cli.peak.into(),
            cell(r, |s| s.force_error.into()),
        ])?;
        phases.push(vec![
            r.p.into(),
            r.n.into(),
            r.assembly.into(),
            r.cholesky.into(),
            r.cholesky_first.into(),
            cell(r, |s| s.condensation.into()),
            cell(r, |s| s.iterations_s.into()),
            cell(r, |s| s.recovery.into()),
            r.route_b.into(),
        ])?;
        cli.push(vec![
            r.p.into(),
            r.n.into(),
            t.parse_and_build.into(),
            t.contact_setup.into(),
            t.assembly.into(),
            t.factorisation.into(),
            t.iterations.into(),
            t.post_processing.into(),
            t.output.into(),
            t.sum().into(),
            r.cli.wall.into(),
            r.cholesky.into(),
        ])?;
    }
    Ok([scaling, phases, cli])
}

fn main() -> ExitCode {
    let args: Vec<String> = std::env::args().skip(1).collect();
    if let [mode, p, n] = args.as_slice() {
        if mode.starts_with("--") {
            let (Ok(p), Ok(n)) = (p.parse(), n.parse()) else {
                eprintln!("solver_scaling: {mode} wants a degree and a mesh");
                return ExitCode::FAILURE;
            };
            let r = match mode.as_str() {
                "--case" => case(p, n),
                _ => {
                    eprintln!("solver_scaling: unknown mode {mode}");
                    return ExitCode::FAILURE;
                }
            };
            return match r {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    // the parent records the reason of a case not run
                    println!("failed {e}");
                    ExitCode::FAILURE
                }
            };
        }
    }
    let cases: Result<Vec<(usize, usize)>, String> = if args.is_empty() {
        Ok(CASES.to_vec())
    } else {
        args.iter()
            .map(|a| {
                let (p, n) = a.split_once(':').ok_or(format!("`{a}` is not p:N"))?;
                Ok((
                    p.parse().map_err(|e| format!("`{a}`: {e}"))?,
                    n.parse().map_err(|e| format!("`{a}`: {e}"))?,
                ))
            })
            .collect()
    };
    let cases = match cases {
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
            Err(e) if n > IN_PROCESS_UP_TO => {
                eprintln!("solver_scaling: not run: {e}");
                not_run.push((p, n, e));
            }
            Err(e) => {
                eprintln!("solver_scaling: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    let written = (|| -> iga_contact::Result<()> {
        let mut chapter = Chapter::at(companion::chapter::generated_root().join("solver_scaling"))?;
        let [scaling, phases, cli] = tables(&rows)?;
        print!(
            "{}\n{}\n{}",
            scaling.to_markdown(),
            phases.to_markdown(),
            cli.to_markdown()
        );
        chapter.table("scaling", &scaling)?;
        chapter.table("phases", &phases)?;
        chapter.table("cli", &cli)?;
        for stem in ["scaling", "phases", "cli"] {
            chapter.timed(&format!("{stem}.csv"));
            chapter.timed(&format!("{stem}.md"));
        }
        let facts = chapter.facts();
        // the chapter states when and on what the times were taken
        companion::timing::Machine::here().record(facts, "machine_")?;
        facts.number("parts_within", PARTS_WITHIN, Format::Percent(0))?;
        facts.count("parts_checked_from", PARTS_CHECKED_FROM)?;
        for (p, n, why) in &not_run {
            facts.text(&format!("p{p}_{n}_status"), format!("not run: {why}"))?;
        }
        for r in &rows {
            let key = format!("p{}_{}", r.p, r.n);
            facts.text(&format!("{key}_status"), "run")?;
            facts.timed_number(
                &format!("{key}_cli_ratio_first"),
                r.cli.wall / r.cholesky_first,
                Format::Times(1),
            )?;
            facts.timed_number(
                &format!("{key}_cli_cpu_ratio"),
                r.cli.cpu / r.cholesky_cpu,
                Format::Times(1),
            )?;
            facts.timed_number(
                &format!("{key}_cholesky_first_cpu_ratio"),
                r.cholesky_first_cpu / r.cholesky_cpu,
                Format::Times(1),
            )?;
            facts.timed_number(
                &format!("{key}_cholesky_first"),
                r.cholesky_first,
                Format::Fixed(1),
            )?;
            facts.timed_number(
                &format!("{key}_parts_gap"),
                (r.cli.timing.sum() - r.cli.wall).abs() / r.cli.wall,
                Format::Percent(1),
            )?;
            facts.timed_number(
                &format!("{key}_cli_post"),
                r.cli.timing.post_processing / r.cli.wall,
                Format::Percent(0),
            )?;
            facts.count(&format!("{key}_dofs"), r.dofs)?;
            let cli = &r.cli;
            facts.timed_number(
                &format!("{key}_cli_ratio"),
                cli.wall / r.cholesky,
                Format::Times(1),
            )?;
            facts.timed_number(&format!("{key}_cli_wall"), cli.wall, Format::Fixed(1))?;
            facts.timed_number(
                &format!("{key}_cli_peak_gb"),
                cli.peak / 1e9,
                Format::Fixed(1),
            )?;
            facts.timed_number(
                &format!("{key}_cli_outside_solve"),
                (cli.wall - cli.timing.factorisation - cli.timing.iterations) / cli.wall,
                Format::Percent(0),
            )?;
            facts.timed_number(&format!("{key}_cholesky"), r.cholesky, Format::Fixed(1))?;
            facts.count(&format!("{key}_iterations"), cli.iterations)?;
            facts.text(
                &format!("{key}_cli_budget"),
                cli.max_memory
                    .map_or("the default memory budget".into(), |m| {
                        format!("`--max-memory {m}` (the default budget refuses it)")
                    }),
            )?;
            let Some(s) = &r.solve else { continue };
            facts.timed_number(
                &format!("{key}_ratio"),
                s.total / r.cholesky,
                Format::Times(1),
            )?;
            facts.timed_number(&format!("{key}_total"), s.total, Format::Fixed(1))?;
            facts.timed_number(
                &format!("{key}_cpu_ratio"),
                s.total_cpu / r.cholesky_cpu,
                Format::Times(1),
            )?;
            facts.timed_number(&format!("{key}_peak_gb"), s.peak, Format::Fixed(1))?;
            facts.number(
                &format!("{key}_force_error"),
                s.force_error.max(1e-16),
                Format::Pow10(0),
            )?;
        }
        chapter.finish()
    })();
    if let Err(e) = written {
        eprintln!("solver_scaling: {e}");
        return ExitCode::FAILURE;
    }
    ExitCode::SUCCESS
}
