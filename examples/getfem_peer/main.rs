//! GetFEM beside ours, in one run: the heavy part of the chapter "Error
//! against run time". On the same Hertz ladder, the same machine and the
//! same accuracy targets, it runs GetFEM (Q1, Q2: `scripts/getfem_hertz.py`
//! as a child process, with Debian's `python3-getfem`) and then ours (IGA
//! p = 2, 3, 4, FEM Q1, Q2), both at the penalty of Eq. (11) with the
//! factors [`FACTORS`], and writes one set of tables with both to
//! `book/src/generated/getfem_peer/`.
//!
//! Without GetFEM the program says so and leaves the folder, with the date
//! and machine of its last run, as it is.
//!
//! `cargo run --release --example getfem_peer` (a few minutes).

use companion::getfem;
use companion::hertz as setup;

use companion::chapter::Chapter;
use companion::timing::{median_time, Machine};
use iga_contact::error::{Error, Result};
use iga_contact::post::{relative, Reference};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, SolverKind, SolverOptions};
use std::process::ExitCode;

// ANCHOR: setup
/// Elements per direction: the ladder of the chapter.
const LADDER: [usize; 5] = [4, 8, 16, 32, 64];
/// The penalty factors F of Eq. (11), for both codes: 1 is the paper's,
/// 10 a stiffer one, on which GetFEM's Newton converges on more rungs.
const FACTORS: [f64; 2] = [1.0, 10.0];
/// The reference: IGA p = 3 on 128², Newton, at the paper's penalty.
const REFERENCE: (usize, usize) = (3, 128);
/// Accuracy targets (relative), their key and header.
const TARGETS: [(f64, &str, &str); 3] = [
    (0.05, "5pct", "5 %"),
    (0.01, "1pct", "1 %"),
    (0.001, "0_1pct", "0.1 %"),
];
// ANCHOR_END: setup

/// A discretisation of either code.
#[derive(Clone, Copy, Debug, PartialEq)]
enum Method {
    Iga(usize),
    Fem(usize),
    GetFem(usize),
}

impl Method {
    const OURS: [Method; 5] = [
        Method::Iga(2),
        Method::Iga(3),
        Method::Iga(4),
        Method::Fem(1),
        Method::Fem(2),
    ];
    const PEER: [Method; 2] = [Method::GetFem(1), Method::GetFem(2)];

    fn label(self) -> String {
        match self {
            Method::Iga(p) => format!("IGA p = {p}"),
            Method::Fem(q) => format!("FEM Q{q}"),
            Method::GetFem(q) => format!("GetFEM Q{q}"),
        }
    }

    fn key(self) -> String {
        match self {
            Method::Iga(p) => format!("iga_p{p}"),
            Method::Fem(q) => format!("fem_q{q}"),
            Method::GetFem(q) => format!("getfem_q{q}"),
        }
    }

    fn ours(self) -> bool {
        !matches!(self, Method::GetFem(_))
    }
}

/// One rung of either code at one penalty factor.
struct Run {
    method: Method,
    factor: f64,
    elements: usize,
    dofs: usize,
    iterations: usize,
    converged: bool,
    /// Ours: `Scene::build`; GetFEM: its model set-up.
    setup: f64,
    solve: f64,
    /// Errors against the reference (`None` when not converged).
    p0: Option<f64>,
    half_width: Option<f64>,
    /// p₀ by the GetFEM script's estimator.
    p0_peer_estimator: Option<f64>,
}

impl Run {
    fn total(&self) -> f64 {
        self.setup + self.solve
    }
}

// ANCHOR: measure
/// Our rung: build and solve timed apart (medians of 5 below 32², one run
/// above), the default solver.
fn ours(method: Method, n: usize, factor: f64, reference: &Reference) -> Result<Run> {
    let refine = match method {
        Method::Iga(p) => RefineSpec::iga(p, [n, n]),
        Method::Fem(q) => RefineSpec::lagrange(q, [n, n]),
        Method::GetFem(_) => unreachable!("GetFEM's rungs are the script's"),
    };
    let scene = setup::scene(refine)?.with_nitsche(|nit| nit.penalty_factor = factor);
    let repeats = if n < 32 { 5 } else { 1 };
    let build = median_time(repeats, || scene.build())?;
    let problem = build.value;
    let opts = SolverOptions::default();
    let mut run = Run {
        method,
        factor,
        elements: n,
        dofs: problem.n(),
        iterations: 0,
        converged: false,
        setup: build.seconds,
        solve: f64::NAN,
        p0: None,
        half_width: None,
        p0_peer_estimator: None,
    };
    match median_time(repeats, || solve(&problem, &opts)) {
        Ok(t) => {
            let s = &t.value;
            let e = reference.errors(&problem, &s.u, &s.full)?;
            run.iterations = s.history.len();
            run.converged = true;
            run.solve = t.seconds;
            run.p0 = Some(e.p0);
            run.half_width = Some(e.half_width);
            run.p0_peer_estimator = Some(getfem::peak_pressure(&problem, &s.full)?);
        }
        Err(Error::NotConverged { history, .. }) => run.iterations = history.len(),
        Err(e) => return Err(e),
    }
    Ok(run)
}
// ANCHOR_END: measure

/// The cheapest converged run of `method` at `factor` from which on every
/// finer run converges and meets `target` in `err`: (seconds by `time`,
/// elements).
fn first_reaching(
    runs: &[Run],
    method: Method,
    factor: f64,
    target: f64,
    err: fn(&Run) -> Option<f64>,
    time: fn(&Run) -> f64,
) -> Option<(f64, usize)> {
    let mine: Vec<&Run> = runs
        .iter()
        .filter(|r| r.method == method && r.factor == factor)
        .collect();
    (0..mine.len())
        .find(|&i| {
            mine[i..]
                .iter()
                .all(|r| err(r).is_some_and(|e| e <= target))
        })
        .map(|i| (time(mine[i]), mine[i].elements))
}

/// A time in the unit that keeps it short: 0.8 ms, 27.5 ms, 5.06 s.
fn human_seconds(s: f64) -> String {
    if s < 1.0 {
        format!("{} ms", Format::Fixed(1).render(s * 1e3))
    } else {
        format!("{} s", Format::Fixed(2).render(s))
    }
}

/// A quantity compared: key, name, its error in a run.
type Quantity = (&'static str, &'static str, fn(&Run) -> Option<f64>);
const QUANTITIES: [Quantity; 2] = [
    ("p0", "p₀", |r| r.p0),
    ("half_width", "half-width", |r| r.half_width),
];

fn factor_key(f: f64) -> String {
    format!("f{f}")
}

fn main() -> ExitCode {
    if !getfem::available() {
        eprintln!(
            "getfem_peer: GetFEM is not installed ({} cannot import getfem; `apt-get install \
             python3-getfem`): nothing run, book/src/generated/getfem_peer/ keeps its last \
             measured run (its facts give the date and machine)",
            getfem::PYTHON
        );
        return ExitCode::SUCCESS;
    }
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("getfem_peer: {e}");
            ExitCode::FAILURE
        }
    }
}

fn run() -> Result<()> {
    let mut chapter = Chapter::from_args("getfem_peer")?;
    let machine = Machine::here();

    // ANCHOR: reference
    let (rp, rn) = REFERENCE;
    let problem = setup::scene(setup::iga(rp, rn))?.build()?;
    let solution = solve(&problem, &SolverOptions::with_kind(SolverKind::Newton))?;
    let reference = Reference::new(&problem, &solution.u, &solution.full)?;
    // p₀ of the same solution as the GetFEM script measures its own, and
    // the script's estimator of a on it
    let peer_p0 = getfem::peak_pressure(&problem, &solution.full)?;
    let (gap_zero, overlapping) = getfem::first_gap_zero(&problem, &solution.full)?;
    drop((problem, solution));
    // ANCHOR_END: reference

    // GetFEM first, then ours, on the same ladder and factors
    eprintln!("GetFEM …");
    let peer = getfem::run(&LADDER, &FACTORS)?;
    let mut runs: Vec<Run> = peer
        .runs
        .iter()
        .map(|r| Run {
            method: Method::GetFem(r.degree),
            factor: r.factor,
            elements: r.elements,
            dofs: r.dofs,
            iterations: r.newton_iterations,
            converged: r.converged,
            setup: r.setup_seconds,
            solve: r.solve_seconds,
            p0: r.converged.then(|| relative(r.p0, peer_p0).abs()),
            half_width: r
                .converged
                .then(|| relative(r.half_width, reference.measures.half_width).abs()),
            p0_peer_estimator: r.converged.then_some(r.p0),
        })
        .collect();
    for &f in &FACTORS {
        for m in Method::OURS {
            for n in LADDER {
                eprintln!("F = {f}, {}, {n}² …", m.label());
                runs.push(ours(m, n, f, &reference)?);
            }
        }
    }
    let methods: Vec<Method> = Method::OURS.into_iter().chain(Method::PEER).collect();

    // ANCHOR: tables
    let mut all = Table::new(vec![
        Column::plain("method", "method"),
        Column::plain("factor", "F"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::plain("iterations", "iterations"),
        Column::plain("converged", "converged"),
        Column::new("setup_seconds", "set-up", Unit::Second, Format::Sci(2)),
        Column::new("solve_seconds", "solve", Unit::Second, Format::Sci(2)),
        Column::new("p0_error", "p₀ error", Unit::None, Format::Sci(1)),
        Column::new("half_width_error", "a error", Unit::None, Format::Sci(1)),
        Column::new(
            "p0_getfem_estimator",
            "p₀ (GetFEM's estimator)",
            Unit::Megapascal,
            Format::Fixed(4),
        ),
    ]);
    for r in &runs {
        let opt = |v: Option<f64>| v.map_or(Cell::Empty, Cell::from);
        all.push(vec![
            r.method.label().into(),
            Format::Plain.render(r.factor).into(),
            r.elements.into(),
            r.dofs.into(),
            r.iterations.into(),
            if r.converged { "yes" } else { "no" }.into(),
            r.setup.into(),
            if r.solve.is_finite() {
                r.solve.into()
            } else {
                Cell::Empty
            },
            opt(r.p0),
            opt(r.half_width),
            opt(r.p0_peer_estimator),
        ])?;
    }
    chapter.csv("runs", &all)?;

    // Iterations on the same mesh: GetFEM's Newton and our default solver
    let mut its = vec![
        Column::plain("factor", "F"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
    ];
    for m in &methods {
        // a column per method: seven names for the life of the program
        let (key, label) = (m.key().leak(), m.label().leak());
        its.push(Column::plain(key, label));
    }
    let mut iterations = Table::new(its);
    for &f in &FACTORS {
        for n in LADDER {
            let mut row: Vec<Cell> = vec![Format::Plain.render(f).into(), n.into()];
            for &m in &methods {
                let r = runs
                    .iter()
                    .find(|r| r.method == m && r.factor == f && r.elements == n)
                    .expect("every rung ran");
                row.push(if r.converged {
                    r.iterations.into()
                } else {
                    format!("{} (failed)", r.iterations).into()
                });
            }
            iterations.push(row)?;
        }
    }
    chapter.table("iterations", &iterations)?;

    // The penalty mapping, checked: GetFEM Q2 and our FEM Q2 at the same
    // factor, p₀ by the same estimator, beside each one's error
    let mut check = Table::new(vec![
        Column::plain("factor", "F"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::new(
            "getfem_p0",
            "GetFEM Q2 p₀",
            Unit::Megapascal,
            Format::Fixed(4),
        ),
        Column::new(
            "ours_p0",
            "our FEM Q2 p₀",
            Unit::Megapascal,
            Format::Fixed(4),
        ),
        Column::new("difference", "difference", Unit::None, Format::Sci(1)),
        Column::new(
            "getfem_error",
            "GetFEM Q2 error",
            Unit::None,
            Format::Sci(1),
        ),
        Column::new("ours_error", "FEM Q2 error", Unit::None, Format::Sci(1)),
    ]);
    for &fac in &FACTORS {
        for n in LADDER {
            let find = |m: Method| {
                runs.iter()
                    .find(|r| r.method == m && r.factor == fac && r.elements == n)
                    .expect("every rung ran")
            };
            let (g, o) = (find(Method::GetFem(2)), find(Method::Fem(2)));
            let (Some(gp), Some(op)) = (g.p0_peer_estimator, o.p0_peer_estimator) else {
                continue;
            };
            let (ge, oe) = (relative(gp, peer_p0).abs(), relative(op, peer_p0).abs());
            let d = relative(gp, op).abs();
            check.push(vec![
                Format::Plain.render(fac).into(),
                n.into(),
                gp.into(),
                op.into(),
                d.into(),
                ge.into(),
                oe.into(),
            ])?;
        }
    }
    chapter.table("penalty_check", &check)?;

    // Which method reaches each target first, in set-up + solve and in
    // solve alone, per factor
    let f = chapter.facts();
    machine.record(f, "machine_")?;
    let mut ratios = Table::new(vec![
        Column::plain("quantity", "quantity"),
        Column::plain("target", "target"),
        Column::plain("factor", "F"),
        Column::plain("ours_first", "ours first"),
        Column::plain("getfem_first", "GetFEM first"),
        Column::new(
            "total_ratio",
            "GetFEM / ours (set-up + solve)",
            Unit::None,
            Format::Times(1),
        ),
        Column::new(
            "solve_ratio",
            "GetFEM / ours (solve)",
            Unit::None,
            Format::Times(1),
        ),
    ]);
    let total: fn(&Run) -> f64 = Run::total;
    let solve_only: fn(&Run) -> f64 = |r| r.solve;
    for (qk, qname, err) in QUANTITIES {
        for (t, tk, th) in TARGETS {
            for &fac in &FACTORS {
                let best = |ours: bool, time: fn(&Run) -> f64| {
                    methods
                        .iter()
                        .filter(|m| m.ours() == ours)
                        .filter_map(|&m| {
                            first_reaching(&runs, m, fac, t, err, time).map(|(s, n)| (s, n, m))
                        })
                        .min_by(|a, b| a.0.total_cmp(&b.0))
                };
                let (o, g) = (best(true, total), best(false, total));
                let (os, gs) = (best(true, solve_only), best(false, solve_only));
                let show = |b: Option<(f64, usize, Method)>| {
                    b.map_or(Cell::from("none"), |(s, n, m)| {
                        format!("{} {n}² ({})", m.label(), human_seconds(s)).into()
                    })
                };
                let ratio =
                    |a: Option<(f64, usize, Method)>, b: Option<(f64, usize, Method)>| match (a, b)
                    {
                        (Some(a), Some(b)) => Some(b.0 / a.0),
                        _ => None,
                    };
                let (rt, rs) = (ratio(o, g), ratio(os, gs));
                let key = format!("{qk}_{tk}_{}", factor_key(fac));
                if let Some(v) = rt {
                    f.timed_number(&format!("{key}_total_ratio"), v, Format::Times(0))?;
                }
                if let Some(v) = rs {
                    f.timed_number(&format!("{key}_solve_ratio"), v, Format::Times(0))?;
                }
                ratios.push(vec![
                    qname.into(),
                    th.into(),
                    Format::Plain.render(fac).into(),
                    show(o),
                    show(g),
                    rt.map_or(Cell::Empty, Cell::from),
                    rs.map_or(Cell::Empty, Cell::from),
                ])?;
            }
        }
    }
    chapter.table("ratios", &ratios)?;
    for stem in ["ratios", "runs"] {
        chapter.timed(&format!("{stem}.csv"));
    }
    chapter.timed("ratios.md");
    // ANCHOR_END: tables

    // ANCHOR: facts
    let f = chapter.facts();
    f.text("getfem_version", &peer.version)?;
    f.text("getfem_date", &peer.date)?;
    f.text("getfem_comment", &peer.comment)?;
    f.count("rungs", LADDER.len())?;
    f.text(
        "ladder",
        format!("{}² to {}²", LADDER[0], LADDER[LADDER.len() - 1]),
    )?;
    f.number(
        "estimator_offset_p0",
        relative(peer_p0, reference.measures.p0),
        Format::SignedPercent(2),
    )?;
    f.number(
        "gamma_deviation",
        peer.runs
            .iter()
            .map(|r| r.gamma_deviation)
            .fold(0.0, f64::max),
        Format::Pow10(0),
    )?;
    // the script's a estimator on our reference solution
    f.number(
        "gap_zero_over_a",
        gap_zero / reference.measures.half_width,
        Format::Fixed(2),
    )?;
    f.count("overlapping_samples", overlapping)?;
    for &fac in &FACTORS {
        let fk = factor_key(fac);
        for m in Method::PEER {
            let failed = runs
                .iter()
                .filter(|r| r.method == m && r.factor == fac && !r.converged)
                .count();
            f.count(&format!("{}_{fk}_failed", m.key()), failed)?;
        }
        let ours_failed = runs
            .iter()
            .filter(|r| r.method.ours() && r.factor == fac && !r.converged)
            .count();
        f.count(&format!("ours_{fk}_failed"), ours_failed)?;
        // iterations on the same mesh and element: our FEM Q_k against
        // GetFEM's Q_k, and the most any of our methods needed
        for q in [1, 2] {
            let mut more = 0;
            for n in LADDER {
                let find = |m: Method| {
                    runs.iter()
                        .find(|r| r.method == m && r.factor == fac && r.elements == n)
                        .expect("every rung ran")
                };
                let (g, o) = (find(Method::GetFem(q)), find(Method::Fem(q)));
                if g.converged && o.converged && o.iterations > g.iterations {
                    more += 1;
                }
            }
            f.count(&format!("fem_q{q}_{fk}_more_iterations_than_getfem"), more)?;
        }
        let most = |ours: bool| {
            runs.iter()
                .filter(|r| r.method.ours() == ours && r.factor == fac && r.converged)
                .map(|r| r.iterations)
                .max()
                .unwrap_or(0)
        };
        f.count(&format!("ours_{fk}_most_iterations"), most(true))?;
        f.count(&format!("getfem_{fk}_most_iterations"), most(false))?;
    }
    // ANCHOR_END: facts
    chapter.finish()
}
