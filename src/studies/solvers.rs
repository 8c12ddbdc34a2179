//! BFGS with the paper's correction, BFGS without it, and semismooth Newton
//! on Hertz (IGA p = 2) as the mesh is refined. Non-convergence is a result
//! and is recorded as such.

use super::iga_vs_fem::{peak_and_half_width, profile, Method};
use crate::error::{Error, Result};
use crate::report::atomic::write_text;
use crate::report::plot::{line_chart, Axes, Series};
use crate::solver::{solve, SolverKind, SolverOptions};
use std::path::Path;
use std::time::Instant;

/// Elements per direction.
pub const MESHES: [usize; 4] = [8, 16, 32, 64];
/// The solvers compared.
pub const SOLVERS: [SolverKind; 3] = [
    SolverKind::Bfgs,
    SolverKind::BfgsNoCorrection,
    SolverKind::Newton,
];

/// Name of a solver as used in the tables.
pub fn name(kind: SolverKind) -> &'static str {
    match kind {
        SolverKind::Bfgs => "BFGS + correction",
        SolverKind::BfgsNoCorrection => "BFGS, no correction",
        SolverKind::Newton => "Newton",
    }
}

/// One solve.
pub struct Outcome {
    pub solver: SolverKind,
    pub elements: usize,
    pub dofs: usize,
    /// None when converged, else the solver's reason.
    pub failure: Option<String>,
    pub iterations: usize,
    pub corrections: usize,
    /// Numeric factorisations (None when the solver failed: not reported).
    pub factorisations: Option<usize>,
    pub final_relative_residual: f64,
    /// Peak contact pressure (converged runs only).
    pub p0: Option<f64>,
    /// Assembly + solve.
    pub seconds: f64,
}

/// Runs `kind` on Hertz IGA p = 2 with `elements`².
pub fn outcome(kind: SolverKind, elements: usize) -> Result<Outcome> {
    let t = Instant::now();
    let problem = Method::Iga(2).hertz(elements).build()?;
    let result = solve(&problem, &SolverOptions::with_kind(kind));
    let seconds = t.elapsed().as_secs_f64();
    let mut o = Outcome {
        solver: kind,
        elements,
        dofs: problem.n(),
        failure: None,
        iterations: 0,
        corrections: 0,
        factorisations: None,
        final_relative_residual: f64::NAN,
        p0: None,
        seconds,
    };
    match result {
        Ok(s) => {
            o.iterations = s.history.len();
            o.corrections = s.history.corrections();
            o.factorisations = Some(s.factorisations);
            o.final_relative_residual = s.history.last_relative_residual();
            o.p0 = Some(peak_and_half_width(&profile(&problem, &s.full)?.0).0);
        }
        Err(Error::NotConverged { reason, history }) => {
            o.iterations = history.len();
            o.corrections = history.corrections();
            o.final_relative_residual = history.last_relative_residual();
            o.failure = Some(reason);
        }
        Err(e) => o.failure = Some(e.to_string()),
    }
    Ok(o)
}

/// Writes `solvers.{csv,md}`, `timings.{csv,md}` and `iterations.svg`.
pub fn run(out: &Path) -> Result<()> {
    let mut all = Vec::new();
    for kind in SOLVERS {
        for n in MESHES {
            all.push(outcome(kind, n)?);
        }
    }
    let mut csv = String::from(
        "solver,elements,dofs,converged,iterations,corrections,factorisations,final_relative_residual,p0,failure\n",
    );
    let mut md = String::from(
        "Hertz, IGA p=2, θ = 0, paper's penalty; tolerances rtol = 1e-10, utol = 1e-8, at most 300 iterations.\n\n\
         | solver | elements | dofs | converged | iterations | corrections | factorisations | final rel. residual | p₀ (Pa) |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    let mut tcsv = String::from("solver,elements,dofs,converged,seconds\n");
    let mut tmd = String::from(
        "Assembly + solve, one run each, measured in one run of the study.\n\n\
         | solver | elements | converged | seconds |\n|---|---|---|---|\n",
    );
    for o in &all {
        let ok = o.failure.is_none();
        let fac = o.factorisations.map_or("".into(), |f| f.to_string());
        let p0 = o.p0.map_or("".into(), |p| format!("{p:.5e}"));
        csv.push_str(&format!(
            "{},{},{},{},{},{},{},{:.3e},{},\"{}\"\n",
            name(o.solver),
            o.elements,
            o.dofs,
            ok,
            o.iterations,
            o.corrections,
            fac,
            o.final_relative_residual,
            p0,
            o.failure.clone().unwrap_or_default().replace('"', "'"),
        ));
        md.push_str(&format!(
            "| {} | {}² | {} | {} | {} | {} | {} | {:.2e} | {} |\n",
            name(o.solver),
            o.elements,
            o.dofs,
            match &o.failure {
                None => "yes".to_string(),
                Some(r) => format!("**no**: {r}"),
            },
            o.iterations,
            o.corrections,
            fac,
            o.final_relative_residual,
            p0,
        ));
        tcsv.push_str(&format!(
            "{},{},{},{},{:.6}\n",
            name(o.solver),
            o.elements,
            o.dofs,
            ok,
            o.seconds
        ));
        tmd.push_str(&format!(
            "| {} | {}² | {} | {:.4} |\n",
            name(o.solver),
            o.elements,
            if ok { "yes" } else { "no" },
            o.seconds
        ));
    }
    write_text(out.join("solvers.csv"), &csv)?;
    write_text(out.join("solvers.md"), &md)?;
    write_text(out.join("timings.csv"), &tcsv)?;
    write_text(out.join("timings.md"), &tmd)?;

    let series: Vec<Series> = SOLVERS
        .iter()
        .map(|&k| {
            Series::line(
                name(k),
                all.iter()
                    .filter(|o| o.solver == k && o.failure.is_none())
                    .map(|o| (o.elements as f64, o.iterations as f64))
                    .collect(),
            )
            .with_markers()
        })
        .collect();
    line_chart(
        out.join("iterations.svg"),
        &Axes {
            title: "Iterations to convergence (failed runs omitted, see table)".into(),
            x_label: "elements per direction".into(),
            y_label: "iterations".into(),
            log_x: true,
            log_y: false,
        },
        &series,
    )?;
    Ok(())
}
