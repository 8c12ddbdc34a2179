//! The peak pressure p₀ and the half-width a of a sampled contact profile.

use super::ends::{SideEndKind, ZoneBounds};
use super::zones::{main_zone, zones_of};
use super::ProfileSample;

/// The peak pressure and the contact half-width of one contact pair.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ContactMeasures {
    /// p₀: the largest sampled pressure −\[P\]₋ in the main contact zone.
    pub p0: f64,
    /// Where p₀ is attained (reference position on the slave).
    pub peak_at: [f64; 2],
    /// a: half the length of the main contact zone, measured along the
    /// contact tangent at the peak — or its whole length when one end of
    /// the zone lies on a symmetry line of the model (a symmetric half
    /// model, [`SideEndKind::Symmetry`]).
    pub half_width: f64,
    /// How many separate contact zones the profile has (1 for a single,
    /// connected zone; more flags contact away from the main zone).
    pub zones: usize,
    /// The largest sampled pressure over every zone: p₀ when there is one
    /// zone, more when another zone peaks higher than the main one.
    pub p_max: f64,
    /// How many samples the main zone holds (with the samples per slave
    /// element, how many elements it spans).
    pub main_samples: usize,
}

/// How the main zone ends on one side, as a position along the tangent.
#[derive(Clone, Copy, Debug, PartialEq)]
enum ZoneEnd {
    /// Where the bracket changes sign, or at an edge of the body, or where
    /// the master runs out.
    Free(f64),
    /// On a symmetry line: the centre of the modelled body's mirror image.
    Symmetry(f64),
}

impl ZoneEnd {
    fn at(self) -> f64 {
        match self {
            ZoneEnd::Free(x) | ZoneEnd::Symmetry(x) => x,
        }
    }
}

impl ContactMeasures {
    /// Measures a profile of one pair: `samples` in order along the slave
    /// side, which may end at `bounds`.
    ///
    /// The contact zones are the runs of consecutive samples where the
    /// bracket P is negative. The **main zone** is the one carrying the
    /// largest force ([`main_zone`]). (A zone elsewhere is real in the
    /// discrete solution, but it is not the contact the measures describe:
    /// for instance a spike where the stress of a degenerate
    /// parametrisation is large; `zones` counts them, `p_max` holds the
    /// highest peak of all.)
    ///
    /// p₀ is the largest pressure of the main zone. Its ends are the sign
    /// changes of P, located by linear interpolation of the *signed* bracket
    /// between neighbouring samples: the clipped pressure cannot be
    /// interpolated, since it is identically 0 beyond the edge, but P is
    /// smooth there. A zone still pressed at its last sample ends where the
    /// samples do: at the end of the slave side, or at the end of the master
    /// if that is nearer (the slave has no contact points beyond it).
    /// Positions are measured along the tangent t = n¹⊥ at the peak (the
    /// common tangent of Hertz's theory). The half-width is half the zone's
    /// extent along t; if one end of the zone is an end of the slave side on
    /// a symmetry line, that end is the zone's centre — the model is a
    /// symmetric half, cut through the contact zone, as the paper's Hertz
    /// disk — and the half-width is the extent itself. With no loaded sample
    /// every measure is 0.
    pub fn of(samples: &[ProfileSample], bounds: &ZoneBounds) -> Self {
        let zones = zones_of(samples);
        let Some(main) = main_zone(&zones) else {
            return Self {
                p0: 0.0,
                peak_at: [0.0; 2],
                half_width: 0.0,
                zones: 0,
                p_max: 0.0,
                main_samples: 0,
            };
        };
        let main = zones[main].samples.clone();
        let peak = samples[main.clone()]
            .iter()
            .max_by(|a, b| a.pressure().total_cmp(&b.pressure()))
            .expect("a zone is not empty");
        let tangent = [-peak.normal[1], peak.normal[0]];
        let along = |x: [f64; 2]| (x[0] - peak.x[0]) * tangent[0] + (x[1] - peak.x[1]) * tangent[1];
        let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        let span = dist(bounds.slave[0].at, bounds.slave[1].at);
        // the zone's end on each side: a sign change, or where the samples
        // stop (the end of the side, or the master's)
        let edge = |inside: usize, outside: Option<usize>, end: usize| match outside {
            Some(o) => {
                let (a, b) = (&samples[inside], &samples[o]);
                let s = a.bracket / (a.bracket - b.bracket);
                ZoneEnd::Free(along([
                    a.x[0] + s * (b.x[0] - a.x[0]),
                    a.x[1] + s * (b.x[1] - a.x[1]),
                ]))
            }
            None => {
                let last = samples[inside].x;
                let side = bounds.slave[end];
                let master = bounds.master[end]
                    .iter()
                    .copied()
                    .min_by(|a, b| dist(last, *a).total_cmp(&dist(last, *b)));
                // a master ending at the side's end (two disks touching on
                // their common symmetry line) leaves the side's end
                match master {
                    Some(m) if dist(last, m) < dist(last, side.at) - 1e-9 * span => {
                        ZoneEnd::Free(along(m))
                    }
                    _ => match side.kind {
                        SideEndKind::Symmetry => ZoneEnd::Symmetry(along(side.at)),
                        SideEndKind::Edge => ZoneEnd::Free(along(side.at)),
                    },
                }
            }
        };
        let lo = edge(main.start, main.start.checked_sub(1), 0);
        let hi = edge(
            main.end - 1,
            Some(main.end).filter(|&e| e < samples.len()),
            1,
        );
        let half_width = match (lo, hi) {
            // cut by a symmetry line at one end: that end is the centre
            (ZoneEnd::Symmetry(c), ZoneEnd::Free(e)) | (ZoneEnd::Free(e), ZoneEnd::Symmetry(c)) => {
                (e - c).abs()
            }
            (a, b) => 0.5 * (b.at() - a.at()).abs(),
        };
        Self {
            p0: peak.pressure(),
            peak_at: peak.x,
            half_width,
            zones: zones.len(),
            p_max: zones.iter().map(|z| z.p0).fold(0.0, f64::max),
            main_samples: main.len(),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::super::ends::SlaveEnd;
    use super::super::tests::sample;
    use super::*;

    fn side(from: f64, from_kind: SideEndKind, to: f64) -> ZoneBounds {
        ZoneBounds::on_side([
            SlaveEnd {
                at: [from, 0.0],
                kind: from_kind,
            },
            SlaveEnd {
                at: [to, 0.0],
                kind: SideEndKind::Edge,
            },
        ])
    }

    /// On a sampled Hertz ellipse P(x) = −p₀√(1 − x²/a²) continued by a
    /// positive gap beyond a, the estimators find p₀ at the centre and a
    /// to second order in the sample spacing.
    #[test]
    fn measures_of_a_sampled_hertz_profile() {
        let (p0, a) = (2.0, 0.45);
        let half = side(0.0, SideEndKind::Symmetry, 1.0);
        for (n, tol) in [(40, 2e-3), (400, 2e-5)] {
            let samples: Vec<_> = (0..n)
                .map(|i| {
                    let x = (i as f64 + 0.5) / n as f64;
                    // smooth across the edge: −p₀(1 − x²/a²) has the same root
                    sample(x, -p0 * (1.0 - x * x / (a * a)))
                })
                .collect();
            let m = ContactMeasures::of(&samples, &half);
            assert!((m.p0 - p0).abs() <= 1e-3 * p0, "{m:?}");
            assert!((m.half_width - a).abs() <= tol, "n = {n}: {m:?}");
        }
        // a symmetric whole zone [−a, a] gives the same a as its half
        let samples: Vec<_> = (0..800)
            .map(|i| {
                let x = -1.0 + (i as f64 + 0.5) / 400.0;
                sample(x, -p0 * (1.0 - x * x / (a * a)))
            })
            .collect();
        let m = ContactMeasures::of(&samples, &side(-1.0, SideEndKind::Edge, 1.0));
        assert!((m.half_width - a).abs() <= 2e-5, "{m:?}");
        assert!(m.peak_at[0].abs() <= 2e-3);
        assert_eq!(m.zones, 1);
    }

    /// The same half profile on a side whose start is an edge of the
    /// body, not a symmetry line: the zone [0, a] is the whole zone, and
    /// its half-width is a/2.
    #[test]
    fn a_zone_at_an_edge_is_not_a_half() {
        let (p0, a) = (2.0, 0.45);
        let samples: Vec<_> = (0..400)
            .map(|i| {
                let x = (i as f64 + 0.5) / 400.0;
                sample(x, -p0 * (1.0 - x * x / (a * a)))
            })
            .collect();
        let m = ContactMeasures::of(&samples, &side(0.0, SideEndKind::Edge, 1.0));
        assert!((m.half_width - 0.5 * a).abs() <= 2e-5, "{m:?}");
    }

    /// A zone pressed up to its last sample, where the master ends short
    /// of the slave side's end, ends at the master's end.
    #[test]
    fn a_zone_ends_where_the_master_does() {
        let samples: Vec<_> = (0..300)
            .map(|i| sample((i as f64 + 0.5) / 1000.0, -1.0))
            .collect();
        let mut bounds = side(0.0, SideEndKind::Symmetry, 1.0);
        let m = ContactMeasures::of(&samples, &bounds);
        // on the side alone, the zone runs to the side's far end
        assert_eq!(m.half_width, 1.0);
        bounds.master[1] = vec![[-2.0, 0.0], [0.3, 0.0]];
        let m = ContactMeasures::of(&samples, &bounds);
        assert!((m.half_width - 0.3).abs() <= 1e-12, "{m:?}");
        bounds.slave[0].kind = SideEndKind::Edge;
        let m = ContactMeasures::of(&samples, &bounds);
        assert!((m.half_width - 0.15).abs() <= 1e-12, "{m:?}");
    }

    /// A spike of pressure far from the first touch (as the stress of a
    /// degenerate parametrisation can make) is a zone of its own: counted,
    /// but it changes neither p₀ nor a of the main zone.
    #[test]
    fn a_spurious_zone_is_counted_but_not_measured() {
        let (p0, a) = (2.0, 0.45);
        let mut samples: Vec<_> = (0..400)
            .map(|i| {
                let x = (i as f64 + 0.5) / 400.0;
                sample(x, -p0 * (1.0 - x * x / (a * a)))
            })
            .collect();
        let half = side(0.0, SideEndKind::Symmetry, 1.0);
        let clean = ContactMeasures::of(&samples, &half);
        samples[395].bracket = -100.0 * p0;
        let spiked = ContactMeasures::of(&samples, &half);
        assert_eq!(spiked.zones, 2);
        assert_eq!((spiked.p0, spiked.half_width), (clean.p0, clean.half_width));
    }

    #[test]
    fn no_contact_measures_zero() {
        let samples: Vec<_> = (0..10).map(|i| sample(i as f64, 1.0)).collect();
        let ends = side(0.0, SideEndKind::Edge, 1.0);
        let m = ContactMeasures::of(&samples, &ends);
        assert_eq!((m.p0, m.half_width), (0.0, 0.0));
        assert_eq!(ContactMeasures::of(&[], &ends).p0, 0.0);
    }
}
