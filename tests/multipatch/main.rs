//! Bodies of several patches with matching interfaces: the builders'
//! geometry is exact and regular, the joined DOF map reproduces affine
//! fields across the interfaces, non-matching interfaces are tied (and
//! sides meeting over part of their length refused), and
//! the multi-patch Hertz scenes agree with the closed form.
//!
//! One module per concern: [`geometry`] (the builders' patches are exact
//! and regular), [`interfaces`] (the joined DOF map and tied interfaces),
//! [`input`] (multi-patch keys and supports, checked), [`hertz`] (the
//! multi-patch Hertz scenes against the closed form and the one-patch
//! scene), [`zones`] (the zone warnings at patch and side ends). The
//! builders they share are here.

#[path = "../common/mod.rs"]
mod common;

mod geometry;
mod hertz;
mod input;
mod interfaces;
mod zones;

use iga_contact::dofs::Body;
use iga_contact::geometry::MultiPatch;
use iga_contact::material::{Formulation, Material, Plane};
use iga_contact::post::{ContactMeasures, PressureProfile};
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::{solve, Warning};
use iga_contact::space::Space;

const R: f64 = 0.2;
const C: [f64; 2] = [0.0, 0.2];

/// The patches of `mp`, each refined to degree `p` with `elements`.
fn bodies(mp: &MultiPatch, p: usize, elements: [usize; 2]) -> Vec<Body> {
    bodies_q(mp, p, elements, None)
}

/// As [`bodies`], with `quad` Gauss points per direction.
fn bodies_q(mp: &MultiPatch, p: usize, elements: [usize; 2], quad: Option<usize>) -> Vec<Body> {
    let material = Material::new(2.0e7, 0.1, Plane::Strain).unwrap();
    mp.refined(p, elements)
        .unwrap()
        .into_iter()
        .map(|patch| Body {
            name: "disk".into(),
            space: Space::new(patch, quad).unwrap(),
            material,
            formulation: Formulation::Displacement,
        })
        .collect()
}

fn rel(a: f64, b: f64) -> f64 {
    (a - b).abs() / b.abs()
}

/// The shipped scene `file` with its disk refined to p = 2 on `n × n`.
fn refined(file: &str, n: usize) -> Scene {
    companion::shipped(file)
        .unwrap()
        .refined("disk", RefineSpec::iga(2, [n, n]))
        .unwrap()
}

/// A solve of `scene`: the dense profile's measures over its first
/// contact's pieces, and the solution's warnings.
fn measured(scene: &Scene) -> iga_contact::Result<(ContactMeasures, Vec<Warning>)> {
    let problem = scene.build()?;
    let sol = solve(&problem, &scene.solver)?;
    let profile = PressureProfile::dense(&problem, &sol.full)?;
    Ok((
        profile.measures_joined(problem.contacts.pieces(0)),
        sol.warnings,
    ))
}

/// The shipped scene `file`, refined to `n × n`, its body force times
/// `factor`: (p₀, a, zones, warnings) over its first contact's pieces.
fn run(file: &str, n: usize, factor: f64) -> (f64, f64, usize, Vec<Warning>) {
    let mut scene = refined(file, n);
    common::scale_body_force(&mut scene, factor);
    let (m, warnings) = measured(&scene).unwrap_or_else(|e| panic!("{file} {n} ×{factor}: {e}"));
    (m.p0, m.half_width, m.zones, warnings)
}
