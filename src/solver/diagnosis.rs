//! Why a solve failed: the reason its stopping rule gave, completed by
//! what the last iterate and the history show (a floating body, an exact
//! cycle, skipped BFGS pairs, points below the stability bound).

use super::history::History;
use super::options::Start;
use super::system::System;
use crate::error::{Diagnosis, Error, Finding, Halt};
use crate::problem::Problem;

/// The error of a failed solve, with what the last iterate `u` (in the
/// space of `sys`) and the history say about why: a floating body, an
/// exact cycle, skipped BFGS pairs, active points below the stability
/// bound of the penalty.
pub(crate) fn failure(
    sys: &dyn System,
    problem: &Problem,
    u: &[f64],
    reason: &Halt,
    start: Start,
    history: History,
) -> Error {
    let mut findings = Vec::new();
    if let Some(period) = history.cycle_period() {
        findings.push(Finding::Cycle {
            period,
            active_points: history.rows[history.len() - period..]
                .iter()
                .map(|r| r.active_points)
                .collect(),
        });
        // measured: Hertz p = 3 on 8² cycles with period 7 from the tied
        // start and converges from the secant one (tests/solver/); by
        // hand, hertz.toml at penalty factor 0.71 cycles with period 6 and
        // converges in 9 iterations after the advice
        if start == Start::Tied {
            findings.push(Finding::TiedStartCycles);
        }
    }
    let p = sys.p_values(u);
    let active: Vec<usize> = (0..p.len()).filter(|&q| p[q] <= 0.0).collect();
    if active.is_empty() {
        findings.push(Finding::Floating);
    } else {
        let below: Vec<usize> = active
            .iter()
            .copied()
            .filter(|&q| problem.points[q].below_stability_bound())
            .collect();
        if !below.is_empty() {
            let mut contacts: Vec<usize> = below
                .iter()
                .map(|&q| problem.contacts.of(problem.points[q].pair))
                .collect();
            contacts.sort_unstable();
            contacts.dedup();
            findings.push(Finding::BelowBound {
                below: below.len(),
                active: active.len(),
                contacts,
            });
        }
    }
    let skipped = history.skipped_updates();
    if skipped > 0 {
        findings.push(Finding::SkippedUpdates(skipped));
    }
    Error::NotConverged {
        diagnosis: Diagnosis {
            halt: *reason,
            findings,
        },
        history,
    }
}
