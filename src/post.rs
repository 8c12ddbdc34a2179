//! Post-processing: what the book, the chapter programs and the scene
//! outputs measure on a converged solution — the contact pressure along the
//! slave boundary, its peak and the contact half-width, the contact and
//! load resultants, and errors against a reference solution.
//!
//! Each quantity has exactly one estimator, here, so every chapter quotes
//! the same number for the same solution. Everything about the contact
//! pressure is built on the Nitsche bracket P = σ_n + γ g_n and the
//! projection of Eq. (10): the pressure the master exerts is −\[P\]₋.

pub mod ends;
pub mod hertz;
mod measures;
pub mod zone_warnings;
pub mod zones;

pub use ends::{SideEndKind, SlaveEnd, ZoneBounds};
pub use measures::ContactMeasures;
pub use zone_warnings::zone_warnings;
pub use zones::Zone;

use crate::assembly::load_vector;
use crate::contact::nitsche::negative_part;
use crate::contact::pair::checked_contact_points;
pub use crate::contact::penalty::{stability_of, PenaltyStability};
use crate::contact::{ContactPoint, Integration, Role};
use crate::contact::{GaussCount, GaussPoints};
use crate::dofs::DofMap;
use crate::error::{Error, Result};
use crate::linsolve::mul;
use crate::problem::Problem;

/// Sample points per slave element of the dense pressure profile: the
/// points of a 20-point Gauss rule, so element ends (where the pressure
/// may have a kink) are never sampled, and no point is sampled twice.
pub const PROFILE_SAMPLES_PER_ELEMENT: usize = 20;

/// One point of a [`PressureProfile`].
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ProfileSample {
    /// Index of the contact pair.
    pub pair: usize,
    /// Parameter of the point on the slave side.
    pub t: f64,
    /// Reference position x¹ on the slave.
    pub x: [f64; 2],
    /// n¹, the slave normal (pointing towards the master).
    pub normal: [f64; 2],
    /// The initial gap g₀.
    pub g0: f64,
    /// The Nitsche bracket P = σ_n + γ g_n; negative where the bodies press.
    pub bracket: f64,
    /// Quadrature weight of the sampling rule, arc length included.
    pub weight: f64,
    /// False on a slave element whose geometric map is singular at an end
    /// ([`crate::contact::pair::regular_map`]): σ_n there is a division by
    /// det J ≈ 0, and the bracket is not a pressure. The measures skip such samples, and the
    /// profile's table marks them.
    pub regular: bool,
}

impl ProfileSample {
    /// The contact pressure −\[P\]₋ ≥ 0 of Eq. (9)–(10).
    pub fn pressure(&self) -> f64 {
        -negative_part(self.bracket)
    }
}

/// The Nitsche bracket sampled densely along every slave side.
///
/// The samples are contact points built by [`contact_points`](crate::contact::contact_points) exactly as the
/// solver's (same normal, gap, penalty and σ_n functional); only the rule
/// differs: Gauss points per slave element, never cut at master knots.
#[derive(Clone, Debug, PartialEq)]
pub struct PressureProfile {
    /// Sorted by pair, then by slave parameter.
    samples: Vec<ProfileSample>,
    /// Where the zones of every pair's slave side may end.
    bounds: Vec<ZoneBounds>,
    /// Samples per slave element, when they were placed per element
    /// ([`PressureProfile::sample`]); unknown for given points.
    per_element: Option<usize>,
}

/// The contact points of `problem`'s pairs placed at `per_element` Gauss
/// points of every slave element, whatever rule the solver used: the
/// denser sampling that post-processing measures on.
///
/// The pairs are the problem's, checked when it was built; only
/// `per_element` is new here, and checked ([`GaussCount`]).
pub fn dense_contact_points(problem: &Problem, per_element: usize) -> Result<Vec<ContactPoint>> {
    let per_element = GaussPoints::Fixed(GaussCount::new(per_element, "per_element")?);
    let pairs: Vec<_> = problem
        .pairs
        .iter()
        .map(|p| {
            let mut p = p.clone();
            p.nitsche.integration = Integration::Gauss;
            p.nitsche.gauss_points = per_element;
            p
        })
        .collect();
    checked_contact_points(&problem.bodies, &problem.map, &pairs, &problem.contacts)
}

impl PressureProfile {
    /// Samples the bracket of `full` (all DOFs) at `per_element` Gauss
    /// points of every slave element (`per_element` in 1..=30).
    pub fn sample(problem: &Problem, full: &[f64], per_element: usize) -> Result<Self> {
        if full.len() != problem.map.n_total() {
            return Err(Error::invalid(
                "displacement",
                format!("{} values", full.len()),
                format!("the DOF map has {} DOFs", problem.map.n_total()),
            ));
        }
        let points = dense_contact_points(problem, per_element)?;
        Ok(Self {
            per_element: Some(per_element),
            ..Self::from_points(problem, &points, full)
        })
    }

    /// The profile at the given contact points of `problem` (for instance
    /// the solver's own), on each pair's slave side.
    pub fn from_points(problem: &Problem, points: &[ContactPoint], full: &[f64]) -> Self {
        let bounds = (0..problem.pairs.len())
            .map(|k| ZoneBounds::of_pair(problem, k))
            .collect();
        let mut samples: Vec<ProfileSample> = points
            .iter()
            .filter(|cp| cp.role == Role::Slave)
            .map(|cp| ProfileSample {
                pair: cp.pair,
                t: cp.t,
                x: cp.x,
                normal: cp.normal,
                g0: cp.g0,
                bracket: cp.p(full),
                weight: cp.weight,
                regular: cp.regular,
            })
            .collect();
        samples.sort_by(|a, b| a.pair.cmp(&b.pair).then(a.t.total_cmp(&b.t)));
        Self {
            samples,
            bounds,
            per_element: None,
        }
    }

    /// The dense profile: [`PROFILE_SAMPLES_PER_ELEMENT`] points per slave
    /// element, or, where the map of a slave element is not invertible at
    /// some of them, the largest of 16, 12, 10, 8, 6, 4 points that works.
    /// (The isoparametric Q2 interpolant of the disk folds slightly at the
    /// far corner of its contact side, away from the contact zone.)
    pub fn dense(problem: &Problem, full: &[f64]) -> Result<Self> {
        let mut last = None;
        for n in [PROFILE_SAMPLES_PER_ELEMENT, 16, 12, 10, 8, 6, 4] {
            match Self::sample(problem, full, n) {
                Ok(p) => return Ok(p),
                Err(e @ Error::Geometry(_)) => last = Some(e),
                Err(e) => return Err(e),
            }
        }
        Err(last.expect("tried at least once"))
    }

    pub fn samples(&self) -> &[ProfileSample] {
        &self.samples
    }

    /// The samples of contact pair `pair`, in order along the slave side.
    pub fn pair(&self, pair: usize) -> &[ProfileSample] {
        let lo = self.samples.partition_point(|s| s.pair < pair);
        let hi = self.samples.partition_point(|s| s.pair <= pair);
        &self.samples[lo..hi]
    }

    /// Peak pressure p₀ and half-width a of pair `pair`
    /// (see [`ContactMeasures::of`]), over the samples where the map is
    /// regular ([`ProfileSample::regular`]).
    pub fn measures(&self, pair: usize) -> ContactMeasures {
        let regular: Vec<ProfileSample> = self
            .pair(pair)
            .iter()
            .filter(|s| s.regular)
            .copied()
            .collect();
        ContactMeasures::of(&regular, &self.bounds[pair])
    }

    /// As [`PressureProfile::measures`], over the consecutive pairs
    /// `pairs` taken as one slave boundary joined end to end (the pieces of
    /// a multi-patch boundary, each running on from the last): one zone
    /// crossing a join is one zone, and the boundary's own ends are the
    /// first piece's start and the last piece's end, in the boundary's
    /// direction.
    ///
    /// A piece's samples run along its patch side's parameter, which may
    /// run against the boundary (a side shared by two patches runs one way
    /// on each), so each piece is turned to start where the last one ended.
    /// Unturned, a zone on a reversed piece was cut into runs out of order
    /// (a new user's half disk under a ceiling: half_width 0.0187 where the
    /// floor gave 0.0470 for the same profile).
    pub fn measures_joined(&self, pairs: std::ops::Range<usize>) -> ContactMeasures {
        let (samples, joined) = self.joined(pairs);
        ContactMeasures::of(&samples, &joined)
    }

    /// The zones of the consecutive pairs `pairs` joined end to end, as in
    /// [`PressureProfile::measures_joined`], with the index of the main one
    /// ([`zones::main_zone`]).
    pub fn zones_joined(&self, pairs: std::ops::Range<usize>) -> (Vec<Zone>, Option<usize>) {
        let zones = zones::zones_of(&self.joined(pairs).0);
        let main = zones::main_zone(&zones);
        (zones, main)
    }

    /// Samples per slave element, if the profile was sampled per element.
    pub fn per_element(&self) -> Option<usize> {
        self.per_element
    }

    /// The regular samples of `pairs` in order along the boundary they
    /// make, and where its zones may end (see
    /// [`PressureProfile::measures_joined`]).
    fn joined(&self, pairs: std::ops::Range<usize>) -> (Vec<ProfileSample>, ZoneBounds) {
        let dist = |a: [f64; 2], b: [f64; 2]| (a[0] - b[0]).hypot(a[1] - b[1]);
        let ends_of = |k: usize| self.bounds[k].slave.map(|e| e.at);
        // distance of a point to the nearer end of piece k
        let near = |x: [f64; 2], k: usize| {
            let [a, b] = ends_of(k);
            dist(x, a).min(dist(x, b))
        };
        let mut samples: Vec<ProfileSample> = Vec::new();
        let mut joined = self.bounds[pairs.start].clone();
        let mut first_sampled = true;
        for k in pairs.clone() {
            let [a, b] = self.bounds[k].slave;
            let reversed = if k == pairs.start {
                // the first piece ends where the second one touches it
                k + 1 < pairs.end && near(a.at, k + 1) < near(b.at, k + 1)
            } else {
                dist(b.at, joined.slave[1].at) < dist(a.at, joined.slave[1].at)
            };
            let mut piece: Vec<ProfileSample> =
                self.pair(k).iter().filter(|s| s.regular).copied().collect();
            let (start, end) = if reversed {
                piece.reverse();
                (b, a)
            } else {
                (a, b)
            };
            if k == pairs.start {
                joined.slave[0] = start;
            }
            joined.slave[1] = end;
            // the samples at each end of the boundary face the master of
            // the first and the last piece that has any
            if !piece.is_empty() {
                if first_sampled {
                    joined.master[0] = self.bounds[k].master[0].clone();
                    first_sampled = false;
                }
                joined.master[1] = self.bounds[k].master[1].clone();
            }
            samples.extend(piece);
        }
        (samples, joined)
    }

    /// The largest pressure of pair `pair` over its regular samples: the
    /// profile's own maximum, which the measures' p₀ does not exceed.
    pub fn max_pressure(&self, pair: usize) -> f64 {
        self.pair(pair)
            .iter()
            .filter(|s| s.regular)
            .map(ProfileSample::pressure)
            .fold(0.0, f64::max)
    }
}

/// The force the masters exert on the slaves, Σ_q w \[P\]₋ n¹ over the
/// contact points of `problem` (the solver's own quadrature, so that it
/// balances the load exactly at convergence), per pair. A point on the
/// master side (the mirrored half of the unbiased form) carries the
/// reaction, so it counts with the opposite sign.
pub fn contact_resultants(problem: &Problem, full: &[f64]) -> Vec<[f64; 2]> {
    let mut f = vec![[0.0; 2]; problem.pairs.len()];
    for cp in &problem.points {
        let sign = match cp.role {
            Role::Slave => 1.0,
            Role::Master => -1.0,
        };
        let pm = sign * negative_part(cp.p(full));
        f[cp.pair][0] += cp.weight * pm * cp.normal[0];
        f[cp.pair][1] += cp.weight * pm * cp.normal[1];
    }
    f
}

/// [`contact_resultants`] summed over the pairs.
pub fn contact_resultant(problem: &Problem, full: &[f64]) -> [f64; 2] {
    contact_resultants(problem, full)
        .iter()
        .fold([0.0; 2], |a, f| [a[0] + f[0], a[1] + f[1]])
}

/// The resultant of the applied loads, ∫ b dΩ + ∫ t dΓ: the load vector with
/// no DOF fixed, summed per component (the basis is a partition of unity).
pub fn applied_resultant(problem: &Problem) -> Result<[f64; 2]> {
    let free = DofMap::builder(&problem.bodies).build();
    let f = load_vector(&problem.bodies, &free, &problem.loads)?;
    let mut sum = [0.0; 2];
    for (g, v) in f.iter().enumerate() {
        sum[g % 2] += v;
    }
    Ok(sum)
}

/// Strain energy ½ uᵀKu of the free displacement `u` (exact when every
/// prescribed displacement is zero, as in the paper's set-ups).
pub fn strain_energy(problem: &Problem, u: &[f64]) -> f64 {
    0.5 * mul(&problem.k, u)
        .iter()
        .zip(u)
        .map(|(a, b)| a * b)
        .sum::<f64>()
}

/// Signed relative difference (value − target)/target.
pub fn relative(value: f64, target: f64) -> f64 {
    (value - target) / target
}

/// Errors of one solution against a reference solution of the same problem.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Errors {
    /// |p₀ − p₀,ref| / p₀,ref.
    pub p0: f64,
    /// |a − a_ref| / a_ref.
    pub half_width: f64,
    /// The relative L² distance of the pressure profiles over
    /// x ∈ \[0, 1.2 a_ref\] (see [`Reference::profile_error`]).
    pub pressure_l2: f64,
    /// √(|E − E_ref| / E_ref) with E the strain energy: for a conforming
    /// discretisation of a linear problem this is the relative energy norm
    /// of the error; here it is a proxy of it.
    pub energy: f64,
}

/// What a reference (fine-mesh) solution provides for measuring errors:
/// its dense profile of the first contact pair, measures and strain energy.
#[derive(Clone, Debug)]
pub struct Reference {
    pub profile: PressureProfile,
    pub measures: ContactMeasures,
    pub energy: f64,
}

/// The part of the contact zone over which pressure profiles are compared,
/// in units of the reference half-width.
pub const PROFILE_ERROR_EXTENT: f64 = 1.2;

impl Reference {
    pub fn new(problem: &Problem, u: &[f64], full: &[f64]) -> Result<Self> {
        let profile = PressureProfile::dense(problem, full)?;
        Ok(Self {
            measures: profile.measures(0),
            profile,
            energy: strain_energy(problem, u),
        })
    }

    /// The relative L² distance √(Σ w (p − p_ref)²) / √(Σ w p_ref²) of a
    /// profile of pair 0 to the reference's, over the samples with
    /// x ≤ [`PROFILE_ERROR_EXTENT`]·a_ref, with the profile's own weights
    /// and the reference interpolated linearly in x.
    pub fn profile_error(&self, profile: &PressureProfile) -> f64 {
        let reference = self.profile.pair(0);
        let x_max = PROFILE_ERROR_EXTENT * self.measures.half_width;
        let (mut num, mut den) = (0.0, 0.0);
        for s in profile.pair(0).iter().filter(|s| s.x[0] <= x_max) {
            let r = interpolate_pressure(reference, s.x[0]);
            num += s.weight * (s.pressure() - r).powi(2);
            den += s.weight * r * r;
        }
        (num / den).sqrt()
    }

    /// Every error of a solution (`u` free DOFs, `full` all DOFs).
    pub fn errors(&self, problem: &Problem, u: &[f64], full: &[f64]) -> Result<Errors> {
        let profile = PressureProfile::dense(problem, full)?;
        let m = profile.measures(0);
        let energy = strain_energy(problem, u);
        Ok(Errors {
            p0: relative(m.p0, self.measures.p0).abs(),
            half_width: relative(m.half_width, self.measures.half_width).abs(),
            pressure_l2: self.profile_error(&profile),
            energy: relative(energy, self.energy).abs().sqrt(),
        })
    }
}

/// The pressure of samples ordered by x, interpolated linearly at `x`
/// (constant beyond the ends).
fn interpolate_pressure(samples: &[ProfileSample], x: f64) -> f64 {
    let i = samples.partition_point(|s| s.x[0] < x);
    match (samples.get(i.wrapping_sub(1)), samples.get(i)) {
        (Some(a), Some(b)) if b.x[0] > a.x[0] => {
            a.pressure() + (b.pressure() - a.pressure()) * (x - a.x[0]) / (b.x[0] - a.x[0])
        }
        (_, Some(b)) => b.pressure(),
        (Some(a), None) => a.pressure(),
        (None, None) => 0.0,
    }
}

/// [`PenaltyStability`] of every pair at the displacement `full`: the
/// active points are those with P(u) ≤ 0.
pub fn penalty_stability(problem: &Problem, full: &[f64]) -> Vec<PenaltyStability> {
    stability_of(
        &problem.points,
        problem.pairs.len(),
        |_, cp| cp.p(full) <= 0.0,
        crate::solver::warning::OVER_PENALTY,
    )
}

/// [`PenaltyStability`] of every pair before solving: the active points
/// are those where the bodies first touch
/// ([`crate::contact::penalty::first_touch`]).
pub fn first_touch_stability(points: &[ContactPoint], pairs: usize) -> Vec<PenaltyStability> {
    let touch = crate::contact::penalty::first_touch(points, pairs);
    stability_of(
        points,
        pairs,
        |q, _| touch[q],
        crate::solver::warning::OVER_PENALTY,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sample at (x, 0) on a floor below, first touching at x = 0.
    pub(crate) fn sample(x: f64, bracket: f64) -> ProfileSample {
        ProfileSample {
            pair: 0,
            t: x,
            x: [x, 0.0],
            normal: [0.0, -1.0],
            g0: x * x,
            bracket,
            weight: 1.0,
            regular: true,
        }
    }

    #[test]
    fn interpolation_is_linear_and_constant_outside() {
        let s = [sample(0.0, -1.0), sample(1.0, -3.0)];
        assert_eq!(interpolate_pressure(&s, 0.25), 1.5);
        assert_eq!(interpolate_pressure(&s, -1.0), 1.0);
        assert_eq!(interpolate_pressure(&s, 2.0), 3.0);
    }
}
