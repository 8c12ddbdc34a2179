//! The contact zones of a sampled profile: the runs of consecutive samples
//! where the bodies press, each with the force it carries and its peak.

use super::ProfileSample;
use std::ops::Range;

/// One contact zone of a profile: a run of consecutive samples with a
/// negative bracket.
#[derive(Clone, Debug, PartialEq)]
pub struct Zone {
    /// The zone's samples, as indices into the samples measured.
    pub samples: Range<usize>,
    /// The force it carries: Σ w p over its samples (per unit thickness).
    pub force: f64,
    /// Its largest pressure, and where (reference position on the slave).
    pub p0: f64,
    pub peak_at: [f64; 2],
}

/// The zones of `samples` (in order along a slave boundary), in that order.
pub fn zones_of(samples: &[ProfileSample]) -> Vec<Zone> {
    let mut runs: Vec<Range<usize>> = Vec::new();
    for (k, s) in samples.iter().enumerate() {
        if s.bracket < 0.0 {
            match runs.last_mut() {
                Some(z) if z.end == k => z.end = k + 1,
                _ => runs.push(k..k + 1),
            }
        }
    }
    runs.into_iter()
        .map(|r| {
            let zone = &samples[r.clone()];
            let peak = zone
                .iter()
                .max_by(|a, b| a.pressure().total_cmp(&b.pressure()))
                .expect("a run is not empty");
            Zone {
                force: zone.iter().map(|s| s.weight * s.pressure()).sum(),
                p0: peak.pressure(),
                peak_at: peak.x,
                samples: r,
            }
        })
        .collect()
}

/// The main zone among `zones`: the one carrying the largest force, so
/// that which zone a profile describes depends neither on the direction of
/// the slave side nor on which zone touched first (an arch on a floor
/// touching near both ends, at g₀ = 0 at both, was measured at one end or
/// the other with the side's direction: p₀ 88,605 or 186,309). A spike of
/// large pressure on a few samples carries little force, so it is not the
/// main zone. Of zones carrying the same force, the first.
pub fn main_zone(zones: &[Zone]) -> Option<usize> {
    let mut best: Option<usize> = None;
    for (k, z) in zones.iter().enumerate() {
        if best.is_none_or(|b| z.force > zones[b].force) {
            best = Some(k);
        }
    }
    best
}
