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
//! Convergence (both solvers): ‖R(u_k)‖ ≤ `rtol`·‖R(u_0)‖ and
//! ‖Δu_k‖ ≤ `utol`·‖u_k‖. Where round-off keeps ‖R‖ above that
//! ([`Floor`]: ε ‖ |f| + |A||u| + |contact terms| ‖, the contact terms
//! counted as computed or before they cancel), an iterate at the floor
//! converges if ‖R‖ ≤ [`RESOLVABLE`]·‖R(u_0)‖, and fails saying so if not:
//! a residual that round-off cannot resolve is not a root. A damped iteration
//! that stops making progress has stalled; by default the solve then
//! starts once more from the tied kernel ([`OnStall`]). The iteration
//! count is bounded by `max_iter`; when it runs out, the residual stops
//! being finite or the last start stalls, the solver returns
//! [`crate::Error::NotConverged`] carrying the whole [`history::History`]
//! and a diagnosis. A converged [`Solution`] lists its [`Warning`]s.

pub mod bfgs;
pub(crate) mod guard;
pub mod history;
pub mod kernel;
pub mod newton;
pub(crate) mod system;
pub mod trace;
pub mod warning;

use crate::error::{Error, Result};
use crate::problem::Problem;
use history::{Event, History, Iteration};
pub use kernel::Factorisation;
use serde::{Deserialize, Serialize};
use std::time::Instant;
use system::{BodySystem, System, TraceSystem};
pub use warning::{warnings, Warning, RESOLVED};

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

/// How a secant kernel takes the points its iterate adds to the active
/// set ([`kernel::cut_growth`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
///
/// The default is still [`Growth::Full`]: [`Growth::Auto`] takes at most 7
/// iterations on the disk on an elastic block from 16² to 128² at penalty
/// factors 1–30 (8–42 with `Full`), and 4–9 on Hertz to 512², with the
/// same roots where the root is unique; it becomes the default once the
/// book's chapters are regenerated with it (their iteration counts change),
/// and where a problem has several discrete roots (Hertz under 8× load,
/// ν = 0.4999) it can end on another one.
pub enum Growth {
    /// [`Growth::Cut`] after the balanced secant start, [`Growth::Full`]
    /// after the tied start (the paper's iteration, which enters every
    /// zone from above, where there is no growth to cut).
    Auto,
    /// Every point with P ≤ 0: the plain semismooth Newton set.
    #[default]
    Full,
    /// After a full step, a run of added points next to one zone of the
    /// last kernel keeps only the [`kernel::KEPT`] of it nearest the zone.
    Cut,
}

impl Growth {
    /// Whether the kernels of a start from `start` cut the growth.
    pub fn cuts(self, start: Start) -> bool {
        match self {
            Growth::Auto => start == Start::Secant,
            Growth::Full => false,
            Growth::Cut => true,
        }
    }
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

/// What a solve does when its damped steps stop making progress: the
/// best ‖R‖ has not fallen by [`STALL_PROGRESS`] in [`STALL_WINDOW`]
/// damped iterations. Full-step iterations are never judged stalled (they
/// may legitimately raise ‖R‖ for a while).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OnStall {
    /// Stop with [`crate::Error::NotConverged`], saying so.
    Fail,
    /// Start again once from u = 0 with the tied kernel (17), keeping the
    /// history ([`Event::Restart`]); stop if that stalls too. A problem
    /// whose discrete tangent is not coercive on the active sets the first
    /// start meets can have roots that the iteration from the tied side
    /// reaches (measured: Hertz 16×16 at ν = 0.4999).
    #[default]
    RestartTied,
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
    /// What a stalled damped iteration does.
    pub on_stall: OnStall,
    /// How the secant kernels take the points added to the active set.
    pub growth: Growth,
}

impl Default for SolverOptions {
    /// The library's default, not the paper's iteration (that is
    /// [`SolverOptions::paper`]): BFGS started from the balanced secant
    /// kernel (rigid shifts until the contact forces carry the load), with
    /// the secant correction at every change of the active set (so on Hertz
    /// it behaves like semismooth Newton), full steps until the active sets
    /// cycle, the whole growth of the active set at each step
    /// ([`Growth::Full`]; see [`Growth`] for the faster `Auto`), the
    /// iteration on the contact layer, a restart from
    /// the tied kernel on a stall, and the tolerances rtol = 1e-10, utol = 1e-8 within
    /// 300 iterations.
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
            on_stall: OnStall::RestartTied,
            growth: Growth::Full,
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
            on_stall: OnStall::Fail,
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
    /// What the answer may not be ([`warnings`]).
    pub warnings: Vec<Warning>,
}

/// How one start of an iteration ended: converged, or stalled at `u`.
pub(crate) struct Attempt {
    pub u: Vec<f64>,
    pub history: History,
    pub factorisations: usize,
    pub stalled: bool,
}

/// What a solver does with the `status` of its last row: go on (`None`),
/// or end this start with the iterate `u`.
pub(crate) fn settle(
    status: Status,
    u: &mut Vec<f64>,
    tracker: &mut Tracker,
    sys: &dyn System,
    problem: &Problem,
    factorisations: usize,
) -> Option<Result<Attempt>> {
    let history = std::mem::take(&mut tracker.history);
    let stalled = match status {
        Status::Continue => {
            tracker.history = history;
            return None;
        }
        Status::Converged => false,
        Status::Stalled => true,
        Status::Failed(reason) => return Some(Err(failure(sys, problem, u, &reason, history))),
    };
    Some(Ok(Attempt {
        u: std::mem::take(u),
        history,
        factorisations,
        stalled,
    }))
}

/// What an iteration of either solver ends with, for [`end_iteration`].
pub(crate) struct Iterate<'a> {
    pub du: &'a [f64],
    pub r: &'a [f64],
    pub floor: Floor,
    pub active: usize,
    pub events: Vec<Event>,
    /// The step went through the line search.
    pub damped: bool,
}

/// The end of an iteration of either solver: records its row at `u` and
/// [`settle`]s the status (`None`: go on).
pub(crate) fn end_iteration(
    tracker: &mut Tracker,
    kernels: &kernel::Kernels,
    problem: &Problem,
    u: &mut Vec<f64>,
    it: Iterate,
) -> Option<Result<Attempt>> {
    let max_u = kernels.sys.max_displacement(u);
    let status = tracker.record(
        u, it.du, it.r, it.floor, it.active, max_u, it.events, it.damped,
    );
    settle(
        status,
        u,
        tracker,
        &*kernels.sys,
        problem,
        kernels.factorisations,
    )
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
            let reason = format!(
                "stalled: the damped steps lowered ‖R‖ by less than {} in {STALL_WINDOW} iterations",
                crate::report::table::Format::Percent(0).render(STALL_PROGRESS)
            );
            return Err(failure(sys.as_ref(), problem, &attempt.u, &reason, history));
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

/// The multiple of the round-off floor of ‖R‖ below which a residual
/// counts as converged. A backward-stable kernel solve leaves a residual of
/// a few to a few tens of floors (measured: 5–25 on Hertz 8², θ = −1), so
/// a smaller multiple would ask for iterations that cannot help.
pub const ROUND_OFF: f64 = 100.0;

/// A damped iteration whose best ‖R‖ has not fallen by this fraction in
/// [`STALL_WINDOW`] iterations has stalled.
pub const STALL_PROGRESS: f64 = 0.01;
/// See [`STALL_PROGRESS`].
pub const STALL_WINDOW: usize = 10;

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

/// The error of a failed solve, with what the last iterate `u` (in the
/// space of `sys`) and the history say about why: a floating body, an
/// exact cycle, skipped BFGS pairs, active points below the stability
/// bound of the penalty.
pub(crate) fn failure(
    sys: &dyn System,
    problem: &Problem,
    u: &[f64],
    reason: &str,
    history: History,
) -> Error {
    let mut parts = vec![reason.to_string()];
    if let Some(period) = history.cycle_period() {
        parts.push(format!(
            "the iterates repeat with period {period} (active points {})",
            history.rows[history.len() - period..]
                .iter()
                .map(|r| r.active_points.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ));
    }
    let p = sys.p_values(u);
    let active: Vec<usize> = (0..p.len()).filter(|&q| p[q] <= 0.0).collect();
    if active.is_empty() {
        parts.push("active set empty: the body floats".into());
    } else {
        let below = active
            .iter()
            .filter(|&&q| problem.points[q].below_stability_bound())
            .count();
        if below > 0 {
            parts.push(format!(
                "{below} of the {} active points {} a penalty below the stability bound of their element, so the tangent need not be coercive (raise nitsche.penalty_factor, or use theta = -1)",
                active.len(),
                if below == 1 { "has" } else { "have" }
            ));
        }
    }
    let skipped = history.skipped_updates();
    if skipped > 0 {
        parts.push(if skipped == 1 {
            "curvature condition failed once".to_string()
        } else {
            format!("curvature condition failed {skipped} times")
        });
    }
    Error::NotConverged {
        reason: parts.join("; "),
        history,
    }
}

/// Shared bookkeeping: record a row, decide convergence, failure or a stall.
pub(crate) struct Tracker<'a> {
    pub opts: &'a SolverOptions,
    pub history: History,
    /// The best ‖R‖ that counts as progress, and the row count when it
    /// was reached.
    best: (f64, usize),
}

pub(crate) enum Status {
    Converged,
    Continue,
    Stalled,
    Failed(String),
}

impl<'a> Tracker<'a> {
    /// Continues `history` (empty, or the rows of an earlier start) from a
    /// start whose residual is `r0`.
    pub fn new(opts: &'a SolverOptions, r0: f64, mut history: History) -> Self {
        history.initial_residual = r0;
        let rows = history.len();
        Self {
            opts,
            history,
            best: (f64::INFINITY, rows),
        }
    }

    /// Records an iteration and checks the stopping rules; `damped`: the
    /// step went through the line search (only such an iteration can be
    /// judged stalled).
    #[allow(clippy::too_many_arguments)]
    pub fn record(
        &mut self,
        u: &[f64],
        du: &[f64],
        r: &[f64],
        floor: Floor,
        active: usize,
        max_displacement: f64,
        events: Vec<Event>,
        damped: bool,
    ) -> Status {
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
            return Status::Failed("the iteration diverged".into());
        }
        if self.converged(u, du, r, floor) {
            return Status::Converged;
        }
        if let Some(level) = self.unresolvable(u, du, r, floor) {
            return Status::Failed(format!(
                "the residual stays at {rel:.1e} of its initial value, above the {RESOLVABLE:e} that round-off may excuse (it can mask up to {level:.1e} here: K u and the contact forces at displacements up to {max_displacement:.3e}) and above rtol = {:e}, so this iterate is no root: a penalty too small to hold the bodies lets them move that far (raise nitsche.penalty_factor), or the input's scale is extreme",
                self.opts.rtol
            ));
        }
        if self.history.len() >= self.opts.max_iter {
            return Status::Failed("iteration limit reached".into());
        }
        if rn < (1.0 - STALL_PROGRESS) * self.best.0 {
            self.best = (rn, self.history.len());
        } else if damped && self.history.len() - self.best.1 >= STALL_WINDOW {
            return Status::Stalled;
        }
        Status::Continue
    }

    /// Whether ‖R‖ is at the round-off floor: no iteration can lower it.
    pub fn at_floor(r: &[f64], floor: Floor) -> bool {
        norm(r) <= ROUND_OFF * floor.typical
    }

    /// The largest ‖R‖ that a round-off floor may excuse: max(`rtol`,
    /// [`RESOLVABLE`]) ‖R₀‖.
    fn resolvable(&self) -> f64 {
        self.opts.rtol.max(RESOLVABLE) * self.history.initial_residual
    }

    /// Whether the update is small: ‖Δu‖ ≤ `utol`·‖u‖.
    fn settled(&self, u: &[f64], du: &[f64]) -> bool {
        norm(du) <= self.opts.utol * norm(u).max(f64::MIN_POSITIVE)
    }

    /// Whether ‖R‖ is at a round-off floor (the typical one, or the
    /// cancelling one with the update small) and yet above what a floor
    /// may excuse: no iteration can lower it, and the iterate is not a
    /// root to the accuracy asked. Returns the floor's level, ROUND_OFF ·
    /// floor / ‖R₀‖.
    pub fn unresolvable(&self, u: &[f64], du: &[f64], r: &[f64], floor: Floor) -> Option<f64> {
        let rn = norm(r);
        let r0 = self.history.initial_residual;
        if rn <= self.resolvable() {
            return None;
        }
        if Self::at_floor(r, floor) {
            return Some(ROUND_OFF * floor.typical / r0);
        }
        (rn <= ROUND_OFF * floor.cancelling && self.settled(u, du))
            .then(|| ROUND_OFF * floor.cancelling / r0)
    }

    /// The stopping rule: ‖R‖ ≤ rtol·‖R₀‖ and ‖Δu‖ ≤ utol·‖u‖; or, where
    /// round-off keeps ‖R‖ above rtol·‖R₀‖, ‖R‖ ≤ [`RESOLVABLE`]·‖R₀‖ at
    /// a floor: the typical one whatever the update, the cancelling one
    /// with a small update.
    pub fn converged(&self, u: &[f64], du: &[f64], r: &[f64], floor: Floor) -> bool {
        let rn = norm(r);
        let r0 = self.history.initial_residual;
        if rn <= self.opts.rtol * r0 {
            Self::at_floor(r, floor) || self.settled(u, du)
        } else {
            rn <= self.resolvable()
                && (Self::at_floor(r, floor)
                    || (rn <= ROUND_OFF * floor.cancelling && self.settled(u, du)))
        }
    }
}

/// The largest relative residual ‖R‖/‖R₀‖ that round-off may excuse when
/// `rtol` asks for less: six digits of the residual. Beyond it the iterate
/// is as close to a root as floating point can tell, but that is not close
/// enough to call it one (a penalty 10⁻¹² of Eq. (11) stops at 1.4e-2 and
/// leaves Hertz at a few percent). Within it a tiny penalty of the skew
/// variant θ = −1, whose contact terms of size w|σ_n|/γ cancel, converges:
/// at 10⁻⁴ of Eq. (11) on Hertz 8² its residual stalls at 4e-8 with p₀
/// within 1 % (`tests/solver.rs::the_skew_variant_converges_with_a_tiny_penalty`);
/// the √ε this was once set to rejected that answer.
pub const RESOLVABLE: f64 = 1e-6;

/// What floating point can resolve of ‖R‖ at an iterate: ε times the
/// norm of the component-wise sums of the magnitudes of the terms of R.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Floor {
    /// Each contact force counted as computed: the round-off R carries
    /// in practice. A residual within [`ROUND_OFF`] of it is converged,
    /// whatever the update.
    pub typical: f64,
    /// Each contact force counted by its terms before they cancel
    /// ([`crate::contact::nitsche::add_force_size_at`]): a bound, far above
    /// `typical` when the penalty is small or the stresses large. A
    /// residual within [`ROUND_OFF`] of it is converged once the update is
    /// small too.
    pub cancelling: f64,
}

/// The outcome of [`line_search`].
pub(crate) struct Step {
    pub alpha: f64,
    pub cuts: usize,
    pub u: Vec<f64>,
    pub r: Vec<f64>,
    pub state: crate::problem::ContactState,
    /// The round-off floors of ‖R‖ at `u`.
    pub floor: Floor,
}

const MAX_CUTS: usize = 30;
const ARMIJO: f64 = 1e-4;

/// What a line search does when no step length decreases ‖R‖ enough.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Fallback {
    /// Take the best step tried (Newton: a full step could cycle).
    Best,
    /// Take the full step. BFGS asks for this from an iterate with no
    /// active contact point (a body floating above the obstacle): there R
    /// is affine for steps that keep the points open, and its component
    /// along a floating mode t is tᵀL whatever the step, so ‖R‖ stays at
    /// or above |tᵀL|/‖t‖, the Armijo test may fail for every short step,
    /// a tiny step would stall the iteration, and the correction handles
    /// the rest.
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
