//! What a converged solve reports about its answer ([`Warning`]): it
//! solves the discrete equations, but may not be the contact solution the
//! user wants.
//!
//! Each warning names one cause, the measurement that shows it, and one
//! remedy; the remedy is chosen so that, followed, the warning goes away and
//! the answer is right to the method's accuracy (`tests/warnings.rs` checks
//! each). The thresholds are measured on the shipped Hertz scenes; the
//! book's scene chapter lists them with their measurements.

use crate::contact::penalty::{first_touch, stability_of, PenaltyStability};
use crate::contact::projection::closest_point;
use crate::contact::{ContactPair, ContactPoint, Master, Modulus, Penalty, Role};
use crate::dofs::Body;
use crate::material::{Formulation, Plane};
use crate::nurbs::Side;
use crate::problem::Problem;

/// The fewest active points that count as resolving a contact zone.
pub const RESOLVED: usize = 3;

/// γ over the θ = 0 stability bound C_T/4 of its element above which p₀
/// drifts with the penalty (commonly explained by a penalty that
/// over-constrains the contact, which is not tested): on Hertz 8×8, θ = 0, the error of
/// p₀ is +2.5 % at a ratio of 7, +3.0 % at 10, +5.2 % at 24 and +8.2 % at
/// 270 (the factor-1 value is near 2.4, whatever the mesh). The error
/// depends on γ, not on θ, so the θ = 0 bound is the scale for every θ.
pub const OVER_PENALTY: f64 = 10.0;

/// γ over the θ = 0 bound C_T/4 below which the skew variant θ = −1,
/// stable for any γ > 0, holds the gap too loosely for its answer: Hertz
/// p = 3 on 8² gives p₀ +2.3 % at 10⁻¹ of Eq. (11), +3.5 % at 10⁻² and
/// +4.9 % at 10⁻³ (ratios near 0.05 and 0.005 at the active points), while
/// on 16² and 32² it moves by under 0.5 % down to 10⁻⁵; the warning marks
/// the answers a coarse mesh may get wrong.
pub const LOOSE_PENALTY: f64 = 1e-2;

/// Where an advised penalty factor puts the binding point: twice its
/// stability bound (θ = 0, 1) or twice the θ = 0 bound (θ = −1). On
/// every element the penalty then lies in [1, [`OVER_PENALTY`]] times its
/// θ = 0 bound (θ = 1: 4 to 8).
pub const PENALTY_TARGET: f64 = 2.0;

/// A slave whose Young's modulus exceeds its master's by more than this
/// factor: the penalty (11), scaled by the slave's modulus, then
/// over-penalises the softer master. Disk on block (16×16 on 32×16), the
/// block as slave: p₀ +6.8 % at a contrast of 30, +7.9 % at 100, +152 % at
/// 10⁴; with the roles swapped +0.9 %.
pub const STIFFER_SLAVE: f64 = 10.0;

/// The locking indicator (λ/μ)/N³ (N: the fewest elements of the body in
/// one direction) above which a displacement formulation in plane strain
/// locks: on Hertz with p = 2, 16×16: ν = 0.4 (indicator 1.0·10⁻³) +0.7 %,
/// ν = 0.45 (2.2·10⁻³) +5 %, ν = 0.49 (1.2·10⁻²) +22 %; 32×32: ν = 0.49
/// (1.5·10⁻³) +1.3 %, ν = 0.499 (1.5·10⁻²) +21 %.
pub const LOCKING: f64 = 1e-3;

/// The Poisson ratio at and below which no mesh is judged to lock: the
/// atlas's Hertz 16×16 is within 0.7 % of Hertz at ν = 0.3 and 0.4, and a
/// coarse block at ν = 0.3 (`minimal.toml`) is exact; the indicator alone
/// would flag it.
pub const LOCKING_POISSON: f64 = 0.4;

/// Where a penalty warning was counted.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Counted {
    /// At the active points of a solution.
    Solution,
    /// Before solving, at the points where the bodies first touch.
    FirstTouch,
}

/// The one change a penalty warning advises.
#[derive(Clone, Copy, Debug, PartialEq)]
pub enum PenaltyRemedy {
    /// Set the pair's `penalty_factor` to this value.
    Factor(f64),
    /// Set `penalty = "sharp"` with this safety factor: one factor cannot
    /// fit elements whose bounds differ this much.
    Sharp(f64),
    /// Set `modulus = "slave"`: the stiffer master's modulus in (11) is
    /// what over-penalises.
    SlaveModulus,
}

/// Which end of a slave side.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SideEnd {
    Start,
    End,
}

/// Something a converged solve reports about its answer: it solves the
/// discrete equations, but may not be the contact solution the user wants.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// Active points of contact pair `pair` whose penalty lies below the
    /// stability bound of their element: the tangent need not be coercive
    /// on this active set, so the root found need not be the only one.
    PenaltyBelowBound {
        pair: usize,
        below: usize,
        active: usize,
        /// Inactive points below θ C_T (θ > 0: their −(θ/γ) w σ_n σ_nᵀ stays
        /// in the tangent).
        inactive_below: usize,
        /// The smallest γ / bound over the points counted.
        min_ratio: Option<f64>,
        counted: Counted,
        remedy: PenaltyRemedy,
    },
    /// Active points of pair `pair` whose penalty exceeds [`OVER_PENALTY`]
    /// times the θ = 0 bound of their element: there p₀ was measured to
    /// grow with the penalty (Hertz 8×8, see [`OVER_PENALTY`]); that the
    /// contact over-constrains the mesh is the usual explanation, not
    /// tested.
    PenaltyFarAboveBound {
        pair: usize,
        over: usize,
        active: usize,
        /// The largest γ / (θ = 0 bound) over the active points.
        max_ratio: f64,
        counted: Counted,
        remedy: PenaltyRemedy,
    },
    /// θ = −1 with active points of pair `pair` whose penalty is below
    /// [`LOOSE_PENALTY`] times the θ = 0 bound of their element: stable, but
    /// the gap condition is held so loosely that p₀ may be off by a few
    /// percent on a coarse mesh.
    PenaltyLoose {
        pair: usize,
        active: usize,
        /// The smallest γ / (θ = 0 bound) over the active points.
        min_ratio: f64,
        counted: Counted,
        remedy: PenaltyRemedy,
    },
    /// The slave of pair `pair` is more than [`STIFFER_SLAVE`] times
    /// stiffer than its master.
    StifferSlave {
        pair: usize,
        slave: String,
        master: String,
        contrast: f64,
    },
    /// Body `body` is nearly incompressible (ν above [`LOCKING_POISSON`]) in
    /// plane strain on a mesh too coarse for its formulation ([`LOCKING`]).
    /// The local mixed formulation is judged by the same indicator (it still
    /// locks); the mixed one is not judged (it does not).
    NearlyIncompressible {
        body: String,
        formulation: Formulation,
        poisson: f64,
        indicator: f64,
        /// The fewest elements per direction that bring the indicator to
        /// [`LOCKING`].
        elements: usize,
    },
    /// The contact zone of pair `pair` runs to an end of its slave side
    /// where the body's boundary goes on smoothly, and the master goes on
    /// beyond it: the contact surface is cut off there.
    ZoneAtSideEnd {
        pair: usize,
        /// Body and side name of the slave side, for the advice.
        slave: String,
        side: &'static str,
        end: SideEnd,
        at: [f64; 2],
        /// Whether the slave's map is singular at that end (det J = 0, as
        /// at the degenerate corner of the nine-point disk).
        singular: bool,
    },
    /// The contact zone of pair `pair` rests on fewer than [`RESOLVED`]
    /// active points, or on the points of a single slave element: the mesh
    /// does not resolve it, and measures of the pressure (its peak, its
    /// width) are set by the quadrature spacing, the penalty and one
    /// element's polynomial rather than by the load (measured: Hertz p = 5
    /// on one element, three active points, p₀ twice the reference).
    UnresolvedContact {
        pair: usize,
        active: usize,
        elements: usize,
    },
}

impl Warning {
    /// A short note for the iteration history, for the warnings that
    /// concern the iteration itself (a penalty below its bound).
    pub fn note(&self) -> Option<String> {
        match self {
            Warning::PenaltyBelowBound { pair, below, .. } => Some(format!(
                "penalty below bound: contact[{pair}], {below} points"
            )),
            _ => None,
        }
    }
}

fn counted_words(c: Counted) -> &'static str {
    match c {
        Counted::Solution => "active points",
        Counted::FirstTouch => "points where the bodies first touch",
    }
}

fn remedy_words(pair: usize, r: PenaltyRemedy) -> String {
    let key = format!("contact[{pair}].nitsche");
    match r {
        PenaltyRemedy::Factor(f) => format!("set {key}.penalty_factor = {}", round2(f)),
        PenaltyRemedy::Sharp(f) => {
            format!("set {key}.penalty = \"sharp\" with {key}.penalty_factor = {f}")
        }
        PenaltyRemedy::SlaveModulus => format!("set {key}.modulus = \"slave\""),
    }
}

/// `x` to two significant digits: advice a user types.
fn round2(x: f64) -> f64 {
    if x == 0.0 || !x.is_finite() {
        return x;
    }
    // divide by a power of ten when there are decimals, so that 1.7 prints
    // as 1.7 and not as 17 × 0.1 = 1.7000000000000002
    let digits = 1 - x.abs().log10().floor() as i32;
    if digits > 0 {
        let p = 10f64.powi(digits);
        (x * p).round() / p
    } else {
        let p = 10f64.powi(-digits);
        (x / p).round() * p
    }
}

impl std::fmt::Display for Warning {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        match self {
            Warning::PenaltyBelowBound {
                pair,
                below,
                active,
                inactive_below,
                min_ratio,
                counted,
                remedy,
            } => {
                write!(
                    f,
                    "contact[{pair}]: {below} of the {active} {} {} a penalty below the stability bound of their element",
                    counted_words(*counted),
                    if *below == 1 { "has" } else { "have" }
                )?;
                if *inactive_below > 0 {
                    write!(
                        f,
                        ", and {inactive_below} other {} below θ·C_T, which θ > 0 needs at every point",
                        if *inactive_below == 1 { "point lies" } else { "points lie" }
                    )?;
                }
                if let Some(r) = min_ratio {
                    write!(f, " (smallest γ/bound {r:.3})")?;
                }
                write!(
                    f,
                    ", so the solution need not be unique: {}",
                    remedy_words(*pair, *remedy)
                )
            }
            Warning::PenaltyFarAboveBound {
                pair,
                over,
                active,
                max_ratio,
                counted,
                remedy,
            } => write!(
                f,
                "contact[{pair}]: {over} of the {active} {} {} a penalty over {OVER_PENALTY} times the θ = 0 stability bound of their element (largest γ/bound {max_ratio:.3}); above that ratio the peak pressure was measured to grow with the penalty: {}",
                counted_words(*counted),
                if *over == 1 { "has" } else { "have" },
                remedy_words(*pair, *remedy)
            ),
            Warning::PenaltyLoose {
                pair,
                active,
                min_ratio,
                counted,
                remedy,
            } => write!(
                f,
                "contact[{pair}]: θ = -1 with a penalty down to {} times the θ = 0 stability bound at its {active} {}, which holds the gap too loosely for an accurate p₀ on a coarse mesh: {}",
                round2(*min_ratio),
                counted_words(*counted),
                remedy_words(*pair, *remedy)
            ),
            Warning::StifferSlave {
                pair,
                slave,
                master,
                contrast,
            } => write!(
                f,
                "contact[{pair}]: the slave {slave:?} is {contrast:.3} times stiffer than the master {master:?}, and the penalty scales with the slave's modulus, so it over-penalises the softer body: make {master:?} the slave and {slave:?} the master"
            ),
            Warning::NearlyIncompressible {
                body,
                formulation: Formulation::Displacement,
                poisson,
                indicator,
                elements,
            } => write!(
                f,
                "body {body:?}: ν = {poisson} in plane strain locks this displacement formulation on its mesh (λ/μ over the cube of its elements per direction is {indicator:.2e}, above {LOCKING:e}), so the answer is unreliable: set formulation = \"mixed\" on {body:?} (its continuous pressure does not lock), or refine it to at least {elements} elements in each direction"
            ),
            Warning::NearlyIncompressible {
                body,
                formulation: Formulation::Mixed | Formulation::LocalMixed,
                // (never raised for `Mixed`; the words fit the local one)
                poisson,
                indicator,
                elements,
            } => write!(
                f,
                "body {body:?}: ν = {poisson} in plane strain locks its formulation on its mesh (a pressure of degree p − 1 per element over-constrains the spline space; λ/μ over the cube of its elements per direction is {indicator:.2e}, above {LOCKING:e}), so the answer is unreliable: set formulation = \"mixed\" on {body:?}, or refine it to at least {elements} elements in each direction"
            ),
            Warning::ZoneAtSideEnd {
                pair,
                slave,
                side,
                end,
                at,
                singular,
            } => write!(
                f,
                "contact[{pair}]: the contact zone reaches the {} of the slave side {side} of {slave:?} at ({:.6e}, {:.6e}){} while the master goes on, so the zone is cut off there: extend the slave side beyond the contact zone",
                match end {
                    SideEnd::Start => "start",
                    SideEnd::End => "end",
                },
                at[0],
                at[1],
                if *singular {
                    ", where the map is singular (det J = 0) and the pressure is not a contact pressure"
                } else {
                    ""
                }
            ),
            Warning::UnresolvedContact {
                pair,
                active,
                elements,
            } => write!(
                f,
                "contact[{pair}]: the contact zone rests on {active} quadrature point(s) in {elements} slave element(s): the mesh does not resolve it, and its peak pressure and width are not meaningful (refine the slave side until the zone spans several elements)"
            ),
        }
    }
}

/// The penalty warnings of every pair: below the bound, or far above it,
/// counted at the points where `active` holds. One count
/// ([`stability_of`]) feeds both.
fn penalty_warnings(
    bodies: &[Body],
    pairs: &[ContactPair],
    points: &[ContactPoint],
    counted: Counted,
    active: impl Fn(usize, &ContactPoint) -> bool,
) -> Vec<Warning> {
    let stability = stability_of(points, pairs.len(), active, OVER_PENALTY);
    let mut out = Vec::new();
    for (k, s) in stability.iter().enumerate() {
        let pair = &pairs[k];
        if s.active_below + s.inactive_below > 0 {
            out.push(Warning::PenaltyBelowBound {
                pair: k,
                below: s.active_below,
                active: s.active,
                inactive_below: s.inactive_below,
                min_ratio: s.min_ratio(),
                counted,
                remedy: below_remedy(pair, s),
            });
        } else if let (true, Some(min_ratio)) = (
            pair.nitsche.theta.value() < 0.0,
            s.min_active_scale.filter(|&r| r < LOOSE_PENALTY),
        ) {
            out.push(Warning::PenaltyLoose {
                pair: k,
                active: s.active,
                min_ratio,
                counted,
                remedy: scaled(pair, s, PENALTY_TARGET / min_ratio),
            });
        } else if let (true, Some(max_ratio)) = (s.active_over > 0, s.max_active_scale) {
            out.push(Warning::PenaltyFarAboveBound {
                pair: k,
                over: s.active_over,
                active: s.active,
                max_ratio,
                counted,
                remedy: over_remedy(bodies, pair, s, max_ratio),
            });
        }
    }
    out
}

/// Scaling the pair's penalty by `scale`, if that keeps every active point
/// between its bound and [`OVER_PENALTY`] times the θ = 0 bound: the
/// factor; otherwise the sharp penalty, which sets each element's γ from
/// its own bound.
fn scaled(pair: &ContactPair, s: &PenaltyStability, scale: f64) -> PenaltyRemedy {
    let low_ok = s.min_ratio().is_none_or(|m| m * scale >= 1.0);
    let high_ok = s.max_active_scale.is_none_or(|m| m * scale <= OVER_PENALTY);
    match pair.nitsche.penalty {
        Penalty::Empirical if low_ok && high_ok => {
            PenaltyRemedy::Factor(round2(pair.nitsche.penalty_factor * scale))
        }
        Penalty::Empirical => PenaltyRemedy::Sharp(PENALTY_TARGET),
        Penalty::Sharp => PenaltyRemedy::Factor(PENALTY_TARGET),
    }
}

/// Below the bound: the smallest active point lifted to [`PENALTY_TARGET`]
/// times its bound.
fn below_remedy(pair: &ContactPair, s: &PenaltyStability) -> PenaltyRemedy {
    let ratio = s.min_ratio().unwrap_or(1.0);
    scaled(pair, s, PENALTY_TARGET / ratio)
}

/// Far above: the stiffer master's modulus, if that is what raises γ;
/// otherwise the largest active point brought to [`PENALTY_TARGET`] times
/// its own θ's bound (θ = 1: 4 times the θ = 0 one; θ = −1: the θ = 0 one).
fn over_remedy(
    bodies: &[Body],
    pair: &ContactPair,
    s: &PenaltyStability,
    max_ratio: f64,
) -> PenaltyRemedy {
    if let (Modulus::Max, Master::Body { body, .. }) = (pair.nitsche.modulus, &pair.master) {
        let (es, em) = (
            bodies[pair.slave].material.young,
            bodies[*body].material.young,
        );
        if em > es && max_ratio * es / em <= OVER_PENALTY {
            return PenaltyRemedy::SlaveModulus;
        }
    }
    let own = if pair.nitsche.theta.value() > 0.0 {
        4.0
    } else {
        1.0
    };
    scaled(pair, s, PENALTY_TARGET * own / max_ratio)
}

/// The warnings that do not depend on the solution: the choice of slave,
/// and locking of nearly incompressible bodies.
pub fn setup_warnings(bodies: &[Body], pairs: &[ContactPair]) -> Vec<Warning> {
    let mut out = Vec::new();
    for (k, pair) in pairs.iter().enumerate() {
        if let Master::Body { body, .. } = pair.master {
            let (s, m) = (&bodies[pair.slave], &bodies[body]);
            let contrast = s.material.young / m.material.young;
            if contrast > STIFFER_SLAVE {
                out.push(Warning::StifferSlave {
                    pair: k,
                    slave: s.name.clone(),
                    master: m.name.clone(),
                    contrast,
                });
            }
        }
    }
    for b in bodies {
        if let Some(w) = locking(b) {
            out.push(w);
        }
    }
    out
}

/// [`Warning::NearlyIncompressible`] for body `b`, if its indicator is
/// above [`LOCKING`].
pub fn locking(b: &Body) -> Option<Warning> {
    let nu = b.material.poisson;
    // the mixed formulation's continuous pressure does not lock (chapter
    // "Near incompressibility")
    if b.material.plane != Plane::Strain
        || nu <= LOCKING_POISSON
        || b.formulation == Formulation::Mixed
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
    })
}

/// The warnings of a problem before it is solved: [`setup_warnings`], and
/// the penalty counted where the bodies first touch
/// ([`crate::contact::penalty::first_touch`]).
pub fn before_solve(
    bodies: &[Body],
    pairs: &[ContactPair],
    points: &[ContactPoint],
) -> Vec<Warning> {
    let touch = first_touch(points, pairs.len());
    let mut out = setup_warnings(bodies, pairs);
    out.extend(penalty_warnings(
        bodies,
        pairs,
        points,
        Counted::FirstTouch,
        |q, _| touch[q],
    ));
    out
}

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
