//! The warnings of a converged solution.

use super::kinds::{Counted, Warning, RESOLVED};
use super::penalty::penalty_warnings;
use super::setup::{defer_penalty_to_locking, setup_warnings};
use super::side_end::zones_at_side_end;
use crate::contact::{ContactPoint, Role};
use crate::problem::Problem;

/// The warnings of a converged solution `full` (all DOFs).
pub fn warnings(problem: &Problem, full: &[f64]) -> Vec<Warning> {
    let p: Vec<f64> = problem.points.iter().map(|cp| cp.p(full)).collect();
    let contacts = &problem.contacts;
    let mut out = setup_warnings(&problem.bodies, &problem.pairs, contacts);
    out.extend(penalty_warnings(
        &problem.bodies,
        &problem.pairs,
        contacts,
        &problem.points,
        Counted::Solution,
        |q, _| p[q] <= 0.0,
    ));
    defer_penalty_to_locking(&mut out, &problem.bodies, &problem.pairs, contacts);
    // below the bound the active set itself is in doubt: that one cause is
    // reported, not the extent of the zone it produces
    let doubtful: Vec<usize> = out
        .iter()
        .filter_map(|w| match w {
            Warning::PenaltyBelowBound { contact, .. } => Some(*contact),
            _ => None,
        })
        .collect();
    out.extend(zones_at_side_end(problem, &p).into_iter().filter(
        |w| !matches!(w, Warning::ZoneAtSideEnd { contact, .. } if doubtful.contains(contact)),
    ));
    for (c, pieces) in contacts.iter() {
        // over the pieces of the contact: the active points, and the slave
        // elements the zone touches (points of the slave side; the
        // mirrored half of the unbiased form lies on the master)
        let (mut active, mut elements) = (0, 0);
        for k in pieces.clone() {
            let pair = &problem.pairs[k];
            let own: Vec<&ContactPoint> = (0..p.len())
                .filter(|&q| problem.points[q].pair == k && p[q] <= 0.0)
                .map(|q| &problem.points[q])
                .collect();
            let sides = problem.bodies[pair.slave].space.boundary(pair.slave_side);
            let mut touched: Vec<usize> = own
                .iter()
                .filter(|cp| cp.role == Role::Slave)
                .filter_map(|cp| {
                    sides
                        .iter()
                        .position(|be| be.range[0] <= cp.t && cp.t <= be.range[1])
                })
                .collect();
            touched.sort_unstable();
            touched.dedup();
            active += own.len();
            elements += touched.len();
        }
        if active == 0 {
            continue;
        }
        let away = (0..p.len())
            .filter(|&q| {
                let cp = &problem.points[q];
                // edge-on and grazing count too: a side at (nearly) right
                // angles to the master reaches it only at its end, where it
                // is no contact surface (a block's right side against the
                // floor, upright or tilted)
                pieces.contains(&cp.pair) && p[q] <= 0.0 && cp.grazes()
            })
            .count();
        if away > 0 {
            let slave = &problem.bodies[problem.pairs[pieces.start].slave].name;
            out.push(Warning::ClosedFacingAway {
                contact: c,
                slave: slave.clone(),
                away,
                active,
            });
        }
        if active < RESOLVED || elements == 1 {
            out.push(Warning::UnresolvedContact {
                contact: c,
                active,
                elements,
            });
        }
    }
    // A contact closed through its slave body has that one cause: its
    // penalty, zone and resolution are measured on gaps that are not gaps,
    // and following their advice would leave it as wrong.
    let through: Vec<usize> = out
        .iter()
        .filter_map(|w| match w {
            Warning::ClosedFacingAway { contact, .. } => Some(*contact),
            _ => None,
        })
        .collect();
    // (the choice of slave is a set-up matter, which stands)
    out.retain(|w| match (w, w.contact()) {
        (Warning::ClosedFacingAway { .. } | Warning::StifferSlave { .. }, _) | (_, None) => true,
        (_, Some(c)) => !through.contains(&c),
    });
    out
}
