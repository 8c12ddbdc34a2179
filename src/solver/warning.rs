//! What a converged solve reports about its answer ([`Warning`]): it
//! solves the discrete equations, but may not be the contact solution the
//! user wants.

use crate::problem::Problem;

/// Something a converged solve reports about its answer: it solves the
/// discrete equations, but may not be the contact solution the user wants.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum Warning {
    /// Active points of contact pair `pair` whose penalty lies below the
    /// stability bound of their element: the tangent need not be coercive
    /// on this active set, so the root found need not be the only one.
    PenaltyBelowBound {
        pair: usize,
        below: usize,
        active: usize,
    },
    /// The contact zone of pair `pair` rests on fewer than [`RESOLVED`]
    /// active points: the mesh does not resolve it, and measures of the
    /// pressure (its peak, its width) are set by the quadrature spacing and
    /// the penalty rather than by the load.
    UnresolvedContact { pair: usize, active: usize },
}

/// The fewest active points that count as resolving a contact zone.
pub const RESOLVED: usize = 3;

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::PenaltyBelowBound {
                pair,
                below,
                active,
            } => write!(
                f,
                "contact[{pair}]: {below} of the {active} active points {} a penalty below the stability bound of their element, so this solution need not be unique (raise nitsche.penalty_factor, or use theta = -1)",
                if *below == 1 { "has" } else { "have" }
            ),
            Warning::UnresolvedContact { pair, active } => write!(
                f,
                "contact[{pair}]: the contact zone rests on {active} quadrature point(s): the mesh does not resolve it, and its peak pressure and width are not meaningful"
            ),
        }
    }
}

/// The warnings of a converged solution `full` (all DOFs).
pub fn warnings(problem: &Problem, full: &[f64]) -> Vec<Warning> {
    let mut out = Vec::new();
    for pair in 0..problem.pairs.len() {
        let active: Vec<_> = problem
            .points
            .iter()
            .filter(|cp| cp.pair == pair && cp.p(full) <= 0.0)
            .collect();
        let below = active
            .iter()
            .filter(|cp| cp.below_stability_bound())
            .count();
        if below > 0 {
            out.push(Warning::PenaltyBelowBound {
                pair,
                below,
                active: active.len(),
            });
        }
        if (1..RESOLVED).contains(&active.len()) {
            out.push(Warning::UnresolvedContact {
                pair,
                active: active.len(),
            });
        }
    }
    out
}
