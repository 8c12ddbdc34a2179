//! What the solvers can be asked to do: the choice of solver, its start,
//! damping, correction rule, iteration space and stall policy, with the
//! tolerances, gathered in [`SolverOptions`] and checked once by
//! [`SolverOptions::validate`] before a solve.

use super::factorise::Factorisation;
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

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
/// set ([`super::kernel::cut_growth`]).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
///
/// The default is [`Growth::Auto`]: it takes at most 7 iterations on the
/// disk on an elastic block from 16² to 128² at penalty factors 1–30 (8–42
/// with `Full`), and 4–9 on Hertz to 512², with the same roots where the
/// root is unique. The paper's iteration (the tied start) is unchanged by
/// it. Where a problem has several discrete roots (Hertz under 8× load,
/// ν = 0.4999) the two growths can end on different ones; the solution
/// then carries the warning that makes it doubtful (the zone at the end of
/// the slave side, the penalty below its bound).
pub enum Growth {
    /// [`Growth::Cut`] after the balanced secant start, [`Growth::Full`]
    /// after the tied start (the paper's iteration, which enters every
    /// zone from above, where there is no growth to cut).
    #[default]
    Auto,
    /// Every point with P ≤ 0: the plain semismooth Newton set.
    Full,
    /// After a full step, a run of added points next to one zone of the
    /// last kernel keeps only the [`super::kernel::KEPT`] of it nearest the zone.
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
/// best ‖R‖ has not fallen by [`super::STALL_PROGRESS`] in [`super::STALL_WINDOW`]
/// damped iterations. Full-step iterations are never judged stalled (they
/// may legitimately raise ‖R‖ for a while).
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum OnStall {
    /// Stop with [`crate::Error::NotConverged`], saying so.
    Fail,
    /// Start again once from u = 0 with the tied kernel (17), keeping the
    /// history ([`super::history::Event::Restart`]); stop if that stalls too. A problem
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
    /// cycle, the growth of the active set cut next to each zone
    /// ([`Growth::Auto`]), the iteration on the contact layer, a restart from
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
            growth: Growth::Auto,
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
