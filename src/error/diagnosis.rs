//! Why a solve failed, as data: the stopping rule that ended it
//! ([`Halt`]) and what the last iterate and the history show besides
//! ([`Finding`]). [`Diagnosis`] renders both once, by `Display`, into the
//! message of [`crate::Error::NotConverged`]; a caller that acts on the
//! cause matches on the variants, never on the text.

use std::fmt;

/// Why the stopping rules ended a solve without a root.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum Halt {
    /// ‖R‖ or ‖Δu‖ stopped being finite, or ‖R‖ grew past 10¹² ‖R₀‖.
    Diverged,
    /// `max_iter` iterations ran.
    IterationLimit,
    /// ‖R‖ sits at a round-off floor above what a floor may excuse.
    Unresolvable {
        /// ‖R‖/‖R₀‖.
        relative: f64,
        /// What the floor can mask, relative to ‖R₀‖.
        level: f64,
        /// The largest displacement of the iterate (m).
        max_displacement: f64,
        /// The solve's relative tolerance.
        rtol: f64,
        /// The largest ‖R‖/‖R₀‖ that round-off may excuse.
        excusable: f64,
    },
    /// The damped steps of the last start lowered the best ‖R‖ by less
    /// than `progress` (a fraction) in `window` iterations.
    Stalled { progress: f64, window: usize },
}

impl fmt::Display for Halt {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match *self {
            Halt::Diverged => write!(f, "the iteration diverged"),
            Halt::IterationLimit => write!(f, "iteration limit reached"),
            Halt::Unresolvable {
                relative,
                level,
                max_displacement,
                rtol,
                excusable,
            } => write!(
                f,
                "the residual stays at {relative:.1e} of its initial value, above the {excusable:e} that round-off may excuse (it can mask up to {level:.1e} here: K u and the contact forces at displacements up to {max_displacement:.3e}) and above rtol = {rtol:e}, so this iterate is no root: a penalty far from its bound does this, too small to hold the bodies (they move that far) or so large that its forces swamp the balance in round-off (follow the penalty warning if the run gives one), or else the input's scale is extreme"
            ),
            // the fraction as the book's tables print a percentage (`{:.0} %`)
            Halt::Stalled { progress, window } => write!(
                f,
                "stalled: the damped steps lowered ‖R‖ by less than {:.0} % in {window} iterations",
                100.0 * progress
            ),
        }
    }
}

/// What the last iterate and the history of a failed solve show.
#[derive(Clone, Debug, PartialEq)]
pub enum Finding {
    /// The iterates repeat with `period`; the active-point counts of the
    /// last period.
    Cycle {
        period: usize,
        active_points: Vec<usize>,
    },
    /// The cycle started from the tied kernel (17): the secant start's
    /// balanced active set is the remedy.
    TiedStartCycles,
    /// No point is active: the body floats.
    Floating,
    /// `below` of the `active` points have a penalty below the stability
    /// bound of their element; `contacts`: the scene's contacts they
    /// belong to.
    BelowBound {
        below: usize,
        active: usize,
        contacts: Vec<usize>,
    },
    /// The BFGS curvature condition failed in this many iterations.
    SkippedUpdates(usize),
}

impl fmt::Display for Finding {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            Finding::Cycle {
                period,
                active_points,
            } => {
                let counts: Vec<String> = active_points.iter().map(|a| a.to_string()).collect();
                write!(
                    f,
                    "the iterates repeat with period {period} (active points {})",
                    counts.join(", ")
                )
            }
            Finding::TiedStartCycles => write!(
                f,
                "the tied start (17) cycles between active sets here: set solver.start = \"secant\" \
                 (the default), which starts from a balanced active set"
            ),
            Finding::Floating => write!(f, "active set empty: the body floats"),
            Finding::BelowBound {
                below,
                active,
                contacts,
            } => {
                // the key to raise is the user's: each contact by its index in the scene
                let key = |name: &str| {
                    contacts
                        .iter()
                        .map(|c| format!("contact[{c}].nitsche.{name}"))
                        .collect::<Vec<_>>()
                        .join(" and ")
                };
                write!(
                    f,
                    "{below} of the {active} active points {} a penalty below the stability bound of their element, so the tangent need not be coercive (raise {}, or set {} = -1)",
                    if *below == 1 { "has" } else { "have" },
                    key("penalty_factor"),
                    key("theta"),
                )
            }
            Finding::SkippedUpdates(1) => write!(
                f,
                "the BFGS curvature condition failed in 1 iteration (its pair was skipped)"
            ),
            Finding::SkippedUpdates(n) => write!(
                f,
                "the BFGS curvature condition failed in {n} iterations (their pairs were skipped)"
            ),
        }
    }
}

/// Why a solve failed: the stopping rule, then the findings, in the order
/// a reader acts on them.
#[derive(Clone, Debug, PartialEq)]
pub struct Diagnosis {
    pub halt: Halt,
    pub findings: Vec<Finding>,
}

impl fmt::Display for Diagnosis {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}", self.halt)?;
        for finding in &self.findings {
            write!(f, "; {finding}")?;
        }
        Ok(())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_diagnosis_reads_halt_then_findings() {
        let d = Diagnosis {
            halt: Halt::IterationLimit,
            findings: vec![
                Finding::BelowBound {
                    below: 1,
                    active: 4,
                    contacts: vec![0, 2],
                },
                Finding::SkippedUpdates(3),
            ],
        };
        assert_eq!(
            d.to_string(),
            "iteration limit reached; 1 of the 4 active points has a penalty below the stability \
             bound of their element, so the tangent need not be coercive (raise \
             contact[0].nitsche.penalty_factor and contact[2].nitsche.penalty_factor, or set \
             contact[0].nitsche.theta and contact[2].nitsche.theta = -1); the BFGS curvature \
             condition failed in 3 iterations (their pairs were skipped)"
        );
    }
}
