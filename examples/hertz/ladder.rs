//! "The solver ladder": every degree and mesh of the ladder solved by each
//! solver, one converged solve measured, or its failure kept.

use crate::{LADDER_DEGREES, LADDER_ELEMENTS};
use companion::hertz as setup;
use companion::timing::median_time;
use companion::Solver;
use iga_contact::error::{Error, Result};
use iga_contact::post::{self, PressureProfile};
use iga_contact::problem::Problem;
use iga_contact::scene::Scene;
use iga_contact::solver::history::History;
use iga_contact::solver::{solve, Solution, SolverOptions};

/// One converged solve, measured.
pub struct Run {
    pub degree: usize,
    pub elements: usize,
    pub solver: Solver,
    pub problem: Problem,
    pub solution: Solution,
    pub p0: f64,
    pub half_width: f64,
    /// Vertical force of the floor on the half disk.
    pub contact_force: f64,
    /// Vertical resultant of the applied load (downwards, so negative).
    pub applied_force: f64,
    /// Build + solve, wall time.
    pub seconds: f64,
}

/// A solve that did not converge.
pub struct Failure {
    pub degree: usize,
    pub elements: usize,
    pub solver: Solver,
    pub history: History,
    pub reason: String,
}

// ANCHOR: measure
/// Builds and solves the p-degree scene on `elements`², measuring p₀ and a
/// on the dense profile. Non-convergence is a result, kept as a Failure.
pub fn run(
    degree: usize,
    elements: usize,
    solver: Solver,
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

/// The runs of the ladder that converged, and those that did not.
pub struct Ladder {
    pub runs: Vec<Run>,
    pub failures: Vec<Failure>,
}

// ANCHOR: ladder
/// "The solver ladder": every degree and mesh of the ladder, solved by
/// each solver (in the order of `ladder.csv`), the paper's iteration being
/// the scene's own `[solver]` table.
pub fn solve_ladder(base: &Scene) -> Result<Ladder> {
    let mut ladder = Ladder {
        runs: Vec::new(),
        failures: Vec::new(),
    };
    for p in LADDER_DEGREES {
        for n in LADDER_ELEMENTS {
            for solver in Solver::ALL {
                match run(p, n, solver, &solver.options_from(base.solver))? {
                    Ok(r) => ladder.runs.push(r),
                    Err(f) => ladder.failures.push(f),
                }
            }
        }
    }
    Ok(ladder)
}
// ANCHOR_END: ladder

impl Ladder {
    /// The run of `solver` on p, `n`² that a section shows (it must have
    /// converged).
    pub fn run(&self, solver: Solver, p: usize, n: usize) -> Result<&Run> {
        self.runs
            .iter()
            .find(|r| r.solver == solver && r.degree == p && r.elements == n)
            .ok_or_else(|| {
                Error::invalid(
                    "hertz ladder",
                    format!("{} {n}²", solver.key()),
                    "this run did not converge",
                )
            })
    }
}

/// The error of a run a table needs that did not converge.
pub fn not_converged(f: &Failure) -> Error {
    Error::invalid(
        "hertz ladder",
        format!("{} on p = {}, {}²", f.solver.key(), f.degree, f.elements),
        format!(
            "needed by a table, but not converged after {} iterations: {}",
            f.history.len(),
            f.reason
        ),
    )
}
