//! The warnings of a converged solution.

use super::kinds::{Counted, Warning, RESOLVED};
use super::penalty::penalty_warnings;
use super::setup::setup_warnings;
use super::side_end::zones_at_side_end;
use crate::contact::{ContactPoint, Role};
use crate::problem::Problem;

/// The warnings of a converged solution `full` (all DOFs).
pub fn warnings(problem: &Problem, full: &[f64]) -> Vec<Warning> {
    let p: Vec<f64> = problem.points.iter().map(|cp| cp.p(full)).collect();
    let mut out = setup_warnings(&problem.bodies, &problem.pairs);
    out.extend(penalty_warnings(
        &problem.bodies,
        &problem.pairs,
        &problem.points,
        Counted::Solution,
        |q, _| p[q] <= 0.0,
    ));
    // below the bound the active set itself is in doubt: that one cause is
    // reported, not the extent of the zone it produces
    let doubtful: Vec<usize> = out
        .iter()
        .filter_map(|w| match w {
            Warning::PenaltyBelowBound { pair, .. } => Some(*pair),
            _ => None,
        })
        .collect();
    out.extend(
        zones_at_side_end(problem, &p).into_iter().filter(
            |w| !matches!(w, Warning::ZoneAtSideEnd { pair, .. } if doubtful.contains(pair)),
        ),
    );
    for (k, pair) in problem.pairs.iter().enumerate() {
        let active: Vec<&ContactPoint> = (0..p.len())
            .filter(|&q| problem.points[q].pair == k && p[q] <= 0.0)
            .map(|q| &problem.points[q])
            .collect();
        if active.is_empty() {
            continue;
        }
        // the slave elements the zone touches (points of the slave side;
        // the mirrored half of the unbiased form lies on the master)
        let sides = problem.bodies[pair.slave].space.boundary(pair.slave_side);
        let mut touched: Vec<usize> = active
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
        if active.len() < RESOLVED || touched.len() == 1 {
            out.push(Warning::UnresolvedContact {
                pair: k,
                active: active.len(),
                elements: touched.len(),
            });
        }
    }
    out
}
