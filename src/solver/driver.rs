//! The entry point of a solve: the iteration space and factorisation
//! chosen, the starts run in turn (the restart after a stall), and the
//! body recovered from the converged iterate with its warnings.

use super::diagnosis::failure;
use super::factorise::Factorisation;
use super::history::History;
use super::options::{IterationSpace, OnStall, SolverKind, SolverOptions, Start};
use super::stopping::STALL;
use super::system::{BodySystem, System, TraceSystem};
use super::warning::{warnings, Warning};
use super::{bfgs, newton, trace};
use crate::error::Result;
use crate::problem::Problem;
use std::time::Instant;

/// Wall times of the phases of a solve (s).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct Phases {
    /// The factorisation of A₀ and the condensation (0 for the per-kernel
    /// factorisations).
    pub condensation: f64,
    /// The iterations, kernel factorisations included.
    pub iterations: f64,
    /// The recovery of the body from the layer (0 in the body space).
    pub recovery: f64,
}

/// A converged solution.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Free DOFs.
    pub u: Vec<f64>,
    /// All DOFs, prescribed ones included.
    pub full: Vec<f64>,
    pub history: History,
    /// Numeric kernel factorisations performed (one per kernel (17)–(18);
    /// the one-off factorisation of A₀ is not counted).
    pub factorisations: usize,
    /// Whether the iteration ran on the layer.
    pub on_trace: bool,
    pub phases: Phases,
    /// What the answer may not be ([`warnings`]).
    pub warnings: Vec<Warning>,
}

/// Runs the solver chosen in `opts`.
pub fn solve(problem: &Problem, opts: &SolverOptions) -> Result<Solution> {
    opts.validate("solver")?;
    problem.check_support()?;
    let t = Instant::now();
    let mut how = opts.factorisation;
    if how == Factorisation::Auto && problem.layer().len() > trace::MAX_LAYER {
        how = Factorisation::LowRank;
    }
    let on_trace = how == Factorisation::Auto && opts.space != IterationSpace::Body;
    let mut sys: Box<dyn System> = if on_trace {
        Box::new(TraceSystem::new(problem)?)
    } else {
        Box::new(BodySystem::new(problem, how)?)
    };
    let condensation = if how == Factorisation::Auto {
        t.elapsed().as_secs_f64()
    } else {
        0.0
    };
    let t = Instant::now();
    let mut starts = vec![opts.start];
    if opts.on_stall == OnStall::RestartTied && opts.start != Start::Tied {
        starts.push(Start::Tied);
    }
    let mut history = History::default();
    let mut factorisations = 0;
    let mut solved = None;
    for (k, &start) in starts.iter().enumerate() {
        let attempt = match opts.kind {
            SolverKind::Bfgs => bfgs::solve(sys.as_mut(), problem, opts, start, history, true)?,
            SolverKind::BfgsNoCorrection => {
                bfgs::solve(sys.as_mut(), problem, opts, start, history, false)?
            }
            SolverKind::Newton => newton::solve(sys.as_mut(), problem, opts, start, history)?,
        };
        factorisations += attempt.factorisations;
        history = attempt.history;
        if !attempt.stalled {
            solved = Some(attempt.u);
            break;
        }
        if k + 1 == starts.len() {
            return Err(failure(
                sys.as_ref(),
                problem,
                &attempt.u,
                &STALL,
                start,
                history,
            ));
        }
    }
    let u = solved.expect("the last start either converges or returns");
    let iterations = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let u = sys.body(u);
    let recovery = if on_trace {
        t.elapsed().as_secs_f64()
    } else {
        0.0
    };
    let full = problem.map.expand(&u);
    let warnings = warnings(problem, &full);
    Ok(Solution {
        u,
        full,
        history,
        factorisations,
        on_trace,
        phases: Phases {
            condensation,
            iterations,
            recovery,
        },
        warnings,
    })
}
