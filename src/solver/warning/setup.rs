//! The warnings known before the solve: the choice of slave and modulus, near
//! incompressibility, and the penalty at the points that touch first.

use super::kinds::{Counted, LockingRemedy, Warning, LOCKING, LOCKING_POISSON, STIFFER_SLAVE};
use super::penalty::penalty_warnings;
use crate::contact::penalty::first_touch_of;
use crate::contact::{ContactPair, ContactPoint, Contacts, Master, Sides};
use crate::dofs::Body;
use crate::material::{Formulation, Plane};

/// The warnings that do not depend on the solution: the choice of slave,
/// and locking of nearly incompressible bodies.
pub fn setup_warnings(bodies: &[Body], pairs: &[ContactPair], contacts: &Contacts) -> Vec<Warning> {
    let mut out = Vec::new();
    for (c, pieces) in contacts.iter() {
        // the pieces of a contact share its slave body and its master
        let pair = &pairs[pieces.start];
        if let Master::Body { body, .. } = pair.master {
            let (mut s, mut m) = (&bodies[pair.slave], &bodies[body]);
            let sides = pair.nitsche.sides;
            // the unbiased form's mirrored half has the master as its
            // slave: the stiffer body is a slave whichever is named
            if sides == Sides::Unbiased && m.material.young > s.material.young {
                std::mem::swap(&mut s, &mut m);
            }
            let contrast = s.material.young / m.material.young;
            if contrast > STIFFER_SLAVE {
                out.push(Warning::StifferSlave {
                    contact: c,
                    slave: s.name.clone(),
                    master: m.name.clone(),
                    contrast,
                    sides,
                });
            }
        }
    }
    // the patches of one body share its name and material: one warning,
    // from its coarsest patch
    let mut locked: Vec<(&str, f64, Warning)> = Vec::new();
    for b in bodies {
        let Some(w) = locking(b) else { continue };
        let Warning::NearlyIncompressible { indicator, .. } = w else {
            continue;
        };
        match locked.iter_mut().find(|(name, ..)| *name == b.name) {
            Some(prev) if indicator > prev.1 => *prev = (&b.name, indicator, w),
            Some(_) => {}
            None => locked.push((&b.name, indicator, w)),
        }
    }
    out.extend(locked.into_iter().map(|(name, _, mut w)| {
        if let Warning::NearlyIncompressible { remedy, .. } = &mut w {
            if bodies.iter().filter(|b| b.name == name).count() > 1 {
                *remedy = LockingRemedy::Refine;
            }
        }
        w
    }));
    out
}

/// [`Warning::NearlyIncompressible`] for body `b`, if its indicator is
/// above [`LOCKING`].
pub fn locking(b: &Body) -> Option<Warning> {
    let nu = b.material.poisson;
    // the mixed formulation's continuous pressure does not lock (chapter
    // "Near incompressibility")
    // nor, on a C⁰ mesh (Lagrange, interior knots repeated p times), does
    // the local one: there it is Q1/P0, Q2/Q1-disc, … (a discontinuous
    // pressure of degree p − 1 in each direction), whose pressure per element
    // the displacement space can meet (Hertz at ν = 0.49999: Q1/P0 on 32²
    // +0.5 %, Q2/Q1-disc on 16² +1.3 %, against +71 % for Q1 alone)
    let c0 = is_c0(b);
    if b.material.plane != Plane::Strain
        || nu <= LOCKING_POISSON
        || b.formulation == Formulation::Mixed
        || (b.formulation == Formulation::LocalMixed && c0)
    {
        return None;
    }
    let lambda_over_mu = 2.0 * nu / (1.0 - 2.0 * nu);
    let spans = |d: usize| b.space.patch.knots[d].breaks().len().saturating_sub(1);
    let fewest = spans(0).min(spans(1)).max(1) as f64;
    let indicator = lambda_over_mu / fewest.powi(3);
    (indicator > LOCKING).then(|| Warning::NearlyIncompressible {
        body: b.name.clone(),
        formulation: b.formulation,
        poisson: nu,
        indicator,
        elements: (lambda_over_mu / LOCKING).cbrt().ceil() as usize,
        // one patch as far as this body knows; `setup_warnings` sees the
        // other patches of its name
        remedy: if c0 {
            LockingRemedy::LocalMixedOrRefine
        } else {
            LockingRemedy::MixedOrRefine
        },
    })
}

/// The warnings of a problem before it is solved: [`setup_warnings`], and
/// the penalty counted where the bodies first touch
/// ([`crate::contact::penalty::first_touch_of`]).
pub fn before_solve(
    bodies: &[Body],
    pairs: &[ContactPair],
    contacts: &Contacts,
    points: &[ContactPoint],
) -> Vec<Warning> {
    let touch = first_touch_of(points, contacts);
    let mut out = setup_warnings(bodies, pairs, contacts);
    out.extend(penalty_warnings(
        bodies,
        pairs,
        contacts,
        points,
        Counted::FirstTouch,
        |q, _| touch[q],
    ));
    defer_penalty_to_locking(&mut out, bodies, pairs, contacts);
    out
}

/// Drops the penalty warnings of contacts whose slave body locks: its
/// stability bound then measures the locked stress (C_T grows with λ), so
/// the advised factor is that of the wrong formulation. Measured: two
/// cylinders with ν = 0.4999 on the upper one, 8²: followed together, the
/// locking advice (`formulation = "mixed"`) and the penalty advice (factor
/// 1,600) give p₀ 3.2 times the mixed answer at factor 1, which no longer
/// warns. The locking warning is the one cause; the penalty is judged
/// again on the formulation it leads to.
pub(super) fn defer_penalty_to_locking(
    out: &mut Vec<Warning>,
    bodies: &[Body],
    pairs: &[ContactPair],
    contacts: &Contacts,
) {
    let locked: Vec<String> = out
        .iter()
        .filter_map(|w| match w {
            Warning::NearlyIncompressible { body, .. } => Some(body.clone()),
            _ => None,
        })
        .collect();
    out.retain(|w| {
        let contact = match w {
            Warning::PenaltyBelowBound { contact, .. }
            | Warning::PenaltyFarAboveBound { contact, .. }
            | Warning::PenaltyLoose { contact, .. } => *contact,
            _ => return true,
        };
        let slave = &bodies[pairs[contacts.pieces(contact).start].slave].name;
        !locked.contains(slave)
    });
}

/// Whether body `b`'s displacement space is only C⁰ across its elements
/// (every interior knot repeated as often as the degree): a Lagrange mesh.
fn is_c0(b: &Body) -> bool {
    b.space.patch.knots.iter().all(|k| {
        let m = k.multiplicities();
        m.len() <= 2 || m[1..m.len() - 1].iter().all(|&r| r >= k.degree())
    })
}
