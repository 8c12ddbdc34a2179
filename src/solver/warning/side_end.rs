//! Contact zones that run off the end of the slave side where the body does
//! not go on smoothly.

use super::kinds::{SideEnd, Warning};
use crate::contact::projection::closest_point;
use crate::contact::{ContactPair, ContactPoint, Master, Role};
use crate::dofs::Body;
use crate::nurbs::Side;
use crate::problem::Problem;

/// The pairs whose contact zone, given the bracket `p[q]` of every contact
/// point of `problem` (P ≤ 0: active), reaches an end of its slave side
/// where the body's boundary goes on smoothly (the end is not a corner of
/// the body, nor a symmetry line, which meets the side at a right angle)
/// and the master goes on too: the contact surface stops there though the
/// bodies would touch beyond it. A failed solve can call this too: a zone cut off
/// there is a geometric cause, not a penalty one.
pub fn zones_at_side_end(problem: &Problem, p: &[f64]) -> Vec<Warning> {
    at_side_end(&problem.bodies, &problem.pairs, &problem.points, p)
}

/// The largest angle between the slave side's direction at an end and the
/// next side's that counts as a smooth continuation (a degenerate
/// (det J = 0) corner such as the nine-point disk's has angle 0).
const SMOOTH: f64 = 30.0;

/// Whether the boundary of `body` goes on past `end` of `side` within
/// [`SMOOTH`] degrees of the side's own direction.
fn continues_smoothly(body: &Body, side: Side, end: SideEnd) -> bool {
    let patch = &body.space.patch;
    let curve = patch.side_curve(side);
    let (lo, hi) = (curve.knots.first(), curve.knots.last());
    let d = 1e-6 * (hi - lo);
    let (t, inward) = match end {
        SideEnd::Start => (lo, lo + d),
        SideEnd::End => (hi, hi - d),
    };
    let corner = curve.point(t);
    let inner = curve.point(inward);
    let out = [corner[0] - inner[0], corner[1] - inner[1]];
    // the side that meets this one at the corner
    let next = match (side, end) {
        (Side::EtaMin | Side::EtaMax, SideEnd::Start) => Side::XiMin,
        (Side::EtaMin | Side::EtaMax, SideEnd::End) => Side::XiMax,
        (Side::XiMin | Side::XiMax, SideEnd::Start) => Side::EtaMin,
        (Side::XiMin | Side::XiMax, SideEnd::End) => Side::EtaMax,
    };
    let other = patch.side_curve(next);
    let (a, b) = (other.knots.first(), other.knots.last());
    let e = 1e-6 * (b - a);
    let at_first = {
        let p = other.point(a);
        (p[0] - corner[0]).hypot(p[1] - corner[1])
    } <= {
        let p = other.point(b);
        (p[0] - corner[0]).hypot(p[1] - corner[1])
    };
    let beyond = other.point(if at_first { a + e } else { b - e });
    let from = other.point(if at_first { a } else { b });
    let on = [beyond[0] - from[0], beyond[1] - from[1]];
    let (n1, n2) = (out[0].hypot(out[1]), on[0].hypot(on[1]));
    if !(n1 > 0.0 && n2 > 0.0) {
        return false;
    }
    let cos = (out[0] * on[0] + out[1] * on[1]) / (n1 * n2);
    cos >= SMOOTH.to_radians().cos()
}

fn at_side_end(
    bodies: &[Body],
    pairs: &[ContactPair],
    points: &[ContactPoint],
    p: &[f64],
) -> Vec<Warning> {
    let mut out = Vec::new();
    for (k, pair) in pairs.iter().enumerate() {
        let slave = &bodies[pair.slave];
        let curve = slave.space.patch.side_curve(pair.slave_side);
        let own: Vec<usize> = (0..points.len())
            .filter(|&q| points[q].pair == k && points[q].role == Role::Slave)
            .collect();
        let first = own
            .iter()
            .copied()
            .min_by(|&a, &b| points[a].t.total_cmp(&points[b].t));
        let last = own
            .iter()
            .copied()
            .max_by(|&a, &b| points[a].t.total_cmp(&points[b].t));
        let master_curve = match &pair.master {
            Master::Rigid(c) => c.clone(),
            Master::Body { body, side } => bodies[*body].space.patch.side_curve(*side),
        };
        let ends = [
            (SideEnd::Start, first, curve.knots.first()),
            (SideEnd::End, last, curve.knots.last()),
        ];
        for (end, q, t) in ends {
            let Some(q) = q else { continue };
            if p[q] > 0.0 {
                continue;
            }
            if !continues_smoothly(slave, pair.slave_side, end) {
                continue; // a corner of the body, or a symmetry line
            }
            let at = curve.point(t);
            let Ok(pr) = closest_point(&master_curve, at) else {
                continue;
            };
            let (lo, hi) = (master_curve.knots.first(), master_curve.knots.last());
            let tol = 1e-6 * (hi - lo);
            if !pr.orthogonal || pr.t <= lo + tol || pr.t >= hi - tol {
                continue; // the master ends there too
            }
            out.push(Warning::ZoneAtSideEnd {
                pair: k,
                slave: slave.name.clone(),
                side: pair.slave_side.name(),
                end,
                at,
                singular: !points[q].regular,
            });
        }
    }
    out
}
