//! IGA against FEM on the paper's coarse Hertz mesh: the program behind the
//! chapter "IGA against FEM on the coarse mesh".
//!
//! The exact NURBS half disk with p = 2 is compared with isoparametric
//! Lagrange Q1 and Q2 meshes of the same 8×8 elements (nodes on the exact
//! circle), all with the same Nitsche contact and the same solver, beside
//! the paper's single-thread figures. Output: `book/src/generated/iga_vs_fem/`.
//!
//! Run it with `cargo run --release --example iga_vs_fem`.

use companion::hertz as setup;

use companion::chapter::Chapter;
use companion::timing::median_time;
use companion::Facts;
use iga_contact::error::{Error, Result};
use iga_contact::post::hertz::Hertz;
use iga_contact::post::{relative, PressureProfile};
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, SolverKind, SolverOptions};

// ANCHOR: paper
/// The paper's 8×8 single-thread comparison: total time (s) and the largest
/// contact-stress error (relative).
const PAPER_IGA_SECONDS: f64 = 323.0;
const PAPER_FEM_SECONDS: f64 = 213.0;
const PAPER_IGA_ERROR: f64 = 0.0991;
const PAPER_FEM_ERROR: f64 = 0.287;
// ANCHOR_END: paper

/// The paper's mesh, elements per direction.
const ELEMENTS: usize = 8;
/// Timing repeats per method (the median is kept).
const REPEATS: usize = 11;

// ANCHOR: methods
/// The three discretisations compared: their label and refinement.
fn methods() -> [(&'static str, RefineSpec); 3] {
    let n = [ELEMENTS, ELEMENTS];
    [
        ("IGA p = 2", RefineSpec::iga(2, n)),
        ("FEM Q1", RefineSpec::lagrange(1, n)),
        ("FEM Q2", RefineSpec::lagrange(2, n)),
    ]
}
// ANCHOR_END: methods

/// One method, solved and measured.
struct Row {
    label: &'static str,
    dofs: usize,
    iterations: usize,
    corrections: usize,
    /// The solver that produced the solution: BFGS, or Newton if BFGS failed.
    solver: String,
    profile: PressureProfile,
    /// Median seconds, default solver, the machine's threads.
    seconds: f64,
    /// Median seconds, default solver, one thread: with `seconds` it
    /// separates the effect of the threads from that of the solver.
    one_thread_seconds: f64,
    /// Median seconds of the paper's iteration on one thread, the paper's
    /// setting; `None` if it did not converge.
    paper_seconds: Option<f64>,
    /// Iterations and corrections of the paper's iteration (`None` if it
    /// did not converge): the time ratios of Table F2 compare these solves,
    /// not those of the default solver.
    paper_iterations: Option<(usize, usize)>,
}

// ANCHOR: run
/// Builds and solves one method `REPEATS` times with the default BFGS and
/// keeps the median time of assembly + solve. If BFGS does not converge,
/// that is recorded and the method is measured with Newton instead. Then
/// the same solver on one thread, and the paper's setting: its iteration
/// (the scene's `[solver]`) on one thread.
fn measure(label: &'static str, refine: RefineSpec) -> Result<Row> {
    let scene = setup::scene(refine)?;
    let mut solver = "BFGS".to_string();
    let mut timed = None;
    for kind in [SolverKind::Bfgs, SolverKind::Newton] {
        let opts = SolverOptions::with_kind(kind);
        match median_time(REPEATS, || {
            let problem = scene.build()?;
            let solution = solve(&problem, &opts)?;
            Ok((problem, solution))
        }) {
            Ok(t) => {
                timed = Some((t, opts));
                break;
            }
            Err(Error::NotConverged { diagnosis, .. }) => {
                solver = format!("Newton (BFGS failed: {diagnosis})")
            }
            Err(e) => return Err(e),
        }
    }
    let (timed, opts) =
        timed.ok_or_else(|| Error::invalid(label, &solver, "no solver converged"))?;
    let one_thread = rayon::ThreadPoolBuilder::new()
        .num_threads(1)
        .build()
        .map_err(|e| Error::invalid("thread pool", 1, e.to_string()))?;
    let one_thread_seconds = one_thread
        .install(|| {
            median_time(REPEATS, || {
                let problem = scene.build()?;
                solve(&problem, &opts)
            })
        })?
        .seconds;
    let paper = one_thread.install(|| {
        median_time(REPEATS, || {
            let problem = scene.build()?;
            solve(&problem, &scene.solver)
        })
    });
    let (paper_seconds, paper_iterations) = match paper {
        Ok(t) => (
            Some(t.seconds),
            Some((t.value.history.len(), t.value.history.corrections())),
        ),
        Err(Error::NotConverged { .. }) => (None, None),
        Err(e) => return Err(e),
    };
    let (problem, solution) = timed.value;
    Ok(Row {
        label,
        dofs: problem.n(),
        iterations: solution.history.len(),
        corrections: solution.history.corrections(),
        solver,
        profile: PressureProfile::dense(&problem, &solution.full)?,
        seconds: timed.seconds,
        one_thread_seconds,
        paper_seconds,
        paper_iterations,
    })
}
// ANCHOR_END: run

/// The chapter "IGA against FEM on the coarse mesh", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("iga_vs_fem")?;
    let exact = setup::analytic(&setup::scene(setup::iga(2, ELEMENTS))?)?;
    let reference = hertz_reference()?;
    let rows = methods()
        .into_iter()
        .map(|(label, refine)| measure(label, refine))
        .collect::<Result<Vec<_>>>()?;

    // Results: Tables F1 and F2.
    chapter.table("comparison", &comparison_table(&rows, &exact, reference)?)?;
    chapter.table("timings", &timings_table(&rows)?)?;
    chapter.timed("timings.csv");
    chapter.timed("timings.md");

    // The numbers the prose quotes.
    let f = chapter.facts();
    record_setting_facts(f)?;
    record_method_facts(f, &rows, &exact, reference)?;
    record_gap_facts(f, &rows, reference)?;

    // Results: Fig. F1.
    profile_figure(&chapter, &rows, &exact)?;
    chapter.finish()
}

/// p₀ and a of the disk's converged solution (the Hertz chapter's
/// reference, p = 3, 128²): Hertz's formula is itself off this model by
/// about 1–2 %, so the errors are given against both.
fn hertz_reference() -> Result<(f64, f64)> {
    let hertz_facts = companion::facts("hertz")?;
    let reference = |key: &str, scale: f64| {
        hertz_facts
            .value(key)
            .map(|v| v * scale)
            .ok_or_else(|| Error::invalid("hertz facts", key, "missing"))
    };
    Ok((
        reference("reference_p0_mpa", 1e6)?,
        reference("reference_a_mm", 1e-3)?,
    ))
}

// ANCHOR: tables
/// Table F1: the three methods' DOFs, iterations, and errors against Hertz
/// and the reference, beside the paper's errors.
fn comparison_table(rows: &[Row], exact: &Hertz, (ref_p0, ref_a): (f64, f64)) -> Result<Table> {
    let mut comparison = Table::new(vec![
        Column::plain("method", "method"),
        Column::plain("dofs", "DOFs"),
        Column::plain("iterations", "default: its (corr.)"),
        Column::plain("paper_iterations", "paper's: its (corr.)"),
        // the values themselves in the CSV only: the Markdown table keeps to
        // the errors, to fit the page
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)).csv_only(),
        Column::new(
            "p0_error",
            "p₀ vs Hertz",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(2)).csv_only(),
        Column::new(
            "half_width_error",
            "a vs Hertz",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::new(
            "p0_vs_reference",
            "p₀ vs ref.",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::new(
            "half_width_vs_reference",
            "a vs ref.",
            Unit::None,
            Format::SignedPercent(2),
        ),
        Column::plain("corrections", "corrections").csv_only(),
        Column::plain("solver", "solver").csv_only(),
    ]);
    for r in rows {
        let m = r.profile.measures(0);
        comparison.push(vec![
            r.label.into(),
            r.dofs.into(),
            format!("{} ({})", r.iterations, r.corrections).into(),
            r.paper_iterations
                .map_or_else(|| "failed".to_string(), |(i, c)| format!("{i} ({c})"))
                .into(),
            m.p0.into(),
            relative(m.p0, exact.p0).into(),
            m.half_width.into(),
            relative(m.half_width, exact.half_width).into(),
            relative(m.p0, ref_p0).into(),
            relative(m.half_width, ref_a).into(),
            r.corrections.into(),
            r.solver.clone().into(),
        ])?;
    }
    // The paper's rows: it reports one error per method, the largest
    // contact-stress error, and no p₀, a or DOFs.
    // (the paper's precision: 9.91 %, 28.7 %)
    for (label, error, digits) in [
        ("the paper: IGA", PAPER_IGA_ERROR, 2),
        ("the paper: FEM (element not stated)", PAPER_FEM_ERROR, 1),
    ] {
        let text = format!(
            "{} (max stress error)",
            Format::Percent(digits).render(error)
        );
        comparison.push(vec![
            label.into(),
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
            text.into(),
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
            Cell::Empty,
        ])?;
    }
    Ok(comparison)
}

/// Table F2: the wall times of the three methods (the paper's setting,
/// then the default on one thread and on all), beside the paper's.
fn timings_table(rows: &[Row]) -> Result<Table> {
    let mut timings = Table::new(vec![
        Column::plain("method", "method"),
        Column::plain("solver", "solver, threads"),
        Column::plain("time", "assembly + solve"),
        Column::new(
            "ratio",
            "IGA time / method time",
            Unit::None,
            Format::Times(2),
        ),
        Column::plain("repeats", "repeats").csv_only(),
    ]);
    let ms = |s: f64| format!("{} ms", Format::Fixed(2).render(1e3 * s));
    let threads = rayon::current_num_threads();
    let iga_seconds = rows[0].seconds;
    let iga_one_thread_seconds = rows[0].one_thread_seconds;
    let iga_paper_seconds = rows[0].paper_seconds;
    for r in rows {
        timings.push(vec![
            r.label.into(),
            "the paper's BFGS, 1 thread".into(),
            r.paper_seconds
                .map_or_else(|| "not converged".to_string(), ms)
                .into(),
            match (iga_paper_seconds, r.paper_seconds) {
                (Some(i), Some(m)) => (i / m).into(),
                _ => Cell::Empty,
            },
            REPEATS.into(),
        ])?;
    }
    for r in rows {
        timings.push(vec![
            r.label.into(),
            "default, 1 thread".into(),
            ms(r.one_thread_seconds).into(),
            (iga_one_thread_seconds / r.one_thread_seconds).into(),
            REPEATS.into(),
        ])?;
    }
    for r in rows {
        timings.push(vec![
            r.label.into(),
            format!("default, {threads} threads").into(),
            ms(r.seconds).into(),
            (iga_seconds / r.seconds).into(),
            REPEATS.into(),
        ])?;
    }
    for (label, seconds, ratio) in [
        ("the paper: IGA", PAPER_IGA_SECONDS, Some(1.0)),
        (
            "the paper: FEM",
            PAPER_FEM_SECONDS,
            Some(PAPER_IGA_SECONDS / PAPER_FEM_SECONDS),
        ),
    ] {
        timings.push(vec![
            label.into(),
            "the paper's BFGS, 1 thread".into(),
            format!("{} s", Format::Fixed(0).render(seconds)).into(),
            ratio.map_or(Cell::Empty, Cell::from),
            Cell::Empty,
        ])?;
    }
    Ok(timings)
}
// ANCHOR_END: tables

// ANCHOR: facts
/// "How it is measured" and the paper's side of "Results": the mesh, the
/// repeats, the threads, and the paper's own numbers.
fn record_setting_facts(f: &mut Facts) -> Result<()> {
    f.count("elements", ELEMENTS)?;
    f.count("repeats", REPEATS)?;
    f.timed_number(
        "threads",
        rayon::current_num_threads() as f64,
        Format::Plain,
    )?;
    f.number("paper_iga_error", PAPER_IGA_ERROR, Format::Percent(2))?;
    f.number("paper_fem_error", PAPER_FEM_ERROR, Format::Percent(1))?;
    f.number("paper_iga_seconds", PAPER_IGA_SECONDS, Format::Fixed(0))?;
    f.number("paper_fem_seconds", PAPER_FEM_SECONDS, Format::Fixed(0))?;
    f.number(
        "paper_ratio",
        PAPER_IGA_SECONDS / PAPER_FEM_SECONDS,
        Format::Times(2),
    )
}

/// "Discussion" quotes each method's errors, iterations and time ratios.
fn record_method_facts(
    f: &mut Facts,
    rows: &[Row],
    exact: &Hertz,
    (ref_p0, ref_a): (f64, f64),
) -> Result<()> {
    let iga_seconds = rows[0].seconds;
    let iga_one_thread_seconds = rows[0].one_thread_seconds;
    let iga_paper_seconds = rows[0].paper_seconds;
    // the time ratios are printed as Table F2 prints them, two decimals, so
    // that prose and table show the same figure
    for (key, r) in ["iga", "q1", "q2"].iter().zip(rows) {
        let m = r.profile.measures(0);
        f.number(
            &format!("{key}_p0_error"),
            relative(m.p0, exact.p0).abs(),
            Format::Percent(1),
        )?;
        f.number(
            &format!("{key}_a_error"),
            relative(m.half_width, exact.half_width).abs(),
            Format::Percent(1),
        )?;
        f.number(
            &format!("{key}_p0_vs_reference"),
            relative(m.p0, ref_p0).abs(),
            Format::Percent(1),
        )?;
        f.number(
            &format!("{key}_a_vs_reference"),
            relative(m.half_width, ref_a).abs(),
            Format::Percent(1),
        )?;
        f.count(&format!("{key}_dofs"), r.dofs)?;
        f.count(&format!("{key}_iterations"), r.iterations)?;
        f.count(&format!("{key}_corrections"), r.corrections)?;
        if let Some((i, c)) = r.paper_iterations {
            f.count(&format!("{key}_paper_iterations"), i)?;
            f.count(&format!("{key}_paper_corrections"), c)?;
        }
        f.number(&format!("{key}_p0_mpa"), m.p0 * 1e-6, Format::Fixed(5))?;
        f.number(&format!("{key}_a_mm"), m.half_width * 1e3, Format::Fixed(4))?;
        f.timed_number(
            &format!("{key}_ratio"),
            iga_seconds / r.seconds,
            Format::Times(2),
        )?;
        f.timed_number(
            &format!("{key}_one_thread_ratio"),
            iga_one_thread_seconds / r.one_thread_seconds,
            Format::Times(2),
        )?;
        if let (Some(i), Some(m)) = (iga_paper_seconds, r.paper_seconds) {
            f.timed_number(&format!("{key}_paper_ratio"), i / m, Format::Times(2))?;
        }
        f.text(
            &format!("{key}_paper_converged"),
            if r.paper_seconds.is_some() {
                "yes"
            } else {
                "no"
            },
        )?;
        f.text(&format!("{key}_solver"), r.solver.clone())?;
    }
    Ok(())
}

/// "Discussion" sets the gap between Q1 and IGA, as the ratio of their
/// errors against the reference, beside the paper's ratio of its two
/// errors.
fn record_gap_facts(f: &mut Facts, rows: &[Row], (ref_p0, ref_a): (f64, f64)) -> Result<()> {
    let (iga, q1) = (rows[0].profile.measures(0), rows[1].profile.measures(0));
    let gap =
        |q1: f64, iga: f64, reference: f64| relative(q1, reference) / relative(iga, reference);
    f.number("gap_p0", gap(q1.p0, iga.p0, ref_p0), Format::Times(1))?;
    f.number(
        "gap_a",
        gap(q1.half_width, iga.half_width, ref_a),
        Format::Times(1),
    )?;
    f.number(
        "paper_gap",
        PAPER_FEM_ERROR / PAPER_IGA_ERROR,
        Format::Times(1),
    )
}
// ANCHOR_END: facts

/// Fig. F1: the three profiles against Hertz, in mm and MPa, up to 1.5 a.
fn profile_figure(chapter: &Chapter, rows: &[Row], exact: &Hertz) -> Result<()> {
    let x_max = 1.5 * exact.half_width;
    let mut series: Vec<Series> = rows
        .iter()
        .map(|r| {
            let pts = r
                .profile
                .pair(0)
                .iter()
                .filter(|s| s.x[0] <= x_max)
                .map(|s| (s.x[0] * 1e3, s.pressure() * 1e-6))
                .collect();
            Series::line(r.label, pts)
        })
        .collect();
    let ellipse = (0..=300)
        .map(|k| {
            let x = x_max * k as f64 / 300.0;
            (x * 1e3, exact.pressure(x) * 1e-6)
        })
        .collect();
    series.push(Series::line("Hertz", ellipse).dashed());
    line_chart(
        chapter.path("pressure_profiles.svg"),
        &Axes {
            title: format!("Contact pressure, Hertz {ELEMENTS}×{ELEMENTS}"),
            x_label: "x (mm)".into(),
            y_label: "pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )
}
