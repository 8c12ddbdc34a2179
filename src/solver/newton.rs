//! Semismooth Newton, Eq. (12)–(14), with the active-set tangent (18) and a
//! backtracking line search on ‖R‖.
//!
//! Without globalisation the full-step method can cycle between active
//! sets (period 4 on Hertz 8×8, p = 2). Since Δu = K_T⁻¹R is a descent
//! direction of ½‖R‖² wherever R is differentiable, halving the step until
//! ‖R‖ decreases enough (Armijo) removes the cycle. At a kink the direction
//! may fail to descend; then the best step tried is taken.
//!
//! The first step uses the tied kernel (17), exactly like BFGS: at u = 0 an
//! open initial gap leaves the active set empty and (18) singular.

use super::history::Event;
use super::kernel::Kernels;
use super::{line_search, norm, Fallback, Solution, SolverOptions, Status, Tracker};
use crate::error::Result;
use crate::problem::Problem;

pub fn solve(problem: &Problem, opts: &SolverOptions) -> Result<Solution> {
    let n = problem.n();
    let mut u = vec![0.0; n];
    let (mut r, _) = problem.residual(&u);
    let mut tracker = Tracker::new(problem, opts, norm(&r));
    if norm(&r) == 0.0 {
        return Ok(tracker.finish(u, 0));
    }
    let mut kernels = Kernels::new(problem, opts.factorisation)?;
    loop {
        let mut events = kernels.take_startup_events();
        let tangent = if tracker.history.is_empty() {
            kernels.tied()
        } else {
            kernels.secant(&u, &mut events)?
        };
        let dir = tangent.solve(&r)?;
        let step = line_search(
            problem,
            &u,
            &dir,
            &r,
            !tracker.history.is_empty(),
            Fallback::Best,
        );
        if step.cuts > 0 {
            events.push(Event::LineSearchCuts(step.cuts));
        }
        let (alpha, trial_u, trial_r, state) = (step.alpha, step.u, step.r, step.state);
        let du: Vec<f64> = dir.iter().map(|d| alpha * d).collect();
        u = trial_u;
        r = trial_r;
        if let Status::Converged = tracker.record(&u, &du, &r, state.active, events)? {
            return Ok(tracker.finish(u, kernels.factorisations));
        }
    }
}
