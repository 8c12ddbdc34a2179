//! The numbers the prose quotes: the model and Hertz's solution, the
//! convergence study, the 8×8 runs, and the ladder (which the claims
//! chapter reads run by run).

use crate::convergence::Convergence;
use crate::ladder::{Ladder, Run};
use crate::{PAPER_CORRECTION_ITERATION, REFERENCE};
use companion::{Facts, Solver};
use iga_contact::error::Result;
use iga_contact::post::hertz::Hertz;
use iga_contact::post::{relative, PressureProfile};
use iga_contact::report::table::Format;
use iga_contact::solver::history::Event;

// ANCHOR: facts
/// "The model" and "What Hertz predicts" quote the load and Hertz's
/// solution.
pub fn record_model_facts(f: &mut Facts, exact: &Hertz) -> Result<()> {
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
pub fn record_convergence_facts(f: &mut Facts, study: &Convergence, exact: &Hertz) -> Result<()> {
    let (rp0, ra) = (study.reference.p0, study.reference.half_width);
    f.count("reference_degree", REFERENCE.0)?;
    f.count("reference_elements", REFERENCE.1)?;
    f.count("reference_dofs", study.reference.dofs)?;
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
    let (cp0, ca) = (study.check.p0, study.check.half_width);
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
    for rung in &study.rows {
        let key = format!("p{}_{}", rung.degree, rung.elements);
        let (p0, a) = (rung.measured.p0, rung.measured.half_width);
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
pub fn record_8x8_facts(
    f: &mut Facts,
    paper: &Run,
    default: &Run,
    study: &Convergence,
    exact: &Hertz,
) -> Result<()> {
    let (rp0, ra) = (study.reference.p0, study.reference.half_width);
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
pub fn record_ladder_facts(f: &mut Facts, ladder: &Ladder, exact: &Hertz) -> Result<()> {
    let (runs, failures) = (&ladder.runs, &ladder.failures);
    let force_balance = runs
        .iter()
        .map(|r| relative(r.contact_force, -r.applied_force).abs())
        .fold(0.0, f64::max);
    f.number("force_balance", force_balance, Format::Pow10(0))?;
    let quadrature = runs
        .iter()
        .map(|r| relative(-r.applied_force, exact.load / 2.0).abs())
        .fold(0.0, f64::max);
    f.number("load_quadrature", quadrature, Format::Pow10(0))?;
    f.number("solver_spread", solver_spread(runs), Format::Pow10(0))?;
    for solver in Solver::ALL {
        let its: Vec<usize> = runs
            .iter()
            .filter(|r| r.solver == solver)
            .map(|r| r.solution.history.len())
            .collect();
        let (lo, hi) = (its.iter().min(), its.iter().max());
        if let (Some(lo), Some(hi)) = (lo, hi) {
            let key = solver.key();
            f.text(&format!("{key}_iterations"), format!("{lo}–{hi}"))?;
        }
    }
    f.count("failures", failures.len())?;
    // Every run of the ladder by solver, degree and mesh: its iterations,
    // or "failed" (the claims chapter reads these).
    for r in runs {
        let key = format!("its_{}_p{}_{}", r.solver.key(), r.degree, r.elements);
        f.count(&key, r.solution.history.len())?;
    }
    for r in failures {
        let key = format!("its_{}_p{}_{}", r.solver.key(), r.degree, r.elements);
        f.text(&key, "failed")?;
    }
    Ok(())
}
// ANCHOR_END: facts

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
