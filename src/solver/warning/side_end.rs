//! Contact zones that run off the end of the slave boundary where the body
//! goes on smoothly.

use super::kinds::{SideEnd, SlaveExtent, Warning};
use crate::contact::projection::closest_point;
use crate::contact::{Master, Role};
use crate::nurbs::Side;
use crate::problem::Problem;
use std::ops::Range;

/// The contacts whose zone, given the bracket `p[q]` of every contact
/// point of `problem` (P ≤ 0: active), reaches an end of its slave
/// boundary (the start of its first piece, the end of its last) where the
/// body's boundary goes on smoothly (the end is not a corner of the body,
/// nor a symmetry line, which meets the side at a right angle; on a body
/// of several patches the boundary may go on on another patch) and the
/// master goes on too: the contact surface stops there though the bodies
/// would touch beyond it. A failed solve can call this too: a zone cut off
/// there is a geometric cause, not a penalty one.
pub fn zones_at_side_end(problem: &Problem, p: &[f64]) -> Vec<Warning> {
    let mut out = Vec::new();
    for (c, pieces) in problem.contacts.iter() {
        let ends = [
            (SideEnd::Start, pieces.start),
            (SideEnd::End, pieces.end - 1),
        ];
        for (end, k) in ends {
            if let Some(w) = cut_off(problem, c, &pieces, k, end, p) {
                out.push(w);
            }
        }
    }
    out
}

/// The largest angle between the slave side's direction at an end and the
/// next side's that counts as a smooth continuation (a degenerate
/// (det J = 0) corner such as the nine-point disk's has angle 0).
const SMOOTH: f64 = 30.0;

/// The warning for contact `c` at `end` of its piece `k`, if its zone is
/// cut off there.
fn cut_off(
    problem: &Problem,
    c: usize,
    pieces: &Range<usize>,
    k: usize,
    end: SideEnd,
    p: &[f64],
) -> Option<Warning> {
    let (bodies, points) = (&problem.bodies, &problem.points);
    let pair = &problem.pairs[k];
    let slave = &bodies[pair.slave];
    let curve = slave.space.patch.side_curve(pair.slave_side);
    let own: Vec<usize> = (0..points.len())
        .filter(|&q| points[q].pair == k && points[q].role == Role::Slave)
        .collect();
    let by_t = |&a: &usize, &b: &usize| points[a].t.total_cmp(&points[b].t);
    let last = |qs: &mut dyn Iterator<Item = usize>| match end {
        SideEnd::Start => qs.min_by(by_t),
        SideEnd::End => qs.max_by(by_t),
    };
    let t = match end {
        SideEnd::Start => curve.knots.first(),
        SideEnd::End => curve.knots.last(),
    };
    let q_end = last(&mut own.iter().copied())?;
    // In an element at a singular corner the bracket is 1/det J of the
    // stress, not a contact pressure, and its points may open while the
    // zone presses on up to that element (measured: the half disk at 16
    // times the load with the sharp penalty, whose γ grows with that
    // element's C_T: its points open, the last regular one carries
    // 6 MPa). There the zone's end is judged at the last regular point.
    let q = if !points[q_end].regular && p[q_end] > 0.0 {
        last(&mut own.iter().copied().filter(|&q| points[q].regular)).unwrap_or(q_end)
    } else {
        q_end
    };
    if p[q] > 0.0 {
        return None;
    }
    let sides: Vec<(usize, Side)> = pieces
        .clone()
        .map(|k| (problem.pairs[k].slave, problem.pairs[k].slave_side))
        .collect();
    if !continues_smoothly(problem, &sides, (pair.slave, pair.slave_side), end) {
        return None; // a corner of the body, or a symmetry line
    }
    let master_curve = match &pair.master {
        Master::Rigid(c) => c.clone(),
        Master::Body { body, side } => bodies[*body].space.patch.side_curve(*side),
    };
    let at = curve.point(t);
    let pr = closest_point(&master_curve, at).ok()?;
    let (lo, hi) = (master_curve.knots.first(), master_curve.knots.last());
    let tol = 1e-6 * (hi - lo);
    if !pr.orthogonal || pr.t <= lo + tol || pr.t >= hi - tol {
        return None; // the master ends there too
    }
    let group = problem.map.group(pair.slave);
    let patches = (0..bodies.len())
        .filter(|&b| problem.map.group(b) == group)
        .count();
    Some(Warning::ZoneAtSideEnd {
        contact: c,
        slave: slave.name.clone(),
        extent: if patches > 1 {
            SlaveExtent::Boundary
        } else {
            SlaveExtent::Side(pair.slave_side.name())
        },
        end,
        at,
        singular: !points[q_end].regular,
    })
}

/// Whether the boundary of the slave body goes on past `end` of `side`
/// (patch, side) within [`SMOOTH`] degrees of the side's own direction:
/// along a side of any patch of the same body that starts at that point,
/// the contact's own sides `own` aside.
fn continues_smoothly(
    problem: &Problem,
    own: &[(usize, Side)],
    (slave, side): (usize, Side),
    end: SideEnd,
) -> bool {
    let bodies = &problem.bodies;
    let patch = &bodies[slave].space.patch;
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
    let n1 = out[0].hypot(out[1]);
    let size = patch
        .points
        .iter()
        .map(|p| (p[0] - corner[0]).hypot(p[1] - corner[1]))
        .fold(0.0, f64::max);
    let dist = |p: [f64; 2]| (p[0] - corner[0]).hypot(p[1] - corner[1]);
    let group = problem.map.group(slave);
    let candidates = (0..bodies.len())
        .filter(|&b| problem.map.group(b) == group)
        .flat_map(|b| Side::ALL.map(|s| (b, s)))
        .filter(|bs| !own.contains(bs));
    for (b, s) in candidates {
        let other = bodies[b].space.patch.side_curve(s);
        let (a, z) = (other.knots.first(), other.knots.last());
        let e = 1e-6 * (z - a);
        // the end of the other side at the corner, and a point just past it
        let (from, beyond) = if dist(other.point(a)) <= 1e-9 * size {
            (other.point(a), other.point(a + e))
        } else if dist(other.point(z)) <= 1e-9 * size {
            (other.point(z), other.point(z - e))
        } else {
            continue;
        };
        let on = [beyond[0] - from[0], beyond[1] - from[1]];
        let n2 = on[0].hypot(on[1]);
        if !(n1 > 0.0 && n2 > 0.0) {
            continue;
        }
        let cos = (out[0] * on[0] + out[1] * on[1]) / (n1 * n2);
        if cos >= SMOOTH.to_radians().cos() {
            return true;
        }
    }
    false
}
