//! The cost of a whole Hertz solve against one Cholesky factorisation of
//! the bulk, on growing meshes, in one run.
//!
//! For each case (degree p, N² elements) it measures, each phase in a child
//! process of its own so that the peak memory is the phase's:
//!
//! - **assembly**: `Problem::new` (stiffness pattern and values, load,
//!   contact points);
//! - **one Cholesky**: faer's symbolic (AMD) plus numeric Cholesky of
//!   A₀ = K + Σ w γ jn jnᵀ, the bulk stiffness plus the contact penalty
//!   (the Hertz disk floats without contact, so K alone is singular);
//! - the default solve, split into **condensation** (Cholesky of A₀ with
//!   the contact layer last, the Schur complement S₀ and the condensed
//!   load), **iterations** (count and time, on the layer) and
//!   **back-substitution** (the body from the layer);
//! - **total** (assembly + solve), **total / one Cholesky**, and the peak
//!   resident memory (VmHWM) of the solve;
//! - the other route to the layer operator, for the record: blocked
//!   multi-right-hand-side solves with the factor of A₀ for the ℓ layer
//!   columns of A₀⁻¹ (route B), timed on one block of 64 columns and
//!   scaled to ℓ.
//!
//! Each phase is timed 3 times (7 on the smallest mesh): the median is kept
//! for the solve's phases, the fastest for the reference Cholesky.
//!
//! Writes `book/src/generated/solver_scaling/` (the tables `scaling`, the
//! totals, and `phases`, the split of the time) and prints them.
//! `cargo run --release --example solver_scaling [-- p:N ...]` (default
//! 2:64 2:256 2:512 3:256 4:256; a few minutes, about 3 GB).

use iga_contact::post;
use iga_contact::problem::Problem;
use iga_contact::report::chapter::Chapter;
use iga_contact::report::table::{Column, Format, Table, Unit};
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::{solve, SolverOptions};
use iga_contact::timing::median_time;
use std::process::{Command, ExitCode};
use std::time::Instant;

const CASES: [(usize, usize); 5] = [(2, 64), (2, 256), (2, 512), (3, 256), (4, 256)];
/// Right-hand sides per block of route B.
const BLOCK: usize = 64;

/// Peak resident memory of this process (GB), from /proc/self/status.
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

/// How often a phase is timed (the median is kept): on a shared machine one
/// sample of a phase varies by tens of per cent, and a phase of a few
/// hundredths of a second on the small mesh is mostly timer and scheduler
/// noise.
fn repeats(n: usize) -> usize {
    if n <= 64 {
        7
    } else {
        3
    }
}

fn build(p: usize, n: usize) -> iga_contact::Result<(Problem, f64)> {
    let scene = Scene::shipped("hertz.toml")?.refined("disk", RefineSpec::iga(p, [n, n]))?;
    let timed = median_time(repeats(n), || scene.build())?;
    Ok((timed.value, timed.seconds))
}

/// Child: one Cholesky of A₀ and route B. Prints `chol route_b`.
fn cholesky(p: usize, n: usize) -> iga_contact::Result<()> {
    use faer::linalg::solvers::SolveCore;
    use faer::sparse::linalg::solvers::{Llt, SymbolicLlt};
    let (problem, _) = build(p, n)?;
    let a0 = problem.bulk_plus_penalty()?;
    let layer = problem.layer();
    // The reference is the fastest of the repeats (our phases are medians):
    // any noise can only make the ratio look worse than it is.
    let mut chol = f64::INFINITY;
    let mut llt = None;
    for _ in 0..repeats(n) {
        let t = Instant::now();
        let symbolic = SymbolicLlt::try_new(a0.symbolic(), faer::Side::Lower)
            .map_err(|e| iga_contact::Error::Singular(format!("{e:?}")))?;
        let factor = Llt::try_new_with_symbolic(symbolic, a0.as_ref(), faer::Side::Lower)
            .map_err(|e| iga_contact::Error::Singular(format!("{e:?}")))?;
        chol = chol.min(t.elapsed().as_secs_f64());
        llt = Some(factor);
    }
    let llt = llt.expect("at least one repeat");
    let cols = BLOCK.min(layer.len());
    let mut rhs = faer::Mat::<f64>::zeros(problem.n(), cols);
    for (c, &i) in layer.iter().take(cols).enumerate() {
        rhs[(i, c)] = 1.0;
    }
    let t = Instant::now();
    llt.solve_in_place_with_conj(faer::Conj::No, rhs.as_mut());
    let route_b = t.elapsed().as_secs_f64() * layer.len() as f64 / cols as f64;
    println!("{chol} {route_b}");
    Ok(())
}

/// Child: assembly and the default solve. Prints the row's measured fields.
fn solve_case(p: usize, n: usize) -> iga_contact::Result<()> {
    let (problem, assembly) = build(p, n)?;
    // the phases printed are those of the last repeat, the total the median
    let timed = median_time(repeats(n), || solve(&problem, &SolverOptions::default()))?;
    let (s, seconds) = (timed.value, timed.seconds);
    let load = -post::applied_resultant(&problem)?[1];
    let force = post::contact_resultant(&problem, &s.full)[1];
    println!(
        "{} {} {assembly} {} {} {} {} {seconds} {} {}",
        problem.n(),
        problem.layer().len(),
        s.phases.condensation,
        s.history.len(),
        s.phases.iterations,
        s.phases.recovery,
        (force - load).abs() / load,
        peak_gb()
    );
    Ok(())
}

struct Row {
    p: usize,
    n: usize,
    dofs: usize,
    layer: usize,
    assembly: f64,
    cholesky: f64,
    condensation: f64,
    iterations: usize,
    iterations_s: f64,
    recovery: f64,
    total: f64,
    force_error: f64,
    peak: f64,
    route_b: f64,
}

fn child(mode: &str, p: usize, n: usize) -> Result<Vec<f64>, String> {
    let exe = std::env::current_exe().map_err(|e| e.to_string())?;
    let out = Command::new(exe)
        .args([mode, &p.to_string(), &n.to_string()])
        .output()
        .map_err(|e| e.to_string())?;
    if !out.status.success() {
        return Err(format!(
            "{mode} p = {p}, {n}²: {}",
            String::from_utf8_lossy(&out.stderr)
        ));
    }
    String::from_utf8_lossy(&out.stdout)
        .split_whitespace()
        .map(|v| v.parse::<f64>().map_err(|e| format!("{mode}: {e}")))
        .collect()
}

fn measure(p: usize, n: usize) -> Result<Row, String> {
    let c = child("--cholesky", p, n)?;
    let s = child("--solve", p, n)?;
    Ok(Row {
        p,
        n,
        dofs: s[0] as usize,
        layer: s[1] as usize,
        assembly: s[2],
        cholesky: c[0],
        condensation: s[3],
        iterations: s[4] as usize,
        iterations_s: s[5],
        recovery: s[6],
        total: s[2] + s[7],
        force_error: s[8],
        peak: s[9],
        route_b: c[1],
    })
}

/// The totals (`scaling`) and the split of the time (`phases`).
fn tables(rows: &[Row]) -> iga_contact::Result<(Table, Table)> {
    let seconds = |key, header| Column::new(key, header, Unit::Second, Format::Fixed(2));
    let mut scaling = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::plain("layer", "layer ℓ"),
        Column::plain("iterations", "its"),
        seconds("total", "total"),
        Column::new("ratio", "total / Cholesky", Unit::None, Format::Times(2)),
        Column::new("peak_gb", "peak", Unit::Gigabyte, Format::Fixed(2)),
        Column::new("force_error", "force error", Unit::None, Format::Sci(1)).csv_only(),
    ]);
    let mut phases = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        seconds("assembly", "assemble"),
        seconds("one_cholesky", "Cholesky"),
        seconds("condensation", "condense"),
        seconds("iterations_seconds", "iterate"),
        Column::new(
            "back_substitution",
            "recover",
            Unit::Second,
            Format::Fixed(3),
        ),
        Column::new("route_b_estimate", "B", Unit::Second, Format::Fixed(1)),
    ]);
    for r in rows {
        scaling.push(vec![
            r.p.into(),
            r.n.into(),
            r.dofs.into(),
            r.layer.into(),
            r.iterations.into(),
            r.total.into(),
            (r.total / r.cholesky).into(),
            (r.peak * 1e9).into(),
            r.force_error.into(),
        ])?;
        phases.push(vec![
            r.p.into(),
            r.n.into(),
            r.assembly.into(),
            r.cholesky.into(),
            r.condensation.into(),
            r.iterations_s.into(),
            r.recovery.into(),
            r.route_b.into(),
        ])?;
    }
    Ok((scaling, phases))
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
                "--cholesky" => cholesky(p, n),
                "--solve" => solve_case(p, n),
                _ => {
                    eprintln!("solver_scaling: unknown mode {mode}");
                    return ExitCode::FAILURE;
                }
            };
            return match r {
                Ok(()) => ExitCode::SUCCESS,
                Err(e) => {
                    eprintln!("{e}");
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
    for (p, n) in cases {
        eprintln!("p = {p}, {n}² …");
        match measure(p, n) {
            Ok(r) => rows.push(r),
            Err(e) => {
                eprintln!("solver_scaling: {e}");
                return ExitCode::FAILURE;
            }
        }
    }
    let written = (|| -> iga_contact::Result<()> {
        let mut chapter =
            Chapter::at(iga_contact::report::chapter::generated_root().join("solver_scaling"))?;
        let (scaling, phases) = tables(&rows)?;
        print!("{}\n{}", scaling.to_markdown(), phases.to_markdown());
        chapter.table("scaling", &scaling)?;
        chapter.table("phases", &phases)?;
        for f in ["scaling.csv", "scaling.md", "phases.csv", "phases.md"] {
            chapter.timed(f);
        }
        let facts = chapter.facts();
        // the chapter states when and on what the times were taken
        iga_contact::timing::Machine::here().record(facts, "machine_")?;
        for r in &rows {
            let key = format!("p{}_{}", r.p, r.n);
            facts.timed_number(
                &format!("{key}_ratio"),
                r.total / r.cholesky,
                Format::Times(1),
            )?;
            facts.timed_number(&format!("{key}_total"), r.total, Format::Fixed(1))?;
            facts.timed_number(&format!("{key}_peak_gb"), r.peak, Format::Fixed(1))?;
            facts.count(&format!("{key}_iterations"), r.iterations)?;
            facts.count(&format!("{key}_dofs"), r.dofs)?;
            facts.number(
                &format!("{key}_force_error"),
                r.force_error.max(1e-16),
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
