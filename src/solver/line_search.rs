//! The backtracking (Armijo) line search on ‖R‖ that damps the steps of
//! both solvers.

use super::stopping::Floor;
use super::system::System;
use super::vector::norm;

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
