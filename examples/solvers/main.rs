//! Solvers compared: the program behind the chapter "Solvers: BFGS, its
//! correction, and Newton". The paper's BFGS with its correction, the same
//! BFGS without it, and semismooth Newton on the Hertz problem (IGA p = 2)
//! as the mesh is refined. Output: `book/src/generated/solvers/`.
//!
//! Run it with `cargo run --release --example solvers`.

use companion::hertz as setup;

use companion::chapter::Chapter;
use companion::timing::median_time;
use companion::{Facts, Solver};
use iga_contact::error::{Error, Result};
use iga_contact::post::PressureProfile;
use iga_contact::report::history::history_table;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::solver::history::Event;
use iga_contact::solver::history::History;
use iga_contact::solver::{solve, Solution, SolverKind, SolverOptions, Start};

/// Elements per direction.
const MESHES: [usize; 4] = [8, 16, 32, 64];
/// Timing repeats per run (the median is kept): single runs of a few
/// milliseconds on a shared machine do not rank the solvers.
const REPEATS: usize = 5;

// ANCHOR: solvers
/// The solvers compared, in the order of the tables (each named there by
/// [`Solver::name`], in the facts by [`Solver::key`], with the options
/// [`Solver::options`]): the library's default BFGS (balanced secant start,
/// a correction at every change of the active set, on the contact layer),
/// the same never corrected, Newton, and the paper's iteration
/// (`SolverOptions::paper()`: tied start, the correction when ‖R‖ grows
/// after 8 iterations, full steps, over the body) with and without its
/// correction.
const SOLVERS: [Solver; 5] = [
    Solver::Bfgs,
    Solver::BfgsNoCorrection,
    Solver::Newton,
    Solver::Paper,
    Solver::PaperNoCorrection,
];
// ANCHOR_END: solvers

/// One solve: its history, and what was measured if it converged.
struct Outcome {
    solver: Solver,
    elements: usize,
    dofs: usize,
    history: History,
    /// `None` when converged, else the solver's reason.
    failure: Option<String>,
    factorisations: Option<usize>,
    p0: Option<f64>,
    seconds: f64,
}

// ANCHOR: run
/// Runs one solver on Hertz p = 2 with `elements`²; non-convergence is a
/// result and is recorded.
fn outcome(solver: Solver, elements: usize) -> Result<Outcome> {
    let scene = setup::scene(setup::iga(2, elements))?;
    let opts = solver.options();
    let timed = median_time(REPEATS, || {
        let problem = scene.build()?;
        let result = solve(&problem, &opts);
        Ok((problem, result))
    })?;
    let (problem, result) = timed.value;
    let mut o = Outcome {
        solver,
        elements,
        dofs: problem.n(),
        history: History::default(),
        failure: None,
        factorisations: None,
        p0: None,
        seconds: timed.seconds,
    };
    match result {
        Ok(s) => {
            o.p0 = Some(PressureProfile::dense(&problem, &s.full)?.measures(0).p0);
            o.factorisations = Some(s.factorisations);
            o.history = s.history;
        }
        Err(Error::NotConverged { diagnosis, history }) => {
            o.history = history;
            o.failure = Some(diagnosis.to_string());
        }
        Err(e) => o.failure = Some(e.to_string()),
    }
    Ok(o)
}
// ANCHOR_END: run

// ANCHOR: paper_runs
/// One run on a shipped scene: its fact key, the scene, the labels of its
/// solver and steps in the table, and its options.
#[derive(Clone, Copy)]
struct PaperRun {
    key: &'static str,
    file: &'static str,
    solver: &'static str,
    steps: &'static str,
    options: SolverOptions,
}

/// The runs on the shipped scenes (Hertz 8×8 and Taylor, θ = 0) that the
/// chapters "Newton and BFGS" and "Starting and correcting BFGS" quote.
fn paper_runs() -> [PaperRun; 8] {
    let paper = SolverOptions::paper();
    let damped = SolverOptions {
        line_search_after: 0,
        ..paper
    };
    let plain = SolverKind::BfgsNoCorrection;
    let hertz = |key, solver, steps, options| PaperRun {
        key,
        file: "hertz.toml",
        solver,
        steps,
        options,
    };
    [
        PaperRun {
            key: "taylor",
            file: "taylor.toml",
            solver: "BFGS",
            steps: "full",
            options: paper,
        },
        hertz("paper", "BFGS", "full", paper),
        hertz(
            "paper_plain",
            "BFGS, no corr.",
            "full",
            SolverOptions {
                kind: plain,
                ..paper
            },
        ),
        hertz("damped", "BFGS", "damped", damped),
        hertz(
            "damped_plain",
            "BFGS, no corr.",
            "damped",
            SolverOptions {
                kind: plain,
                ..damped
            },
        ),
        // the correction allowed from iteration 3: it meets the disk in the air
        hertz(
            "guard",
            "BFGS, corr. from 3",
            "full",
            SolverOptions {
                correction_after: 2,
                ..paper
            },
        ),
        hertz(
            "newton_tied",
            "Newton, tied start",
            "default",
            SolverOptions {
                kind: SolverKind::Newton,
                start: Start::Tied,
                ..SolverOptions::default()
            },
        ),
        hertz("default", "default", "default", SolverOptions::default()),
    ]
}
// ANCHOR_END: paper_runs

/// The runs of [`paper_runs`] whose iteration history the chapters show.
const HISTORIES: [&str; 2] = ["paper", "newton_tied"];

/// The iteration of the first row of `s` that carries `event`, or 0.
fn first(s: &Solution, event: Event) -> usize {
    s.history
        .rows
        .iter()
        .find(|r| r.events.contains(&event))
        .map_or(0, |r| r.iteration)
}

/// The chapter "Solvers: BFGS, its correction, and Newton", section by
/// section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("solvers")?;

    // The shipped scenes, for the chapters "Newton and BFGS" and "Starting
    // and correcting BFGS": two iteration histories, their summary table
    // and facts.
    let shipped = solve_shipped()?;
    for run in shipped.iter().filter(|r| HISTORIES.contains(&r.run.key)) {
        let t = history_table(&run.solution.history, Unit::NewtonPerMetre, Unit::Metre)?;
        chapter.table(&format!("history_{}", run.run.key), &t)?;
    }
    chapter.table("shipped", &shipped_table(&shipped)?)?;
    record_shipped_facts(chapter.facts(), &shipped)?;

    // How it is measured: Table S1 and Fig. S1.
    let all = solve_ladder()?;
    chapter.table("solvers", &solvers_table(&all)?)?;
    chapter.timed("solvers.csv"); // its `seconds` column
    draw_iterations(&chapter, &all)?;

    // The facts of "How it is measured" and "Discussion": the iterations,
    // their ratios, the failures and the wall times.
    record_ladder_facts(chapter.facts(), &all)?;
    chapter.finish()
}

/// One run of [`paper_runs`], solved.
struct ShippedRun {
    run: PaperRun,
    solution: Solution,
}

/// Runs [`paper_runs`].
fn solve_shipped() -> Result<Vec<ShippedRun>> {
    paper_runs()
        .into_iter()
        .map(|run| {
            let problem = companion::shipped(run.file)?.build()?;
            let solution = solve(&problem, &run.options)?;
            Ok(ShippedRun { run, solution })
        })
        .collect()
}

/// The summary of [`paper_runs`] that "Starting and correcting BFGS" shows.
fn shipped_table(runs: &[ShippedRun]) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::plain("scene", "scene"),
        Column::plain("solver", "solver"),
        Column::plain("steps", "steps"),
        Column::plain("iterations", "its"),
        Column::plain("factorisations", "factor."),
        Column::plain("corrections", "corr."),
        Column::plain("first_correction", "first corr."),
    ]);
    for run in runs {
        let s = &run.solution;
        let h = &s.history;
        let corrected = first(s, Event::Correction);
        let scene = if run.run.file == "taylor.toml" {
            "Taylor"
        } else {
            "Hertz 8²"
        };
        table.push(vec![
            scene.into(),
            run.run.solver.into(),
            run.run.steps.into(),
            h.len().into(),
            s.factorisations.into(),
            h.corrections().into(),
            (if corrected == 0 {
                Cell::Empty
            } else {
                corrected.into()
            }),
        ])?;
    }
    Ok(table)
}

/// "Newton and BFGS" and "Starting and correcting BFGS" quote, per run of
/// [`paper_runs`], its counts, its first step, the fall after the first
/// correction and the active points iteration by iteration.
fn record_shipped_facts(f: &mut Facts, runs: &[ShippedRun]) -> Result<()> {
    for run in runs {
        let (key, s) = (run.run.key, &run.solution);
        let h = &s.history;
        let corrected = first(s, Event::Correction);
        f.count(&format!("{key}_its"), h.len())?;
        f.count(&format!("{key}_factorisations"), s.factorisations)?;
        f.count(&format!("{key}_corrections"), h.corrections())?;
        f.count(&format!("{key}_first_correction"), corrected)?;
        f.count(&format!("{key}_guard_at"), first(s, Event::FloatingGuard))?;
        if let Some(row) = h.rows.first() {
            // the first step: how far it pulls the body, how much ‖R‖ rises
            f.number(
                &format!("{key}_first_drop_cm"),
                -row.max_displacement * 100.0,
                Format::Fixed(1),
            )?;
            f.number(
                &format!("{key}_first_rise"),
                row.relative_residual,
                Format::Fixed(0),
            )?;
        }
        if (1..h.len()).contains(&corrected) {
            // the fall of ‖R‖ over the step after the first correction
            let (at, next) = (&h.rows[corrected - 1], &h.rows[corrected]);
            let orders = (at.residual / next.residual).log10();
            f.number(&format!("{key}_fall_orders"), orders, Format::Fixed(0))?;
        }
        let active: Vec<String> = h.rows.iter().map(|r| r.active_points.to_string()).collect();
        f.text(&format!("{key}_active"), active.join(", "))?;
    }
    Ok(())
}

/// "How it is measured": every solver on every mesh.
fn solve_ladder() -> Result<Vec<Outcome>> {
    let mut all = Vec::new();
    for solver in SOLVERS {
        for n in MESHES {
            all.push(outcome(solver, n)?);
        }
    }
    Ok(all)
}

// ANCHOR: tables
/// Table S1: the five solvers as the mesh is refined (the CSV adds the
/// final residual, the seconds and the failure).
fn solvers_table(all: &[Outcome]) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::plain("solver", "solver"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::plain("converged", "conv."),
        Column::plain("iterations", "its"),
        Column::plain("corrections", "corr."),
        Column::plain("factorisations", "factor."),
        Column::new(
            "final_relative_residual",
            "final ‖R‖/‖R₀‖",
            Unit::None,
            Format::Sci(1),
        )
        .csv_only(),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("seconds", "seconds", Unit::Second, Format::Fixed(3)).csv_only(),
        Column::plain("failure", "failure").csv_only(),
    ]);
    for o in all {
        table.push(vec![
            o.solver.name().into(),
            o.elements.into(),
            o.dofs.into(),
            (if o.failure.is_none() { "yes" } else { "**no**" }).into(),
            o.history.len().into(),
            o.history.corrections().into(),
            o.factorisations.into(),
            o.history.last_relative_residual().into(),
            o.p0.into(),
            o.seconds.into(),
            o.failure.clone().map_or(Cell::Empty, Cell::Text),
        ])?;
    }
    Ok(table)
}
// ANCHOR_END: tables

/// Fig. S1: iterations against the mesh, per solver. Newton dashed: it lies
/// on the default BFGS, which corrects at every iteration here.
fn draw_iterations(chapter: &Chapter, all: &[Outcome]) -> Result<()> {
    let series: Vec<Series> = SOLVERS
        .iter()
        .map(|&solver| {
            let pts = all
                .iter()
                .filter(|o| o.solver == solver && o.failure.is_none())
                .map(|o| (o.elements as f64, o.history.len() as f64))
                .collect();
            let line = Series::line(solver.name(), pts).with_markers();
            if solver == Solver::Newton {
                line.dashed()
            } else {
                line
            }
        })
        .collect();
    line_chart(
        chapter.path("iterations.svg"),
        &Axes {
            title: "Iterations to convergence (failed runs omitted, see the table)".into(),
            x_label: "elements per direction".into(),
            y_label: "iterations".into(),
            log_x: true,
            log_y: false,
        },
        &series,
    )
}

// ANCHOR: facts
/// "Discussion" quotes the iterations on the coarsest and finest mesh, how
/// many more the uncorrected BFGS takes, Newton's range, the failures, and
/// on how many meshes the uncorrected default is the faster.
fn record_ladder_facts(f: &mut Facts, all: &[Outcome]) -> Result<()> {
    let its = |solver: Solver, n: usize| {
        all.iter()
            .find(|o| o.solver == solver && o.elements == n)
            .map_or(0, |o| o.history.len())
    };
    let (coarse, fine) = (MESHES[0], MESHES[MESHES.len() - 1]);
    for solver in SOLVERS {
        let key = solver.key();
        f.count(&format!("{key}_coarse"), its(solver, coarse))?;
        f.count(&format!("{key}_fine"), its(solver, fine))?;
    }
    let ratio = |without, with, n| its(without, n) as f64 / its(with, n) as f64;
    for (key, without, with) in [
        (
            "no_correction_ratio",
            Solver::BfgsNoCorrection,
            Solver::Bfgs,
        ),
        (
            "paper_no_correction_ratio",
            Solver::PaperNoCorrection,
            Solver::Paper,
        ),
    ] {
        f.number(
            &format!("{key}_coarse"),
            ratio(without, with, coarse),
            Format::Times(1),
        )?;
        f.number(
            &format!("{key}_fine"),
            ratio(without, with, fine),
            Format::Times(1),
        )?;
    }
    let newton: Vec<usize> = all
        .iter()
        .filter(|o| o.solver == Solver::Newton)
        .map(|o| o.history.len())
        .collect();
    f.text(
        "newton_range",
        format!(
            "{}–{}",
            newton.iter().min().unwrap_or(&0),
            newton.iter().max().unwrap_or(&0)
        ),
    )?;
    f.count(
        "failures",
        all.iter().filter(|o| o.failure.is_some()).count(),
    )?;
    // wall time: on how many meshes the uncorrected default is the faster
    let seconds = |solver: Solver, n: usize| {
        all.iter()
            .find(|o| o.solver == solver && o.elements == n)
            .map_or(f64::NAN, |o| o.seconds)
    };
    let faster = MESHES
        .iter()
        .filter(|&&n| seconds(Solver::BfgsNoCorrection, n) < seconds(Solver::Bfgs, n))
        .count();
    f.count("repeats", REPEATS)?;
    f.count("meshes", MESHES.len())?;
    f.timed_number("no_correction_faster", faster as f64, Format::Plain)
}
// ANCHOR_END: facts
