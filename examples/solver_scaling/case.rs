//! One case in one process: the build, the reference Cholesky of A₀ (first
//! and fastest), route B, the in-process solve (up to
//! [`IN_PROCESS_UP_TO`]), then, with everything freed, the command-line
//! runs as children of this process. It prints one `key value` per line,
//! which the parent reads back (`measure.rs`).

use crate::cli::cli;
use crate::process::{cholesky_repeats, cpu_seconds, peak_gb, repeats, reset_peak};
use crate::{BLOCK, IN_PROCESS_UP_TO};
use companion::timing::median_time;
use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
use iga_contact::linsolve::FactorError;
use iga_contact::post;
use iga_contact::problem::Problem;
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::{solve, SolverOptions};
use std::time::Instant;

/// The `key value` lines a case prints.
type Lines = Vec<(String, f64)>;

fn scene(p: usize, n: usize) -> iga_contact::Result<Scene> {
    companion::shipped("hertz.toml")?.refined("disk", RefineSpec::iga(p, [n, n]))
}

/// One Cholesky factorisation, timed.
struct Cholesky {
    factor: Llt<usize, f64>,
    /// Wall time.
    seconds: f64,
    /// Processor time.
    cpu: f64,
}

/// One Cholesky factorisation (faer's symbolic analysis with its AMD
/// order, then the numeric factor) of `a`, its wall time and its
/// processor time.
fn one_cholesky(a: &faer::sparse::SparseColMat<usize, f64>) -> iga_contact::Result<Cholesky> {
    let (t, cpu) = (Instant::now(), cpu_seconds());
    let symbolic = SymbolicLlt::try_new(a.symbolic(), faer::Side::Lower)
        .map_err(|e| FactorError::of_faer("symbolic Cholesky", e))?;
    let factor = Llt::try_new_with_symbolic(symbolic, a.as_ref(), faer::Side::Lower)
        .map_err(|e| FactorError::of_llt("Cholesky", e))?;
    Ok(Cholesky {
        factor,
        seconds: t.elapsed().as_secs_f64(),
        cpu: cpu_seconds() - cpu,
    })
}

/// Child: one case in one process. Prints one `key value` per line.
pub fn case(p: usize, n: usize) -> Result<(), String> {
    let e = |e: iga_contact::Error| e.to_string();
    let mut out = Lines::new();
    let scene = scene(p, n).map_err(e)?;
    let cpu = cpu_seconds();
    let timed = median_time(repeats(n), || scene.build()).map_err(e)?;
    let assembly_cpu = (cpu_seconds() - cpu) / timed.repeats as f64;
    let (problem, assembly) = (timed.value, timed.seconds);
    out.push(("dofs".into(), problem.n() as f64));
    out.push(("layer".into(), problem.layer().len() as f64));
    out.push(("assembly".into(), assembly));
    reference_cholesky(&problem, n, &mut out).map_err(e)?;
    if n <= IN_PROCESS_UP_TO {
        in_process(&problem, n, assembly, assembly_cpu, &mut out).map_err(e)?;
    }
    drop(problem);
    reset_peak();
    command_line(p, n, &mut out)?;
    for (k, v) in out {
        println!("{k} {v}");
    }
    Ok(())
}

/// The reference Cholesky of A₀, first and fastest, and route B.
fn reference_cholesky(problem: &Problem, n: usize, out: &mut Lines) -> iga_contact::Result<()> {
    use faer::linalg::solvers::SolveCore;
    let a0 = problem.bulk_plus_penalty()?;
    let layer = problem.layer();
    // The first factorisation runs on memory this process has not
    // touched before; the reference is the fastest of all, so any
    // noise can only make the ratio look worse than it is.
    let first = one_cholesky(&a0)?;
    let (first_seconds, first_cpu) = (first.seconds, first.cpu);
    let (mut fastest, mut least_cpu) = (first_seconds, first_cpu);
    let mut llt = first.factor;
    for _ in 1..cholesky_repeats(n) {
        drop(llt);
        let c = one_cholesky(&a0)?;
        llt = c.factor;
        fastest = fastest.min(c.seconds);
        least_cpu = least_cpu.min(c.cpu);
    }
    out.push(("cholesky_first".into(), first_seconds));
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
    Ok(())
}

/// The default solve in this process: its phases, the total with the
/// assembly, the force balance and the peak memory.
fn in_process(
    problem: &Problem,
    n: usize,
    assembly: f64,
    assembly_cpu: f64,
    out: &mut Lines,
) -> iga_contact::Result<()> {
    reset_peak();
    // the phases printed are those of the last repeat, the total the median
    let cpu = cpu_seconds();
    let timed = median_time(repeats(n), || solve(problem, &SolverOptions::default()))?;
    // the mean processor time of a build and a solve
    let solve_cpu = (cpu_seconds() - cpu) / timed.repeats as f64;
    out.push(("total_cpu".into(), assembly_cpu + solve_cpu));
    let s = timed.value;
    let load = -post::applied_resultant(problem)?[1];
    let force = post::contact_resultant(problem, &s.full)[1];
    out.extend([
        ("condensation".into(), s.phases.condensation),
        ("iterations".into(), s.history.len() as f64),
        ("iterations_s".into(), s.phases.iterations),
        ("recovery".into(), s.phases.recovery),
        ("total".into(), assembly + timed.seconds),
        ("force_error".into(), (force - load).abs() / load),
        ("peak".into(), peak_gb()),
    ]);
    Ok(())
}

/// The command-line runs of the same scene.
fn command_line(p: usize, n: usize, out: &mut Lines) -> Result<(), String> {
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
    Ok(())
}
