//! How one start of either solver ends: each iteration's row is recorded
//! and judged by the stopping rules ([`super::stopping`]); a converged or
//! stalled start hands its iterate to the driver, a failed one its
//! diagnosis.

use super::diagnosis::failure;
use super::history::{Event, History};
use super::kernel::Kernels;
use super::stopping::{Floor, Status, Tracker};
use super::system::System;
use crate::error::Result;
use crate::problem::Problem;

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
        Status::Failed(halt) => {
            let start = tracker.opts.start;
            return Some(Err(failure(sys, problem, u, &halt, start, history)));
        }
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
    kernels: &Kernels,
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
