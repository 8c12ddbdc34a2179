//! Nonlinear solvers for the contact problem: BFGS (16) with the tied start
//! (17) and the secant correction (18)–(19), and a globalised semismooth
//! Newton method.
//!
//! Convergence (both solvers): ‖R(u_k)‖ ≤ `rtol`·‖R(u_0)‖ and
//! ‖Δu_k‖ ≤ `utol`·‖u_k‖. The iteration count is bounded by `max_iter`;
//! when it runs out, or the residual stops being finite, the solver returns
//! [`crate::Error::NotConverged`] carrying the whole [`history::History`].

pub mod bfgs;
pub mod history;
pub mod kernel;
pub mod newton;

use crate::error::{Error, Result};
use crate::problem::Problem;
use history::{Event, History, Iteration};
pub use kernel::Factorisation;
use serde::{Deserialize, Serialize};

/// Which nonlinear solver to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolverKind {
    /// BFGS from the tied kernel with the paper's secant correction.
    Bfgs,
    /// BFGS from the tied kernel, never corrected.
    BfgsNoCorrection,
    /// Semismooth Newton on the active-set tangent with a line search.
    Newton,
}

/// Tolerances and limits.
#[derive(Clone, Copy, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct SolverOptions {
    pub kind: SolverKind,
    /// Relative residual tolerance.
    pub rtol: f64,
    /// Relative update tolerance.
    pub utol: f64,
    pub max_iter: usize,
    /// The correction may fire only after this many iterations (8 in the paper).
    pub correction_after: usize,
    /// A BFGS pair is kept only if yᵀs > `curvature_tol`·‖y‖‖s‖.
    pub curvature_tol: f64,
    /// BFGS steps are damped by a line search once this many corrections
    /// have fired (0: always; `usize::MAX`: never, as in the paper).
    pub line_search_after: usize,
    /// How the kernels (17)–(18) are factorised. Both ways are exact.
    pub factorisation: Factorisation,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            kind: SolverKind::Bfgs,
            rtol: 1e-10,
            utol: 1e-8,
            max_iter: 300,
            correction_after: 8,
            curvature_tol: 1e-12,
            line_search_after: 0,
            factorisation: Factorisation::Auto,
        }
    }
}

impl SolverOptions {
    pub fn with_kind(kind: SolverKind) -> Self {
        Self {
            kind,
            ..Self::default()
        }
    }

    pub fn validate(&self, field: &str) -> Result<()> {
        let pos = |k: &str, v: f64| {
            if v.is_finite() && v > 0.0 && v < 1.0 {
                Ok(())
            } else {
                Err(Error::invalid(
                    format!("{field}.{k}"),
                    v,
                    "must lie in (0, 1)",
                ))
            }
        };
        pos("rtol", self.rtol)?;
        pos("utol", self.utol)?;
        pos("curvature_tol", self.curvature_tol)?;
        if self.max_iter == 0 || self.max_iter > 100_000 {
            return Err(Error::invalid(
                format!("{field}.max_iter"),
                self.max_iter,
                "must lie in 1..=100000",
            ));
        }
        Ok(())
    }
}

/// A converged solution.
#[derive(Clone, Debug)]
pub struct Solution {
    /// Free DOFs.
    pub u: Vec<f64>,
    /// All DOFs, prescribed ones included.
    pub full: Vec<f64>,
    pub history: History,
    /// Numeric factorisations performed (kernel set-ups).
    pub factorisations: usize,
}

/// Runs the solver chosen in `opts`.
pub fn solve(problem: &Problem, opts: &SolverOptions) -> Result<Solution> {
    opts.validate("solver")?;
    problem.check_support()?;
    match opts.kind {
        SolverKind::Bfgs => bfgs::solve(problem, opts, true),
        SolverKind::BfgsNoCorrection => bfgs::solve(problem, opts, false),
        SolverKind::Newton => newton::solve(problem, opts),
    }
}

pub(crate) fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

pub(crate) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

/// Signed displacement component of largest magnitude.
pub(crate) fn max_displacement(full: &[f64]) -> f64 {
    full.iter()
        .copied()
        .fold(0.0, |m: f64, v| if v.abs() > m.abs() { v } else { m })
}

/// Shared bookkeeping: record a row, decide convergence or failure.
pub(crate) struct Tracker<'a> {
    pub problem: &'a Problem,
    pub opts: &'a SolverOptions,
    pub history: History,
}

pub(crate) enum Status {
    Converged,
    Continue,
}

impl<'a> Tracker<'a> {
    pub fn new(problem: &'a Problem, opts: &'a SolverOptions, r0: f64) -> Self {
        Self {
            problem,
            opts,
            history: History {
                initial_residual: r0,
                rows: Vec::new(),
            },
        }
    }

    /// Records iteration `k` and checks the stopping rules.
    pub fn record(
        &mut self,
        u: &[f64],
        du: &[f64],
        r: &[f64],
        active: usize,
        events: Vec<Event>,
    ) -> Result<Status> {
        let full = self.problem.map.expand(u);
        let rn = norm(r);
        let un = norm(du);
        let r0 = self.history.initial_residual;
        let rel = if r0 > 0.0 { rn / r0 } else { 0.0 };
        self.history.rows.push(Iteration {
            iteration: self.history.rows.len() + 1,
            residual: rn,
            relative_residual: rel,
            update: un,
            max_displacement: max_displacement(&full),
            active_points: active,
            events,
        });
        if !rn.is_finite() || !un.is_finite() || rel > 1e12 {
            return Err(self.fail("the iteration diverged"));
        }
        if self.converged(u, du, r) {
            return Ok(Status::Converged);
        }
        if self.history.len() >= self.opts.max_iter {
            return Err(self.fail("iteration limit reached"));
        }
        Ok(Status::Continue)
    }

    /// The stopping rule: ‖R‖ ≤ rtol·‖R₀‖ and ‖Δu‖ ≤ utol·‖u‖.
    pub fn converged(&self, u: &[f64], du: &[f64], r: &[f64]) -> bool {
        let r0 = self.history.initial_residual;
        let rel = if r0 > 0.0 { norm(r) / r0 } else { 0.0 };
        rel <= self.opts.rtol && norm(du) <= self.opts.utol * norm(u).max(f64::MIN_POSITIVE)
    }

    /// The error for a failed solve, diagnosing a floating body.
    pub fn fail(&self, reason: &str) -> Error {
        let floating = self
            .history
            .rows
            .last()
            .is_some_and(|r| r.active_points == 0);
        let skipped = self.history.skipped_updates();
        let reason = if floating {
            format!("{reason}; active set empty: the body floats")
        } else if skipped > 0 {
            format!("{reason}; curvature condition failed {skipped} times")
        } else {
            reason.to_string()
        };
        Error::NotConverged {
            reason,
            history: self.history.clone(),
        }
    }

    pub fn finish(self, u: Vec<f64>, factorisations: usize) -> Solution {
        let full = self.problem.map.expand(&u);
        Solution {
            u,
            full,
            history: self.history,
            factorisations,
        }
    }
}

/// The outcome of [`line_search`].
pub(crate) struct Step {
    pub alpha: f64,
    pub cuts: usize,
    pub u: Vec<f64>,
    pub r: Vec<f64>,
    pub state: crate::problem::ContactState,
}

const MAX_CUTS: usize = 30;
const ARMIJO: f64 = 1e-4;

/// What a line search does when no step length decreases ‖R‖ enough.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Fallback {
    /// Take the best step tried (Newton: a full step could cycle).
    Best,
    /// Take the full step. BFGS asks for this from an iterate with no
    /// active contact point: there (a body floating above the obstacle) no
    /// step along the BFGS direction reduces ‖R‖, a tiny step would stall
    /// the iteration for good, and the correction handles the rest.
    Full,
}

/// Backtracking on ‖R‖ along `dir` from `u` (residual `r`): halve the step
/// until ‖R(u + α dir)‖ ≤ (1 − 10⁻⁴ α)‖R(u)‖. At a kink of the active set
/// the direction may not descend at all; then `fallback` decides. With
/// `enabled = false` the full step is taken.
pub(crate) fn line_search(
    problem: &Problem,
    u: &[f64],
    dir: &[f64],
    r: &[f64],
    enabled: bool,
    fallback: Fallback,
) -> Step {
    let r_norm = norm(r);
    let mut alpha = 1.0;
    let mut best: Option<(f64, Step)> = None;
    let mut full: Option<Step> = None;
    for cuts in 0..=MAX_CUTS {
        let trial: Vec<f64> = u.iter().zip(dir).map(|(a, d)| a + alpha * d).collect();
        let (tr, state) = problem.residual(&trial);
        let tn = norm(&tr);
        let step = Step {
            alpha,
            cuts,
            u: trial,
            r: tr,
            state,
        };
        if !enabled || tn <= (1.0 - ARMIJO * alpha) * r_norm {
            return step;
        }
        if cuts == 0 && fallback == Fallback::Full {
            full = Some(step);
        } else if best.as_ref().is_none_or(|b| tn < b.0) {
            best = Some((tn, step));
        }
        alpha *= 0.5;
    }
    let mut step = match full {
        Some(s) => s,
        None => best.expect("at least one trial").1,
    };
    step.cuts = MAX_CUTS;
    step
}
