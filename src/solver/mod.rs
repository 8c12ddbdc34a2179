//! Nonlinear solvers for the contact problem: BFGS (16) with the tied start
//! (17) and the secant correction (18)–(19), and a globalised semismooth
//! Newton method.
//!
//! By default both iterate on the contact layer: the bulk is factorised
//! once and condensed away ([`crate::condense`], [`trace`]), the iteration
//! runs on the ℓ layer DOFs with dense kernels, and one backward pass
//! recovers the body at the end. `space = Body` runs the same algorithms
//! over every free DOF, which reproduces the paper's iteration history
//! (its start u = 0 is not interior-relaxed, so its first pair differs).
//!
//! Convergence (both solvers): ‖R(u_k)‖ ≤ max(`rtol`·‖R(u_0)‖, floor) and
//! ‖Δu_k‖ ≤ `utol`·‖u_k‖, where the floor is [`ROUND_OFF`] times the
//! round-off of evaluating R at u_k, ε ‖ |f| + |A||u| + |contact terms| ‖.
//! A residual at the floor is converged whatever the update: floating
//! point cannot resolve a smaller one. The iteration count is bounded by
//! `max_iter`; when it runs out, or the residual stops being finite, the
//! solver returns [`crate::Error::NotConverged`] carrying the whole
//! [`history::History`].

pub mod bfgs;
pub(crate) mod guard;
pub mod history;
pub mod kernel;
pub mod newton;
pub(crate) mod system;
pub mod trace;

use crate::error::{Error, Result};
use crate::problem::Problem;
use history::{Event, History, Iteration};
pub use kernel::Factorisation;
use serde::{Deserialize, Serialize};
use std::time::Instant;
use system::{BodySystem, System, TraceSystem};

/// Which nonlinear solver to run.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum SolverKind {
    /// BFGS with the secant correction.
    Bfgs,
    /// BFGS, never corrected.
    BfgsNoCorrection,
    /// Semismooth Newton on the active-set tangent with a line search.
    Newton,
}

/// The kernel of the first step.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Start {
    /// The tied kernel (17), every contact point active: the paper's.
    Tied,
    /// Balance first: shift the bodies rigidly along their floating modes
    /// until the contact forces carry the load along each (a small convex
    /// problem, see `guard`), which closes any initial gap; then the
    /// secant kernel (18) there, completed by the floating guard if its
    /// active set still does not hold the bodies.
    Secant,
}

/// When steps are damped by the backtracking line search on ‖R‖.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Damping {
    /// BFGS: once `line_search_after` corrections have fired (`0`: from
    /// the second step, `usize::MAX`: never, as in the paper). Newton:
    /// every step after the first.
    AfterCorrections,
    /// Full steps until the kernels revisit an active set they had
    /// already been built for (the semismooth iteration cycles), damped
    /// from then on. A full semismooth Newton step lands on the root of
    /// the linear piece of its active set, so the undamped iteration is a
    /// map between active sets; a revisit is the only way it can fail.
    OnCycle,
}

/// What makes BFGS correct its kernel, once `correction_after`
/// iterations have passed.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum CorrectOn {
    /// ‖R‖ grew: the paper's rule.
    Growth,
    /// ‖R‖ grew, or the active set is no longer the kernel's.
    ActiveSet,
}

/// Where the solver iterates.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum IterationSpace {
    /// The layer when the factorisation is `Auto` and the layer is small
    /// enough for dense kernels, the body otherwise.
    #[default]
    Auto,
    /// The contact layer (the condensed problem); needs `Auto` kernels.
    Trace,
    /// Every free DOF, as in the paper.
    Body,
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
    /// With [`Damping::AfterCorrections`], BFGS steps are damped by a line
    /// search once this many corrections have fired (0: always;
    /// `usize::MAX`: never, as in the paper).
    pub line_search_after: usize,
    /// When steps are damped.
    pub damping: Damping,
    /// How the kernels (17)–(18) are factorised. Every way is exact.
    pub factorisation: Factorisation,
    /// The first kernel (both solvers).
    pub start: Start,
    /// The BFGS correction rule.
    pub correct_on: CorrectOn,
    /// Where the iteration runs.
    pub space: IterationSpace,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            kind: SolverKind::Bfgs,
            rtol: 1e-10,
            utol: 1e-8,
            max_iter: 300,
            correction_after: 0,
            curvature_tol: 1e-12,
            line_search_after: 0,
            damping: Damping::OnCycle,
            factorisation: Factorisation::Auto,
            start: Start::Secant,
            correct_on: CorrectOn::ActiveSet,
            space: IterationSpace::Auto,
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

    /// The paper's iteration: BFGS from the tied kernel (17), full steps,
    /// the correction (18) when ‖R‖ grows after 8 iterations, over the
    /// whole body.
    pub fn paper() -> Self {
        Self {
            kind: SolverKind::Bfgs,
            correction_after: 8,
            line_search_after: usize::MAX,
            damping: Damping::AfterCorrections,
            start: Start::Tied,
            correct_on: CorrectOn::Growth,
            space: IterationSpace::Body,
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
        if self.space == IterationSpace::Trace && self.factorisation != Factorisation::Auto {
            return Err(Error::invalid(
                format!("{field}.space"),
                "trace",
                "iterating on the contact layer needs factorisation = \"auto\"",
            ));
        }
        Ok(())
    }
}

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
    let (u, history, factorisations) = match opts.kind {
        SolverKind::Bfgs => bfgs::solve(sys.as_mut(), problem, opts, true)?,
        SolverKind::BfgsNoCorrection => bfgs::solve(sys.as_mut(), problem, opts, false)?,
        SolverKind::Newton => newton::solve(sys.as_mut(), problem, opts)?,
    };
    let iterations = t.elapsed().as_secs_f64();
    let t = Instant::now();
    let u = sys.body(u);
    let recovery = if on_trace {
        t.elapsed().as_secs_f64()
    } else {
        0.0
    };
    let full = problem.map.expand(&u);
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
    })
}

/// The multiple of the round-off floor of ‖R‖ below which a residual
/// counts as converged. A backward-stable kernel solve leaves a residual of
/// a few to a few tens of floors (measured: 5–25 on Hertz 8², θ = −1), so
/// a smaller multiple would ask for iterations that cannot help.
pub const ROUND_OFF: f64 = 100.0;

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
    pub opts: &'a SolverOptions,
    pub history: History,
}

pub(crate) enum Status {
    Converged,
    Continue,
}

impl<'a> Tracker<'a> {
    pub fn new(opts: &'a SolverOptions, r0: f64) -> Self {
        Self {
            opts,
            history: History {
                initial_residual: r0,
                rows: Vec::new(),
            },
        }
    }

    /// Records iteration `k` and checks the stopping rules.
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        u: &[f64],
        du: &[f64],
        r: &[f64],
        floor: f64,
        active: usize,
        max_displacement: f64,
        events: Vec<Event>,
    ) -> Result<Status> {
        let rn = norm(r);
        let un = norm(du);
        let r0 = self.history.initial_residual;
        let rel = if r0 > 0.0 { rn / r0 } else { 0.0 };
        self.history.rows.push(Iteration {
            iteration: self.history.rows.len() + 1,
            residual: rn,
            relative_residual: rel,
            update: un,
            max_displacement,
            active_points: active,
            events,
        });
        if !rn.is_finite() || !un.is_finite() || rel > 1e12 {
            return Err(self.fail("the iteration diverged"));
        }
        if self.converged(u, du, r, floor) {
            return Ok(Status::Converged);
        }
        if self.history.len() >= self.opts.max_iter {
            return Err(self.fail("iteration limit reached"));
        }
        Ok(Status::Continue)
    }

    /// Whether ‖R‖ is at the round-off floor: no iteration can lower it.
    pub fn at_floor(r: &[f64], floor: f64) -> bool {
        norm(r) <= ROUND_OFF * floor
    }

    /// The stopping rule: ‖R‖ ≤ max(rtol·‖R₀‖, floor) and ‖Δu‖ ≤
    /// utol·‖u‖, or ‖R‖ at the floor.
    pub fn converged(&self, u: &[f64], du: &[f64], r: &[f64], floor: f64) -> bool {
        if Self::at_floor(r, floor) {
            return true;
        }
        let r0 = self.history.initial_residual;
        norm(r) <= self.opts.rtol * r0
            && norm(du) <= self.opts.utol * norm(u).max(f64::MIN_POSITIVE)
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
}

/// The outcome of [`line_search`].
pub(crate) struct Step {
    pub alpha: f64,
    pub cuts: usize,
    pub u: Vec<f64>,
    pub r: Vec<f64>,
    pub state: crate::problem::ContactState,
    /// The round-off floor of ‖R‖ at `u`.
    pub floor: f64,
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
    sys: &dyn System,
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
        let (tr, state, floor) = sys.residual_forced(&trial, &[]);
        let tn = norm(&tr);
        let step = Step {
            alpha,
            cuts,
            u: trial,
            r: tr,
            state,
            floor,
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
