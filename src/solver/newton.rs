//! Semismooth Newton, Eq. (12)–(14), with the active-set tangent (18) and a
//! backtracking line search on ‖R‖.
//!
//! R is piecewise linear in u, so a full step lands on the root of the
//! linear piece of the tangent's active set: undamped, the method is a map
//! between active sets, and it can fail only by revisiting one (a cycle;
//! from the tied start on Hertz 8×8 it does not). Since Δu = K_T⁻¹R is a descent direction of
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
//!
//! # Taking the active set in few steps
//!
//! Undamped, the iteration is the map A ↦ {P(u(A)) ≤ 0}, and on the disk on
//! an elastic block that map is lopsided (`examples/iterations.rs`, modes
//! `map`, `emulate`, `history`): from a zone too short the root of its
//! piece penetrates beyond the edge over about as far again, from a zone too
//! long it pulls only at the last point or two. The balanced start lies
//! below the root's zone (the rigid shift that carries the load at a stiff
//! penalty penetrates little), the first step overshoots to about twice the
//! root's zone, and the plain iteration then walks down a point or two per
//! step, through islands of active points beyond the edge: 19–42 iterations
//! at penalty factors 10–30 on 16²…128², the residual between 0.1 and 1.6
//! for most of them. Damping was not the cause (the undamped map is as
//! slow), and neither the tied start nor damping variants helped.
//!
//! What the solvers do instead, by default ([`super::Growth::Auto`] after
//! the balanced start): after each full step the kernel keeps only 40 % of
//! every run of points the iterate adds next to a zone of the last kernel
//! ([`super::kernel::cut_growth`]), and the step's residual is that of the
//! kernel's own active set (the dropped points open: `Built::drive`), so a
//! full step still lands on the root of the kernel's piece. The iterates
//! then stay below each edge and close on it geometrically, and a root is
//! the fixed point of both iterations. Measured with `ladder 128`: the
//! disk on the block at factors 1–30 on 16²…128² in 3–7 iterations (the
//! plain iteration 8–42), Hertz p = 2 and 3 on 16²…128² in 4–6 (4–9).
//! Not kept: per-point extrapolation of P over the last two maps (cycles
//! or singular kernels), a secant on the edge position (the sets
//! fragment, so the edge is not one number), filling holes or keeping the
//! core run (cycles), and half the growth instead of 40 % (from the tiny
//! balanced start of a stiff penalty the first cut lands above the root:
//! 23 maps against 6 on 128², factor 20). Penalty continuation and a
//! coarse-mesh start were not needed.

use super::attempt::{end_iteration, Attempt, Iterate};
use super::history::{Event, History};
use super::kernel::Kernels;
use super::line_search::{line_search, Fallback};
use super::options::{Damping, SolverOptions, Start};
use super::stopping::Tracker;
use super::system::System;
use super::vector::norm;
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
