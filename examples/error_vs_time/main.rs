//! Error against run time: the program behind the chapter of that name.
//! IGA p = 2, 3, 4 and FEM Q1, Q2 over a ladder of Hertz meshes, each error
//! against a converged fine-mesh reference and against the wall time spent.
//! Output: `book/src/generated/error_vs_time/`. GetFEM's runs beside ours
//! are the heavy program `getfem_peer` (its peer module is `companion::getfem`).
//!
//! Run it with `cargo run --release --example error_vs_time`.

use companion::hertz as setup;

use companion::chapter::Chapter;
use companion::timing::median_time;
use companion::Facts;
use iga_contact::error::{Error, Result};
use iga_contact::post::hertz::Hertz;
use iga_contact::post::{relative, Errors, PressureProfile, Reference};
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, SolverKind, SolverOptions};

// ANCHOR: setup
/// Elements per direction of the ladder.
const LADDER: [usize; 5] = [4, 8, 16, 32, 64];
/// The reference: IGA p = 3 on 128².
const REFERENCE: (usize, usize) = (3, 128);
/// Accuracy targets (relative), with the key the facts and CSV files use
/// for them and their header in the tables.
const TARGETS: [(f64, &str, &str); 3] = [
    (0.05, "5pct", "5 %"),
    (0.01, "1pct", "1 %"),
    (0.001, "0_1pct", "0.1 %"),
];

/// A discretisation of the ladder (`method` and `degree` as in runs.csv).
#[derive(Clone, Copy, PartialEq)]
enum Method {
    Iga(usize),
    Fem(usize),
}

impl Method {
    const ALL: [Method; 5] = [
        Method::Iga(2),
        Method::Iga(3),
        Method::Iga(4),
        Method::Fem(1),
        Method::Fem(2),
    ];

    fn refine(self, n: usize) -> RefineSpec {
        match self {
            Method::Iga(p) => RefineSpec::iga(p, [n, n]),
            Method::Fem(q) => RefineSpec::lagrange(q, [n, n]),
        }
    }

    fn key(self) -> (&'static str, usize) {
        match self {
            Method::Iga(p) => ("iga", p),
            Method::Fem(q) => ("fem", q),
        }
    }

    /// `iga_p2`, `fem_q1`: the key of the facts.
    fn fact_key(self) -> String {
        match self {
            Method::Iga(p) => format!("iga_p{p}"),
            Method::Fem(q) => format!("fem_q{q}"),
        }
    }

    fn label(self) -> String {
        match self {
            Method::Iga(p) => format!("IGA p = {p}"),
            Method::Fem(q) => format!("FEM Q{q}"),
        }
    }
}
// ANCHOR_END: setup

/// One rung, measured.
struct Point {
    method: Method,
    elements: usize,
    dofs: usize,
    seconds: f64,
    /// Errors against the reference.
    p0: f64,
    half_width: f64,
    pressure_l2: Option<f64>,
}

/// Our rung: the point and what only our runs have.
struct Run {
    point: Point,
    iterations: usize,
    /// BFGS, or Newton when BFGS failed (the failure is kept).
    solver: String,
    energy: f64,
    p0_error_hertz: f64,
    half_width_error_hertz: f64,
}

// ANCHOR: measure
/// Solves one rung with BFGS (Newton if BFGS fails), timing assembly +
/// solve (median of 5 below 32², one run from 32² on), and measures it against
/// the reference and against Hertz.
fn measure(method: Method, n: usize, reference: &Reference, exact: &Hertz) -> Result<Run> {
    let scene = setup::scene(method.refine(n))?;
    let repeats = if n < 32 { 5 } else { 1 };
    let mut solver = "BFGS".to_string();
    for kind in [SolverKind::Bfgs, SolverKind::Newton] {
        let opts = SolverOptions::with_kind(kind);
        let timed = match median_time(repeats, || {
            let problem = scene.build()?;
            let solution = solve(&problem, &opts)?;
            Ok((problem, solution))
        }) {
            Ok(t) => t,
            Err(Error::NotConverged { diagnosis, .. }) => {
                solver = format!("Newton (BFGS failed: {diagnosis})");
                continue;
            }
            Err(e) => return Err(e),
        };
        let (problem, solution) = &timed.value;
        let Errors {
            p0,
            half_width,
            pressure_l2,
            energy,
        } = reference.errors(problem, &solution.u, &solution.full)?;
        let m = PressureProfile::dense(problem, &solution.full)?.measures(0);
        return Ok(Run {
            point: Point {
                method,
                elements: n,
                dofs: problem.n(),
                seconds: timed.seconds,
                p0,
                half_width,
                pressure_l2: Some(pressure_l2),
            },
            iterations: solution.history.len(),
            solver,
            energy,
            p0_error_hertz: relative(m.p0, exact.p0).abs(),
            half_width_error_hertz: relative(m.half_width, exact.half_width).abs(),
        });
    }
    Err(Error::invalid(
        "solver",
        solver,
        "neither BFGS nor Newton converged",
    ))
}
// ANCHOR_END: measure

/// The cheapest run of `method` from which on every finer run meets
/// `target` in `err`: (seconds, elements).
fn first_reaching(
    points: &[&Point],
    method: Method,
    target: f64,
    err: fn(&Point) -> Option<f64>,
) -> Option<(f64, usize)> {
    let mine: Vec<&Point> = points
        .iter()
        .copied()
        .filter(|p| p.method == method && err(p).is_some())
        .collect();
    (0..mine.len())
        .find(|&i| {
            mine[i..]
                .iter()
                .all(|p| err(p).is_some_and(|e| e <= target))
        })
        .map(|i| (mine[i].seconds, mine[i].elements))
}

/// A measured quantity: its key, its name, and its error in a point (if
/// the point has it).
type Quantity = (&'static str, &'static str, fn(&Point) -> Option<f64>);

/// The quantities whose errors are plotted and ranked.
const QUANTITIES: [Quantity; 3] = [
    ("p0", "p₀", |p| Some(p.p0)),
    ("half_width", "half-width", |p| Some(p.half_width)),
    ("pressure_l2", "pressure L2", |p| p.pressure_l2),
];

/// The chapter "Accuracy per second", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("error_vs_time")?;
    let exact = setup::analytic(&setup::scene(setup::iga(2, 8))?)?;

    // How it is measured: the reference, then every rung of the ladder.
    let reference = solve_reference()?;
    let runs = measure_ladder(&reference, &exact)?;
    let points: Vec<&Point> = runs.iter().map(|r| &r.point).collect();

    // Results: every run, Table ET1, and which method reaches a target
    // first.
    chapter.table("runs", &runs_table(&runs)?)?;
    chapter.timed("runs.csv"); // its `seconds` column
    write_first_tables(&mut chapter, &points)?;
    chapter.table("reference", &reference_table(&reference, &exact)?)?;

    // Results: the errors against the time, one figure per quantity.
    draw_errors_against_time(&mut chapter, &points)?;

    // The numbers the prose quotes.
    let f = chapter.facts();
    record_reference_facts(f, &reference, &runs, &exact)?;
    record_target_facts(f, &points)?;
    record_energy_facts(f, &runs)?;
    chapter.finish()
}

// ANCHOR: reference
/// The converged fine-mesh solution every error is measured against.
fn solve_reference() -> Result<Reference> {
    let (rp, rn) = REFERENCE;
    let scene = setup::scene(setup::iga(rp, rn))?;
    let problem = scene.build()?;
    let solution = solve(&problem, &SolverOptions::with_kind(SolverKind::Newton))?;
    Reference::new(&problem, &solution.u, &solution.full)
}
// ANCHOR_END: reference

/// "How it is measured": every method on every mesh of the ladder.
fn measure_ladder(reference: &Reference, exact: &Hertz) -> Result<Vec<Run>> {
    let mut runs = Vec::new();
    for m in Method::ALL {
        for n in LADDER {
            runs.push(measure(m, n, reference, exact)?);
        }
    }
    Ok(runs)
}

// ANCHOR: tables
/// "Results": every run with its errors (`runs.csv`, in the book without
/// the seconds).
fn runs_table(runs: &[Run]) -> Result<Table> {
    let mut table = Table::new(vec![
        Column::plain("method", "method"),
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::new("seconds", "seconds", Unit::Second, Format::Sci(2)).csv_only(),
        Column::new("p0_error", "p₀", Unit::None, Format::Sci(1)),
        Column::new("half_width_error", "a", Unit::None, Format::Sci(1)),
        Column::new(
            "pressure_l2_error",
            "pressure L2",
            Unit::None,
            Format::Sci(1),
        ),
        Column::new("energy_error", "energy", Unit::None, Format::Sci(1)),
        Column::new("p0_error_hertz", "p₀ vs Hertz", Unit::None, Format::Sci(1)).csv_only(),
        Column::new(
            "half_width_error_hertz",
            "a vs Hertz",
            Unit::None,
            Format::Sci(1),
        )
        .csv_only(),
        Column::plain("iterations", "iterations").csv_only(),
        Column::plain("solver", "solver").csv_only(),
    ]);
    for r in runs {
        let (method, degree) = r.point.method.key();
        table.push(vec![
            method.into(),
            degree.into(),
            r.point.elements.into(),
            r.point.dofs.into(),
            r.point.seconds.into(),
            r.point.p0.into(),
            r.point.half_width.into(),
            r.point.pressure_l2.map_or(Cell::Empty, Cell::from),
            r.energy.into(),
            r.p0_error_hertz.into(),
            r.half_width_error_hertz.into(),
            r.iterations.into(),
            r.solver.clone().into(),
        ])?;
    }
    Ok(table)
}

/// "Which method reaches a target first": one table per quantity, a row
/// per method, a column per target (timed: the cells are seconds).
fn write_first_tables(chapter: &mut Chapter, points: &[&Point]) -> Result<()> {
    for (key, _, err) in QUANTITIES {
        let mut columns = vec![Column::plain("method", "method")];
        for (_, key, header) in TARGETS {
            columns.push(Column::plain(key, header));
        }
        let mut first = Table::new(columns);
        let mut best: Vec<Option<(f64, Method)>> = vec![None; TARGETS.len()];
        let mut rows = Vec::new();
        for m in Method::ALL {
            if !points.iter().any(|p| p.method == m && err(p).is_some()) {
                continue;
            }
            let mut row: Vec<Cell> = vec![m.label().into()];
            for (k, (t, _, _)) in TARGETS.iter().enumerate() {
                row.push(match first_reaching(points, m, *t, err) {
                    Some((s, n)) => {
                        if best[k].is_none_or(|(b, _)| s < b) {
                            best[k] = Some((s, m));
                        }
                        format!("{} ({n}²)", human_seconds(s)).into()
                    }
                    None => Cell::Empty,
                });
            }
            rows.push(row);
        }
        let mut last: Vec<Cell> = vec!["first".into()];
        last.extend(
            best.iter()
                .map(|b| b.map_or(Cell::from("none"), |(_, m)| m.label().into())),
        );
        for row in rows.into_iter().chain([last]) {
            first.push(row)?;
        }
        let stem = format!("first_{key}");
        chapter.table(&stem, &first)?;
        chapter.timed(&format!("{stem}.csv"));
        chapter.timed(&format!("{stem}.md"));
    }
    Ok(())
}

/// Table ET1: the reference and Hertz's values.
fn reference_table(reference: &Reference, exact: &Hertz) -> Result<Table> {
    let (rp, rn) = REFERENCE;
    let mut refs = Table::new(vec![
        Column::plain("solution", "solution"),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(3)),
        Column::new(
            "energy",
            "strain energy",
            Unit::JoulePerMetre,
            Format::Fixed(2),
        ),
    ]);
    refs.push(vec![
        format!("reference: IGA p = {rp}, {rn}²").into(),
        reference.measures.p0.into(),
        reference.measures.half_width.into(),
        reference.energy.into(),
    ])?;
    refs.push(vec![
        "Hertz".into(),
        exact.p0.into(),
        exact.half_width.into(),
        Cell::Empty,
    ])?;
    Ok(refs)
}
// ANCHOR_END: tables

// ANCHOR: figures
/// "Results": each quantity's error against the wall time, with the
/// targets as horizontal lines (timed: the abscissae are seconds).
fn draw_errors_against_time(chapter: &mut Chapter, points: &[&Point]) -> Result<()> {
    for (key, name, err) in QUANTITIES {
        let line = |m: Method| {
            let pts = points
                .iter()
                .filter(|p| p.method == m)
                .filter_map(|p| err(p).filter(|e| *e > 0.0).map(|e| (p.seconds, e)))
                .collect();
            Series::line(m.label(), pts).with_markers()
        };
        let mut series: Vec<Series> = Method::ALL.into_iter().map(line).collect();
        // the targets, as horizontal lines across the times plotted
        let plotted: Vec<&Point> = points
            .iter()
            .copied()
            .filter(|p| err(p).is_some())
            .collect();
        let (t0, t1) = plotted.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(p.seconds), b.max(p.seconds))
        });
        for (t, _, pct) in TARGETS {
            series.push(Series::line(format!("target {pct}"), vec![(t0, t), (t1, t)]).dashed());
        }
        chapter.timed(&format!("{key}_vs_time.svg"));
        line_chart(
            chapter.path(&format!("{key}_vs_time.svg")),
            &Axes {
                title: format!("{name} error against wall time"),
                x_label: "assembly + solve (s)".into(),
                y_label: format!("relative {name} error"),
                log_x: true,
                log_y: true,
            },
            &series,
        )?;
    }
    Ok(())
}
// ANCHOR_END: figures

// ANCHOR: facts
/// "How it is measured" and "Discussion" quote how far the reference and
/// the finest meshes lie from Hertz.
fn record_reference_facts(
    f: &mut Facts,
    reference: &Reference,
    runs: &[Run],
    exact: &Hertz,
) -> Result<()> {
    f.number(
        "reference_p0_vs_hertz",
        relative(reference.measures.p0, exact.p0),
        Format::SignedPercent(1),
    )?;
    f.number(
        "reference_a_vs_hertz",
        relative(reference.measures.half_width, exact.half_width),
        Format::SignedPercent(1),
    )?;
    let finest_hertz: Vec<f64> = runs
        .iter()
        .filter(|r| r.point.elements == 64)
        .map(|r| r.p0_error_hertz)
        .collect();
    let (lo, hi) = finest_hertz
        .iter()
        .fold((f64::INFINITY, 0.0f64), |(a, b), &e| (a.min(e), b.max(e)));
    f.text(
        "finest_p0_vs_hertz",
        format!(
            "{}–{}",
            Format::Percent(1).render(lo).trim_end_matches(" %"),
            Format::Percent(1).render(hi)
        ),
    )
}

/// "Which method reaches a target first": which method reaches each
/// target first in time, and on the coarsest mesh, per quantity and
/// target.
fn record_target_facts(f: &mut Facts, points: &[&Point]) -> Result<()> {
    let (mut reached, mut iga_first, mut iga_first_cells) = (0, 0, Vec::new());
    for (qk, qname, err) in QUANTITIES {
        for (t, tk, th) in TARGETS {
            let mut fastest: Option<(f64, Method)> = None;
            for m in Method::ALL {
                let reached = first_reaching(points, m, t, err);
                if let Some((s, _)) = reached {
                    if fastest.is_none_or(|(b, _)| s < b) {
                        fastest = Some((s, m));
                    }
                }
                let mesh = reached.map_or("never".into(), |(_, n)| format!("{n}²"));
                f.text(&format!("{qk}_{tk}_{}", m.fact_key()), mesh)?;
            }
            if let Some((_, m)) = fastest {
                reached += 1;
                if matches!(m, Method::Iga(_)) {
                    iga_first += 1;
                    iga_first_cells.push(format!("{qname} {th}"));
                }
            }
        }
    }
    f.timed_number("targets_reached", reached as f64, Format::Plain)?;
    f.timed_number("targets_iga_first", iga_first as f64, Format::Plain)?;
    f.timed_text("targets_iga_first_list", iga_first_cells.join(", "))
}

/// "Discussion" names the methods along which the energy indicator rises
/// somewhere from one mesh to the next.
fn record_energy_facts(f: &mut Facts, runs: &[Run]) -> Result<()> {
    let rising: Vec<String> = Method::ALL
        .iter()
        .filter(|&&m| {
            let e: Vec<f64> = runs
                .iter()
                .filter(|r| r.point.method == m)
                .map(|r| r.energy)
                .collect();
            e.windows(2).any(|w| w[1] > w[0])
        })
        .map(|m| m.label())
        .collect();
    f.count("energy_rising_methods", rising.len())?;
    f.text("energy_rising_list", rising.join(", "))
}
// ANCHOR_END: facts

/// A time in the unit that keeps it short: 0.8 ms, 27.5 ms, 5.06 s.
fn human_seconds(s: f64) -> String {
    if s < 1.0 {
        format!("{} ms", Format::Fixed(1).render(s * 1e3))
    } else {
        format!("{} s", Format::Fixed(2).render(s))
    }
}
