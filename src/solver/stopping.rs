//! The stopping rules shared by both solvers: convergence against the
//! tolerances or at a round-off floor, failure, and the stall of a damped
//! iteration. [`Tracker`] records each iteration's row and applies them.

use super::history::{Event, History, Iteration};
use super::options::SolverOptions;
use super::vector::norm;
use crate::error::Halt;

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

/// The halt of a stall by the rule above.
pub(crate) const STALL: Halt = Halt::Stalled {
    progress: STALL_PROGRESS,
    window: STALL_WINDOW,
};

/// The largest relative residual ‖R‖/‖R₀‖ that round-off may excuse when
/// `rtol` asks for less: six digits of the residual. Beyond it the iterate
/// is as close to a root as floating point can tell, but that is not close
/// enough to call it one (a penalty 10⁻¹² of Eq. (11) stops at 1.4e-2 and
/// leaves Hertz at a few percent). Within it a tiny penalty of the skew
/// variant θ = −1, whose contact terms of size w|σ_n|/γ cancel, converges:
/// at 10⁻⁴ of Eq. (11) on Hertz 8² its residual stalls at 4e-8 with p₀
/// within 1 % (`tests/solver/hard_cases.rs::the_skew_variant_converges_with_a_tiny_penalty`);
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
    Failed(Halt),
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
            return Status::Failed(Halt::Diverged);
        }
        if self.converged(u, du, r, floor) {
            return Status::Converged;
        }
        if let Some(level) = self.unresolvable(u, du, r, floor) {
            return Status::Failed(Halt::Unresolvable {
                relative: rel,
                level,
                max_displacement,
                rtol: self.opts.rtol,
                excusable: RESOLVABLE,
            });
        }
        if self.history.len() >= self.opts.max_iter {
            return Status::Failed(Halt::IterationLimit);
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

#[cfg(test)]
mod tests {
    use super::*;

    /// The reasons are data until printed; the stall's is the text the
    /// stability atlas records.
    #[test]
    fn a_stall_reads_as_the_atlas_records_it() {
        assert_eq!(
            STALL.to_string(),
            "stalled: the damped steps lowered ‖R‖ by less than 1 % in 10 iterations"
        );
        assert_eq!(Halt::IterationLimit.to_string(), "iteration limit reached");
        assert_eq!(Halt::Diverged.to_string(), "the iteration diverged");
    }
}
