//! The warnings a solve can report, their thresholds, and the words each
//! prints: the cause, the measurement and the one remedy.

use crate::contact::Sides;
use crate::material::Formulation;

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
/// over-penalises the softer master, and the bracket carries the stiffer
/// body's stress. Disk on block (16×16 on 32×16), the block as slave: p₀
/// +6.8 % at a contrast of 30, +7.9 % at 100, +152 % at 10⁴; with the roles
/// swapped +0.9 %. The shipped two cylinders (8×8 and 16×16, the lower one
/// the slave): +3.4 % at a contrast of 1, +9.8 % at 2, +31 % at 5 (+8 %
/// with the sharp penalty, +7 % on meshes twice as fine); with the softer
/// upper one as slave +2 % at 5. So the warning starts below a factor of 2.
pub const STIFFER_SLAVE: f64 = 1.5;

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

/// The share of a contact's force above which a zone besides the main one
/// is reported ([`Warning::SeveralZones`]): below it, a zone is a speck the
/// measures may ignore (the spike of a degenerate corner).
pub const ZONE_SHARE: f64 = 0.01;

/// The fewest slave elements across the main contact zone (its modelled
/// part) below which p₀ and the half-width are judged unresolved
/// ([`Warning::CoarseZone`]). Measured against Hertz's closed form, with
/// elements across (p₀ error, a error): Hertz p = 2 on 4² 1.3 (+4.2 %,
/// +9.5 %), 8² 2.35 (+2.7 %, +3.8 %), 16² 4.5 (+0.7 %, +0.7 %); p = 3 on
/// 4² 1.25 (+3.6 %, +3.9 %), 8² 2.3 (+0.4 %, +0.8 %); two cylinders 4²/8²
/// 1.05 (+4.3 %, +2.1 %), 8²/16² 1.9 (+2.0 %, −0.3 %). The shipped scenes
/// (2.35 and 1.9) lie above it.
pub const ZONE_ELEMENTS: f64 = 1.5;

/// The elements across the main zone a [`Warning::CoarseZone`] advises:
/// from 2.3 on, every run measured is within 4 % of Hertz, p = 3 within 1 %.
pub const ZONE_ELEMENTS_TARGET: f64 = 3.0;

/// The fewest slave elements across the main zone for slave degree
/// `degree`: [`ZONE_ELEMENTS`], or half the support of one basis function,
/// (p + 1)/2, if that is more, and the elements a warning advises with it.
///
/// Why half a support: a zone whose modelled half lies within one basis
/// function's reach is imposed at p + 2 points per element on fewer
/// functions than that, so the discrete pressure is over-constrained and
/// its peak grows with the penalty. Measured on the Hertz disk against the
/// converged p₀ (p = 3, 64²), at the penalty the below-bound warning
/// advises: four-patch half disk p = 5, 8² (2.1 across) +14.4 %, 16² (4.3)
/// +2.9 %; one-patch half disk p = 5, 8² (2.3 across) at factors 2.2, 3,
/// 4.4: +4.5, +8.1, +15 %, and 32² at 4.4: +0.25 %; p = 3 and 4 on 8²
/// (2.2 across): within 5 % at the advised factor. For p ≤ 2 it is
/// [`ZONE_ELEMENTS`] as before.
pub fn zone_elements(degree: usize) -> (f64, f64) {
    let half_support = (degree as f64 + 1.0) / 2.0;
    (
        ZONE_ELEMENTS.max(half_support),
        ZONE_ELEMENTS_TARGET.max(2.0 * half_support),
    )
}

/// One zone of a contact with several ([`Warning::SeveralZones`]).
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct ZoneShare {
    /// Its part of the contact's force (the zones' forces sum to 1).
    pub share: f64,
    /// Its largest pressure, and where (reference position on the slave).
    pub p0: f64,
    pub at: [f64; 2],
    /// Whether it is the main zone, which `p0` and `half_width` describe.
    pub main: bool,
}

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
    /// Set the contact's `penalty_factor` to this value.
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

/// Where on its body a contact's slave boundary lies: one side of a
/// one-patch body, or sides of a body of several patches, whose boundary
/// can go on past the end of one patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum SlaveExtent {
    Side(&'static str),
    Boundary,
}

/// What a locking body can be told: a one-patch body may take the mixed
/// formulation or a finer mesh; a body of several patches only the finer
/// mesh, since the mixed formulation is built for one patch.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum LockingRemedy {
    MixedOrRefine,
    /// On a C⁰ (Lagrange) mesh, where `mixed` is refused and `local_mixed`
    /// does not lock.
    LocalMixedOrRefine,
    Refine,
}

/// Something a converged solve reports about its answer: it solves the
/// discrete equations, but may not be the contact solution the user wants.
#[derive(Clone, Debug, PartialEq)]
pub enum Warning {
    /// Active points of contact `contact` whose penalty lies below the
    /// stability bound of their element: the tangent need not be coercive
    /// on this active set, so the root found need not be the only one.
    PenaltyBelowBound {
        contact: usize,
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
    /// Active points of contact `contact` whose penalty exceeds [`OVER_PENALTY`]
    /// times the θ = 0 bound of their element: there p₀ was measured to
    /// grow with the penalty (Hertz 8×8, see [`OVER_PENALTY`]); that the
    /// contact over-constrains the mesh is the usual explanation, not
    /// tested.
    PenaltyFarAboveBound {
        contact: usize,
        over: usize,
        active: usize,
        /// The largest γ / (θ = 0 bound) over the active points.
        max_ratio: f64,
        counted: Counted,
        remedy: PenaltyRemedy,
    },
    /// θ = −1 with active points of contact `contact` whose penalty is below
    /// [`LOOSE_PENALTY`] times the θ = 0 bound of their element: stable, but
    /// the gap condition is held so loosely that p₀ may be off by a few
    /// percent on a coarse mesh.
    PenaltyLoose {
        contact: usize,
        active: usize,
        /// The smallest γ / (θ = 0 bound) over the active points.
        min_ratio: f64,
        counted: Counted,
        remedy: PenaltyRemedy,
    },
    /// The slave of contact `contact` is more than [`STIFFER_SLAVE`] times
    /// stiffer than its master. Under the unbiased form (`sides`), which
    /// makes each body the slave of one half, `slave` is the stiffer body
    /// whichever the scene names the slave, and `master` the softer.
    StifferSlave {
        contact: usize,
        slave: String,
        master: String,
        contrast: f64,
        sides: Sides,
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
        /// What the body can be told to do.
        remedy: LockingRemedy,
    },
    /// The contact zone of contact `contact` runs to an end of its slave side
    /// where the body's boundary goes on smoothly, and the master goes on
    /// beyond it: the contact surface is cut off there.
    ZoneAtSideEnd {
        contact: usize,
        /// The slave body and where on it the contact lies, for the advice.
        slave: String,
        extent: SlaveExtent,
        end: SideEnd,
        at: [f64; 2],
        /// Whether the slave's map is singular at that end (det J = 0, as
        /// at the degenerate corner of the nine-point disk).
        singular: bool,
    },
    /// The contact zone of contact `contact` rests on fewer than [`RESOLVED`]
    /// active points, or on the points of a single slave element: the mesh
    /// does not resolve it, and measures of the pressure (its peak, its
    /// width) are set by the quadrature spacing, the penalty and one
    /// element's polynomial rather than by the load (measured: Hertz p = 5
    /// on one element, three active points, p₀ twice the reference).
    UnresolvedContact {
        contact: usize,
        active: usize,
        elements: usize,
    },
    /// Active points of contact `contact` lie where its slave faces away
    /// from the master, or meets it edge-on: the master is behind (or in
    /// line with) the slave's surface, the gap closed there is measured
    /// through the slave body (or along its surface), and what the
    /// solution holds there is no contact of the two surfaces. The set-up
    /// refuses a contact that starts closed that way; this one closed
    /// under the load (a disk's top drawn as slave against the floor it is
    /// pushed through).
    ClosedFacingAway {
        contact: usize,
        slave: String,
        away: usize,
        active: usize,
    },
    /// The contact has more than one zone carrying at least [`ZONE_SHARE`]
    /// of its force (an arch on a floor, touching near both ends): the
    /// measures p₀ and half-width describe the main zone only.
    SeveralZones {
        contact: usize,
        /// Every zone above [`ZONE_SHARE`], in order along the slave.
        zones: Vec<ZoneShare>,
    },
    /// The main contact zone spans fewer slave elements than its degree
    /// needs ([`zone_elements`]): p₀ and the half-width are set by the
    /// element's polynomial and the penalty more than by the load.
    CoarseZone {
        contact: usize,
        /// Slave elements across the main zone (fractional).
        across: f64,
        /// The fewest elements across for the slave's degree, and the
        /// number the advice aims at ([`zone_elements`]).
        needed: f64,
        target: f64,
        /// Elements of the slave boundary now, and the number that would
        /// put `target` elements across the zone.
        side_elements: usize,
        advised: usize,
    },
}

impl Warning {
    /// The contact the warning is about, if it is about one (the others are
    /// about a body).
    pub fn contact(&self) -> Option<usize> {
        match self {
            Warning::PenaltyBelowBound { contact, .. }
            | Warning::PenaltyFarAboveBound { contact, .. }
            | Warning::PenaltyLoose { contact, .. }
            | Warning::StifferSlave { contact, .. }
            | Warning::ZoneAtSideEnd { contact, .. }
            | Warning::UnresolvedContact { contact, .. }
            | Warning::ClosedFacingAway { contact, .. }
            | Warning::SeveralZones { contact, .. }
            | Warning::CoarseZone { contact, .. } => Some(*contact),
            Warning::NearlyIncompressible { .. } => None,
        }
    }

    /// A short note for the iteration history, for the warnings that
    /// concern the iteration itself (a penalty below its bound).
    pub fn note(&self) -> Option<String> {
        match self {
            Warning::PenaltyBelowBound { contact, below, .. } => Some(format!(
                "penalty below bound: contact[{contact}], {below} points"
            )),
            _ => None,
        }
    }
}

fn counted_words(c: Counted, n: usize) -> &'static str {
    match (c, n) {
        (Counted::Solution, 1) => "active point",
        (Counted::Solution, _) => "active points",
        (Counted::FirstTouch, 1) => "point where the bodies first touch",
        (Counted::FirstTouch, _) => "points where the bodies first touch",
    }
}

fn remedy_words(contact: usize, r: PenaltyRemedy) -> String {
    let key = format!("contact[{contact}].nitsche");
    match r {
        PenaltyRemedy::Factor(f) => format!("set {key}.penalty_factor = {}", round2(f)),
        PenaltyRemedy::Sharp(f) => {
            format!("set {key}.penalty = \"sharp\" with {key}.penalty_factor = {f}")
        }
        PenaltyRemedy::SlaveModulus => format!("set {key}.modulus = \"slave\""),
    }
}

/// `x` to two significant digits: advice a user types.
pub(super) fn round2(x: f64) -> f64 {
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
                contact,
                below,
                active,
                inactive_below,
                min_ratio,
                counted,
                remedy,
            } => {
                let points = counted_words(*counted, *active);
                if *below == 0 {
                    write!(
                        f,
                        "contact[{contact}]: none of the {active} {points} has a penalty below the stability bound of its element, but"
                    )?;
                } else {
                    write!(
                        f,
                        "contact[{contact}]: {below} of the {active} {points} {} a penalty below the stability bound of {} element",
                        if *below == 1 { "has" } else { "have" },
                        if *below == 1 { "its" } else { "their" }
                    )?;
                }
                if *inactive_below > 0 {
                    write!(
                        f,
                        "{} {inactive_below} other {} below θ·C_T, which θ > 0 needs at every point",
                        if *below == 0 { "" } else { ", and" },
                        if *inactive_below == 1 { "point lies" } else { "points lie" }
                    )?;
                }
                if let Some(r) = min_ratio {
                    write!(f, " (smallest γ/bound {r:.3})")?;
                }
                write!(
                    f,
                    ", so the solution need not be unique: {}",
                    remedy_words(*contact, *remedy)
                )
            }
            Warning::PenaltyFarAboveBound {
                contact,
                over,
                active,
                max_ratio,
                counted,
                remedy,
            } => write!(
                f,
                "contact[{contact}]: {over} of the {active} {} {} a penalty over {OVER_PENALTY} times the θ = 0 stability bound of {} element (largest γ/bound {max_ratio:.3}); above that ratio the peak pressure was measured to grow with the penalty: {}",
                counted_words(*counted, *active),
                if *over == 1 { "has" } else { "have" },
                if *over == 1 { "its" } else { "their" },
                remedy_words(*contact, *remedy)
            ),
            Warning::PenaltyLoose {
                contact,
                active,
                min_ratio,
                counted,
                remedy,
            } => write!(
                f,
                "contact[{contact}]: θ = -1 with a penalty down to {} times the θ = 0 stability bound at its {active} {}, which holds the gap too loosely for an accurate p₀ on a coarse mesh: {}",
                round2(*min_ratio),
                counted_words(*counted, *active),
                remedy_words(*contact, *remedy)
            ),
            Warning::StifferSlave {
                contact,
                slave,
                master,
                contrast,
                sides: Sides::Biased,
            } => write!(
                f,
                "contact[{contact}]: the slave {slave:?} is {contrast:.3} times stiffer than the master {master:?}, and the penalty scales with the slave's modulus, so it over-penalises the softer body: make {master:?} the slave and {slave:?} the master"
            ),
            Warning::StifferSlave {
                contact,
                slave,
                master,
                contrast,
                sides: Sides::Unbiased,
            } => write!(
                f,
                "contact[{contact}]: the unbiased form makes {slave:?}, {contrast:.3} times stiffer than {master:?}, the slave of one half, whose penalty scales with {slave:?}'s modulus, so it over-penalises the softer body: set contact[{contact}].nitsche.sides = \"biased\" with {master:?} the slave and {slave:?} the master"
            ),
            Warning::NearlyIncompressible {
                body,
                formulation,
                poisson,
                indicator,
                elements,
                remedy,
            } => {
                let what = match formulation {
                    Formulation::Displacement => "this displacement formulation",
                    // (never raised for `Mixed`; the words fit the local one)
                    Formulation::Mixed | Formulation::LocalMixed => "its formulation",
                };
                let why = match formulation {
                    Formulation::Displacement => "",
                    Formulation::Mixed | Formulation::LocalMixed => {
                        "a pressure of degree p − 1 per element over-constrains the spline space; "
                    }
                };
                let refine = format!("refine it to at least {elements} elements in each direction");
                let advice = match (remedy, formulation) {
                    (LockingRemedy::MixedOrRefine, Formulation::Displacement) => format!(
                        "set formulation = \"mixed\" on {body:?} (its continuous pressure does not lock), or {refine}"
                    ),
                    (LockingRemedy::MixedOrRefine, _) => {
                        format!("set formulation = \"mixed\" on {body:?}, or {refine}")
                    }
                    (LockingRemedy::LocalMixedOrRefine, _) => format!(
                        "set formulation = \"local_mixed\" on {body:?} (on this C⁰ mesh its pressure per element does not lock), or {refine}"
                    ),
                    (LockingRemedy::Refine, _) => format!(
                        "{refine} (every patch: the mixed formulation takes one-patch bodies only)"
                    ),
                };
                write!(
                    f,
                    "body {body:?}: ν = {poisson} in plane strain locks {what} on its mesh ({why}λ/μ over the cube of its elements per direction is {indicator:.2e}, above {LOCKING:e}), so the answer is unreliable: {advice}"
                )
            }
            Warning::ZoneAtSideEnd {
                contact,
                slave,
                extent,
                end,
                at,
                singular,
            } => write!(
                f,
                "contact[{contact}]: the contact zone reaches the {} of {} at ({:.6e}, {:.6e}){} while the master goes on, so the zone is cut off there: {}",
                match end {
                    SideEnd::Start => "start",
                    SideEnd::End => "end",
                },
                match extent {
                    SlaveExtent::Side(side) => format!("the slave side {side} of {slave:?}"),
                    SlaveExtent::Boundary => format!("the slave boundary on {slave:?}"),
                },
                at[0],
                at[1],
                if *singular {
                    ", where the map is singular (det J = 0) and the pressure is not a contact pressure"
                } else {
                    ""
                },
                // a side that ends at a collapsed corner cannot be extended
                // on its own patch: only a body of several patches has a
                // boundary that goes on past it
                match (singular, extent) {
                    (true, _) => "a side cannot be extended past a singular corner of its patch, so make the body of patches without one and give the contact a `slave_boundary` that goes on past the zone (a half disk: `half_disk_4` with `slave_boundary = \"arc_lower\"`, as data/scenes/hertz_multipatch.toml; a full disk: `disk_5` with `layout = \"diagonal\"` and `slave_boundary = \"arc_lower\"`, as data/scenes/disk_full.toml)",
                    (false, SlaveExtent::Side(_)) => "extend the slave side beyond the contact zone",
                    (false, SlaveExtent::Boundary) => "give the contact a `slave_boundary` of more of the body's patches, one that goes on past the zone",
                }
            ),
            Warning::ClosedFacingAway {
                contact,
                slave,
                away,
                active,
            } => write!(
                f,
                "contact[{contact}]: {away} of the {active} active points lie where the slave {slave:?} faces away from its master or meets it edge-on (more than 60° off its normal), so their gaps are measured through the body or along its surface and the answer there is no contact of the two surfaces: give contact[{contact}] the slave side (or boundary) of {slave:?} that faces the master, or, for a rigid master, the direction that puts the obstacle on the body's side (it lies on the right of `from` → `to`)"
            ),
            Warning::UnresolvedContact {
                contact,
                active,
                elements,
            } => write!(
                f,
                "contact[{contact}]: the contact zone rests on {active} quadrature point(s) in {elements} slave element(s): the mesh does not resolve it, and its peak pressure and width are not meaningful (refine the slave side until the zone spans several elements)"
            ),
            Warning::SeveralZones { contact, zones } => {
                write!(
                    f,
                    "contact[{contact}]: {} separate contact zones carry the force:",
                    zones.len()
                )?;
                for (k, z) in zones.iter().enumerate() {
                    write!(
                        f,
                        "{} {:.1} % with peak pressure {:.6e} at ({:.6e}, {:.6e}){}",
                        if k == 0 { "" } else { ";" },
                        100.0 * z.share,
                        z.p0,
                        z.at[0],
                        z.at[1],
                        if z.main { " (main)" } else { "" }
                    )?;
                }
                write!(
                    f,
                    "; p0 and half_width in summary.toml describe the main zone only (p_max is the largest pressure of all): read every zone in pressure_profile.csv, or model each zone as a contact of its own (a [[contact]] per part of the slave boundary)"
                )
            }
            Warning::CoarseZone {
                contact,
                across,
                needed,
                target,
                side_elements,
                advised,
            } => write!(
                f,
                "contact[{contact}]: the main contact zone spans {across:.2} slave elements (fewer than {needed} for its degree), so its peak pressure and half-width may be several percent off (Hertz: up to 15 % at this resolution): refine the slave side to at least {target} elements across the zone (about {advised} elements on the slave boundary, which has {side_elements})"
            ),
        }
    }
}
