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

mod attempt;
pub mod bfgs;
mod diagnosis;
mod driver;
mod factorise;
pub(crate) mod guard;
pub use crate::history;
pub mod kernel;
mod line_search;
pub mod newton;
mod options;
mod stopping;
pub(crate) mod system;
pub mod trace;
mod vector;
pub mod warning;

pub use driver::{solve, Phases, Solution};
pub use factorise::Factorisation;
pub use options::{
    CorrectOn, Damping, Growth, IterationSpace, OnStall, SolverKind, SolverOptions, Start,
};
pub use stopping::{Floor, RESOLVABLE, ROUND_OFF, STALL_PROGRESS, STALL_WINDOW};
pub use warning::{warnings, Warning, RESOLVED};
