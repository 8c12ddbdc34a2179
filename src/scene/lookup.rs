//! Bodies, boundaries and contact pairs by name: the lookups validation and
//! building share, and the edits a program makes to a scene before it
//! builds it.

use super::{BodySpec, NitscheSpec, RefineSpec, Scene};
use crate::error::{Error, Result};
use crate::nurbs::Side;
use std::collections::HashMap;

impl Scene {
    /// The body named `name`, to change it before building.
    pub fn body_mut(&mut self, name: &str) -> Result<&mut BodySpec> {
        let known: Vec<String> = self.bodies.iter().map(|b| b.name.clone()).collect();
        self.bodies
            .iter_mut()
            .find(|b| b.name == name)
            .ok_or_else(|| {
                Error::invalid(
                    "body",
                    name,
                    format!("no such body (bodies: {})", known.join(", ")),
                )
            })
    }

    /// The `nitsche` table of every contact pair, to change it before
    /// building (validated, as the whole scene is, when it is built).
    pub fn nitsche_mut(&mut self) -> impl Iterator<Item = &mut NitscheSpec> {
        self.contacts.iter_mut().map(|c| &mut c.nitsche)
    }

    /// The scene with body `name` discretised by `refine`.
    pub fn refined(mut self, name: &str, refine: RefineSpec) -> Result<Self> {
        self.body_mut(name)?.refine = Some(refine);
        Ok(self)
    }

    /// The scene with `set` applied to the Nitsche parameters of every pair.
    pub fn with_nitsche(mut self, set: impl FnMut(&mut NitscheSpec)) -> Self {
        self.nitsche_mut().for_each(set);
        self
    }

    /// Index of each body by name.
    pub(super) fn body_index(&self) -> HashMap<&str, usize> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(i, b)| (b.name.as_str(), i))
            .collect()
    }

    pub(super) fn resolve(
        &self,
        names: &HashMap<&str, usize>,
        field: String,
        name: &str,
    ) -> Result<usize> {
        names.get(name).copied().ok_or_else(|| {
            let known: Vec<&str> = self.bodies.iter().map(|b| b.name.as_str()).collect();
            Error::invalid(
                field,
                format!("{name:?}"),
                format!("no body of that name (bodies: {})", known.join(", ")),
            )
        })
    }

    /// Refuses a patch side on body `b` when it has several patches.
    pub(super) fn one_patch(&self, b: usize, field: &str, side: &str) -> Result<()> {
        match self.bodies[b].geometry.multipatch() {
            None => Ok(()),
            Some(mp) => {
                let names = mp?.boundary_names().join(", ");
                Err(Error::invalid(
                    field,
                    side,
                    format!(
                        "body {:?} has several patches: name one of its boundaries ({names}) \
                         with `boundary` / `slave_boundary`",
                        self.bodies[b].name
                    ),
                ))
            }
        }
    }

    /// Refuses a surface load on a patch side of body `b` when it has
    /// several patches: a load names one patch side, and a boundary of
    /// several patches is not a load's key, so the advice is what does
    /// load such a body.
    pub(super) fn one_patch_load(&self, b: usize, field: &str, side: &str) -> Result<()> {
        match self.bodies[b].geometry.multipatch() {
            None => Ok(()),
            Some(_) => Err(Error::invalid(
                field,
                side,
                format!(
                    "body {:?} has several patches, and a traction or pressure load takes a \
                     side of a one-patch body only: load it by a `body_force`, or through a \
                     contact with a one-patch body that carries the load",
                    self.bodies[b].name
                ),
            )),
        }
    }

    /// The pieces (patch of the body, side) of boundary `name` of body `b`.
    pub(super) fn boundary_of(
        &self,
        b: usize,
        field: &str,
        name: &str,
    ) -> Result<Vec<(usize, Side)>> {
        let body = &self.bodies[b];
        let Some(mp) = body.geometry.multipatch() else {
            return Err(Error::invalid(
                field,
                format!("{name:?}"),
                format!(
                    "body {:?} is one patch: name a side with `side` / `slave_side`",
                    body.name
                ),
            ));
        };
        let mp = mp?;
        mp.boundary(name).map(<[_]>::to_vec).ok_or_else(|| {
            Error::invalid(
                field,
                format!("{name:?}"),
                format!(
                    "body {:?} has the boundaries {}",
                    body.name,
                    mp.boundary_names().join(", ")
                ),
            )
        })
    }
}
