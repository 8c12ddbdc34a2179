//! The Hertz set-up shared by the chapter programs that solve it ("Hertz
//! contact of a disk on a rigid plane", "IGA against FEM", "Error against
//! run time", "Solvers compared"): the scene file with a chosen mesh, and
//! Hertz's analytic solution for the scene's disk.

use iga_contact::assembly::Load;
use iga_contact::error::{Error, Result};
use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::scene::{GeometrySpec, OutputSpec, RefineSpec, Scene};
use std::f64::consts::PI;

// ANCHOR: setup
/// `data/scenes/hertz.toml` discretised by `refine` (IGA or FEM, elements
/// per direction), with no outputs of its own.
pub fn scene(refine: RefineSpec) -> Result<Scene> {
    let mut s = crate::shipped("hertz.toml")?;
    s.body_mut("disk")?.refine = Some(refine);
    s.output = OutputSpec::default();
    Ok(s)
}

/// IGA of degree `p` on `n` × `n` elements.
pub fn iga(p: usize, n: usize) -> RefineSpec {
    RefineSpec::iga(p, [n, n])
}

/// Hertz's solution for the scene's disk: its radius and material, and the
/// weight P of the whole disk (the half model carries P/2).
pub fn analytic(scene: &Scene) -> Result<Hertz> {
    let disk = &scene.bodies[0];
    let GeometrySpec::HalfDisk { radius, .. } = disk.geometry else {
        return Err(Error::invalid(
            "body[0].geometry",
            disk.geometry.kind(),
            "not a half disk",
        ));
    };
    let weight_density = scene
        .loads
        .iter()
        .find_map(|l| match l {
            Load::BodyForce { force, .. } => Some(force[0].hypot(force[1])),
            _ => None,
        })
        .ok_or_else(|| Error::invalid("load", "none", "the disk is loaded by its weight"))?;
    let disk = Cylinder::Elastic {
        radius,
        material: disk.material,
    };
    Ok(Hertz::new(
        disk,
        Cylinder::RigidPlane,
        weight_density * PI * radius * radius,
    ))
}
// ANCHOR_END: setup
