//! Hertz contact of an elastic disk on a rigid plane: the program behind
//! the chapter "Hertz contact of a disk on a rigid plane" (the paper's
//! Fig. 4, Table 2, Figs. 5 and 6).
//!
//! The scene `data/scenes/hertz.toml` models the right half of the disk,
//! loaded by its own weight and resting on a rigid floor; symmetry holds
//! u_x = 0 on the diameter. The program solves it on a ladder of meshes
//! with four solvers, records the 8×8 iteration history, measures the peak
//! pressure and the contact half-width on every mesh against Hertz and a
//! fine reference, and draws the figures, into `book/src/generated/hertz/`.
//!
//! Run it with `cargo run --release --example hertz`.

use companion::hertz as setup;

use companion::chapter::Chapter;
use companion::timing::median_time;
use companion::Facts;
use iga_contact::error::{Error, Result};
use iga_contact::nurbs::Side;
use iga_contact::post::hertz::Hertz;
use iga_contact::post::{self, relative, PressureProfile};
use iga_contact::problem::Problem;
use iga_contact::report::drawing::{control_net, element_lines, field_cells, labelled, Placement};
use iga_contact::report::history::history_table;
use iga_contact::report::plot::{
    field_figure, geometry_figure, line_chart, Axes, LineKind, Polyline, Series, BLACK_INDEX,
};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit, CONTACT_ERRORS};
use iga_contact::report::vtu::sample_bodies;
use iga_contact::scene::Scene;
use iga_contact::solver::history::{Event, History};
use iga_contact::solver::{solve, Growth, Solution, SolverKind, SolverOptions, Start};
use std::collections::BTreeMap;

// ANCHOR: constants
/// The iteration at which the paper's correction fired on the 8×8 mesh.
const PAPER_CORRECTION_ITERATION: usize = 13;
/// Degrees and meshes (elements per direction) of the solver ladder.
const LADDER_DEGREES: [usize; 2] = [2, 3];
const LADDER_ELEMENTS: [usize; 4] = [8, 16, 32, 64];
/// Meshes of the convergence study (Fig. 6).
const CONVERGENCE_ELEMENTS: [usize; 6] = [4, 8, 16, 32, 64, 128];
/// The converged reference: (degree, elements per direction).
const REFERENCE: (usize, usize) = (3, 128);
/// Meshes of the pressure-profile figure (p = 2).
const PROFILE_ELEMENTS: [usize; 2] = [8, 64];
// ANCHOR_END: constants

// ANCHOR: solvers
/// The solvers of the ladder, by the names `ladder.csv` uses: the
/// library's default BFGS, the paper's iteration (the scene's own
/// `[solver]` table: full steps), the paper's iteration never corrected
/// (the like-for-like test of the correction), the paper's iteration from
/// the balanced secant start instead of the tied kernel (the like-for-like
/// test of the start), the default BFGS never corrected, and Newton.
fn solvers(scene: &Scene) -> [(&'static str, SolverOptions); 6] {
    [
        ("bfgs", SolverOptions::default()),
        ("bfgs_paper", scene.solver),
        (
            "bfgs_paper_secant_start",
            // the start alone: `growth = "auto"` would also cut the growth
            // after a secant start, which the tied start does not
            SolverOptions {
                start: Start::Secant,
                growth: Growth::Full,
                ..scene.solver
            },
        ),
        (
            "bfgs_paper_no_correction",
            SolverOptions {
                kind: SolverKind::BfgsNoCorrection,
                ..scene.solver
            },
        ),
        (
            "bfgs_no_correction",
            SolverOptions::with_kind(SolverKind::BfgsNoCorrection),
        ),
        ("newton", SolverOptions::with_kind(SolverKind::Newton)),
    ]
}
// ANCHOR_END: solvers

/// One converged solve, measured.
struct Run {
    degree: usize,
    elements: usize,
    solver: &'static str,
    problem: Problem,
    solution: Solution,
    p0: f64,
    half_width: f64,
    /// Vertical force of the floor on the half disk.
    contact_force: f64,
    /// Vertical resultant of the applied load (downwards, so negative).
    applied_force: f64,
    /// Build + solve, wall time.
    seconds: f64,
}

/// A solve that did not converge.
struct Failure {
    degree: usize,
    elements: usize,
    solver: &'static str,
    history: History,
    reason: String,
}

// ANCHOR: measure
/// Builds and solves the p-degree scene on `elements`², measuring p₀ and a
/// on the dense profile. Non-convergence is a result, kept as a Failure.
fn run(
    degree: usize,
    elements: usize,
    solver: &'static str,
    opts: &SolverOptions,
) -> Result<std::result::Result<Run, Failure>> {
    let scene = setup::scene(setup::iga(degree, elements))?;
    let timed = median_time(1, || {
        let problem = scene.build()?;
        let solution = solve(&problem, opts);
        Ok((problem, solution))
    })?;
    let (problem, solution) = timed.value;
    let solution = match solution {
        Ok(s) => s,
        Err(Error::NotConverged { diagnosis, history }) => {
            return Ok(Err(Failure {
                degree,
                elements,
                solver,
                history,
                reason: diagnosis.to_string(),
            }))
        }
        Err(e) => return Err(e),
    };
    let m = PressureProfile::dense(&problem, &solution.full)?.measures(0);
    Ok(Ok(Run {
        degree,
        elements,
        solver,
        p0: m.p0,
        half_width: m.half_width,
        contact_force: post::contact_resultant(&problem, &solution.full)[1],
        applied_force: post::applied_resultant(&problem)?[1],
        seconds: timed.seconds,
        problem,
        solution,
    }))
}
// ANCHOR_END: measure

/// The chapter "Hertz contact of a disk on a rigid plane", section by
/// section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("hertz")?;
    let base = setup::scene(setup::iga(2, 8))?;
    let exact = setup::analytic(&base)?;

    // The solver ladder: Tables H5 and H6.
    let (ladder, failures) = solve_ladder(&base)?;
    chapter.table("ladder", &ladder_table(&ladder)?)?;
    chapter.timed("ladder.csv"); // its `seconds` column
    chapter.table("failures", &failure_table(&failures)?)?;

    // The iteration history on 8×8 (the paper's Table 2): Tables H1, H2, Fig. H2.
    let paper = ladder_run(&ladder, "bfgs_paper", 2, 8)?;
    let default = ladder_run(&ladder, "bfgs", 2, 8)?;
    write_histories(&mut chapter, paper, default)?;
    residual_figure(&chapter, paper, default)?;

    // The model and the vertical displacement on 8×8: Figs. H1, H3, the VTU.
    model_figure(&chapter, &default.problem)?;
    uy_figure(&chapter, default)?;
    write_vtu(&chapter, default)?;

    // Convergence under refinement: Tables H3 and H4, Figs. H5 and H6.
    let study = convergence_study(&ladder)?;
    write_convergence(&mut chapter, &study, &exact)?;

    // The pressure profile: Fig. H4.
    profile_outputs(&mut chapter, &pressure_profiles()?, &exact)?;

    // The numbers the prose quotes.
    let f = chapter.facts();
    record_model_facts(f, &exact)?;
    record_convergence_facts(f, &study, &exact)?;
    record_8x8_facts(f, paper, default, &study, &exact)?;
    record_ladder_facts(f, &base, &ladder, &failures, &exact)?;
    chapter.finish()
}

// ANCHOR: ladder
/// "The solver ladder": every degree and mesh of the ladder, solved by
/// each solver; the runs that converged and those that did not.
fn solve_ladder(base: &Scene) -> Result<(Vec<Run>, Vec<Failure>)> {
    let mut ladder = Vec::new();
    let mut failures = Vec::new();
    for p in LADDER_DEGREES {
        for n in LADDER_ELEMENTS {
            for (name, opts) in solvers(base) {
                match run(p, n, name, &opts)? {
                    Ok(r) => ladder.push(r),
                    Err(f) => failures.push(f),
                }
            }
        }
    }
    Ok((ladder, failures))
}
// ANCHOR_END: ladder

/// The run of the ladder that the 8×8 sections show (it must have
/// converged).
fn ladder_run<'a>(ladder: &'a [Run], solver: &str, p: usize, n: usize) -> Result<&'a Run> {
    ladder
        .iter()
        .find(|r| r.solver == solver && r.degree == p && r.elements == n)
        .ok_or_else(|| missing(&format!("{solver} {n}²")))
}

/// Tables H1 and H2 (the paper's Table 2): the paper's iteration and the
/// default on 8×8, p = 2.
fn write_histories(chapter: &mut Chapter, paper: &Run, default: &Run) -> Result<()> {
    for (name, r) in [("iterations_8x8_paper", paper), ("iterations_8x8", default)] {
        chapter.table(
            name,
            &history_table(&r.solution.history, Unit::NewtonPerMetre, Unit::Millimetre)?,
        )?;
    }
    Ok(())
}

/// The solution on the paper's mesh for a viewer (Fig. H3 is drawn from
/// the same run).
fn write_vtu(chapter: &Chapter, default: &Run) -> Result<()> {
    sample_bodies(
        &default.problem.bodies,
        &default.problem.map,
        &default.solution.full,
        4,
    )?
    .write(chapter.path("hertz.vtu"))
}

/// p₀, a and the DOFs of one Newton solve.
type Measured = (f64, f64, usize);

/// What "Convergence under refinement" reports: the reference, every
/// degree and mesh of the study, and the reference's check one mesh
/// coarser.
struct Convergence {
    reference: Measured,
    rows: Vec<(usize, usize, Measured)>,
    /// The reference's degree on half its elements per direction.
    check: Measured,
}

// ANCHOR: convergence
/// Fig. 6: Newton solutions (the discrete solution does not depend on
/// the solver, see the ladder), reused from the ladder where it has them.
fn convergence_study(ladder: &[Run]) -> Result<Convergence> {
    let mut newton: BTreeMap<(usize, usize), Measured> = ladder
        .iter()
        .filter(|r| r.solver == "newton")
        .map(|r| ((r.degree, r.elements), (r.p0, r.half_width, r.problem.n())))
        .collect();
    let newton_opts = SolverOptions::with_kind(SolverKind::Newton);
    let mut measured = |p: usize, n: usize| -> Result<Measured> {
        if let Some(&m) = newton.get(&(p, n)) {
            return Ok(m);
        }
        let r = run(p, n, "newton", &newton_opts)?.map_err(|f| not_converged(&f))?;
        let m = (r.p0, r.half_width, r.problem.n());
        newton.insert((p, n), m);
        Ok(m)
    };
    let reference = measured(REFERENCE.0, REFERENCE.1)?;
    let mut rows = Vec::new();
    for p in LADDER_DEGREES {
        for n in CONVERGENCE_ELEMENTS {
            rows.push((p, n, measured(p, n)?));
        }
    }
    let check = measured(REFERENCE.0, REFERENCE.1 / 2)?;
    Ok(Convergence {
        reference,
        rows,
        check,
    })
}
// ANCHOR_END: convergence

/// "Convergence under refinement": Tables H3 and H4 and Figs. H5 and H6,
/// against Hertz and against the reference.
fn write_convergence(chapter: &mut Chapter, study: &Convergence, exact: &Hertz) -> Result<()> {
    let reference = study.reference;
    chapter.table(
        "convergence",
        &convergence_table(&study.rows, exact, reference)?,
    )?;
    chapter.table("reference", &reference_table(exact, reference)?)?;
    convergence_figures(chapter, &study.rows, exact, reference)
}

/// "The pressure profile": the dense profiles of two meshes, against
/// Hertz's ellipse.
fn pressure_profiles() -> Result<Vec<(usize, PressureProfile)>> {
    let newton_opts = SolverOptions::with_kind(SolverKind::Newton);
    let mut profiles = Vec::new();
    for n in PROFILE_ELEMENTS {
        let r = run(2, n, "newton", &newton_opts)?.map_err(|f| not_converged(&f))?;
        profiles.push((n, PressureProfile::dense(&r.problem, &r.solution.full)?));
    }
    Ok(profiles)
}

// ANCHOR: facts
/// "The model" and "What Hertz predicts" quote the load and Hertz's
/// solution.
fn record_model_facts(f: &mut Facts, exact: &Hertz) -> Result<()> {
    f.number("weight", exact.load, Format::Fixed(0))?;
    f.number("half_load", exact.load / 2.0, Format::Fixed(0))?;
    f.number("hertz_a_mm", exact.half_width * 1e3, Format::Fixed(3))?;
    f.number("hertz_p0_mpa", exact.p0 * 1e-6, Format::Fixed(4))?;
    f.number(
        "a_over_r",
        exact.half_width / exact.radius,
        Format::Fixed(2),
    )?;
    f.number(
        "a_over_r_squared",
        (exact.half_width / exact.radius).powi(2),
        Format::Percent(0),
    )
}

/// "Convergence under refinement" quotes the reference, its check, and
/// every mesh's errors against Hertz and against the reference.
fn record_convergence_facts(f: &mut Facts, study: &Convergence, exact: &Hertz) -> Result<()> {
    let (rp0, ra, rdofs) = study.reference;
    f.count("reference_degree", REFERENCE.0)?;
    f.count("reference_elements", REFERENCE.1)?;
    f.count("reference_dofs", rdofs)?;
    f.number(
        "reference_p0_vs_hertz",
        relative(rp0, exact.p0),
        Format::SignedPercent(1),
    )?;
    f.number(
        "reference_a_vs_hertz",
        relative(ra, exact.half_width),
        Format::SignedPercent(1),
    )?;
    let (cp0, ca, _) = study.check;
    f.number(
        "reference_check_p0",
        relative(cp0, rp0).abs(),
        Format::Percent(2),
    )?;
    f.number(
        "reference_check_a",
        relative(ca, ra).abs(),
        Format::Percent(2),
    )?;
    f.number("reference_p0_mpa", rp0 * 1e-6, Format::Fixed(5))?;
    f.number("reference_a_mm", ra * 1e3, Format::Fixed(4))?;
    for &(p, n, (p0, a, _)) in &study.rows {
        let key = format!("p{p}_{n}");
        let hertz = [exact.p0, exact.half_width];
        f.contact_errors(&key, [p0, a], "hertz", hertz, Format::SignedPercent(2))?;
        f.contact_errors(
            &key,
            [p0, a],
            "reference",
            [rp0, ra],
            Format::SignedPercent(2),
        )?;
    }
    Ok(())
}

/// "Measuring the peak pressure", "The iteration history on 8×8" and "The
/// vertical displacement" quote the paper's mesh: p₀ and a, the solver's
/// own points, both histories, the largest displacement.
fn record_8x8_facts(
    f: &mut Facts,
    paper: &Run,
    default: &Run,
    study: &Convergence,
    exact: &Hertz,
) -> Result<()> {
    let (rp0, ra, _) = study.reference;
    let m8 = PressureProfile::dense(&default.problem, &default.solution.full)?.measures(0);
    f.number("p0_8x8_mpa", m8.p0 * 1e-6, Format::Fixed(4))?;
    f.number("a_8x8_mm", m8.half_width * 1e3, Format::Fixed(2))?;
    f.number(
        "p0_8x8_vs_hertz",
        relative(m8.p0, exact.p0),
        Format::SignedPercent(1),
    )?;
    f.number(
        "a_8x8_vs_hertz",
        relative(m8.half_width, exact.half_width),
        Format::SignedPercent(1),
    )?;
    f.number(
        "p0_8x8_vs_reference",
        relative(m8.p0, rp0),
        Format::SignedPercent(1),
    )?;
    f.number(
        "a_8x8_vs_reference",
        relative(m8.half_width, ra),
        Format::SignedPercent(1),
    )?;
    let solver_points = PressureProfile::from_points(
        &default.problem,
        &default.problem.points,
        &default.solution.full,
    );
    f.number(
        "p0_8x8_solver_points_mpa",
        solver_points.measures(0).p0 * 1e-6,
        Format::Fixed(4),
    )?;
    f.count("paper_correction_iteration", PAPER_CORRECTION_ITERATION)?;
    for (key, r) in [("paper", paper), ("default", default)] {
        let h = &r.solution.history;
        f.count(&format!("{key}_8x8_iterations"), h.len())?;
        f.count(&format!("{key}_8x8_corrections"), h.corrections())?;
        let first = h
            .rows
            .iter()
            .position(|row| row.events.contains(&Event::Correction));
        f.text(
            &format!("{key}_8x8_first_correction"),
            first.map_or("none".into(), |k| (k + 1).to_string()),
        )?;
    }
    f.count("contact_points_8x8", default.problem.points.len())?;
    f.number("uy_max_8x8_mm", -min_uy(default) * 1e3, Format::Fixed(1))?;
    let spacing = default
        .problem
        .points
        .windows(2)
        .map(|w| (w[1].x[0] - w[0].x[0]).abs())
        .fold(0.0, f64::max);
    f.number("solver_point_spacing_mm", spacing * 1e3, Format::Fixed(0))
}

/// "The solver ladder" quotes the balance of forces, the spread between
/// the solvers and their iterations; the claims chapter reads every run.
fn record_ladder_facts(
    f: &mut Facts,
    base: &Scene,
    ladder: &[Run],
    failures: &[Failure],
    exact: &Hertz,
) -> Result<()> {
    let force_balance = ladder
        .iter()
        .map(|r| relative(r.contact_force, -r.applied_force).abs())
        .fold(0.0, f64::max);
    f.number("force_balance", force_balance, Format::Pow10(0))?;
    let quadrature = ladder
        .iter()
        .map(|r| relative(-r.applied_force, exact.load / 2.0).abs())
        .fold(0.0, f64::max);
    f.number("load_quadrature", quadrature, Format::Pow10(0))?;
    f.number("solver_spread", solver_spread(ladder), Format::Pow10(0))?;
    for (name, _) in solvers(base) {
        let its: Vec<usize> = ladder
            .iter()
            .filter(|r| r.solver == name)
            .map(|r| r.solution.history.len())
            .collect();
        let (lo, hi) = (its.iter().min(), its.iter().max());
        if let (Some(lo), Some(hi)) = (lo, hi) {
            f.text(&format!("{name}_iterations"), format!("{lo}–{hi}"))?;
        }
    }
    f.count("failures", failures.len())?;
    // Every run of the ladder by solver, degree and mesh: its iterations,
    // or "failed" (the claims chapter reads these).
    for r in ladder {
        let key = format!("its_{}_p{}_{}", r.solver, r.degree, r.elements);
        f.count(&key, r.solution.history.len())?;
    }
    for r in failures {
        let key = format!("its_{}_p{}_{}", r.solver, r.degree, r.elements);
        f.text(&key, "failed")?;
    }
    Ok(())
}
// ANCHOR_END: facts

fn missing(what: &str) -> Error {
    Error::invalid("hertz ladder", what, "this run did not converge")
}

fn not_converged(f: &Failure) -> Error {
    Error::invalid(
        "hertz ladder",
        format!("{} on p = {}, {}²", f.solver, f.degree, f.elements),
        format!(
            "needed by a table, but not converged after {} iterations: {}",
            f.history.len(),
            f.reason
        ),
    )
}

/// The largest downward displacement of a run.
fn min_uy(r: &Run) -> f64 {
    r.solution
        .full
        .iter()
        .skip(1)
        .step_by(2)
        .copied()
        .fold(0.0, f64::min)
}

/// The largest relative spread of p₀ and a between the solvers on one mesh.
fn solver_spread(ladder: &[Run]) -> f64 {
    let mut spread: f64 = 0.0;
    for a in ladder {
        for b in ladder
            .iter()
            .filter(|b| (b.degree, b.elements) == (a.degree, a.elements))
        {
            spread = spread
                .max(relative(a.p0, b.p0).abs())
                .max(relative(a.half_width, b.half_width).abs());
        }
    }
    spread
}

// ANCHOR: tables
fn ladder_table(ladder: &[Run]) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs").csv_only(),
        Column::plain("solver", "solver"),
        Column::plain("iterations", "its"),
        Column::plain("corrections", "corr."),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(2)),
        Column::new(
            "contact_force",
            "F_c",
            Unit::NewtonPerMetre,
            Format::Fixed(0),
        )
        .csv_only(),
        Column::new(
            "applied_force",
            "F_app",
            Unit::NewtonPerMetre,
            Format::Fixed(0),
        )
        .csv_only(),
        Column::new("seconds", "seconds", Unit::Second, Format::Fixed(3)).csv_only(),
    ]);
    for r in ladder {
        t.push(vec![
            r.degree.into(),
            r.elements.into(),
            r.problem.n().into(),
            r.solver.into(),
            r.solution.history.len().into(),
            r.solution.history.corrections().into(),
            r.p0.into(),
            r.half_width.into(),
            r.contact_force.into(),
            (-r.applied_force).into(),
            r.seconds.into(),
        ])?;
    }
    Ok(t)
}
// ANCHOR_END: tables

fn failure_table(failures: &[Failure]) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("solver", "solver"),
        Column::plain("iterations", "iterations"),
        Column::plain("corrections", "corrections"),
        Column::plain("reason", "reason"),
    ]);
    for f in failures {
        t.push(vec![
            f.degree.into(),
            f.elements.into(),
            f.solver.into(),
            f.history.len().into(),
            f.history.corrections().into(),
            f.reason.clone().into(),
        ])?;
    }
    Ok(t)
}

fn convergence_table(
    rows: &[(usize, usize, (f64, f64, usize))],
    exact: &Hertz,
    (rp0, ra, _): (f64, f64, usize),
) -> Result<Table> {
    let mut columns = vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(3)),
    ];
    columns.extend(CONTACT_ERRORS);
    let mut t = Table::new(columns);
    for &(p, n, (p0, a, dofs)) in rows {
        // The reference measured against itself is no result: its row says
        // so instead of showing a zero error.
        let against_reference = |v: f64, r: f64| -> Cell {
            if (p, n) == REFERENCE {
                "reference".into()
            } else {
                relative(v, r).into()
            }
        };
        t.push(vec![
            p.into(),
            n.into(),
            dofs.into(),
            p0.into(),
            a.into(),
            relative(p0, exact.p0).into(),
            relative(a, exact.half_width).into(),
            against_reference(p0, rp0),
            against_reference(a, ra),
        ])?;
    }
    Ok(t)
}

fn reference_table(exact: &Hertz, (rp0, ra, dofs): (f64, f64, usize)) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("solution", "solution"),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(3)),
        Column::plain("dofs", "DOFs"),
    ]);
    t.push(vec![
        "Hertz".into(),
        exact.p0.into(),
        exact.half_width.into(),
        Cell::Empty,
    ])?;
    let name = format!("reference, p = {}, {}²", REFERENCE.0, REFERENCE.1);
    t.push(vec![name.into(), rp0.into(), ra.into(), dofs.into()])?;
    Ok(t)
}

// ANCHOR: figures
/// Fig. 4: elements, control net, slave arc, symmetry line and floor.
fn model_figure(chapter: &Chapter, problem: &Problem) -> Result<()> {
    let patch = &problem.bodies[0].space.patch;
    let mut lines = labelled(element_lines(patch, LineKind::Thin, 0), "elements");
    lines.extend(labelled(control_net(patch, 1), "control net"));
    let slave = patch.side_curve(Side::EtaMin);
    let (a, b) = (slave.knots.first(), slave.knots.last());
    let arc = (0..=64)
        .map(|i| slave.point(a + (b - a) * i as f64 / 64.0))
        .collect();
    lines.push(Polyline::new(arc, LineKind::Solid, 3).labelled("slave side Γc (eta_min)"));
    let top = patch.point(patch.knots[0].first(), patch.knots[1].last());
    lines.push(
        Polyline::new(vec![[0.0, 0.0], top], LineKind::Dashed, 2)
            .labelled("symmetry line, u_x = 0"),
    );
    lines.push(floor(patch.points.iter().map(|p| p[0]).fold(0.0, f64::max)));
    let [e0, e1] = problem.bodies[0].space.n_elements();
    geometry_figure(
        chapter.path("model.svg"),
        &format!("Half disk, p = 2, {e0}×{e1} elements, on a rigid floor"),
        &lines,
    )
}

fn floor(width: f64) -> Polyline {
    Polyline::new(
        vec![[-0.1 * width, 0.0], [1.1 * width, 0.0]],
        LineKind::Solid,
        BLACK_INDEX,
    )
    .labelled("rigid floor y = 0")
}

/// Fig. 5: u_y on the deformed half disk (true scale).
fn uy_figure(chapter: &Chapter, r: &Run) -> Result<()> {
    let cells = field_cells(&r.problem, &r.solution.full, 6, Placement::Deformed, |q| {
        q.displacement[1] * 1e3
    })?;
    let patch = &r.problem.bodies[0].space.patch;
    let overlay = vec![
        Polyline::new(patch.outline(64), LineKind::Dashed, BLACK_INDEX).labelled("undeformed"),
        floor(patch.points.iter().map(|p| p[0]).fold(0.0, f64::max)),
    ];
    let [e0, e1] = r.problem.bodies[0].space.n_elements();
    field_figure(
        chapter.path("uy.svg"),
        &format!("Vertical displacement on the deformed half disk (true scale), p = 2, {e0}×{e1}"),
        "u_y (mm)",
        &cells,
        &overlay,
    )
}

/// Table 2 as a picture: the relative residual of both 8×8 histories.
fn residual_figure(chapter: &Chapter, paper: &Run, default: &Run) -> Result<()> {
    let series = |name: &str, r: &Run| {
        let pts = r
            .solution
            .history
            .rows
            .iter()
            .map(|row| (row.iteration as f64, row.relative_residual))
            .collect();
        Series::line(name, pts).with_markers()
    };
    line_chart(
        chapter.path("iterations_8x8.svg"),
        &Axes {
            title: "BFGS on 8×8, p = 2: each residual relative to its own first".into(),
            x_label: "iteration".into(),
            y_label: "‖R‖ / ‖R₀‖ (dimensionless)".into(),
            log_x: false,
            log_y: true,
        },
        &[
            series("paper's iteration: full steps, whole body", paper),
            series("default: full steps, contact layer", default),
        ],
    )
}

/// Fig. 6a, 6b and the errors against the reference.
fn convergence_figures(
    chapter: &Chapter,
    rows: &[(usize, usize, (f64, f64, usize))],
    exact: &Hertz,
    (rp0, ra, _): (f64, f64, usize),
) -> Result<()> {
    let xs = [CONVERGENCE_ELEMENTS[0] as f64, REFERENCE.1 as f64];
    let reference = format!("reference (p = {}, {}²)", REFERENCE.0, REFERENCE.1);
    let horizontal =
        |name: String, y: f64| Series::line(name, xs.iter().map(|&x| (x, y)).collect()).dashed();
    for (file, title, label, value, hertz, refv) in [
        (
            "half_width.svg",
            "Contact half-width against the mesh",
            "a (mm)",
            1,
            exact.half_width * 1e3,
            ra * 1e3,
        ),
        (
            "peak_pressure.svg",
            "Peak contact pressure against the mesh",
            "p₀ (MPa)",
            0,
            exact.p0 * 1e-6,
            rp0 * 1e-6,
        ),
    ] {
        let mut series: Vec<Series> = LADDER_DEGREES
            .iter()
            .map(|&p| {
                let pts = rows
                    .iter()
                    .filter(|r| r.0 == p)
                    .map(|&(_, n, (p0, a, _))| {
                        (n as f64, if value == 0 { p0 * 1e-6 } else { a * 1e3 })
                    })
                    .collect();
                Series::line(format!("IGA p = {p}"), pts).with_markers()
            })
            .collect();
        series.push(horizontal("Hertz".into(), hertz));
        series.push(horizontal(reference.clone(), refv));
        line_chart(
            chapter.path(file),
            &Axes {
                title: title.into(),
                x_label: "elements per direction".into(),
                y_label: label.into(),
                log_x: true,
                log_y: false,
            },
            &series,
        )?;
    }
    let mut series = Vec::new();
    for p in LADDER_DEGREES {
        let mine: Vec<_> = rows
            .iter()
            .filter(|r| r.0 == p && (p, r.1) != REFERENCE)
            .collect();
        let p0 = mine
            .iter()
            .map(|&&(_, n, (p0, _, _))| (n as f64, relative(p0, rp0).abs()))
            .collect();
        let a = mine
            .iter()
            .map(|&&(_, n, (_, a, _))| (n as f64, relative(a, ra).abs()))
            .collect();
        series.push(Series::line(format!("p₀, p = {p}"), p0).with_markers());
        series.push(
            Series::line(format!("a, p = {p}"), a)
                .with_markers()
                .dashed(),
        );
    }
    line_chart(
        chapter.path("errors.svg"),
        &Axes {
            title: format!("Error against the {reference}"),
            x_label: "elements per direction".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
        },
        &series,
    )
}
// ANCHOR_END: figures

/// The dense profiles as a table and a figure, up to 1.5 a.
fn profile_outputs(
    chapter: &mut Chapter,
    profiles: &[(usize, PressureProfile)],
    exact: &Hertz,
) -> Result<()> {
    let x_max = 1.5 * exact.half_width;
    let mut t = Table::new(vec![
        Column::plain("elements", "elements"),
        Column::new("x", "x", Unit::Millimetre, Format::Fixed(3)),
        Column::new("pressure", "pressure", Unit::Megapascal, Format::Fixed(4)),
        Column::new("hertz", "Hertz", Unit::Megapascal, Format::Fixed(4)),
    ]);
    let mut series = Vec::new();
    for (n, profile) in profiles {
        let samples: Vec<_> = profile.pair(0).iter().filter(|s| s.x[0] <= x_max).collect();
        for s in &samples {
            t.push(vec![
                (*n).into(),
                s.x[0].into(),
                s.pressure().into(),
                exact.pressure(s.x[0]).into(),
            ])?;
        }
        let pts = samples
            .iter()
            .map(|s| (s.x[0] * 1e3, s.pressure() * 1e-6))
            .collect();
        series.push(Series::line(format!("IGA p = 2, {n}×{n}"), pts));
    }
    let ellipse = (0..=300)
        .map(|i| {
            let x = x_max * i as f64 / 300.0;
            (x * 1e3, exact.pressure(x) * 1e-6)
        })
        .collect();
    series.push(Series::line("Hertz p₀√(1 − x²/a²)", ellipse).dashed());
    // CSV only: the Markdown would be thousands of rows
    chapter.csv("pressure_profile", &t)?;
    line_chart(
        chapter.path("pressure_profile.svg"),
        &Axes {
            title: "Contact pressure along the floor".into(),
            x_label: "x (mm)".into(),
            y_label: "pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )
}
