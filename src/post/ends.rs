//! Where a contact zone can stop without the bracket changing sign: at an
//! end of the slave side — a symmetry line of a half model, or an edge of
//! the body — or where the master runs out, beyond which the slave has no
//! contact points at all.
//!
//! The half-width needs to know which: only a symmetry line is the centre
//! of the zone. Taken for one, the end of a short floor under a block
//! doubled the half-width (a zone 0.5 long reported `half_width = 0.5`).

use crate::contact::Master;
use crate::nurbs::Side;
use crate::problem::Problem;

/// What the model is at one end of a slave side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SideEndKind {
    /// The end lies on a symmetry line: a straight side of the same body
    /// through it whose control points all hold the displacement normal to
    /// it at 0 (the Hertz half disk's diameter). The modelled body is half of a
    /// symmetric one.
    Symmetry,
    /// Any other end: a corner or edge of the body, or a boundary that goes
    /// on beyond the contact side.
    Edge,
}

/// One end of a slave side.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct SlaveEnd {
    /// The end point (reference configuration).
    pub at: [f64; 2],
    pub kind: SideEndKind,
}

/// The places where a zone of one slave boundary may end with no sample
/// beyond it: the boundary's two ends, in its direction, and, for each of
/// them, the end points of the master that the samples nearest it face
/// (the slave has contact points only where a master faces it).
#[derive(Clone, Debug, PartialEq)]
pub struct ZoneBounds {
    pub slave: [SlaveEnd; 2],
    pub master: [Vec<[f64; 2]>; 2],
}

impl ZoneBounds {
    /// Bounds whose slave ends are `slave` and whose master goes on
    /// beyond them (no master end to stop at).
    pub fn on_side(slave: [SlaveEnd; 2]) -> Self {
        Self {
            slave,
            master: [Vec::new(), Vec::new()],
        }
    }

    /// The bounds of contact pair `pair` of `problem`.
    pub fn of_pair(problem: &Problem, pair: usize) -> Self {
        let p = &problem.pairs[pair];
        let curve = problem.bodies[p.slave].space.patch.side_curve(p.slave_side);
        let (lo, hi) = (curve.knots.first(), curve.knots.last());
        let end = |t: f64| SlaveEnd {
            at: curve.point(t),
            kind: end_kind(problem, p.slave, p.slave_side, curve.point(t)),
        };
        let master = match &p.master {
            Master::Rigid(c) => c.clone(),
            Master::Body { body, side } => problem.bodies[*body].space.patch.side_curve(*side),
        };
        let master = vec![
            master.point(master.knots.first()),
            master.point(master.knots.last()),
        ];
        Self {
            slave: [end(lo), end(hi)],
            master: [master.clone(), master],
        }
    }
}

/// Whether `corner`, an end of `side` of patch `slave`, lies on a
/// symmetry line of the slave body (see [`SideEndKind::Symmetry`]): a
/// straight side of the same body through it, held normal to itself at 0. A
/// support holds one Cartesian component, so the line runs along an axis.
/// The angle it makes with the slave side does not matter (the
/// isoparametric Q2 disk meets its diameter a little off 90°).
fn end_kind(problem: &Problem, slave: usize, side: Side, corner: [f64; 2]) -> SideEndKind {
    const AXIS: f64 = 1e-9;
    let (bodies, map) = (&problem.bodies, &problem.map);
    let group = map.group(slave);
    let dist = |p: [f64; 2]| (p[0] - corner[0]).hypot(p[1] - corner[1]);
    let size = bodies[slave]
        .space
        .patch
        .points
        .iter()
        .map(|&p| dist(p))
        .fold(0.0, f64::max);
    // relative to the body's size, and at least the round-off of the
    // coordinates themselves: a scene far from the origin (map-grid
    // coordinates, 3e6 m) carries ~1e-9 m of it, more than 1e-9 of a
    // 0.4 m body, and its symmetry line was missed (half_width halved)
    let magnitude = corner[0].abs().max(corner[1].abs());
    let tol = 1e-9 * size + 64.0 * f64::EPSILON * magnitude;
    let symmetric = (0..bodies.len())
        .filter(|&b| map.group(b) == group)
        .flat_map(|b| Side::ALL.map(|s| (b, s)))
        .filter(|&bs| bs != (slave, side))
        .any(|(b, s)| {
            let patch = &bodies[b].space.patch;
            let cps = patch.side_indices(s);
            let at = |i: usize| patch.points[i];
            let (first, last) = (at(cps[0]), at(cps[cps.len() - 1]));
            let far = if dist(first) <= tol {
                last
            } else if dist(last) <= tol {
                first
            } else {
                return false; // not through the corner
            };
            let n = dist(far);
            if n <= tol {
                return false; // collapsed into the corner: no line
            }
            let line = [(far[0] - corner[0]) / n, (far[1] - corner[1]) / n];
            // the component normal to an axis-parallel line
            let Some(comp) = (0..2).find(|&c| line[1 - c].abs() >= 1.0 - AXIS) else {
                return false;
            };
            // straight: every control point on the line
            let straight = cps
                .iter()
                .all(|&i| (at(i)[comp] - corner[comp]).abs() <= tol);
            // held normal to it, and in place: a side pushed normal to
            // itself (u_n = δ ≠ 0) moves the body there, while its mirror
            // image would move by −δ, so it is no symmetry line (a block on
            // such rollers, its zone the whole bottom [0, 1], reported
            // half_width = 1 instead of 0.5)
            let held = cps.iter().all(|&i| {
                let g = map.global(b, i, comp);
                map.free(g).is_none() && map.prescribed(g) == 0.0
            });
            straight && held
        });
    if symmetric {
        SideEndKind::Symmetry
    } else {
        SideEndKind::Edge
    }
}
