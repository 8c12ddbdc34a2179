//! What a converged solve reports about its answer ([`Warning`]): it
//! solves the discrete equations, but may not be the contact solution the
//! user wants.
//!
//! Each warning names one cause, the measurement that shows it, and one
//! remedy; the remedy is chosen so that, followed, the warning goes away and
//! the answer is right to the method's accuracy (`tests/warnings/` checks
//! each). The thresholds are measured on the shipped Hertz scenes; the
//! book's scene chapter lists them with their measurements.

mod kinds;
mod penalty;
mod setup;
mod side_end;
mod solution;

pub use kinds::{
    zone_elements, Counted, LockingRemedy, PenaltyRemedy, SideEnd, SlaveExtent, Warning, ZoneShare,
    LOCKING, LOCKING_POISSON, LOOSE_PENALTY, OVER_PENALTY, PENALTY_TARGET, RESOLVED, STIFFER_SLAVE,
    ZONE_ELEMENTS, ZONE_ELEMENTS_TARGET, ZONE_SHARE,
};
pub use setup::{before_solve, locking, setup_warnings};
pub use side_end::zones_at_side_end;
pub use solution::warnings;
