//! Contact pairs and their quadrature points: everything about a point of
//! Γc that does not depend on the displacement (small deformation).

use super::contacts::Contacts;
use super::params::{Integration, Modulus, Nitsche, Penalty, Sides};
use super::penalty::{empirical_penalty, PenaltyInputs};
pub use super::point::{ContactPoint, Role};
use super::projection::{along_normal, closest_point, Projection};
use super::trace::set_trace_constant;
use crate::assembly::ElementStress;
use crate::dofs::{Body, DofMap};
use crate::error::{ContactPart, Error, GeometryError, Result};
use crate::material::Formulation;
use crate::nurbs::{NurbsCurve, Side};
use crate::pressure::SplinePressure;
use crate::quadrature;
use std::sync::Arc;

/// What the slave side is pressed against.
#[derive(Clone, Debug)]
pub enum Master {
    /// A rigid obstacle bounded by `curve`. The obstacle lies on the right
    /// of the curve's direction, so its outward normal is the tangent turned
    /// by +90° (a segment from left to right is a floor).
    Rigid(NurbsCurve),
    /// A side of another (elastic) body.
    Body { body: usize, side: Side },
}

/// A slave side, a master, and the Nitsche parameters of Eq. (9)–(11).
#[derive(Clone, Debug)]
pub struct ContactPair {
    pub slave: usize,
    pub slave_side: Side,
    pub master: Master,
    pub nitsche: Nitsche,
}

impl ContactPair {
    /// A pair with the default [`Nitsche`] parameters (the paper's θ and
    /// penalty, with segment integration, which is the library's).
    pub fn new(slave: usize, slave_side: Side, master: Master) -> Self {
        Self {
            slave,
            slave_side,
            master,
            nitsche: Nitsche::default(),
        }
    }
}

/// The master side as a curve with everything needed to evaluate it.
enum MasterGeometry<'a> {
    Rigid(&'a NurbsCurve),
    Body {
        body: usize,
        side: Side,
        curve: NurbsCurve,
        bodies: &'a [Body],
    },
}

impl MasterGeometry<'_> {
    fn curve(&self) -> &NurbsCurve {
        match self {
            MasterGeometry::Rigid(c) => c,
            MasterGeometry::Body { curve, .. } => curve,
        }
    }
}

fn validate(pair: &ContactPair, ip: usize, bodies: &[Body]) -> Result<()> {
    let f = |k: &str| format!("contact[{ip}].{k}");
    if pair.slave >= bodies.len() {
        return Err(Error::invalid(
            f("slave"),
            pair.slave,
            format!("there are {} bodies", bodies.len()),
        ));
    }
    if let Master::Body { body, .. } = pair.master {
        if body >= bodies.len() {
            return Err(Error::invalid(
                f("master"),
                body,
                format!("there are {} bodies", bodies.len()),
            ));
        }
        if body == pair.slave {
            return Err(Error::invalid(
                f("master"),
                body,
                "self-contact is not supported",
            ));
        }
    }
    Ok(())
}

/// Builds every contact quadrature point of every pair, after checking
/// the pairs' body indices (the penalty and the Gauss points are valid by
/// their types).
///
/// Points whose projection falls beyond the end of the master are left
/// out: no master surface faces them. For the unbiased form, each body of
/// a pair is the slave once, with half the quadrature weight.
pub fn contact_points(
    bodies: &[Body],
    map: &DofMap,
    pairs: &[ContactPair],
) -> Result<Vec<ContactPoint>> {
    for (ip, pair) in pairs.iter().enumerate() {
        validate(pair, ip, bodies)?;
    }
    checked_contact_points(bodies, map, pairs, &Contacts::each_pair(pairs.len()))
}

/// A pair's index among the pairs, which its points record, and that of
/// the contact it is a piece of, which messages name.
#[derive(Clone, Copy, Debug)]
struct PairId {
    pair: usize,
    contact: usize,
}

/// [`contact_points`] of pairs already checked: built by a validated scene,
/// or taken from a [`crate::problem::Problem`], whose construction checked
/// them. A second check would only repeat the first. Messages name the
/// contacts of `contacts`, and a contact whose slave faces away from its
/// master at every point, closed at one at least, is refused.
pub(crate) fn checked_contact_points(
    bodies: &[Body],
    map: &DofMap,
    pairs: &[ContactPair],
    contacts: &Contacts,
) -> Result<Vec<ContactPoint>> {
    let mut out = Vec::new();
    for (ip, pair) in pairs.iter().enumerate() {
        let id = PairId {
            pair: ip,
            contact: contacts.of(ip),
        };
        match (&pair.master, pair.nitsche.sides) {
            (Master::Body { body, side }, Sides::Unbiased) => {
                one_side(bodies, map, id, pair, Role::Slave, 0.5, &mut out)?;
                let mirrored = ContactPair {
                    slave: *body,
                    slave_side: *side,
                    master: Master::Body {
                        body: pair.slave,
                        side: pair.slave_side,
                    },
                    nitsche: pair.nitsche,
                };
                one_side(bodies, map, id, &mirrored, Role::Master, 0.5, &mut out)?;
            }
            _ => one_side(bodies, map, id, pair, Role::Slave, 1.0, &mut out)?,
        }
    }
    for (c, pieces) in contacts.iter() {
        let slave_points = out
            .iter()
            .filter(|cp| pieces.contains(&cp.pair) && cp.role == Role::Slave);
        // Facing away but open everywhere, the contact can never close (a
        // floor beyond the far side of the body): inert, not wrong. Closed
        // where the slave faces away, the master lies behind the slave's
        // surface, inside the body, and the gap is measured through it: a
        // ceiling drawn under a disk whose boundary also climbs its sides
        // faces the ceiling at the sides only, so the closed points are
        // weighed, not counted as all or none. Normals at right angles to
        // n¹ (a block's sides below a floor it starts into) weigh on
        // neither side. A contact that closes later where it faces away is
        // warned at the solution (`Warning::ClosedFacingAway`).
        let (mut any, mut away, mut closed) = (false, true, false);
        let (mut closed_away, mut closed_facing) = (0.0, 0.0);
        for cp in slave_points {
            any = true;
            away &= cp.facing <= 0.0;
            if cp.g0 <= 0.0 {
                closed = true;
                if cp.faces_away() {
                    closed_away += cp.weight;
                } else if cp.faces_master() {
                    closed_facing += cp.weight;
                }
            }
        }
        if any && closed && (away || closed_away > closed_facing) {
            return Err(facing_away(c, &pairs[pieces.start], bodies));
        }
    }
    Ok(out)
}

/// The error of contact `c`, first piece `pair`, whose slave faces away
/// from the master where it starts closed: the gap is measured through the
/// slave body, so no contact of the two surfaces is modelled (a floor drawn
/// from right to left is a ceiling over the body).
fn facing_away(c: usize, pair: &ContactPair, bodies: &[Body]) -> Error {
    let slave = &bodies[pair.slave].name;
    let (field, value, advice) = match &pair.master {
        Master::Rigid(curve) => (
            format!("contact[{c}].master"),
            match (curve.points.first(), curve.points.last()) {
                (Some(a), Some(b)) => format!("the rigid curve from {a:?} to {b:?}"),
                _ => "the rigid curve".to_string(),
            },
            "the obstacle lies on the right of the curve's direction (a rigid_segment from \
             left to right is a floor): swap `from` and `to`, or name the slave side that \
             faces the obstacle",
        ),
        Master::Body { body, side } => (
            format!("contact[{c}]"),
            format!(
                "body {slave:?} against side {} of body {:?}",
                side.name(),
                bodies[*body].name
            ),
            "name the slave side (or boundary) and the master side that face each other",
        ),
    };
    Error::invalid(
        field,
        value,
        format!(
            "where body {slave:?} starts in contact, its outward normal points away from the \
             master, so the gap would be measured through the slave body: {advice}"
        ),
    )
}

/// The points of `pair` on its slave side, weights scaled by `scale`.
fn one_side(
    bodies: &[Body],
    map: &DofMap,
    id: PairId,
    pair: &ContactPair,
    role: Role,
    scale: f64,
    points: &mut Vec<ContactPoint>,
) -> Result<()> {
    let slave = &bodies[pair.slave];
    let master = match &pair.master {
        Master::Rigid(c) => MasterGeometry::Rigid(c),
        Master::Body { body, side } => MasterGeometry::Body {
            body: *body,
            side: *side,
            curve: bodies[*body].space.patch.side_curve(*side),
            bodies,
        },
    };
    let (young, degree) = match &master {
        MasterGeometry::Rigid(_) => (slave.material.young, max_degree(slave)),
        MasterGeometry::Body { body, .. } => {
            let m = &bodies[*body];
            let young = match pair.nitsche.modulus {
                Modulus::Slave => slave.material.young,
                Modulus::Max => slave.material.young.max(m.material.young),
            };
            (young, max_degree(slave).max(max_degree(m)))
        }
    };
    let n_gauss = pair.nitsche.points(degree);
    // the slave's pressure space, once per side (mixed formulation)
    let pressure = match slave.formulation {
        Formulation::Mixed => Some(Arc::new(SplinePressure::new(slave)?)),
        _ => None,
    };
    let slave_curve = slave.space.patch.side_curve(pair.slave_side);
    let cuts = match pair.nitsche.integration {
        Integration::Gauss => Vec::new(),
        Integration::Segment => projected_master_knots(master.curve(), &slave_curve)
            .map_err(|e| within(e, id, slave_side(pair, bodies)))?,
    };
    for be in slave.space.boundary(pair.slave_side) {
        let first = points.len();
        let mut breaks = vec![be.range[0]];
        let eps = 1e-10 * (be.range[1] - be.range[0]);
        breaks.extend(
            cuts.iter()
                .copied()
                .filter(|&t| t > be.range[0] + eps && t < be.range[1] - eps),
        );
        breaks.push(be.range[1]);
        for seg in breaks.windows(2) {
            for (t, w) in quadrature::on_interval(n_gauss, seg[0], seg[1]) {
                let point = Sample {
                    be: &be,
                    t,
                    w: scale * w,
                    share: scale,
                };
                if let Some(cp) = make_point(
                    id,
                    pair,
                    role,
                    bodies,
                    map,
                    &master,
                    point,
                    young,
                    degree,
                    pressure.as_ref(),
                )? {
                    points.push(cp);
                }
            }
        }
        set_trace_constant(
            slave,
            &be,
            &pair.nitsche,
            pressure.as_deref(),
            &mut points[first..],
        )
        .map_err(|e| match e {
            // the scene's key path of the contact
            Error::InvalidInput {
                field,
                value,
                reason,
            } if field.starts_with("nitsche.") => Error::invalid(
                format!("contact[{}].{field}", id.contact),
                format!("{value:?}"),
                reason,
            ),
            other => other,
        })?;
    }
    Ok(())
}

/// Where on a slave boundary element a point is placed, its weight and the
/// share of the weight its form carries ([`ContactPoint::share`]).
struct Sample<'a> {
    be: &'a crate::space::BoundaryElement,
    t: f64,
    w: f64,
    share: f64,
}

/// The slave side of a pair, for errors.
fn slave_side(pair: &ContactPair, bodies: &[Body]) -> ContactPart {
    ContactPart::SlaveSide {
        side: pair.slave_side.name(),
        body: bodies[pair.slave].name.clone(),
    }
}

/// A geometry error of the contact of pair `id`, told as happening on
/// `part`.
fn within(e: Error, id: PairId, part: ContactPart) -> Error {
    e.map_geometry(|cause| GeometryError::Contact {
        contact: id.contact,
        part,
        cause: Box::new(cause),
    })
}

fn max_degree(b: &Body) -> usize {
    let d = b.space.patch.degree();
    d[0].max(d[1])
}

/// Slave-side parameters of the master's knots (segment integration).
fn projected_master_knots(master: &NurbsCurve, slave: &NurbsCurve) -> Result<Vec<f64>> {
    let mut out = Vec::new();
    for b in master.knots.breaks() {
        let pr = closest_point(slave, master.point(b))?;
        if pr.orthogonal {
            out.push(pr.t);
        }
    }
    out.sort_by(f64::total_cmp);
    Ok(out)
}

/// The contact point of `pair` at a sample of its slave side, if the
/// master faces it, with whether the slave's outward normal points towards
/// the master there.
#[allow(clippy::too_many_arguments)]
fn make_point(
    id: PairId,
    pair: &ContactPair,
    role: Role,
    bodies: &[Body],
    map: &DofMap,
    master: &MasterGeometry,
    Sample { be, t, w, share }: Sample,
    young: f64,
    degree: usize,
    pressure: Option<&Arc<SplinePressure>>,
) -> Result<Option<ContactPoint>> {
    let slave = &bodies[pair.slave];
    let space = &slave.space;
    let (shape, own_normal, len) = space
        .side_shape(be, t)
        .map_err(|e| within(e, id, slave_side(pair, bodies)))?;
    let x = shape.x;
    // The mirrored half of the unbiased form measures the gap of the other
    // half: along its own normal, to the point of the other body on that
    // line (see `along_normal`).
    let mirrored = role == Role::Master;
    let found = if mirrored {
        along_normal(master.curve(), x, own_normal)
    } else {
        closest_point(master.curve(), x)
    };
    let pr: Projection = found.map_err(|e| {
        let part = match master {
            MasterGeometry::Rigid(_) => ContactPart::RigidMaster,
            MasterGeometry::Body { body, side, .. } => ContactPart::MasterSide {
                side: side.name(),
                body: bodies[*body].name.clone(),
            },
        };
        within(e, id, part)
    })?;
    if !pr.orthogonal {
        return Ok(None);
    }
    // Master outward normal n², then n¹ = −n².
    let (n2, h_master, master_part) = match master {
        MasterGeometry::Rigid(_) => ([-pr.tangent[1], pr.tangent[0]], None, None),
        MasterGeometry::Body {
            body, side, bodies, ..
        } => {
            let mspace = &bodies[*body].space;
            let mb = mspace.boundary(*side);
            let k = mb
                .iter()
                .position(|e| pr.t >= e.range[0] && pr.t <= e.range[1])
                .unwrap_or(mb.len() - 1);
            let mbe = &mb[k];
            let el = &mspace.elements[mbe.element];
            let q = mspace.patch.side_point(*side, pr.t);
            let basis = mspace.patch.basis_in_spans(el.spans, q[0], q[1]);
            let (n, _) = mspace.patch.side_frame(*side, &basis);
            (n, Some(mbe.length), Some((*body, el.cps.clone(), basis.r)))
        }
    };
    let normal = if mirrored {
        own_normal
    } else {
        [-n2[0], -n2[1]]
    };
    let g0 = (pr.point[0] - x[0]) * normal[0] + (pr.point[1] - x[1]) * normal[1];
    let gamma = match pair.nitsche.penalty {
        Penalty::Empirical { factor } => empirical_penalty(
            PenaltyInputs {
                young,
                degree,
                h_slave: be.length,
                h_master,
            },
            factor.get(),
        ),
        // the bound is the whole slave element's: set with the trace
        // constant, by `set_trace_constant`
        Penalty::Sharp { .. } => 0.0,
    };

    // σ_n = mᵀ σ(u) with m = (n_x², n_y², 2 n_x n_y) in Voigt notation and
    // σ the stress of the slave's formulation; for the mixed one θ̄ reaches
    // the control points of the neighbouring elements under the element's
    // pressure functions, which follow the element's own in `dofs`
    let m = [
        normal[0] * normal[0],
        normal[1] * normal[1],
        2.0 * normal[0] * normal[1],
    ];
    let el = &space.elements[be.element];
    let (mut dofs, mut sn) = match slave.formulation {
        Formulation::Displacement => {
            let dofs = map.element_dofs(pair.slave, &el.cps);
            let mut sn = Vec::with_capacity(dofs.len());
            let d = slave.material.d_matrix();
            let q: Vec<f64> = (0..3)
                .map(|j| (0..3).map(|i| m[i] * d[i][j]).sum())
                .collect();
            for g in &shape.grad {
                sn.push(q[0] * g[0] + q[2] * g[1]);
                sn.push(q[1] * g[1] + q[2] * g[0]);
            }
            (dofs, sn)
        }
        Formulation::Mixed | Formulation::LocalMixed => {
            let q = space.patch.side_point(be.side, t);
            let stress = ElementStress::with_pressure(slave, be.element, pressure)?;
            let rows = stress.rows(&shape, q[0], q[1]);
            let dofs = map.element_dofs(pair.slave, stress.cps());
            let sn = (0..dofs.len())
                .map(|k| m[0] * rows[0][k] + m[1] * rows[1][k] + m[2] * rows[2][k])
                .collect();
            (dofs, sn)
        }
    };
    let mut jn = Vec::with_capacity(dofs.len());
    for r in &shape.r {
        jn.push(r * normal[0]);
        jn.push(r * normal[1]);
    }
    jn.resize(dofs.len(), 0.0);
    if let Some((mbody, cps, r)) = master_part {
        for (b, &cp) in cps.iter().enumerate() {
            if r[b] == 0.0 {
                continue;
            }
            for c in 0..2 {
                dofs.push(map.global(mbody, cp, c));
                sn.push(0.0);
                jn.push(-r[b] * normal[c]);
            }
        }
    }
    let regular = regular_map(&space.patch, pair.slave_side, be.range);
    Ok(Some(ContactPoint {
        pair: id.pair,
        role,
        x,
        t,
        normal,
        g0,
        gamma,
        trace_constant: 0.0, // set per slave element by `set_trace_constant`
        theta: pair.nitsche.theta.value(),
        weight: w * len,
        share,
        dofs,
        sn,
        jn,
        regular,
        facing: own_normal[0] * normal[0] + own_normal[1] * normal[1],
    }))
}

/// The fraction of det J at the middle of a boundary element below which
/// det J at one of its ends counts as vanishing: the element touches a
/// point where the map is singular. The nine-point disk collapses a corner
/// of its contact side that way (det J = 0 there); under eight times the
/// load, the 32×32 disk's profile samples in that element show brackets up
/// to hundreds of times p₀, which are the 1/det J of the stress, not
/// contact, and its trace constant is set by the same 1/det J.
pub const SINGULAR_MAP: f64 = 1e-2;

/// Whether the map of `patch` is regular on the boundary element of `side`
/// spanning `range`: |det J| at both its ends is at least [`SINGULAR_MAP`]
/// times its value at the middle. Within a regular element det J varies
/// smoothly, far less than that; it vanishes only at a degenerate point.
pub fn regular_map(patch: &crate::nurbs::NurbsPatch, side: Side, range: [f64; 2]) -> bool {
    let det = |t: f64| {
        let q = patch.side_point(side, t);
        let j = patch.jacobian(q[0], q[1]);
        (j[0][0] * j[1][1] - j[0][1] * j[1][0]).abs()
    };
    let middle = det(0.5 * (range[0] + range[1]));
    det(range[0]).min(det(range[1])) >= SINGULAR_MAP * middle
}
