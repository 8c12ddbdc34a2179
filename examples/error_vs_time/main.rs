//! Accuracy per second: the program behind the chapter "Accuracy per
//! second". IGA p = 2, 3, 4 and FEM Q1, Q2 over a ladder of Hertz meshes,
//! each error against a converged fine-mesh reference and against the wall
//! time spent. Output: `book/src/generated/error_vs_time/`.
//!
//! Run it with `cargo run --release --example error_vs_time`.

#[path = "../common/hertz.rs"]
mod setup;

use iga_contact::error::{Error, Result};
use iga_contact::post::hertz::Hertz;
use iga_contact::post::{relative, Errors, PressureProfile, Reference};
use iga_contact::report::chapter::Chapter;
use iga_contact::report::plot::{line_chart, Axes, Series};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, SolverKind, SolverOptions};
use iga_contact::timing::median_time;

// ANCHOR: setup
/// Elements per direction of the ladder.
const LADDER: [usize; 5] = [4, 8, 16, 32, 64];
/// The reference: IGA p = 3 on 128².
const REFERENCE: (usize, usize) = (3, 128);
/// Accuracy targets (relative), with the key the facts use for them.
const TARGETS: [(f64, &str); 3] = [(0.05, "5pct"), (0.01, "1pct"), (0.001, "0_1pct")];

/// A discretisation of the ladder: (`method` and `degree` as in runs.csv).
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
}
// ANCHOR_END: setup

/// One rung, measured.
struct Point {
    method: Method,
    elements: usize,
    dofs: usize,
    iterations: usize,
    /// BFGS, or Newton when BFGS failed (the failure is kept).
    solver: String,
    seconds: f64,
    errors: Errors,
    p0_error_hertz: f64,
    half_width_error_hertz: f64,
}

// ANCHOR: measure
/// Solves one rung with BFGS (Newton if BFGS fails), timing assembly +
/// solve (median of 5 below 32², one run above), and measures it against
/// the reference and against Hertz.
fn measure(method: Method, n: usize, reference: &Reference, exact: &Hertz) -> Result<Point> {
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
            Err(Error::NotConverged { reason, .. }) => {
                solver = format!("Newton (BFGS failed: {reason})");
                continue;
            }
            Err(e) => return Err(e),
        };
        let (problem, solution) = &timed.value;
        let errors = reference.errors(problem, &solution.u, &solution.full)?;
        let m = PressureProfile::dense(problem, &solution.full)?.measures(0);
        return Ok(Point {
            method,
            elements: n,
            dofs: problem.n(),
            iterations: solution.history.len(),
            solver,
            seconds: timed.seconds,
            errors,
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
    points: &[Point],
    method: Method,
    target: f64,
    err: fn(&Point) -> f64,
) -> Option<(f64, usize)> {
    let mine: Vec<&Point> = points.iter().filter(|p| p.method == method).collect();
    (0..mine.len())
        .find(|&i| mine[i..].iter().all(|p| err(p) <= target))
        .map(|i| (mine[i].seconds, mine[i].elements))
}

/// A measured quantity: its key, its name, and its error in a point.
type Quantity = (&'static str, &'static str, fn(&Point) -> f64);

/// The quantities whose errors are plotted and ranked.
const QUANTITIES: [Quantity; 3] = [
    ("p0", "p₀", |p| p.errors.p0),
    ("half_width", "half-width", |p| p.errors.half_width),
    ("pressure_l2", "pressure L2", |p| p.errors.pressure_l2),
];

fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("error_vs_time")?;
    let exact = setup::analytic(&setup::scene(setup::iga(2, 8))?)?;

    // ANCHOR: reference
    let (rp, rn) = REFERENCE;
    let scene = setup::scene(setup::iga(rp, rn))?;
    let problem = scene.build()?;
    let solution = solve(&problem, &SolverOptions::with_kind(SolverKind::Newton))?;
    let reference = Reference::new(&problem, &solution.u, &solution.full)?;
    // ANCHOR_END: reference
    let mut points = Vec::new();
    for m in Method::ALL {
        for n in LADDER {
            points.push(measure(m, n, &reference, &exact)?);
        }
    }

    // ANCHOR: tables
    let mut runs = Table::new(vec![
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
    for p in &points {
        let (method, degree) = p.method.key();
        runs.push(vec![
            method.into(),
            degree.into(),
            p.elements.into(),
            p.dofs.into(),
            p.seconds.into(),
            p.errors.p0.into(),
            p.errors.half_width.into(),
            p.errors.pressure_l2.into(),
            p.errors.energy.into(),
            p.p0_error_hertz.into(),
            p.half_width_error_hertz.into(),
            p.iterations.into(),
            p.solver.clone().into(),
        ])?;
    }
    chapter.table("runs", &runs)?;
    chapter.timed("runs.csv"); // its `seconds` column

    // Which method reaches each target first: seconds (mesh) per method.
    let label = |m: Method| match m {
        Method::Iga(p) => format!("IGA p = {p}"),
        Method::Fem(q) => format!("Q{q}"),
    };
    let mut columns = vec![
        Column::plain("quantity", "quantity"),
        Column::new("target", "target", Unit::None, Format::Percent(1)),
    ];
    let keys = ["iga_p2", "iga_p3", "iga_p4", "fem_q1", "fem_q2"];
    let headers = ["IGA p = 2", "IGA p = 3", "IGA p = 4", "FEM Q1", "FEM Q2"];
    for (k, h) in keys.iter().zip(headers) {
        columns.push(Column::plain(k, h));
    }
    columns.push(Column::plain("first", "first"));
    let mut first = Table::new(columns);
    for (_, name, err) in QUANTITIES.iter().filter(|q| q.0 != "half_width") {
        for (t, _) in TARGETS {
            let mut row: Vec<Cell> = vec![(*name).into(), t.into()];
            let mut best: Option<(f64, Method)> = None;
            for m in Method::ALL {
                row.push(match first_reaching(&points, m, t, *err) {
                    Some((s, n)) => {
                        if best.is_none_or(|(b, _)| s < b) {
                            best = Some((s, m));
                        }
                        format!("{} ms ({n}²)", Format::Fixed(1).render(s * 1e3)).into()
                    }
                    None => Cell::Empty,
                });
            }
            row.push(best.map_or("none".to_string(), |(_, m)| label(m)).into());
            first.push(row)?;
        }
    }
    chapter.table("accuracy_per_second", &first)?;
    chapter.timed("accuracy_per_second.csv");
    chapter.timed("accuracy_per_second.md");
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
    chapter.table("reference", &refs)?;
    // ANCHOR_END: tables

    // ANCHOR: figures
    for (key, name, err) in QUANTITIES {
        let mut series: Vec<Series> = Method::ALL
            .iter()
            .map(|&m| {
                let pts = points
                    .iter()
                    .filter(|p| p.method == m && err(p) > 0.0)
                    .map(|p| (p.seconds, err(p)))
                    .collect();
                Series::line(label(m), pts).with_markers()
            })
            .collect();
        // the targets, as horizontal lines across the measured times
        let (t0, t1) = points.iter().fold((f64::INFINITY, 0.0f64), |(a, b), p| {
            (a.min(p.seconds), b.max(p.seconds))
        });
        for (t, _) in TARGETS {
            let pct = Format::Percent(1).render(t);
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
    // ANCHOR_END: figures

    // ANCHOR: facts
    let f = chapter.facts();
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
    let finest_hertz: Vec<f64> = points
        .iter()
        .filter(|p| p.elements == 64)
        .map(|p| p.p0_error_hertz)
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
    )?;
    for (qk, _, err) in QUANTITIES {
        for (t, tk) in TARGETS {
            for (mk, m) in keys.iter().zip(Method::ALL) {
                let key = format!("{qk}_{tk}_{mk}");
                f.text(
                    &key,
                    first_reaching(&points, m, t, err)
                        .map_or("never".into(), |(_, n)| format!("{n}²")),
                )?;
            }
        }
    }
    // ANCHOR_END: facts
    chapter.finish()
}
