//! Why a solve failed: the reason its stopping rule gave, completed by
//! what the last iterate and the history show (a floating body, an exact
//! cycle, skipped BFGS pairs, points below the stability bound).

use super::history::History;
use super::options::Start;
use super::stopping::Halt;
use super::system::System;
use crate::error::Error;
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
    let mut parts = vec![reason.to_string()];
    if let Some(period) = history.cycle_period() {
        parts.push(format!(
            "the iterates repeat with period {period} (active points {})",
            history.rows[history.len() - period..]
                .iter()
                .map(|r| r.active_points.to_string())
                .collect::<Vec<_>>()
                .join(", ")
        ));
        // measured: Hertz p = 3 on 8² cycles with period 7 from the tied
        // start and converges from the secant one (tests/solver.rs); by
        // hand, hertz.toml at penalty factor 0.71 cycles with period 6 and
        // converges in 9 iterations after the advice
        if start == Start::Tied {
            parts.push(
                "the tied start (17) cycles between active sets here: set solver.start = \"secant\" \
                 (the default), which starts from a balanced active set"
                    .into(),
            );
        }
    }
    let p = sys.p_values(u);
    let active: Vec<usize> = (0..p.len()).filter(|&q| p[q] <= 0.0).collect();
    if active.is_empty() {
        parts.push("active set empty: the body floats".into());
    } else {
        let below: Vec<usize> = active
            .iter()
            .copied()
            .filter(|&q| problem.points[q].below_stability_bound())
            .collect();
        if !below.is_empty() {
            // The key to raise is the user's: name each contact whose
            // points are below the bound, by its index in the scene.
            let mut contacts: Vec<usize> = below
                .iter()
                .map(|&q| problem.contacts.of(problem.points[q].pair))
                .collect();
            contacts.sort_unstable();
            contacts.dedup();
            let key = |name: &str| {
                contacts
                    .iter()
                    .map(|c| format!("contact[{c}].nitsche.{name}"))
                    .collect::<Vec<_>>()
                    .join(" and ")
            };
            parts.push(format!(
                "{} of the {} active points {} a penalty below the stability bound of their element, so the tangent need not be coercive (raise {}, or set {} = -1)",
                below.len(),
                active.len(),
                if below.len() == 1 { "has" } else { "have" },
                key("penalty_factor"),
                key("theta"),
            ));
        }
    }
    let skipped = history.skipped_updates();
    if skipped > 0 {
        parts.push(if skipped == 1 {
            "the BFGS curvature condition failed in 1 iteration (its pair was skipped)".to_string()
        } else {
            format!("the BFGS curvature condition failed in {skipped} iterations (their pairs were skipped)")
        });
    }
    Error::NotConverged {
        reason: parts.join("; "),
        history,
    }
}
