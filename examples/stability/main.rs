//! The stability atlas: the program behind the chapter "Stability atlas".
//! The method on stiff and extreme cases — penalties over ten decades for
//! the three θ, stiffness contrast, near incompressibility, load levels,
//! open and penetrating gaps, very coarse and fine meshes — each ending
//! either converged or in a typed, diagnosed error.
//! Output: `book/src/generated/stability/`.
//!
//! Run it with `cargo run --release --example stability`.

use companion::hertz as setup;

use companion::chapter::Chapter;
use companion::Facts;
use iga_contact::assembly::{strain_stress, Load};
use iga_contact::contact::{Integration, PenaltyKind, Theta};
use iga_contact::error::{Error, ErrorKind, Result};
use iga_contact::post::{relative, PressureProfile};
use iga_contact::problem::Problem;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::{GeometrySpec, RefineSpec, Scene};
use iga_contact::solver::history::{Event, History};
use iga_contact::solver::warning::OVER_PENALTY;
use iga_contact::solver::{solve, Solution, SolverOptions, Warning};

// ANCHOR: metric
/// What a case is measured against.
#[derive(Clone, Copy)]
enum Metric {
    /// The peak contact pressure p₀, relative to this value.
    PeakPressure(f64),
    /// The largest relative deviation of σ_yy from this uniform value.
    UniformStress(f64),
    /// The bodies must not touch: no active point.
    NoContact,
}
// ANCHOR_END: metric

/// One case: its name, θ and penalty factor (for the table), its scene, and
/// its metric.
struct Case {
    name: String,
    theta: Theta,
    penalty_factor: f64,
    scene: Scene,
    metric: Metric,
}

/// The penalty factors of the penalty axis.
fn factors() -> impl Iterator<Item = f64> {
    (-4..=6).map(|k| 10f64.powi(k))
}

fn hertz(p: usize, n: usize) -> Result<Scene> {
    setup::scene(setup::iga(p, n))
}

fn taylor() -> Result<Scene> {
    companion::shipped("taylor.toml")
}

/// Every Nitsche parameter group of a scene, set by `f`.
fn with(mut scene: Scene, f: impl Fn(&mut iga_contact::scene::NitscheSpec)) -> Scene {
    scene.nitsche_mut().for_each(f);
    scene
}

/// The scene's loads scaled by `s`.
fn scaled(mut scene: Scene, s: f64) -> Scene {
    for l in &mut scene.loads {
        match l {
            Load::BodyForce { force, .. }
            | Load::Traction {
                traction: force, ..
            } => force.iter_mut().for_each(|f| *f *= s),
            Load::Pressure { pressure, .. } => *pressure *= s,
        }
    }
    scene
}

/// The disk lifted by `lift` above the floor (negative: into it).
fn lifted_disk(mut scene: Scene, lift: f64) -> Scene {
    if let GeometrySpec::HalfDisk { center, .. } = &mut scene.bodies[0].geometry {
        center[1] += lift;
    }
    scene
}

/// The upper Taylor block lifted by `gap` (negative: into the lower one).
fn lifted_block(mut scene: Scene, gap: f64) -> Scene {
    if let GeometrySpec::Rectangle { y0, y1, .. } = &mut scene.bodies[1].geometry {
        *y0 += gap;
        *y1 += gap;
    }
    scene
}

// ANCHOR: cases
/// The safety factor over the stability bound of the sharp-penalty cases.
const SHARP_SAFETY: f64 = 2.0;

fn cases(reference_8x8: f64, reference_fine: f64) -> Result<Vec<Case>> {
    let taylor_stress = Metric::UniformStress(-1e8);
    let case = |name: String, scene: Scene, metric| {
        let n = scene.contacts[0].nitsche;
        Case {
            name,
            theta: n.theta,
            penalty_factor: n.penalty_factor,
            scene,
            metric,
        }
    };
    let mut out = Vec::new();
    for theta in Theta::ALL {
        for f in factors() {
            let set = |n: &mut iga_contact::scene::NitscheSpec| {
                n.theta = theta;
                n.penalty_factor = f;
            };
            let name = Format::Sci(0).render(f).replace('−', "-");
            out.push(case(
                format!("hertz_8x8_penalty_{name}"),
                with(hertz(2, 8)?, set),
                Metric::PeakPressure(reference_8x8),
            ));
            out.push(case(
                format!("taylor_penalty_{name}"),
                with(taylor()?, set),
                taylor_stress,
            ));
        }
    }
    for k in [-6, -4, -2, 0, 2, 4, 6] {
        let c = 10f64.powi(k);
        let mut s = taylor()?;
        s.body_mut("upper")?.material.young *= c;
        out.push(case(format!("taylor_contrast_1e{k}"), s, taylor_stress));
    }
    for nu in [0.3, 0.45, 0.49, 0.499, 0.4999] {
        let mut s = hertz(2, 16)?;
        s.body_mut("disk")?.material.poisson = nu;
        let p0 = setup::analytic(&s)?.p0;
        out.push(case(
            format!("hertz_16x16_nu_{nu}"),
            s,
            Metric::PeakPressure(p0),
        ));
    }
    // The same ν with the penalty held above the stability bound (the sharp
    // penalty, safety factor SHARP_SAFETY): what is left of the error is the
    // discretisation's, locking included.
    for nu in [0.3, 0.45, 0.49, 0.499, 0.4999] {
        let mut s = hertz(2, 16)?;
        s.body_mut("disk")?.material.poisson = nu;
        let p0 = setup::analytic(&s)?.p0;
        let s = with(s, |n| {
            n.penalty = PenaltyKind::Sharp;
            n.penalty_factor = SHARP_SAFETY;
        });
        out.push(case(
            format!("hertz_16x16_nu_{nu}_sharp"),
            s,
            Metric::PeakPressure(p0),
        ));
    }
    for k in [-8, -6, -4, -2, 0, 1, 2, 3] {
        let s = scaled(hertz(2, 16)?, 10f64.powi(k));
        let p0 = setup::analytic(&s)?.p0;
        out.push(case(
            format!("hertz_16x16_load_1e{k}"),
            s,
            Metric::PeakPressure(p0),
        ));
    }
    let gaps = [
        (
            "taylor_open_gap_unloaded",
            scaled(lifted_block(taylor()?, 1e-2), 0.0),
            Metric::NoContact,
        ),
        (
            "taylor_gap_closed_by_load",
            lifted_block(taylor()?, 1e-3),
            taylor_stress,
        ),
        (
            "taylor_initial_penetration",
            lifted_block(taylor()?, -1e-3),
            taylor_stress,
        ),
        (
            "hertz_lifted_and_pulled_up",
            scaled(lifted_disk(hertz(2, 8)?, 1e-2), -1.0),
            Metric::NoContact,
        ),
        (
            "hertz_lifted_then_falls",
            lifted_disk(hertz(2, 8)?, 1e-4),
            Metric::PeakPressure(reference_8x8),
        ),
        (
            "hertz_initial_penetration",
            lifted_disk(hertz(2, 8)?, -1e-4),
            Metric::PeakPressure(reference_8x8),
        ),
    ];
    for (name, scene, metric) in gaps {
        out.push(case(name.into(), scene, metric));
    }
    // The mesh and degree axis is measured against the converged solution
    // of this disk (the Hertz chapter's fine reference), not against Hertz's
    // formula, which approximates the finite disk.
    for degree in 1..=5 {
        for n in [1, 4, 16] {
            // degree 1: the isoparametric Q1 interpolant (NURBS cannot go below the circle's 2)
            let refine = match degree {
                1 => RefineSpec::lagrange(1, [n, n]),
                p => RefineSpec::iga(p, [n, n]),
            };
            let s = setup::scene(refine)?;
            out.push(case(
                format!("hertz_p{degree}_{n}x{n}"),
                s,
                Metric::PeakPressure(reference_fine),
            ));
        }
    }
    for n in [128, 256] {
        out.push(case(
            format!("hertz_p2_{n}x{n}"),
            hertz(2, n)?,
            Metric::PeakPressure(reference_fine),
        ));
    }
    let gauss = with(taylor()?, |n| n.integration = Integration::Gauss);
    out.push(case(
        "taylor_gauss_integration".into(),
        gauss,
        taylor_stress,
    ));
    Ok(out)
}
// ANCHOR_END: cases

/// One row of the atlas.
struct Row {
    case: String,
    theta: Theta,
    penalty_factor: f64,
    status: &'static str,
    history: History,
    error: Option<f64>,
    /// The measured p₀ (peak-pressure cases that converged) and its reference.
    p0: Option<f64>,
    reference: Option<f64>,
    /// Active points at the solution, and how many of them have a penalty
    /// below the stability bound.
    active: Option<usize>,
    below: usize,
    /// Inactive points below the bound. For θ = 1 they matter too: every
    /// point, active or not, adds −(θ/γ) w sₙsₙᵀ to the tangent, negative
    /// semidefinite for θ > 0, so coercivity needs γ above the bound there
    /// as well. The solver's warning counts them too, against θ·C_T.
    below_inactive: usize,
    /// Active points on a singular element (at the degenerate (det J = 0)
    /// corner of the disk), which the library counts but never judges.
    singular_active: usize,
    /// The largest displacement component at the solution (m).
    max_displacement: Option<f64>,
    /// γ g₀ of the only active point, when one point carries the contact:
    /// the penalty bracket at the axis once the disk has sunk to it.
    single_point_bracket: Option<f64>,
    warnings: Vec<Warning>,
    error_kind: String,
    diagnosis: String,
}

impl Row {
    fn restarted(&self) -> bool {
        self.history.count(|e| *e == Event::Restart) > 0
    }

    /// The short note of the Markdown tables: a restart, and the warnings.
    fn note(&self) -> String {
        let mut parts = Vec::new();
        if self
            .active
            .is_some_and(|a| a > 0 && a == self.singular_active)
        {
            parts.push("p₀ not measured: every active point on det J = 0".to_string());
        }
        if self.restarted() {
            parts.push("restarted".to_string());
        }
        for w in &self.warnings {
            parts.push(match w {
                Warning::PenaltyBelowBound { below, active, .. } => {
                    format!("γ < bound at {below}/{active}")
                }
                Warning::UnresolvedContact { active, .. } => {
                    format!(
                        "{active} active point{}",
                        if *active == 1 { "" } else { "s" }
                    )
                }
                Warning::PenaltyFarAboveBound { over, active, .. } => {
                    format!("γ > {OVER_PENALTY} × bound at {over}/{active}")
                }
                Warning::PenaltyLoose { .. } => "loose penalty (θ = −1)".to_string(),
                Warning::StifferSlave { .. } => "stiffer slave".to_string(),
                Warning::NearlyIncompressible { .. } => "locking".to_string(),
                Warning::ZoneAtSideEnd { .. } => "zone at side end".to_string(),
                Warning::ClosedFacingAway { .. } => "closed facing away".to_string(),
                Warning::SeveralZones { zones, .. } => format!("{} zones", zones.len()),
                Warning::CoarseZone { .. } => "coarse zone".to_string(),
            });
        }
        parts.join("; ")
    }
}

/// What the deviation of a case (by its name) is measured against: an
/// error only where that reference is exact (the patch test) or converged
/// (the fine reference); against the paper's 8×8 setting or Hertz's
/// formula it is a distance from another approximation.
fn against(case: &str) -> &'static str {
    if case.starts_with("taylor_open_gap") || case == "hertz_lifted_and_pulled_up" {
        "no contact"
    } else if case.starts_with("taylor") {
        "exact σ_yy"
    } else if case.starts_with("hertz_16x16") {
        "Hertz's formula"
    } else if case.starts_with("hertz_p") {
        "fine reference"
    } else {
        "the paper's 8×8 setting"
    }
}

fn max_syy_error(p: &Problem, s: &Solution, exact: f64) -> Result<f64> {
    let mut worst: f64 = 0.0;
    for (b, body) in p.bodies.iter().enumerate() {
        for el in &body.space.elements {
            for qp in body.space.quadrature(el)? {
                let (_, sig) =
                    strain_stress(&p.bodies, &p.map, &s.full, b, qp.param[0], qp.param[1])?;
                worst = worst.max(relative(sig[1], exact).abs());
            }
        }
    }
    Ok(worst)
}

// ANCHOR: run
/// Solves one case with the default solver and classifies the outcome.
fn run_case(case: &Case) -> Row {
    let mut row = Row {
        case: case.name.clone(),
        theta: case.theta,
        penalty_factor: case.penalty_factor,
        status: "failed",
        history: History::default(),
        error: None,
        p0: None,
        reference: match case.metric {
            Metric::PeakPressure(r) => Some(r),
            _ => None,
        },
        active: None,
        below: 0,
        below_inactive: 0,
        singular_active: 0,
        max_displacement: None,
        single_point_bracket: None,
        warnings: Vec::new(),
        error_kind: String::new(),
        diagnosis: String::new(),
    };
    let solved = case.scene.build().and_then(|p| {
        let s = solve(&p, &SolverOptions::default())?;
        Ok((p, s))
    });
    let (p, s) = match solved {
        Ok(ps) => ps,
        Err(e) => {
            if let Error::NotConverged { history, .. } = &e {
                row.history = history.clone();
            }
            row.error_kind = e.kind().tag().into();
            row.diagnosis = e.to_string();
            return row;
        }
    };
    row.history = s.history.clone();
    row.warnings = s.warnings.clone();
    let active: Vec<_> = p.points.iter().filter(|cp| cp.p(&s.full) <= 0.0).collect();
    row.active = Some(active.len());
    row.below = active
        .iter()
        .filter(|cp| cp.below_stability_bound())
        .count();
    row.below_inactive = p
        .points
        .iter()
        .filter(|cp| cp.p(&s.full) > 0.0 && cp.below_stability_bound())
        .count();
    row.singular_active = active.iter().filter(|cp| !cp.regular).count();
    row.max_displacement = Some(s.full.iter().fold(0.0, |m: f64, u| m.max(u.abs())));
    if let [only] = active.as_slice() {
        row.single_point_bracket = Some(only.gamma * only.g0);
    }
    let error = match case.metric {
        // The profile is sampled where the map is regular: with every active
        // point on the degenerate corner it has no pressure to measure, and a
        // deviation of 1 would only say so.
        Metric::PeakPressure(_) if !active.is_empty() && row.singular_active == active.len() => {
            Ok(None)
        }
        Metric::PeakPressure(reference) => PressureProfile::dense(&p, &s.full).map(|prof| {
            let p0 = prof.measures(0).p0;
            row.p0 = Some(p0);
            Some(relative(p0, reference).abs())
        }),
        Metric::UniformStress(exact) => max_syy_error(&p, &s, exact).map(Some),
        Metric::NoContact => Ok(None),
    };
    match error {
        Err(e) => {
            row.error_kind = e.kind().tag().into();
            row.diagnosis = e.to_string();
        }
        Ok(_) if matches!(case.metric, Metric::NoContact) && !active.is_empty() => {
            row.error_kind = "unexpected_contact".into();
        }
        Ok(e) => {
            row.error = e;
            row.status = if active.is_empty() {
                "no_contact"
            } else {
                "converged"
            };
        }
    }
    row
}
// ANCHOR_END: run

/// The penalty factors at which Hertz 8×8 converges within `tol` of the
/// reference, for one θ.
fn good_factors(rows: &[Row], theta: Theta, tol: f64) -> Vec<f64> {
    rows.iter()
        .filter(|r| r.case.starts_with("hertz_8x8_penalty") && r.theta == theta)
        .filter(|r| r.status == "converged" && r.error.is_some_and(|e| e <= tol))
        .map(|r| r.penalty_factor)
        .collect()
}

/// The accuracy criterion of the penalty ranges.
const PENALTY_TOLERANCE: f64 = 0.05;

/// A cell of a penalty × θ view: the error (in `format`) and the iteration
/// count, `†` where active points have a penalty below the stability bound
/// (the solver warns), `‡` where for θ = 1 only inactive points do (their
/// term −(1/γ) w sₙsₙᵀ enters the tangent too, and the solver warns about
/// them as well).
fn penalty_cell(r: &Row, format: Format) -> String {
    let its = r.history.len();
    match (r.status, r.error) {
        ("converged", Some(e)) => {
            let mark = if r.below > 0 {
                " †"
            } else if r.theta == Theta::Symmetric && r.below_inactive > 0 {
                " ‡"
            } else {
                ""
            };
            format!("{} ({its}){mark}", format.render(e))
        }
        (status, _) => format!("{status} ({its})"),
    }
}

/// The penalty × θ view of the cases whose name starts with `prefix`.
fn penalty_view(rows: &[Row], prefix: &str, format: Format) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::new(
            "penalty_factor",
            "penalty factor",
            Unit::None,
            Format::Sci(0),
        ),
        Column::plain("t1", "θ = 1"),
        Column::plain("t0", "θ = 0"),
        Column::plain("tm1", "θ = −1"),
    ]);
    for f in factors() {
        let mut cells: Vec<Cell> = vec![f.into()];
        for theta in Theta::ALL {
            let r = rows
                .iter()
                .find(|r| r.case.starts_with(prefix) && r.theta == theta && r.penalty_factor == f)
                .ok_or_else(|| Error::invalid("case", prefix, "missing from the atlas"))?;
            cells.push(penalty_cell(r, format).into());
        }
        t.push(cells)?;
    }
    Ok(t)
}

/// The chapter "Stability atlas", section by section.
fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("stability")?;

    // Axes and references: every case of the atlas, solved.
    let fine = reference_fine()?;
    let all = cases(reference_8x8()?, fine)?;
    let rows = run_atlas(&all);

    // The full atlas: every case and its diagnosis (atlas.csv).
    chapter.csv("atlas", &atlas_table(&rows)?)?;

    // The penalty range of each θ: the penalty × θ views of the two problems.
    let hertz_view = penalty_view(&rows, "hertz_8x8_penalty", Format::Percent(1))?;
    chapter.text("penalty_hertz.md", &hertz_view.to_markdown())?;
    let taylor_view = penalty_view(&rows, "taylor_penalty", Format::Sci(0))?;
    chapter.text("penalty_taylor.md", &taylor_view.to_markdown())?;

    // The full atlas: the other axes, case by case.
    chapter.text("cases.md", &others_table(&rows)?.to_markdown())?;

    // The penalty range of each θ: the factors within the tolerance.
    chapter.table("penalty_ranges", &ranges_table(&rows)?)?;

    // The facts of every section: the counts, and each case's measures.
    record_count_facts(chapter.facts(), &rows)?;
    record_case_facts(chapter.facts(), &rows)?;
    record_fine_facts(chapter.facts(), &rows, fine)?;
    chapter.finish()
}

/// "Axes and references": p₀ of the Hertz disk on 8², the reference of the
/// Hertz 8² cases on the penalty and gap axes.
fn reference_8x8() -> Result<f64> {
    let s = hertz(2, 8)?;
    let p = s.build()?;
    let sol = solve(&p, &SolverOptions::default())?;
    Ok(PressureProfile::dense(&p, &sol.full)?.measures(0).p0)
}

/// "Axes and references": the Hertz chapter's converged reference (p = 3,
/// 128²), from its facts; the reference of the mesh and degree axis.
fn reference_fine() -> Result<f64> {
    Ok(companion::facts("hertz")?
        .value("reference_p0_mpa")
        .ok_or_else(|| Error::invalid("hertz facts", "reference_p0_mpa", "missing"))?
        * 1e6)
}

/// Every case solved in turn, with its outcome and warnings reported on
/// standard error as it goes.
fn run_atlas(all: &[Case]) -> Vec<Row> {
    let mut rows = Vec::with_capacity(all.len());
    for (k, case) in all.iter().enumerate() {
        let row = run_case(case);
        eprintln!(
            "  [{}/{}] {} θ = {} → {} {}",
            k + 1,
            all.len(),
            row.case,
            row.theta,
            row.status,
            row.error_kind
        );
        for w in &row.warnings {
            eprintln!("      warning: {w}");
        }
        rows.push(row);
    }
    rows
}

// ANCHOR: tables
/// A text cell, empty where the text is.
fn text_cell(s: &str) -> Cell {
    if s.is_empty() {
        Cell::Empty
    } else {
        s.into()
    }
}

/// "The full atlas": every case with its solver history, active points,
/// error, warnings and diagnosis (`atlas.csv`).
fn atlas_table(rows: &[Row]) -> Result<Table> {
    let mut atlas = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("theta", "θ"),
        Column::new("penalty_factor", "penalty", Unit::None, Format::Sci(0)),
        Column::plain("status", "status"),
        Column::plain("iterations", "its"),
        Column::plain("corrections", "corr."),
        Column::plain("skipped_updates", "skipped"),
        Column::plain("restarted", "restarted"),
        Column::plain("active_points", "active"),
        Column::plain("active_below_bound", "below bound"),
        Column::plain("inactive_below_bound", "inactive below bound"),
        Column::plain("singular_active", "active on det J = 0"),
        Column::new(
            "error_vs_reference",
            "deviation",
            Unit::None,
            Format::Sci(1),
        ),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::plain("warnings", "warnings"),
        Column::plain("error_kind", "error kind"),
        Column::plain("diagnosis", "diagnosis"),
    ]);
    for r in rows {
        let warnings: Vec<String> = r.warnings.iter().map(|w| w.to_string()).collect();
        atlas.push(vec![
            r.case.clone().into(),
            r.theta.value().into(),
            r.penalty_factor.into(),
            r.status.into(),
            r.history.len().into(),
            r.history.corrections().into(),
            r.history.skipped_updates().into(),
            (if r.restarted() { "yes" } else { "no" }).into(),
            r.active.into(),
            r.below.into(),
            r.below_inactive.into(),
            r.singular_active.into(),
            r.error.into(),
            r.p0.into(),
            text_cell(&warnings.join("; ")),
            text_cell(&r.error_kind),
            text_cell(&r.diagnosis),
        ])?;
    }
    Ok(atlas)
}

/// "The full atlas" in Markdown: the axes other than the penalty, case by
/// case (the penalty axis has its views, `penalty_view`).
fn others_table(rows: &[Row]) -> Result<Table> {
    let mut others = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("status", "status"),
        Column::plain("iterations", "its"),
        Column::plain("active_points", "active"),
        Column::new(
            "error_vs_reference",
            "deviation",
            Unit::None,
            Format::Sci(1),
        ),
        Column::plain("against", "against"),
        Column::plain("note", "note"),
    ]);
    for r in rows.iter().filter(|r| !r.case.contains("_penalty_")) {
        others.push(vec![
            r.case.clone().into(),
            r.status.into(),
            r.history.len().into(),
            r.active.into(),
            r.error.into(),
            against(&r.case).into(),
            text_cell(&r.note()),
        ])?;
    }
    Ok(others)
}

/// "The penalty range of each θ": the factors at which Hertz 8×8 is within
/// the tolerance of its reference.
fn ranges_table(rows: &[Row]) -> Result<Table> {
    // The factors themselves, not an interval: the set need not be
    // contiguous (θ = 1 is off by more than the tolerance at factor 1,
    // between two factors within it).
    let mut ranges = Table::new(vec![
        Column::plain("theta", "θ"),
        Column::plain("factors", "factors within 5 %"),
        Column::plain("count", "count"),
    ]);
    for theta in Theta::ALL {
        let ok = good_factors(rows, theta, PENALTY_TOLERANCE);
        let list: Vec<String> = ok.iter().map(|&x| Format::Sci(0).render(x)).collect();
        ranges.push(vec![
            theta.value().into(),
            list.join(" ").into(),
            ok.len().into(),
        ])?;
    }
    Ok(ranges)
}
// ANCHOR_END: tables

// ANCHOR: facts
/// The prose counts the cases by outcome, and quotes the tolerance and the
/// sharp penalty's safety factor.
fn record_count_facts(f: &mut Facts, rows: &[Row]) -> Result<()> {
    f.count("cases", rows.len())?;
    let count = |pred: &dyn Fn(&Row) -> bool| rows.iter().filter(|r| pred(r)).count();
    f.count("converged", count(&|r| r.status == "converged"))?;
    f.count("failed", count(&|r| r.status == "failed"))?;
    f.count("no_contact", count(&|r| r.status == "no_contact"))?;
    f.count("restarted", count(&|r| r.restarted()))?;
    f.count("warned_below_bound", count(&|r| r.below > 0))?;
    f.count(
        "singular",
        count(&|r| r.error_kind == ErrorKind::SingularKernel.tag()),
    )?;
    f.number("tolerance", PENALTY_TOLERANCE, Format::Percent(0))?;
    f.number("sharp_safety", SHARP_SAFETY, Format::Plain)
}

/// The facts' key of a case: its name with `_` for `.` and `-`, then the
/// θ (t1, t0, tm1).
fn fact_key(r: &Row) -> String {
    let theta = match r.theta {
        Theta::Symmetric => "t1",
        Theta::Incomplete => "t0",
        Theta::Skew => "tm1",
    };
    format!("{}_{theta}", r.case.replace(['.', '-'], "_"))
}

/// Every section quotes single cases: per case and θ, its error, p₀ and
/// reference, its points, its displacement, warnings, status and
/// iterations.
fn record_case_facts(f: &mut Facts, rows: &[Row]) -> Result<()> {
    for r in rows {
        let key = fact_key(r);
        if let Some(e) = r.error {
            f.number(&format!("{key}_error"), e, Format::Pow10(1))?;
            f.number(&format!("{key}_percent"), e, Format::Percent(1))?;
        }
        if let Some(p0) = r.p0 {
            f.number(&format!("{key}_p0"), p0 * 1e-6, Format::Pow10(2))?;
        }
        if let Some(p0) = r.reference {
            f.number(&format!("{key}_reference"), p0 * 1e-6, Format::Pow10(2))?;
        }
        if let Some(b) = r.single_point_bracket {
            f.number(&format!("{key}_bracket"), b * 1e-6, Format::Pow10(2))?;
        }
        if let Some(a) = r.active {
            f.count(&format!("{key}_active"), a)?;
        }
        f.count(&format!("{key}_below"), r.below)?;
        f.count(&format!("{key}_below_inactive"), r.below_inactive)?;
        f.count(&format!("{key}_singular_active"), r.singular_active)?;
        if let Some(u) = r.max_displacement {
            f.number(&format!("{key}_umax_mm"), u * 1e3, Format::Fixed(2))?;
        }
        f.count(&format!("{key}_warnings"), r.warnings.len())?;
        f.text(&format!("{key}_status"), r.status)?;
        f.count(&format!("{key}_iterations"), r.history.len())?;
    }
    Ok(())
}
/// "The penalty range of each θ" measures the penalty axis against the
/// paper's 8×8 setting, itself a coarse solution: each of its p₀ is also
/// set against the converged disk (the fine reference), signed.
fn record_fine_facts(f: &mut Facts, rows: &[Row], fine: f64) -> Result<()> {
    for r in rows
        .iter()
        .filter(|r| r.case.starts_with("hertz_8x8_penalty"))
    {
        if let Some(p0) = r.p0 {
            let key = format!("{}_vs_fine", fact_key(r));
            f.number(&key, relative(p0, fine), Format::SignedPercent(1))?;
        }
    }
    Ok(())
}
// ANCHOR_END: facts
