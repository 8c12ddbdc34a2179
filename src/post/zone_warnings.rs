//! The warnings about the contact zones of a solution, which need its
//! dense pressure profile: several zones sharing the force
//! ([`Warning::SeveralZones`]), and a main zone too few elements wide to
//! measure ([`Warning::CoarseZone`]).

use super::PressureProfile;
use crate::problem::Problem;
use crate::solver::warning::{zone_elements, ZoneShare, ZONE_SHARE};
use crate::solver::Warning;

/// The zone warnings of every contact of `problem`, measured on `profile`
/// (the dense profile of the solution), beside the solver's `existing`
/// warnings: a contact already warned for a cause that makes its zones
/// meaningless (closed through its slave, resting on too few points, its
/// active set in doubt, a stiffer slave, a slave body that locks) gets no
/// zone warning, whose advice would not fix it: refining a locked or
/// over-penalised slave as the zone advice says was measured to make the
/// answer worse (disk on a block 10⁶ stiffer as slave: p₀ 18.7 × Hertz's,
/// 280 × after the advised refinement).
pub fn zone_warnings(
    problem: &Problem,
    profile: &PressureProfile,
    existing: &[Warning],
) -> Vec<Warning> {
    let doubtful = |c: usize, slave: &str| {
        existing.iter().any(|w| match w {
            Warning::NearlyIncompressible { body, .. } => body == slave,
            _ => {
                w.contact() == Some(c)
                    && matches!(
                        w,
                        Warning::ClosedFacingAway { .. }
                            | Warning::UnresolvedContact { .. }
                            | Warning::PenaltyBelowBound { .. }
                            | Warning::StifferSlave { .. }
                    )
            }
        })
    };
    let mut out = Vec::new();
    for (c, pieces) in problem.contacts.iter() {
        let slave_index = problem.pairs[pieces.start].slave;
        let slave = &problem.bodies[slave_index].name;
        if doubtful(c, slave) {
            continue;
        }
        let (zones, main) = profile.zones_joined(pieces.clone());
        let total: f64 = zones.iter().map(|z| z.force).sum();
        let Some(main) = main.filter(|_| total > 0.0) else {
            continue;
        };
        let shares: Vec<ZoneShare> = zones
            .iter()
            .enumerate()
            .map(|(k, z)| ZoneShare {
                share: z.force / total,
                p0: z.p0,
                at: z.peak_at,
                main: k == main,
            })
            .filter(|z| z.share >= ZONE_SHARE)
            .collect();
        if shares.len() > 1 {
            out.push(Warning::SeveralZones {
                contact: c,
                zones: shares,
            });
        }
        // the samples were placed per element: their count is the width
        if let Some(per) = profile.per_element() {
            let across = zones[main].samples.len() as f64 / per as f64;
            let side_elements = pieces.clone().map(|k| profile.pair(k).len()).sum::<usize>() / per;
            let degree = problem.bodies[slave_index].space.patch.degree();
            let (needed, target) = zone_elements(degree[0].max(degree[1]));
            if across < needed {
                let advised = (side_elements as f64 * target / across).ceil() as usize;
                out.push(Warning::CoarseZone {
                    contact: c,
                    across,
                    needed,
                    target,
                    side_elements,
                    advised,
                });
            }
        }
    }
    out
}
