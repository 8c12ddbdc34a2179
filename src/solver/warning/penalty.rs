//! The penalty warnings of every contact, counted from the stability of each
//! point's penalty against the bound of its element, and their remedies.

use super::kinds::{
    round2, Counted, PenaltyRemedy, Warning, LOOSE_PENALTY, OVER_PENALTY, PENALTY_TARGET,
};
use crate::contact::penalty::{stability_of, PenaltyStability};
use crate::contact::{ContactPair, ContactPoint, Contacts, Master, Modulus, Penalty};
use crate::dofs::Body;

/// The penalty warnings of every contact: below the bound, or far above
/// it, counted at the points where `active` holds, over the pieces of the
/// contact together. One count ([`stability_of`]) feeds both.
pub(super) fn penalty_warnings(
    bodies: &[Body],
    pairs: &[ContactPair],
    contacts: &Contacts,
    points: &[ContactPoint],
    counted: Counted,
    active: impl Fn(usize, &ContactPoint) -> bool,
) -> Vec<Warning> {
    let per_pair = stability_of(points, pairs.len(), active, OVER_PENALTY);
    let mut out = Vec::new();
    for (c, pieces) in contacts.iter() {
        // the pieces of a contact share its master and its parameters
        let pair = &pairs[pieces.start];
        let s = per_pair[pieces]
            .iter()
            .copied()
            .reduce(PenaltyStability::merge)
            .unwrap_or_default();
        let s = &s;
        if s.active_below + s.inactive_below > 0 {
            out.push(Warning::PenaltyBelowBound {
                contact: c,
                below: s.active_below,
                active: s.active,
                inactive_below: s.inactive_below,
                min_ratio: s.min_ratio(),
                counted,
                remedy: below_remedy(pair, s),
            });
        } else if let (true, Some(min_ratio)) = (
            pair.nitsche.theta.value() < 0.0,
            s.min_active_scale.filter(|&r| r < LOOSE_PENALTY),
        ) {
            out.push(Warning::PenaltyLoose {
                contact: c,
                active: s.active,
                min_ratio,
                counted,
                remedy: scaled(pair, s, PENALTY_TARGET / min_ratio),
            });
        } else if let (true, Some(max_ratio)) = (s.active_over > 0, s.max_active_scale) {
            out.push(Warning::PenaltyFarAboveBound {
                contact: c,
                over: s.active_over,
                active: s.active,
                max_ratio,
                counted,
                remedy: over_remedy(bodies, pair, s, max_ratio),
            });
        }
    }
    out
}

/// Scaling the pair's penalty by `scale`, if that keeps every active point
/// between its bound and [`OVER_PENALTY`] times the θ = 0 bound: the
/// factor; otherwise the sharp penalty, which sets each element's γ from
/// its own bound.
fn scaled(pair: &ContactPair, s: &PenaltyStability, scale: f64) -> PenaltyRemedy {
    let low_ok = s.min_ratio().is_none_or(|m| m * scale >= 1.0);
    let high_ok = s.max_active_scale.is_none_or(|m| m * scale <= OVER_PENALTY);
    match pair.nitsche.penalty {
        Penalty::Empirical { factor } if low_ok && high_ok => {
            PenaltyRemedy::Factor(round2(factor.get() * scale))
        }
        Penalty::Empirical { .. } => PenaltyRemedy::Sharp(PENALTY_TARGET),
        Penalty::Sharp { .. } => PenaltyRemedy::Factor(PENALTY_TARGET),
    }
}

/// Below the bound: the smallest active point lifted to [`PENALTY_TARGET`]
/// times its bound.
fn below_remedy(pair: &ContactPair, s: &PenaltyStability) -> PenaltyRemedy {
    let ratio = s.min_ratio().unwrap_or(1.0);
    scaled(pair, s, PENALTY_TARGET / ratio)
}

/// Far above: the stiffer master's modulus, if that is what raises γ;
/// otherwise the largest active point brought to [`PENALTY_TARGET`] times
/// its own θ's bound (θ = 1: 4 times the θ = 0 one; θ = −1: the θ = 0 one).
fn over_remedy(
    bodies: &[Body],
    pair: &ContactPair,
    s: &PenaltyStability,
    max_ratio: f64,
) -> PenaltyRemedy {
    if let (Modulus::Max, Master::Body { body, .. }) = (pair.nitsche.modulus, &pair.master) {
        let (es, em) = (
            bodies[pair.slave].material.young,
            bodies[*body].material.young,
        );
        if em > es && max_ratio * es / em <= OVER_PENALTY {
            return PenaltyRemedy::SlaveModulus;
        }
    }
    let own = if pair.nitsche.theta.value() > 0.0 {
        4.0
    } else {
        1.0
    };
    scaled(pair, s, PENALTY_TARGET * own / max_ratio)
}
