//! Semismooth Newton, Eq. (12)–(14), with the active-set tangent (18) and a
//! backtracking line search on ‖R‖.
//!
//! R is piecewise linear in u, so a full step lands on the root of the
//! linear piece of the tangent's active set: undamped, the method is a map
//! between active sets, and it can cycle (period 4 on Hertz 8×8, p = 2,
//! from the tied start). Since Δu = K_T⁻¹R is a descent direction of
//! ½‖R‖² wherever R is differentiable, halving the step until ‖R‖
//! decreases enough (Armijo) removes the cycle; at a kink the direction may
//! fail to descend, and then the best step tried is taken. But damping
//! also slows the iteration down where no cycle threatens, so by default
//! ([`Damping::OnCycle`]) steps are full until a tangent revisits an active
//! set, and damped from then on.
//!
//! The first step uses the kernel of `opts.start`: the tied kernel (17), or
//! the secant kernel after the rigid balance (an open initial gap leaves
//! the active set empty and (18) singular).

use super::history::{Event, History};
use super::kernel::Kernels;
use super::system::System;
use super::{
    end_iteration, line_search, norm, Attempt, Damping, Fallback, Iterate, SolverOptions, Start,
    Tracker,
};
use crate::error::Result;
use crate::problem::Problem;

/// One start of the iteration, from u = 0 with the kernel of `start`,
/// continuing `history` (the rows of an earlier start, or none).
pub(crate) fn solve(
    sys: &mut dyn System<'_>,
    problem: &Problem,
    opts: &SolverOptions,
    start: Start,
    history: History,
) -> Result<Attempt> {
    let n = sys.dim();
    let mut u = vec![0.0; n];
    let (mut r, _, floor) = sys.residual_forced(&u, &[]);
    let restarted = !history.is_empty();
    let mut tracker = Tracker::new(opts, norm(&r), history);
    if Tracker::at_floor(&r, floor) {
        return Ok(Attempt {
            u,
            history: tracker.history,
            factorisations: 0,
            stalled: false,
        });
    }
    let mut kernels = Kernels::new(sys, problem, opts.growth, start);
    let mut cycled = false;
    let mut full = false;
    let first_row = tracker.history.len();
    loop {
        let mut events = Vec::new();
        let first = tracker.history.len() == first_row;
        if first && restarted {
            events.push(Event::Restart);
        }
        let tangent = if first {
            kernels.start(start, &mut u, &mut r, &mut events)?
        } else {
            kernels.secant(&u, full, &mut events)?
        };
        cycled |= kernels.cycled();
        let drive = tangent.drive(&*kernels.sys, &u, &r);
        let dir = tangent.factor.solve(&drive)?;
        // the first step, and a guarded one (the rigid motion that closes
        // a gap), are taken in full
        let damped = !first
            && !tangent.guarded()
            && match opts.damping {
                Damping::AfterCorrections => true,
                Damping::OnCycle => cycled,
            };
        let step = line_search(&*kernels.sys, &u, &dir, &r, damped, Fallback::Best);
        if step.cuts > 0 {
            events.push(Event::LineSearchCuts(step.cuts));
        }
        let du: Vec<f64> = dir.iter().map(|d| step.alpha * d).collect();
        full = step.alpha == 1.0;
        u = step.u;
        r = step.r;
        let it = Iterate {
            du: &du,
            r: &r,
            floor: step.floor,
            active: step.state.active,
            events,
            damped,
        };
        if let Some(end) = end_iteration(&mut tracker, &kernels, problem, &mut u, it) {
            return end;
        }
    }
}
