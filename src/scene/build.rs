//! From a validated scene to the library's bodies, DOF map, loads and
//! contact pairs, and from those to a [`Problem`].

use super::patches::discretise_error;
use super::rules::show;
use super::validate::Valid;
use super::{MasterSpec, Scene, SlaveAt, SupportAt};
use crate::assembly::Load;
use crate::contact::pair::checked_contact_points;
use crate::contact::{ContactPair, Contacts, Master};
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::geometry;
use crate::nurbs::{NurbsPatch, Side};
use crate::problem::Problem;
use crate::space::Space;
use crate::timing::{Phase, Stopwatch};
use crate::wellposed;

/// Whether [`Scene::discretise`] evaluates the map of every body at every
/// quadrature point. The assembly evaluates it there anyway, so a run
/// checks only when the assembly fails, for the message; a check, which
/// assembles nothing, checks up front.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(super) enum MapCheck {
    EveryPoint,
    OnFailure,
}

/// The discretised scene before anything of the size of the system is
/// assembled: bodies, DOF numbering, loads and contact pairs.
pub(super) struct Discrete {
    pub(super) bodies: Vec<Body>,
    pub(super) map: DofMap,
    pub(super) loads: Vec<Load>,
    pub(super) pairs: Vec<ContactPair>,
    /// The `[[contact]]` entries the pairs make up, in order.
    pub(super) contacts: Contacts,
}

/// True if every control point of `side` coincides with the first: the
/// side is collapsed to a point.
fn degenerate_side(patch: &NurbsPatch, side: Side) -> bool {
    let idx = patch.side_indices(side);
    let p0 = patch.points[idx[0]];
    let scale = patch
        .points
        .iter()
        .map(|p| (p[0] - p0[0]).hypot(p[1] - p0[1]))
        .fold(0.0, f64::max);
    idx.iter().all(|&i| {
        let p = patch.points[i];
        (p[0] - p0[0]).hypot(p[1] - p0[1]) <= 1e-12 * scale
    })
}

/// The control point of the patches `patches` nearest `x`, as (patch,
/// control point), accepted only where it lies on the body: at a patch
/// corner, where the basis interpolates (elsewhere a control point is off
/// the body and fixing it is no point support). Support `i` of body `name`.
fn corner_at(
    bodies: &[Body],
    patches: std::ops::Range<usize>,
    x: [f64; 2],
    i: usize,
    name: &str,
) -> Result<(usize, usize)> {
    let mut best = (f64::INFINITY, 0, 0);
    for p in patches {
        for (a, y) in bodies[p].space.patch.points.iter().enumerate() {
            let d = (y[0] - x[0]).hypot(y[1] - x[1]);
            if d < best.0 {
                best = (d, p, a);
            }
        }
    }
    let (d, p, a) = best;
    let patch = &bodies[p].space.patch;
    let [n0, n1] = patch.n();
    let (ia, ja) = (a % n0, a / n0);
    let corner = (ia == 0 || ia == n0 - 1) && (ja == 0 || ja == n1 - 1);
    let size = crate::interface::extent(patch);
    if !corner || d > 1e-9 * size {
        return Err(Error::invalid(
            format!("support[{i}].point"),
            format!("{x:?}"),
            format!(
                "the nearest control point of body {name:?}, {:?}, is {} away{}; a point \
                 support needs a patch corner, where the control point lies on the body",
                patch.points[a],
                show(d),
                if corner {
                    ""
                } else {
                    " and not a patch corner"
                }
            ),
        ));
    }
    Ok((p, a))
}

impl Valid<'_> {
    /// Refines every body (with [`MapCheck::EveryPoint`], checking its map
    /// at every quadrature point and naming the body where it folds),
    /// numbers the DOFs and resolves loads and contact pairs; assembles
    /// nothing.
    pub(super) fn discretise(&self, check: MapCheck) -> Result<Discrete> {
        let names = self.body_index();
        // every body is one or more patches: `first[i]` is the patch index
        // (into `bodies`) of scene body i's first
        let mut first = Vec::with_capacity(self.bodies.len());
        let mut bodies = Vec::with_capacity(self.bodies.len());
        for (i, b) in self.bodies.iter().enumerate() {
            first.push(bodies.len());
            for patch in self.body_patches(i)? {
                let fault = |e| discretise_error(e, i, &b.name, b.geometry.kind());
                let space = Space::new(patch, b.quadrature).map_err(fault)?;
                if check == MapCheck::EveryPoint {
                    for e in &space.elements {
                        space.quadrature(e).map_err(fault)?;
                    }
                }
                bodies.push(Body {
                    name: b.name.clone(),
                    space,
                    material: b.material,
                    formulation: b.formulation,
                });
            }
        }
        first.push(bodies.len());
        let idx = |name: &str| first[names[name]];
        let patches_of = |name: &str| first[names[name]]..first[names[name] + 1];
        let mut dofs = DofMap::builder(&bodies);
        for b in &self.bodies {
            let patches: Vec<usize> = patches_of(&b.name).collect();
            if patches.len() > 1 {
                dofs.join(&b.name, &patches)?;
            }
        }
        for (i, s) in self.supports.iter().enumerate() {
            let c = s.component.index();
            match &s.at {
                SupportAt::Side(side) => {
                    dofs.fix_side(idx(&s.body), *side, c, s.value)?;
                }
                SupportAt::Boundary(name) => {
                    let f = format!("support[{i}].boundary");
                    for (p, side) in self.boundary_of(names[s.body.as_str()], &f, name)? {
                        dofs.fix_side(idx(&s.body) + p, side, c, s.value)?;
                    }
                }
                SupportAt::Point(x) => {
                    let (p, cp) = corner_at(&bodies, patches_of(&s.body), *x, i, &s.body)?;
                    dofs.fix(p, cp, c, s.value)?;
                }
            }
        }
        let map = dofs.build();
        let mut loads = Vec::with_capacity(self.loads.len());
        for (i, l) in self.loads.iter().enumerate() {
            if let Load::Pressure { body, side, .. } = l {
                if degenerate_side(&bodies[idx(body)].space.patch, *side) {
                    return Err(Error::invalid(
                        format!("load[{i}].pressure.side"),
                        side.name(),
                        format!("this side of body {body:?} is collapsed to a point"),
                    ));
                }
            }
            match l {
                // a body force acts on every patch of its body
                Load::BodyForce { body, force } => {
                    for p in patches_of(body) {
                        loads.push(Load::BodyForce {
                            body: p,
                            force: *force,
                        });
                    }
                }
                _ => loads.push(l.map_body(|b| idx(b))),
            }
        }
        let mut pairs = Vec::with_capacity(self.contacts.len());
        let mut sizes = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let pieces = match &c.slave_at {
                &SlaveAt::Side(side) => {
                    let slave = idx(&c.slave);
                    if degenerate_side(&bodies[slave].space.patch, side) {
                        return Err(Error::invalid(
                            format!("contact[{i}].slave_side"),
                            side.name(),
                            format!("this side of body {:?} is collapsed to a point", c.slave),
                        ));
                    }
                    vec![(slave, side)]
                }
                SlaveAt::Boundary(name) => {
                    let f = format!("contact[{i}].slave_boundary");
                    self.boundary_of(names[c.slave.as_str()], &f, name)?
                        .into_iter()
                        .map(|(p, side)| (idx(&c.slave) + p, side))
                        .collect()
                }
            };
            let master = match &c.master {
                MasterSpec::RigidSegment { from, to } => {
                    Master::Rigid(geometry::segment(*from, *to)?)
                }
                MasterSpec::Body { body: name, side } => {
                    let (body, side) = (idx(name), *side);
                    if degenerate_side(&bodies[body].space.patch, side) {
                        return Err(Error::invalid(
                            format!("contact[{i}].master.side"),
                            side.name(),
                            format!("this side of body {name:?} is collapsed to a point"),
                        ));
                    }
                    Master::Body { body, side }
                }
            };
            sizes.push(pieces.len());
            for (slave, slave_side) in pieces {
                pairs.push(ContactPair {
                    slave,
                    slave_side,
                    master: master.clone(),
                    nitsche: self.nitsche[i],
                });
            }
        }
        Ok(Discrete {
            bodies,
            map,
            loads,
            pairs,
            contacts: Contacts::of_sizes(&sizes)?,
        })
    }

    /// Discretises, builds the contact points and checks the rigid modes on
    /// them (before the assembly: the points cost only the boundary), then
    /// assembles the problem on those same points, with the time of each
    /// step charged to `clock`.
    pub(super) fn assemble(&self, clock: &mut Stopwatch) -> Result<Problem> {
        let Discrete {
            bodies,
            map,
            loads,
            pairs,
            contacts,
        } = self.discretise(MapCheck::OnFailure)?;
        clock.lap(Phase::ParseAndBuild);
        let points = checked_contact_points(&bodies, &map, &pairs, &contacts)
            .and_then(|points| {
                wellposed::check_rigid_modes(&bodies, &map, &points)?;
                Ok(points)
            })
            .map_err(|e| self.map_error_or(e))?;
        clock.lap(Phase::ContactSetup);
        let problem = Problem::with_points(bodies, map, &loads, pairs, points)
            .and_then(|p| p.with_contacts(contacts))
            .map_err(|e| self.map_error_or(e))?;
        clock.lap(Phase::Assembly);
        Ok(problem)
    }

    /// A failure after a discretisation without the map check: the map's
    /// error (naming the body where it folds) when there is one, as the
    /// check up front would have reported it, else `e`.
    fn map_error_or(&self, e: Error) -> Error {
        match self.discretise(MapCheck::EveryPoint) {
            Err(map) => map,
            Ok(_) => e,
        }
    }
}

impl Scene {
    /// Validates the scene and assembles its [`Problem`] (no solve),
    /// rejecting rigid motions nothing holds
    /// ([`wellposed::check_rigid_modes`]).
    pub fn build(&self) -> Result<Problem> {
        self.valid()?.assemble(&mut Stopwatch::start())
    }
}
