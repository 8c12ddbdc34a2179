//! [`Scene::check`]: everything a run checks before it solves, without
//! assembling or solving.

use super::build::MapCheck;
use super::{OutputSpec, Scene};
use crate::contact::pair::checked_contact_points;
use crate::dofs::Body;
use crate::error::{Error, Result};
use crate::report::vtu;
use crate::resources::{human_bytes, human_count, Budget, Estimate};
use crate::solver;
use crate::wellposed;
use std::fmt;

/// What [`Scene::check`] found: the scene is valid, fits the memory
/// budget, and is well posed.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckReport {
    pub bodies: usize,
    /// Free degrees of freedom.
    pub dofs: usize,
    pub contact_points: usize,
    /// The resource estimate the budget was checked against.
    pub estimate: Estimate,
    /// What may make a run's answer doubtful, known before solving
    /// ([`solver::warning::before_solve`]): the choice of slave, locking,
    /// and the penalty where the bodies first touch.
    pub warnings: Vec<solver::Warning>,
}

impl fmt::Display for CheckReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ok ({} bod{}, {} free DOFs, {} contact points; a run needs about {} of memory, \
             {} matrix non-zeros)",
            self.bodies,
            if self.bodies == 1 { "y" } else { "ies" },
            self.dofs,
            self.contact_points,
            human_bytes(self.estimate.peak_bytes()),
            human_count(self.estimate.nonzeros)
        )
    }
}

impl Scene {
    /// Everything [`Scene::run`] checks before it solves — validity, the
    /// resource estimate against `budget`, the geometric map of every
    /// body at every quadrature point, that a requested VTU can be
    /// sampled, the contact points and the rigid modes — without
    /// assembling or solving anything.
    pub fn check(&self, budget: &Budget) -> Result<CheckReport> {
        let valid = self.valid()?;
        let estimate = valid.estimate()?;
        estimate.check(budget, "output.vtu_subdivisions")?;
        let d = valid.discretise(MapCheck::EveryPoint)?;
        vtu_samplable(&self.output, &d.bodies)?;
        let points = checked_contact_points(&d.bodies, &d.map, &d.pairs, &d.contacts)?;
        wellposed::check_rigid_modes(&d.bodies, &d.map, &points)?;
        let warnings = solver::warning::before_solve(&d.bodies, &d.pairs, &d.contacts, &points);
        Ok(CheckReport {
            // the scene's bodies, not their patches
            bodies: self.bodies.len(),
            dofs: d.map.n_free(),
            contact_points: points.len(),
            estimate,
            warnings,
        })
    }
}

/// With `vtu = true`, refuses (as a bad `output.vtu`, exit 2) bodies the VTU
/// sampler cannot evaluate ([`vtu::check_sampling`]): the solution does not
/// change where samples are taken, so this is known before the solve and
/// must not cost one.
pub(super) fn vtu_samplable(output: &OutputSpec, bodies: &[Body]) -> Result<()> {
    if !output.vtu {
        return Ok(());
    }
    vtu::check_sampling(bodies).map_err(|e| {
        Error::invalid(
            "output.vtu",
            true,
            format!("the fields cannot be sampled ({e}); set `vtu = false`"),
        )
    })
}
