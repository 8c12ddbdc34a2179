//! The stability atlas: the program behind the chapter "Stability atlas".
//! The method on stiff and extreme cases — penalties over ten decades for
//! the three θ, stiffness contrast, near incompressibility, load levels,
//! open and penetrating gaps, very coarse and fine meshes — each ending
//! either converged or in a typed, diagnosed error.
//! Output: `book/src/generated/stability/`.
//!
//! Run it with `cargo run --release --example stability`.

#[path = "../common/hertz.rs"]
mod setup;

use iga_contact::assembly::{strain_stress, Load};
use iga_contact::contact::{Integration, Theta};
use iga_contact::error::{Error, Result};
use iga_contact::post::{relative, PressureProfile};
use iga_contact::problem::Problem;
use iga_contact::report::chapter::Chapter;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};
use iga_contact::scene::{GeometrySpec, RefineSpec, Scene};
use iga_contact::solver::history::{Event, History};
use iga_contact::solver::{solve, Solution, SolverOptions};

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
    Scene::shipped("taylor.toml")
}

/// Every Nitsche parameter group of a scene, set by `f`.
fn with(mut scene: Scene, f: impl Fn(&mut iga_contact::contact::Nitsche)) -> Scene {
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
fn cases(reference_8x8: f64) -> Result<Vec<Case>> {
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
            let set = |n: &mut iga_contact::contact::Nitsche| {
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
    let analytic = setup::analytic(&hertz(2, 8)?)?.p0;
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
                Metric::PeakPressure(analytic),
            ));
        }
    }
    for n in [128, 256] {
        out.push(case(
            format!("hertz_p2_{n}x{n}"),
            hertz(2, n)?,
            Metric::PeakPressure(analytic),
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
    error_kind: String,
    diagnosis: String,
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
            row.error_kind = e.kind().into();
            row.diagnosis = e.to_string();
            return row;
        }
    };
    row.history = s.history.clone();
    let active = p.active_points(&s.u);
    let error = match case.metric {
        Metric::PeakPressure(reference) => PressureProfile::dense(&p, &s.full)
            .map(|prof| Some(relative(prof.measures(0).p0, reference).abs())),
        Metric::UniformStress(exact) => max_syy_error(&p, &s, exact).map(Some),
        Metric::NoContact => Ok(None),
    };
    match error {
        Err(e) => {
            row.error_kind = e.kind().into();
            row.diagnosis = e.to_string();
        }
        Ok(_) if matches!(case.metric, Metric::NoContact) && active > 0 => {
            row.error_kind = "unexpected_contact".into();
        }
        Ok(e) => {
            row.error = e;
            row.status = if active == 0 {
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

fn main() -> Result<()> {
    let mut chapter = Chapter::from_args("stability")?;
    let reference = {
        let s = hertz(2, 8)?;
        let p = s.build()?;
        let sol = solve(&p, &SolverOptions::default())?;
        PressureProfile::dense(&p, &sol.full)?.measures(0).p0
    };
    let all = cases(reference)?;
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
        rows.push(row);
    }

    // ANCHOR: tables
    let mut atlas = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("theta", "θ"),
        Column::new("penalty_factor", "penalty", Unit::None, Format::Sci(0)),
        Column::plain("status", "status"),
        Column::plain("iterations", "its"),
        Column::plain("corrections", "corr.").csv_only(),
        Column::plain("skipped_updates", "skipped").csv_only(),
        Column::new("error_vs_reference", "error", Unit::None, Format::Sci(1)),
        Column::plain("error_kind", "error kind").csv_only(),
        Column::plain("diagnosis", "diagnosis").csv_only(),
    ]);
    for r in &rows {
        let text = |s: &str| if s.is_empty() { Cell::Empty } else { s.into() };
        atlas.push(vec![
            r.case.clone().into(),
            r.theta.value().into(),
            r.penalty_factor.into(),
            r.status.into(),
            r.history.len().into(),
            r.history.corrections().into(),
            r.history.skipped_updates().into(),
            r.error.into(),
            text(&r.error_kind),
            text(&r.diagnosis),
        ])?;
    }
    chapter.table("atlas", &atlas)?;

    let mut ranges = Table::new(vec![
        Column::plain("theta", "θ"),
        Column::new("lowest", "lowest factor", Unit::None, Format::Sci(0)),
        Column::new("highest", "highest factor", Unit::None, Format::Sci(0)),
        Column::plain("count", "factors within 5 %"),
    ]);
    for theta in Theta::ALL {
        let ok = good_factors(&rows, theta, PENALTY_TOLERANCE);
        let lo = ok.iter().copied().reduce(f64::min);
        let hi = ok.iter().copied().reduce(f64::max);
        ranges.push(vec![
            theta.value().into(),
            lo.into(),
            hi.into(),
            ok.len().into(),
        ])?;
    }
    chapter.table("penalty_ranges", &ranges)?;

    let mut kernels = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("theta", "θ"),
        Column::plain("refined", "refined factorisations"),
        Column::plain("lu_fallbacks", "LU fallbacks"),
    ]);
    let count = |h: &History, e: Event| h.count(|x| *x == e);
    for r in &rows {
        let (refined, lu) = (
            count(&r.history, Event::KernelRefined),
            count(&r.history, Event::KernelLuFallback),
        );
        if refined + lu > 0 {
            kernels.push(vec![
                r.case.clone().into(),
                r.theta.value().into(),
                refined.into(),
                lu.into(),
            ])?;
        }
    }
    chapter.table("kernel_paths", &kernels)?;
    // ANCHOR_END: tables

    // ANCHOR: facts
    let f = chapter.facts();
    f.count("cases", rows.len())?;
    f.count(
        "converged",
        rows.iter().filter(|r| r.status == "converged").count(),
    )?;
    f.count(
        "failed",
        rows.iter().filter(|r| r.status == "failed").count(),
    )?;
    f.number("tolerance", PENALTY_TOLERANCE, Format::Percent(0))?;
    for r in &rows {
        // keys: the case name with `_` for `.` and `-`, then the θ: t1, t0, tm1
        let theta = match r.theta {
            Theta::Symmetric => "t1",
            Theta::Incomplete => "t0",
            Theta::Skew => "tm1",
        };
        let key = format!("{}_{theta}", r.case.replace(['.', '-'], "_"));
        if let Some(e) = r.error {
            f.number(&format!("{key}_error"), e, Format::Pow10(1))?;
            f.number(&format!("{key}_percent"), e, Format::Percent(1))?;
        }
        f.text(&format!("{key}_status"), r.status)?;
        f.count(&format!("{key}_iterations"), r.history.len())?;
    }
    let total = |e: Event| {
        rows.iter()
            .map(|r| count(&r.history, e.clone()))
            .sum::<usize>()
    };
    f.count("kernel_refined", total(Event::KernelRefined))?;
    f.count("kernel_lu_fallbacks", total(Event::KernelLuFallback))?;
    // ANCHOR_END: facts
    chapter.finish()
}
