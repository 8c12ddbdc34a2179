//! Every rule a scene must satisfy beyond its shape, each failure naming
//! the key path and the value.

use super::patches::multipatch_lagrange;
use super::rules::{finite, finite_point, in_range};
use super::{load_kind, MasterSpec, RefineSpec, Scene, SlaveAt, SupportAt, MAX_VTU_SUBDIVISIONS};
use crate::assembly::Load;
use crate::contact::Nitsche;
use crate::error::{Error, Result};
use crate::material::{Formulation, Plane};
use crate::wellposed;
use std::collections::HashMap;
use std::ops::Deref;

/// A scene that passed [`Scene::validate`], as only [`Scene::valid`] makes
/// one, with what validation read into typed values: what estimating,
/// building and checking work on, so that each public entry point
/// validates once and nothing below it again.
pub(super) struct Valid<'a> {
    scene: &'a Scene,
    /// The Nitsche parameters of each `[[contact]]`, in order.
    pub(super) nitsche: Vec<Nitsche>,
}

impl Deref for Valid<'_> {
    type Target = Scene;

    fn deref(&self) -> &Scene {
        self.scene
    }
}

impl Scene {
    /// Checks every rule a scene must satisfy, naming the key path and value
    /// of the first violation. [`Scene::from_toml_str`] calls it, and so do
    /// [`Scene::build`], [`Scene::estimate`], [`Scene::check`] and
    /// [`Scene::run`], once each: a scene's fields are public, and may have
    /// changed since it was read.
    pub fn validate(&self) -> Result<()> {
        self.valid().map(|_| ())
    }

    /// The scene, validated.
    pub(super) fn valid(&self) -> Result<Valid<'_>> {
        if self.bodies.is_empty() {
            return Err(Error::invalid(
                "body",
                "[]",
                "a scene needs at least one [[body]]",
            ));
        }
        let mut seen: HashMap<&str, usize> = HashMap::new();
        for (i, b) in self.bodies.iter().enumerate() {
            let f = format!("body[{i}]");
            if b.name.trim().is_empty() {
                return Err(Error::invalid(
                    format!("{f}.name"),
                    format!("{:?}", b.name),
                    "must not be empty",
                ));
            }
            if let Some(j) = seen.insert(b.name.as_str(), i) {
                return Err(Error::invalid(
                    format!("{f}.name"),
                    format!("{:?}", b.name),
                    format!("duplicate body name (also body[{j}])"),
                ));
            }
            b.geometry.validate(&format!("{f}.geometry"))?;
            if let Some(r) = &b.refine {
                r.validate(&format!("{f}.refine"), b.geometry.degree())?;
                if let (RefineSpec::Lagrange { degree, .. }, Some(_)) = (r, b.geometry.multipatch())
                {
                    return Err(multipatch_lagrange(i, *degree));
                }
            }
            if b.formulation != Formulation::Displacement && b.geometry.multipatch().is_some() {
                return Err(Error::invalid(
                    format!("{f}.formulation"),
                    format!("{:?}", b.formulation.name()),
                    "the mixed formulations are built for one-patch bodies only",
                ));
            }
            if b.formulation == Formulation::Mixed {
                // `mixed` projects onto the continuous splines of degree
                // p − 1 on the body's own knots: that space is empty at
                // p = 1 and discontinuous on a C⁰ Lagrange mesh, whose
                // interior knots repeat p times
                let refusal = match b.refine {
                    Some(RefineSpec::Lagrange { degree, .. }) => Some(format!(
                        "the continuous pressure space of degree p − 1 needs a k-refined (IGA) \
                         body, not the C⁰ Lagrange mesh Q{degree}: use formulation = \
                         \"local_mixed\" (its pressure is per element) or refine = {{ degree = … }}"
                    )),
                    _ if b.degree() < 2 => Some(
                        "the pressure space of degree p − 1 is empty at p = 1: use \
                         formulation = \"local_mixed\" (Q1 with a constant pressure per element) \
                         or refine to degree 2 or more"
                            .to_string(),
                    ),
                    _ => None,
                };
                if let Some(reason) = refusal {
                    return Err(Error::invalid(
                        format!("{f}.formulation"),
                        format!("{:?}", b.formulation.name()),
                        reason,
                    ));
                }
            }
            b.material.validate(&format!("{f}.material"))?;
            if b.formulation != Formulation::Displacement && b.material.plane != Plane::Strain {
                return Err(Error::invalid(
                    format!("{f}.formulation"),
                    format!("{:?}", b.formulation.name()),
                    "the mixed formulation is for plane strain; plane stress does not lock (σ_zz = 0 frees the thickness), so use formulation = \"displacement\"",
                ));
            }
            if let Some(q) = b.quadrature {
                in_range(format!("{f}.quadrature"), q, 1, 30)?;
                let p = b.degree();
                self.enough_points(
                    format!("{f}.quadrature"),
                    q,
                    wellposed::min_quadrature(p),
                    format!("a body of degree {p} needs per direction (p + 1: the stiffness is exact on affine elements; fewer may leave zero-energy modes)"),
                )?;
            }
        }
        let names = self.body_index();
        for (i, s) in self.supports.iter().enumerate() {
            let f = format!("support[{i}]");
            let b = self.resolve(&names, format!("{f}.body"), &s.body)?;
            finite(format!("{f}.value"), s.value)?;
            match &s.at {
                SupportAt::Side(side) => self.one_patch(b, &format!("{f}.side"), side.name())?,
                SupportAt::Boundary(name) => {
                    self.boundary_of(b, &format!("{f}.boundary"), name)?;
                }
                SupportAt::Point(x) => finite_point(&format!("{f}.point"), *x)?,
            }
        }
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}].{}", load_kind(l));
            let b = self.resolve(&names, format!("{f}.body"), l.body())?;
            if let Load::Traction { side, .. } | Load::Pressure { side, .. } = l {
                self.one_patch_load(b, &format!("{f}.side"), side.name())?;
            }
            match l {
                Load::BodyForce { force, .. } => finite_point(&format!("{f}.force"), *force)?,
                Load::Traction { traction, .. } => {
                    finite_point(&format!("{f}.traction"), *traction)?
                }
                Load::Pressure { pressure, .. } => finite(format!("{f}.pressure"), *pressure)?,
            }
        }
        let mut nitsche = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let f = format!("contact[{i}]");
            let slave = self.resolve(&names, format!("{f}.slave"), &c.slave)?;
            match &c.slave_at {
                SlaveAt::Side(side) => {
                    self.one_patch(slave, &format!("{f}.slave_side"), side.name())?
                }
                SlaveAt::Boundary(name) => {
                    self.boundary_of(slave, &format!("{f}.slave_boundary"), name)?;
                }
            }
            match &c.master {
                MasterSpec::RigidSegment { from, to } => {
                    let g = format!("{f}.master.rigid_segment");
                    finite_point(&format!("{g}.from"), *from)?;
                    finite_point(&format!("{g}.to"), *to)?;
                    let len = (to[0] - from[0]).hypot(to[1] - from[1]);
                    if !(len.is_finite() && len > 0.0) {
                        return Err(Error::invalid(
                            format!("{g}.to"),
                            format!("{to:?}"),
                            "must differ from `from` by a finite distance",
                        ));
                    }
                }
                MasterSpec::Body { body: name, side } => {
                    let master = self.resolve(&names, format!("{f}.master.body"), name)?;
                    if self.bodies[master].geometry.multipatch().is_some() {
                        // The master's side is one patch side (`MasterSpec::Body`);
                        // naming a boundary of several patches there is not built yet,
                        // so the advice is the swap the contact pair does allow.
                        return Err(Error::invalid(
                            format!("{f}.master.body"),
                            format!("{name:?}"),
                            "a master body must be one patch: make the multi-patch body the \
                             slave (`slave_boundary`) and the other the master, or give the \
                             master a one-patch geometry",
                        ));
                    }
                    self.one_patch(master, &format!("{f}.master.side"), side.name())?;
                    if master == slave {
                        return Err(Error::invalid(
                            format!("{f}.master.body"),
                            format!("{name:?}"),
                            "the master must be another body than the slave (no self-contact)",
                        ));
                    }
                }
            }
            nitsche.push(c.nitsche.validate(&format!("{f}.nitsche"))?);
            if let Some(n) = c.nitsche.gauss_points {
                let mut p = self.bodies[slave].degree();
                if let Some(m) = c.master.body().and_then(|m| names.get(m)) {
                    p = p.max(self.bodies[*m].degree());
                }
                self.enough_points(
                    format!("{f}.nitsche.gauss_points"),
                    n,
                    wellposed::min_contact_gauss_points(p),
                    format!("a contact side of degree {p} needs (p + 1: the products of two traces are exact on straight sides)"),
                )?;
            }
        }
        self.refuse_repeated_contacts(&names)?;
        self.validate_scales()?;
        self.solver.validate("solver")?;
        let o = &self.output;
        in_range(
            "output.vtu_subdivisions",
            o.vtu_subdivisions,
            1,
            MAX_VTU_SUBDIVISIONS,
        )?;
        if self.contacts.is_empty() {
            for (k, on) in [
                ("pressure_profile", o.pressure_profile),
                ("figures", o.figures),
            ] {
                if on {
                    return Err(Error::invalid(
                        format!("output.{k}"),
                        true,
                        "needs at least one [[contact]] pair",
                    ));
                }
            }
        }
        Ok(Valid {
            scene: self,
            nitsche,
        })
    }

    /// Refuses fewer quadrature points than `need`, unless the scene allows
    /// under-integration.
    fn enough_points(&self, field: String, n: usize, need: usize, why: String) -> Result<()> {
        if n >= need || self.allow_underintegration {
            return Ok(());
        }
        Err(Error::invalid(
            field,
            n,
            format!(
                "below the {need} Gauss points {why}; set `allow_underintegration = true` at \
                 the top of the scene to run it anyway"
            ),
        ))
    }
}
