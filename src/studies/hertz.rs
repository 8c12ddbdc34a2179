//! Hertz contact of an elastic disk on a rigid plane (the paper's section
//! 5.2: Fig. 4, Table 2, Figs. 5 and 6).
//!
//! The model is the right half (x ≥ 0) of the disk of radius R = 0.2
//! centred at (0, R), loaded by its own weight and resting on the rigid
//! floor y = 0; u_x = 0 on the symmetry line removes the horizontal rigid
//! mode. The contact force of the model is therefore half the load of the
//! full disk.
//!
//! The contact pressure is the Nitsche bracket −[σ_n + γ g_n]₋. It is
//! evaluated *densely* along the slave arc ([`pressure_profile`]), not only
//! at the contact quadrature points, so that the peak pressure and the
//! contact half-width ([`measure`]) do not depend on where the solver's
//! Gauss points happen to sit.
//!
//! [`run`] writes the chapter's tables and figures. Only two files carry
//! wall-clock times, `ladder.csv` (its `seconds` column) and `timings.csv`;
//! every other file is identical from one run to the next.

use crate::benchmarks::{Hertz, HertzAnalytic, HERTZ_RADIUS};
use crate::contact::{contact_points, ContactPair, Integration};
use crate::error::{Error, Result};
use crate::linsolve::Factoriser;
use crate::nurbs::Side;
use crate::problem::{Kernel, Problem};
use crate::report::atomic::write_text;
use crate::report::plot::{
    field_figure, geometry_figure, line_chart, Axes, FieldCell, LineKind, Polyline, Series,
    BLACK_INDEX,
};
use crate::report::vtu::sample_bodies;
use crate::solver::history::{Event, History};
use crate::solver::kernel::factor_kernel;
use crate::solver::{solve, Factorisation, Solution, SolverKind, SolverOptions};
use std::collections::BTreeMap;
use std::fmt;
use std::path::Path;
use std::time::Instant;

/// Sample points per slave element of the dense pressure profile (Gauss
/// points of a 20-point rule, so element ends are never sampled twice).
pub const SAMPLES_PER_ELEMENT: usize = 20;
/// The iteration at which the paper's correction fired on the 8×8 mesh.
pub const PAPER_CORRECTION_ITERATION: usize = 13;
/// Degrees and meshes (elements per direction) of the solver ladder.
pub const LADDER_DEGREES: [usize; 2] = [2, 3];
pub const LADDER_ELEMENTS: [usize; 4] = [8, 16, 32, 64];
/// Meshes of the convergence study (Fig. 6).
pub const CONVERGENCE_ELEMENTS: [usize; 6] = [4, 8, 16, 32, 64, 128];
/// The converged reference: (degree, elements per direction).
pub const REFERENCE: (usize, usize) = (3, 128);
/// Meshes of the per-phase timing benchmark (p = 2).
pub const TIMING_ELEMENTS: [usize; 3] = [8, 64, 256];
/// The LU comparison row (`bfgs_lu`) is timed up to this mesh only: at
/// 256² the LU factors need about 8 GB.
pub const LU_TIMING_MAX_ELEMENTS: usize = 64;
/// Meshes of the pressure-profile figure.
pub const PROFILE_ELEMENTS: [usize; 2] = [8, 64];

// ------------------------------------------------------------ measuring

/// The Nitsche bracket P = σ_n + γ g_n (negative where the disk is pressed
/// on the floor) at `per_element` Gauss points of every slave element of
/// every contact pair of `problem`, as `(x, P)` sorted by x.
///
/// The points are built by [`contact_points`] exactly as the solver's are
/// (same normal, gap, penalty and σ_n functional); only the rule is denser.
/// `per_element` must lie in 1..=30.
pub fn signed_profile(
    problem: &Problem,
    full: &[f64],
    per_element: usize,
) -> Result<Vec<(f64, f64)>> {
    if full.len() != problem.map.n_total() {
        return Err(Error::invalid(
            "hertz.displacement",
            format!("{} values", full.len()),
            format!("the DOF map has {} DOFs", problem.map.n_total()),
        ));
    }
    let pairs: Vec<ContactPair> = problem
        .pairs
        .iter()
        .map(|p| ContactPair {
            integration: Integration::Gauss,
            gauss_points: Some(per_element),
            ..p.clone()
        })
        .collect();
    let points = contact_points(&problem.bodies, &problem.map, &pairs)?;
    let mut out: Vec<(f64, f64)> = points.iter().map(|cp| (cp.x[0], cp.p(full))).collect();
    out.sort_by(|a, b| a.0.total_cmp(&b.0));
    Ok(out)
}

/// The contact pressure −[σ_n + γ g_n]₋ ≥ 0 sampled densely along the slave
/// boundary: `(x, pressure)` at `per_element` points per slave element
/// (see [`signed_profile`]).
pub fn pressure_profile(
    problem: &Problem,
    full: &[f64],
    per_element: usize,
) -> Result<Vec<(f64, f64)>> {
    Ok(signed_profile(problem, full, per_element)?
        .into_iter()
        .map(|(x, p)| (x, -p.min(0.0)))
        .collect())
}

/// Peak pressure and contact half-width of a signed profile `(x, P)` sorted
/// by x: p₀ = max −\[P\]₋, and the half-width is the x where the pressure
/// falls to zero, found by linear interpolation of P between the last
/// loaded sample (P < 0) and the sample after it (P ≥ 0). With no loaded
/// sample both are 0; if the last sample is loaded, the half-width is its x.
pub fn measure_signed(signed: &[(f64, f64)]) -> (f64, f64) {
    let p0 = signed.iter().map(|s| -s.1.min(0.0)).fold(0.0, f64::max);
    let Some(last) = signed.iter().rposition(|s| s.1 < 0.0) else {
        return (0.0, 0.0);
    };
    let (x1, p1) = signed[last];
    let a = match signed.get(last + 1) {
        Some(&(x2, p2)) if p2 > p1 => x1 + (x2 - x1) * (-p1) / (p2 - p1),
        _ => x1,
    };
    (p0, a)
}

/// (p₀, half-width) of the solution `full` of a Hertz problem, from the
/// dense profile with `per_element` samples per slave element.
pub fn measure(problem: &Problem, full: &[f64], per_element: usize) -> Result<(f64, f64)> {
    Ok(measure_signed(&signed_profile(problem, full, per_element)?))
}

/// The resultant of the applied load that the floor must balance, from the
/// assembled load vector: −Σ F_y over the free vertical DOFs (every
/// vertical DOF of the Hertz model is free). Equals
/// [`HertzAnalytic::load`]/2 up to the quadrature error of the disk's area.
pub fn applied_force(problem: &Problem) -> f64 {
    let mut f = 0.0;
    for (bi, body) in problem.bodies.iter().enumerate() {
        for cp in 0..body.space.n_cp() {
            if let Some(i) = problem.map.free(problem.map.global(bi, cp, 1)) {
                f -= problem.rhs[i];
            }
        }
    }
    f
}

/// `bfgs`, `bfgs_no_correction` or `newton`.
pub fn solver_name(kind: SolverKind) -> &'static str {
    match kind {
        SolverKind::Bfgs => "bfgs",
        SolverKind::BfgsNoCorrection => "bfgs_no_correction",
        SolverKind::Newton => "newton",
    }
}

/// The solvers of the ladder: the three [`SolverKind`]s with default
/// options, and `bfgs_paper`, BFGS with the correction and full steps
/// (`line_search_after: usize::MAX`), the paper's iteration.
pub fn ladder_solvers() -> Vec<(&'static str, SolverOptions)> {
    let mut v: Vec<(&'static str, SolverOptions)> = [
        SolverKind::Bfgs,
        SolverKind::BfgsNoCorrection,
        SolverKind::Newton,
    ]
    .into_iter()
    .map(|k| (solver_name(k), SolverOptions::with_kind(k)))
    .collect();
    v.insert(1, ("bfgs_paper", paper_bfgs()));
    v
}

/// The paper's iteration: BFGS with the correction, full steps.
pub fn paper_bfgs() -> SolverOptions {
    SolverOptions {
        line_search_after: usize::MAX,
        ..SolverOptions::with_kind(SolverKind::Bfgs)
    }
}

/// The p-degree Hertz problem on an `elements`² mesh (the paper's
/// set-up: θ = 0, the empirical penalty, Gauss integration of Γc).
pub fn problem(degree: usize, elements: usize) -> Result<Problem> {
    Hertz {
        degree,
        elements,
        ..Hertz::default()
    }
    .build()
}

// ------------------------------------------------------------ the ladder

/// One converged run of the solver ladder.
#[derive(Clone, Debug, PartialEq)]
pub struct LadderRow {
    pub degree: usize,
    pub elements: usize,
    pub dofs: usize,
    /// A name of [`ladder_solvers`].
    pub solver: &'static str,
    pub iterations: usize,
    pub corrections: usize,
    pub p0: f64,
    pub half_width: f64,
    /// Vertical force of the floor on the half disk (N/m).
    pub contact_force: f64,
    /// [`applied_force`] (N/m).
    pub applied_force: f64,
    /// Wall time of `Problem::new` + solve.
    pub seconds: f64,
}

/// A run of the ladder that did not converge.
#[derive(Clone, Debug, PartialEq)]
pub struct Failure {
    pub degree: usize,
    pub elements: usize,
    pub solver: &'static str,
    pub iterations: usize,
    pub corrections: usize,
    pub reason: String,
}

/// Either outcome of one ladder run.
pub enum Outcome {
    Converged(LadderRow, Box<Problem>, Solution),
    Failed(Failure),
}

/// Builds and solves one rung; a solver that does not converge is a
/// [`Failure`], any other error is returned.
pub fn ladder_run(
    degree: usize,
    elements: usize,
    solver: &'static str,
    opts: &SolverOptions,
) -> Result<Outcome> {
    let t = Instant::now();
    let problem = problem(degree, elements)?;
    match solve(&problem, opts) {
        Ok(solution) => {
            let seconds = t.elapsed().as_secs_f64();
            let (p0, half_width) = measure(&problem, &solution.full, SAMPLES_PER_ELEMENT)?;
            let row = LadderRow {
                degree,
                elements,
                dofs: problem.n(),
                solver,
                iterations: solution.history.len(),
                corrections: solution.history.corrections(),
                p0,
                half_width,
                contact_force: problem.contact_force(&solution.full)[1],
                applied_force: applied_force(&problem),
                seconds,
            };
            Ok(Outcome::Converged(row, Box::new(problem), solution))
        }
        Err(Error::NotConverged { reason, history }) => Ok(Outcome::Failed(Failure {
            degree,
            elements,
            solver,
            iterations: history.len(),
            corrections: history.corrections(),
            reason,
        })),
        Err(e) => Err(e),
    }
}

/// Exactly `degree,elements,dofs,solver,iterations,corrections,p0,half_width,contact_force,applied_force,seconds`.
pub fn ladder_csv(rows: &[LadderRow]) -> String {
    let mut s = String::from(
        "degree,elements,dofs,solver,iterations,corrections,p0,half_width,contact_force,applied_force,seconds\n",
    );
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{},{},{},{:.9e},{:.9e},{:.12e},{:.12e},{:.6}\n",
            r.degree,
            r.elements,
            r.dofs,
            r.solver,
            r.iterations,
            r.corrections,
            r.p0,
            r.half_width,
            r.contact_force,
            r.applied_force,
            r.seconds
        ));
    }
    s
}

/// The ladder without its timing column, errors against Hertz, and the
/// failed runs.
pub fn ladder_md(rows: &[LadderRow], failures: &[Failure]) -> String {
    let exact = HertzAnalytic::new();
    let half_load = exact.load / 2.0;
    let mut t = String::from(
        "| p | elements | DOFs | solver | iterations | corrections | p₀ (MPa) | p₀ vs Hertz | a (mm) | a vs Hertz | \\|F_c − F_applied\\| / F_applied | \\|F_applied − P/2\\| / (P/2) |\n\
         |---|---|---|---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        t.push_str(&format!(
            "| {} | {}² | {} | {} | {} | {} | {:.4} | {} | {:.3} | {} | {} | {} |\n",
            r.degree,
            r.elements,
            r.dofs,
            r.solver,
            r.iterations,
            r.corrections,
            r.p0 / 1e6,
            signed_percent(r.p0, exact.p0),
            r.half_width * 1e3,
            signed_percent(r.half_width, exact.half_width),
            sci((r.contact_force - r.applied_force).abs() / r.applied_force),
            sci((r.applied_force - half_load).abs() / half_load),
        ));
    }
    if failures.is_empty() {
        t.push_str("\nEvery run converged.\n");
    } else {
        t.push_str(
            "\nRuns that did not converge (also in `failures.csv`):\n\n\
             | p | elements | solver | iterations | corrections | reason |\n|---|---|---|---|---|---|\n",
        );
        for f in failures {
            t.push_str(&format!(
                "| {} | {}² | {} | {} | {} | {} |\n",
                f.degree, f.elements, f.solver, f.iterations, f.corrections, f.reason
            ));
        }
    }
    t
}

fn failures_csv(failures: &[Failure]) -> String {
    let mut s = String::from("degree,elements,solver,iterations,corrections,reason\n");
    for f in failures {
        s.push_str(&format!(
            "{},{},{},{},{},\"{}\"\n",
            f.degree,
            f.elements,
            f.solver,
            f.iterations,
            f.corrections,
            f.reason.replace('"', "'")
        ));
    }
    s
}

// ------------------------------------------------------------ convergence

/// p₀ and half-width of one discretisation (solved with Newton: the
/// discrete solution does not depend on the solver, see the ladder).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Measured {
    pub degree: usize,
    pub elements: usize,
    pub dofs: usize,
    pub p0: f64,
    pub half_width: f64,
}

/// Solves with Newton and measures.
pub fn measured(degree: usize, elements: usize) -> Result<Measured> {
    let problem = problem(degree, elements)?;
    let solution = solve(&problem, &SolverOptions::with_kind(SolverKind::Newton))?;
    let (p0, half_width) = measure(&problem, &solution.full, SAMPLES_PER_ELEMENT)?;
    Ok(Measured {
        degree,
        elements,
        dofs: problem.n(),
        p0,
        half_width,
    })
}

/// `degree,elements,dofs,p0,half_width,` then the relative errors of both
/// against Hertz and against the reference.
fn convergence_csv(rows: &[Measured], reference: &Measured) -> String {
    let exact = HertzAnalytic::new();
    let mut s = String::from(
        "degree,elements,dofs,p0,half_width,p0_error_hertz,half_width_error_hertz,p0_error_reference,half_width_error_reference\n",
    );
    for r in rows {
        s.push_str(&format!(
            "{},{},{},{:.9e},{:.9e},{:.6e},{:.6e},{:.6e},{:.6e}\n",
            r.degree,
            r.elements,
            r.dofs,
            r.p0,
            r.half_width,
            rel(r.p0, exact.p0),
            rel(r.half_width, exact.half_width),
            rel(r.p0, reference.p0),
            rel(r.half_width, reference.half_width),
        ));
    }
    s
}

fn convergence_md(rows: &[Measured], reference: &Measured, check: Option<&Measured>) -> String {
    let exact = HertzAnalytic::new();
    let mut t = format!(
        "| | p₀ (MPa) | a (mm) |\n|---|---|---|\n\
         | Hertz (half-space, line load) | {:.5} | {:.4} |\n\
         | reference: p = {}, {}² ({} DOFs) | {:.5} | {:.4} |\n\
         | reference against Hertz | {} | {} |\n",
        exact.p0 / 1e6,
        exact.half_width * 1e3,
        reference.degree,
        reference.elements,
        reference.dofs,
        reference.p0 / 1e6,
        reference.half_width * 1e3,
        signed_percent(reference.p0, exact.p0),
        signed_percent(reference.half_width, exact.half_width),
    );
    if let Some(c) = check {
        t.push_str(&format!(
            "| p = {}, {}² against the reference | {} | {} |\n",
            c.degree,
            c.elements,
            signed_percent(c.p0, reference.p0),
            signed_percent(c.half_width, reference.half_width),
        ));
    }
    t.push_str(
        "\nErrors are signed, (value − target) / target.\n\n\
         | p | elements | DOFs | p₀ (MPa) | a (mm) | p₀ vs Hertz | a vs Hertz | p₀ vs reference | a vs reference |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    for r in rows {
        t.push_str(&format!(
            "| {} | {}² | {} | {:.5} | {:.4} | {} | {} | {} | {} |\n",
            r.degree,
            r.elements,
            r.dofs,
            r.p0 / 1e6,
            r.half_width * 1e3,
            signed_percent(r.p0, exact.p0),
            signed_percent(r.half_width, exact.half_width),
            signed_percent(r.p0, reference.p0),
            signed_percent(r.half_width, reference.half_width),
        ));
    }
    t
}

// ------------------------------------------------------------ timings

/// Wall times (s) of the phases of one Hertz solve with BFGS.
#[derive(Clone, Debug, PartialEq)]
pub struct Timing {
    pub degree: usize,
    pub elements: usize,
    pub dofs: usize,
    /// `bfgs` (the default: damped, low-rank kernel factorisation),
    /// `bfgs_paper` (full steps) or `bfgs_lu` (the default with LU kernels).
    pub solver: &'static str,
    /// `Problem::new`: stiffness, load, contact points, sparsity patterns.
    pub assembly: f64,
    /// The tied kernel (17) and its factorisation (symbolic + numeric).
    pub first_factorisation: f64,
    /// The solve minus [`Timing::first_factorisation`]: iterations,
    /// corrections (refactorisations) and line searches.
    pub iterations_seconds: f64,
    pub iterations: usize,
    pub factorisations: usize,
    /// `iterations_seconds / iterations`.
    pub per_iteration: f64,
    /// `Problem::new` + solve.
    pub total: f64,
    /// How many times the case was run (the median of each phase is kept).
    pub repeats: usize,
}

fn median(mut v: Vec<f64>) -> f64 {
    v.sort_by(f64::total_cmp);
    v[v.len() / 2]
}

/// Times the phases of a solve of the p-degree Hertz problem on an
/// `elements`² mesh with `opts` (named `solver`), `repeats` times (median
/// kept). The first factorisation is timed on its own and then dropped
/// (so that at most two factorisations are alive at a time), and the
/// solve repeats it: the iteration phase is the solve time minus it.
pub fn time_phases(
    degree: usize,
    elements: usize,
    solver: &'static str,
    opts: &SolverOptions,
    repeats: usize,
) -> Result<Timing> {
    let (mut asm, mut fac, mut sol) = (Vec::new(), Vec::new(), Vec::new());
    let mut last = None;
    for _ in 0..repeats.max(1) {
        let t = Instant::now();
        let problem = problem(degree, elements)?;
        asm.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        factor_kernel(
            &problem,
            &mut Factoriser::default(),
            Kernel::Tied,
            opts.factorisation,
            &mut Vec::new(),
        )?;
        fac.push(t.elapsed().as_secs_f64());
        let t = Instant::now();
        let solution = solve(&problem, opts)?;
        sol.push(t.elapsed().as_secs_f64());
        last = Some((problem.n(), solution));
    }
    let repeats = asm.len();
    let (dofs, solution) = last.expect("at least one repeat");
    let (assembly, first, solve_s) = (median(asm), median(fac), median(sol));
    let iterations_seconds = (solve_s - first).max(0.0);
    let iterations = solution.history.len();
    Ok(Timing {
        degree,
        elements,
        dofs,
        solver,
        assembly,
        first_factorisation: first,
        iterations_seconds,
        iterations,
        factorisations: solution.factorisations,
        per_iteration: iterations_seconds / iterations.max(1) as f64,
        total: assembly + solve_s,
        repeats,
    })
}

fn timings_csv(t: &[Timing]) -> String {
    let mut s = String::from(
        "degree,elements,dofs,solver,assembly,first_factorisation,iterations_seconds,iterations,factorisations,per_iteration,total,repeats\n",
    );
    for r in t {
        s.push_str(&format!(
            "{},{},{},{},{:.6},{:.6},{:.6},{},{},{:.6},{:.6},{}\n",
            r.degree,
            r.elements,
            r.dofs,
            r.solver,
            r.assembly,
            r.first_factorisation,
            r.iterations_seconds,
            r.iterations,
            r.factorisations,
            r.per_iteration,
            r.total,
            r.repeats
        ));
    }
    s
}

// ------------------------------------------------------------ Table 2

/// The two 8×8 histories of Table 2: the default BFGS (line search on)
/// and the paper's undamped iteration.
fn iterations_md(damped: &History, undamped: &History, contact_points: usize) -> String {
    let n = damped.len().max(undamped.len());
    let mut t = String::from(
        "| it. | ‖R‖/‖R₀‖ | ‖Δu‖ (m) | max u (m) | active | events | ‖R‖/‖R₀‖ | ‖Δu‖ (m) | max u (m) | active | events |\n\
         |---|---|---|---|---|---|---|---|---|---|---|\n\
         | | **paper's iteration (full steps)** | | | | | **default (line search)** | | | | |\n",
    );
    let cells = |h: &History, k: usize| -> [String; 5] {
        match h.rows.get(k) {
            Some(r) => {
                let corrected = r.events.contains(&Event::Correction);
                let ev: Vec<String> = r.events.iter().map(|e| e.to_string()).collect();
                let mut ev = ev.join("; ");
                if corrected {
                    ev = format!("**{ev}**");
                }
                [
                    sci(r.relative_residual),
                    sci(r.update),
                    minus(&format!("{:.6}", r.max_displacement)),
                    r.active_points.to_string(),
                    ev,
                ]
            }
            None => Default::default(),
        }
    };
    for k in 0..n {
        let row: Vec<String> = std::iter::once((k + 1).to_string())
            .chain(cells(undamped, k))
            .chain(cells(damped, k))
            .collect();
        t.push_str(&format!("| {} |\n", row.join(" | ")));
    }
    let first = |h: &History| {
        h.rows
            .iter()
            .find(|r| r.events.contains(&Event::Correction))
            .map_or("none".to_string(), |r| r.iteration.to_string())
    };
    t.push_str(&format!(
        "\n‖R₀‖ = {} N/m, the residual at u = 0. First correction: iteration {} (paper's iteration), \
         {} (default); the paper reports iteration {PAPER_CORRECTION_ITERATION}. \
         Active = contact quadrature points with P ≤ 0 (of {contact_points}). \
         Bold: the iterations at which the secant correction (18) fired.\n",
        sci(undamped.initial_residual),
        first(undamped),
        first(damped),
    ));
    t
}

/// The first iteration carrying a correction, if any.
pub fn first_correction(h: &History) -> Option<usize> {
    h.rows
        .iter()
        .find(|r| r.events.contains(&Event::Correction))
        .map(|r| r.iteration)
}

// ------------------------------------------------------------ figures

fn floor_line() -> Polyline {
    Polyline::new(
        vec![[-0.05, 0.0], [HERTZ_RADIUS + 0.05, 0.0]],
        LineKind::Solid,
        BLACK_INDEX,
    )
    .labelled("rigid floor y = 0")
}

/// Fig. 4: elements, control net, floor.
fn model_figure(problem: &Problem, path: &Path) -> Result<()> {
    let patch = &problem.bodies[0].space.patch;
    let mut lines = Vec::new();
    for dir in 0..2 {
        for b in patch.knots[dir].breaks() {
            lines.push(
                Polyline::new(patch.iso_curve(dir, b, 32), LineKind::Thin, 0).labelled("elements"),
            );
        }
    }
    let [n0, n1] = patch.n();
    for j in 0..n1 {
        let pts = (0..n0).map(|i| patch.points[patch.index(i, j)]).collect();
        lines.push(Polyline::new(pts, LineKind::ControlNet, 1).labelled("control net"));
    }
    for i in 0..n0 {
        let pts = (0..n1).map(|j| patch.points[patch.index(i, j)]).collect();
        lines.push(Polyline::new(pts, LineKind::ControlNet, 1).labelled("control net"));
    }
    let slave = problem.bodies[0].space.patch.side_curve(Side::EtaMin);
    let (a, b) = (slave.knots.first(), slave.knots.last());
    let arc = (0..=64)
        .map(|i| slave.point(a + (b - a) * i as f64 / 64.0))
        .collect();
    lines.push(Polyline::new(arc, LineKind::Solid, 3).labelled("slave side Γc (eta_min)"));
    lines.push(
        Polyline::new(
            vec![[0.0, 0.0], [0.0, 2.0 * HERTZ_RADIUS]],
            LineKind::Dashed,
            2,
        )
        .labelled("symmetry line, u_x = 0"),
    );
    lines.push(floor_line());
    let [e0, e1] = problem.bodies[0].space.n_elements();
    geometry_figure(
        path,
        &format!("Half disk, p = 2, {e0}×{e1} elements, on a rigid floor"),
        &lines,
    )
}

/// Fig. 5: u_y on the deformed half disk (true scale), `sub`² cells per
/// element, with the undeformed outline and the floor.
fn uy_figure(problem: &Problem, full: &[f64], sub: usize, path: &Path) -> Result<()> {
    let body = &problem.bodies[0];
    let space = &body.space;
    let map = &problem.map;
    let mut cells = Vec::new();
    for e in &space.elements {
        let [[xa, xb], [ya, yb]] = e.range;
        // Position and displacement need no Jacobian, so the corners of
        // the patch (where det J = 0) can be sampled too.
        let at = |s: f64, t: f64| -> ([f64; 2], [f64; 2]) {
            let b = space
                .patch
                .basis_in_spans(e.spans, xa + (xb - xa) * s, ya + (yb - ya) * t);
            let mut u = [0.0; 2];
            for (r, &cp) in b.r.iter().zip(&b.indices) {
                let d = map.cp_displacement(full, 0, cp);
                u[0] += r * d[0];
                u[1] += r * d[1];
            }
            (space.patch.map(&b), u)
        };
        let n = sub as f64;
        for j in 0..sub {
            for i in 0..sub {
                let mut corners = [[0.0; 2]; 4];
                let mut values = [0.0; 4];
                for (k, (di, dj)) in [(0, 0), (1, 0), (1, 1), (0, 1)].into_iter().enumerate() {
                    let (x, u) = at((i + di) as f64 / n, (j + dj) as f64 / n);
                    corners[k] = [x[0] + u[0], x[1] + u[1]];
                    values[k] = u[1];
                }
                cells.push(FieldCell::from_corner_values(corners, values));
            }
        }
    }
    let overlay = vec![
        Polyline::new(space.patch.outline(64), LineKind::Dashed, BLACK_INDEX)
            .labelled("undeformed"),
        floor_line(),
    ];
    let [e0, e1] = space.n_elements();
    field_figure(
        path,
        &format!("Vertical displacement on the deformed half disk (true scale), p = 2, {e0}×{e1}"),
        "u_y (m)",
        &cells,
        &overlay,
    )
}

fn convergence_figure(
    path: &Path,
    title: &str,
    y_label: &str,
    rows: &[Measured],
    value: fn(&Measured) -> f64,
    hertz: f64,
    reference: &Measured,
) -> Result<()> {
    let mut series = Vec::new();
    for p in LADDER_DEGREES {
        let pts: Vec<(f64, f64)> = rows
            .iter()
            .filter(|r| r.degree == p)
            .map(|r| (r.elements as f64, value(r)))
            .collect();
        if !pts.is_empty() {
            series.push(Series::line(format!("IGA p = {p}"), pts).with_markers());
        }
    }
    let xs = [
        CONVERGENCE_ELEMENTS[0] as f64,
        CONVERGENCE_ELEMENTS[CONVERGENCE_ELEMENTS.len() - 1] as f64,
    ];
    series.push(Series::line("Hertz", xs.iter().map(|&x| (x, hertz)).collect()).dashed());
    series.push(
        Series::line(
            format!(
                "reference (p = {}, {}²)",
                reference.degree, reference.elements
            ),
            xs.iter().map(|&x| (x, value(reference))).collect(),
        )
        .dashed(),
    );
    line_chart(
        path,
        &Axes {
            title: title.into(),
            x_label: "elements per direction".into(),
            y_label: y_label.into(),
            log_x: true,
            log_y: false,
        },
        &series,
    )
}

fn error_figure(path: &Path, rows: &[Measured], reference: &Measured) -> Result<()> {
    let mut series = Vec::new();
    for p in LADDER_DEGREES {
        let mine: Vec<&Measured> = rows
            .iter()
            .filter(|r| {
                r.degree == p && !(r.degree == reference.degree && r.elements == reference.elements)
            })
            .collect();
        series.push(
            Series::line(
                format!("p₀, p = {p}"),
                mine.iter()
                    .map(|r| (r.elements as f64, rel(r.p0, reference.p0).abs()))
                    .collect(),
            )
            .with_markers(),
        );
        series.push(
            Series::line(
                format!("a, p = {p}"),
                mine.iter()
                    .map(|r| {
                        (
                            r.elements as f64,
                            rel(r.half_width, reference.half_width).abs(),
                        )
                    })
                    .collect(),
            )
            .with_markers()
            .dashed(),
        );
    }
    line_chart(
        path,
        &Axes {
            title: format!(
                "Error against the reference (p = {}, {}²)",
                reference.degree, reference.elements
            ),
            x_label: "elements per direction".into(),
            y_label: "relative error".into(),
            log_x: true,
            log_y: true,
        },
        &series,
    )
}

// ------------------------------------------------------------ run

/// What [`run`] measured.
pub struct HertzSummary {
    pub ladder: Vec<LadderRow>,
    pub failures: Vec<Failure>,
    /// Table 2: default BFGS and the paper's undamped iteration, 8×8, p = 2.
    pub history: History,
    pub history_undamped: History,
    pub convergence: Vec<Measured>,
    pub reference: Measured,
    pub timings: Vec<Timing>,
}

/// Runs the whole Hertz study and writes into `out`:
///
/// - `ladder.csv` (one timing column, `seconds`), `ladder.md` (no times),
///   `failures.csv`: p = 2, 3 × 8², 16², 32², 64² × BFGS, BFGS without
///   correction, Newton;
/// - `iterations_8x8.csv` (default BFGS), `iterations_8x8_paper.csv` (the
///   paper's undamped iteration), `iterations_8x8.md`: Table 2;
/// - `model.svg` (Fig. 4), `uy.svg` (Fig. 5), `half_width.svg`,
///   `peak_pressure.svg`, `errors.svg` (Fig. 6), `pressure_profile.svg`,
///   `pressure_profile.csv`;
/// - `convergence.csv`, `convergence.md`: p₀ and a against Hertz and the
///   reference;
/// - `timings.csv`: per-phase times for p = 2 on [`TIMING_ELEMENTS`];
/// - `hertz.vtu`: the 8×8 solution.
pub fn run(out: &Path) -> Result<HertzSummary> {
    run_with(out, &TIMING_ELEMENTS)
}

/// [`run`] with a chosen set of timing meshes (an empty set skips the
/// benchmark and leaves `timings.csv` alone).
pub fn run_with(out: &Path, timing_elements: &[usize]) -> Result<HertzSummary> {
    let exact = HertzAnalytic::new();

    // Ladder.
    let mut ladder = Vec::new();
    let mut failures = Vec::new();
    let mut newton: BTreeMap<(usize, usize), Measured> = BTreeMap::new();
    for p in LADDER_DEGREES {
        for n in LADDER_ELEMENTS {
            for (name, opts) in ladder_solvers() {
                match ladder_run(p, n, name, &opts)? {
                    Outcome::Converged(row, _, _) => {
                        if opts.kind == SolverKind::Newton {
                            newton.insert(
                                (p, n),
                                Measured {
                                    degree: p,
                                    elements: n,
                                    dofs: row.dofs,
                                    p0: row.p0,
                                    half_width: row.half_width,
                                },
                            );
                        }
                        ladder.push(row);
                    }
                    Outcome::Failed(f) => failures.push(f),
                }
            }
        }
    }
    write_text(out.join("ladder.csv"), &ladder_csv(&ladder))?;
    write_text(out.join("ladder.md"), &ladder_md(&ladder, &failures))?;
    write_text(out.join("failures.csv"), &failures_csv(&failures))?;

    // Table 2 and the 8×8 figures.
    let p8 = problem(2, 8)?;
    let damped = solve(&p8, &SolverOptions::with_kind(SolverKind::Bfgs))?;
    let undamped = solve(&p8, &paper_bfgs())?;
    write_text(out.join("iterations_8x8.csv"), &damped.history.to_csv())?;
    write_text(
        out.join("iterations_8x8_paper.csv"),
        &undamped.history.to_csv(),
    )?;
    write_text(
        out.join("iterations_8x8.md"),
        &iterations_md(&damped.history, &undamped.history, p8.points.len()),
    )?;
    model_figure(&p8, &out.join("model.svg"))?;
    uy_figure(&p8, &damped.full, 6, &out.join("uy.svg"))?;
    sample_bodies(&p8.bodies, &p8.map, &damped.full, 4)?.write(out.join("hertz.vtu"))?;

    // Pressure profiles.
    let mut csv = String::from("elements,x,pressure,hertz\n");
    let mut series = Vec::new();
    for n in PROFILE_ELEMENTS {
        let pr = problem(2, n)?;
        let sol = solve(&pr, &SolverOptions::with_kind(SolverKind::Newton))?;
        let prof: Vec<(f64, f64)> = pressure_profile(&pr, &sol.full, SAMPLES_PER_ELEMENT)?
            .into_iter()
            .filter(|s| s.0 <= 2.0 * exact.half_width)
            .collect();
        for &(x, p) in &prof {
            csv.push_str(&format!("{n},{x:.9e},{p:.9e},{:.9e}\n", exact.pressure(x)));
        }
        series.push(Series::line(
            format!("IGA p = 2, {n}×{n}"),
            prof.iter().map(|&(x, p)| (x * 1e3, p / 1e6)).collect(),
        ));
    }
    let xs: Vec<(f64, f64)> = (0..=400)
        .map(|i| {
            let x = 2.0 * exact.half_width * i as f64 / 400.0;
            (x * 1e3, exact.pressure(x) / 1e6)
        })
        .collect();
    series.push(Series::line("Hertz p₀√(1 − x²/a²)", xs).dashed());
    write_text(out.join("pressure_profile.csv"), &csv)?;
    line_chart(
        out.join("pressure_profile.svg"),
        &Axes {
            title: "Contact pressure along the floor".into(),
            x_label: "x (mm)".into(),
            y_label: "pressure (MPa)".into(),
            log_x: false,
            log_y: false,
        },
        &series,
    )?;

    // Convergence (Fig. 6) against Hertz and the reference.
    let mut get = |p: usize, n: usize| -> Result<Measured> {
        if let Some(m) = newton.get(&(p, n)) {
            return Ok(*m);
        }
        let m = measured(p, n)?;
        newton.insert((p, n), m);
        Ok(m)
    };
    let (rp, rn) = REFERENCE;
    let reference = get(rp, rn)?;
    let mut convergence = Vec::new();
    for p in LADDER_DEGREES {
        for n in CONVERGENCE_ELEMENTS {
            if p == 2 || n <= rn {
                convergence.push(get(p, n)?);
            }
        }
    }
    let check = convergence
        .iter()
        .rfind(|m| m.degree == rp && m.elements < rn)
        .copied();
    write_text(
        out.join("convergence.csv"),
        &convergence_csv(&convergence, &reference),
    )?;
    write_text(
        out.join("convergence.md"),
        &convergence_md(&convergence, &reference, check.as_ref()),
    )?;
    convergence_figure(
        &out.join("half_width.svg"),
        "Contact half-width against the mesh",
        "a (m)",
        &convergence,
        |m| m.half_width,
        exact.half_width,
        &reference,
    )?;
    convergence_figure(
        &out.join("peak_pressure.svg"),
        "Peak contact pressure against the mesh",
        "p₀ (Pa)",
        &convergence,
        |m| m.p0,
        exact.p0,
        &reference,
    )?;
    error_figure(&out.join("errors.svg"), &convergence, &reference)?;

    // Timings.
    let mut timings = Vec::new();
    for &n in timing_elements {
        let repeats = if n <= 16 {
            11
        } else if n <= 64 {
            5
        } else {
            1
        };
        let opts = SolverOptions::with_kind(SolverKind::Bfgs);
        timings.push(time_phases(2, n, "bfgs", &opts, repeats)?);
        timings.push(time_phases(2, n, "bfgs_paper", &paper_bfgs(), repeats)?);
        if n <= LU_TIMING_MAX_ELEMENTS {
            let lu = SolverOptions {
                factorisation: Factorisation::Lu,
                ..opts
            };
            timings.push(time_phases(2, n, "bfgs_lu", &lu, repeats)?);
        }
    }
    if !timings.is_empty() {
        write_text(out.join("timings.csv"), &timings_csv(&timings))?;
    }

    Ok(HertzSummary {
        ladder,
        failures,
        history: damped.history,
        history_undamped: undamped.history,
        convergence,
        reference,
        timings,
    })
}

// ------------------------------------------------------------ formatting

fn rel(value: f64, target: f64) -> f64 {
    (value - target) / target
}

fn signed_percent(value: f64, target: f64) -> String {
    minus(&format!("{:+.2} %", 100.0 * rel(value, target)))
}

fn sci(x: f64) -> String {
    minus(&format!("{x:.2e}"))
}

fn minus(s: &str) -> String {
    s.replace('-', "−")
}

impl fmt::Display for HertzSummary {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let exact = HertzAnalytic::new();
        writeln!(
            f,
            "Hertz: P/2 = {:.6e} N/m, a = {:.6e} m, p0 = {:.6e} Pa",
            exact.load / 2.0,
            exact.half_width,
            exact.p0
        )?;
        writeln!(
            f,
            "Table 2 (p = 2, 8x8): default BFGS {} iterations, first correction {:?}; \
             paper's undamped iteration {} iterations, first correction {:?} (paper: {})",
            self.history.len(),
            first_correction(&self.history),
            self.history_undamped.len(),
            first_correction(&self.history_undamped),
            PAPER_CORRECTION_ITERATION
        )?;
        writeln!(f, "\nladder (seconds = Problem::new + solve):")?;
        writeln!(
            f,
            "{:>2} {:>4} {:>6} {:<19} {:>5} {:>5} {:>12} {:>9} {:>12} {:>9} {:>10} {:>9}",
            "p",
            "n",
            "dofs",
            "solver",
            "its",
            "corr",
            "p0",
            "vs Hertz",
            "a",
            "vs Hertz",
            "force err",
            "seconds"
        )?;
        for r in &self.ladder {
            writeln!(
                f,
                "{:>2} {:>4} {:>6} {:<19} {:>5} {:>5} {:>12.6e} {:>+8.3}% {:>12.6e} {:>+8.3}% {:>10.2e} {:>9.4}",
                r.degree,
                r.elements,
                r.dofs,
                r.solver,
                r.iterations,
                r.corrections,
                r.p0,
                100.0 * rel(r.p0, exact.p0),
                r.half_width,
                100.0 * rel(r.half_width, exact.half_width),
                (r.contact_force - r.applied_force).abs() / r.applied_force,
                r.seconds
            )?;
        }
        for x in &self.failures {
            writeln!(
                f,
                "FAILED p = {} {}² {}: {} iterations, {} corrections: {}",
                x.degree, x.elements, x.solver, x.iterations, x.corrections, x.reason
            )?;
        }
        writeln!(
            f,
            "\nconvergence (reference p = {}, {}²: p0 = {:.6e}, a = {:.6e}):",
            self.reference.degree,
            self.reference.elements,
            self.reference.p0,
            self.reference.half_width
        )?;
        for m in &self.convergence {
            writeln!(
                f,
                "  p = {} {:>4}²: p0 {:+.3}% (Hertz) {:+.3}% (ref), a {:+.3}% (Hertz) {:+.3}% (ref)",
                m.degree,
                m.elements,
                100.0 * rel(m.p0, exact.p0),
                100.0 * rel(m.p0, self.reference.p0),
                100.0 * rel(m.half_width, exact.half_width),
                100.0 * rel(m.half_width, self.reference.half_width),
            )?;
        }
        if !self.timings.is_empty() {
            writeln!(f, "\ntimings (s, p = 2):")?;
            writeln!(
                f,
                "{:>5} {:>7} {:<10} {:>9} {:>9} {:>10} {:>5} {:>4} {:>9} {:>9}",
                "n",
                "dofs",
                "solver",
                "assembly",
                "1st fact.",
                "iterations",
                "its",
                "fact",
                "per it",
                "total"
            )?;
            for t in &self.timings {
                writeln!(
                    f,
                    "{:>5} {:>7} {:<10} {:>9.4} {:>9.4} {:>10.4} {:>5} {:>4} {:>9.5} {:>9.4}",
                    t.elements,
                    t.dofs,
                    t.solver,
                    t.assembly,
                    t.first_factorisation,
                    t.iterations_seconds,
                    t.iterations,
                    t.factorisations,
                    t.per_iteration,
                    t.total
                )?;
            }
        }
        Ok(())
    }
}
