//! Each warning of a doubtful answer ([`Warning`]) against its case: it fires
//! where the answer is wrong, and following its one remedy makes it go away
//! and brings p₀ within the method's accuracy of its reference.
//!
//! The references: Hertz's p₀ for the disk (with the block's compliance
//! when it rests on a block). The method's accuracy there, at the meshes
//! used: the 16×16 disk on a rigid floor is 0.7 % off Hertz and the 32×32
//! one 1.1 % (the finite disk under its own weight is not exactly Hertz's
//! cylinder), so 2 % is the bound for an answer that is right; the doubtful
//! answers are 8 % to 150 % off.
//!
//! One module per concern: [`slave`] (the stiffer body as slave, biased or
//! unbiased), [`penalty`] (penalties below, far above or loose against
//! their bound, one line per cause), [`locking`] (nearly incompressible
//! bodies), [`zones`] (a zone at the end of its slave side, and where the
//! growths part), [`facing`] (a slave that closes facing away). The
//! references and builders they share are here.

#[path = "../common/mod.rs"]
mod common;

mod facing;
mod locking;
mod penalty;
mod slave;
mod zones;

use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::post::{relative, PressureProfile};
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::warning::PenaltyRemedy;
use iga_contact::solver::{solve, Growth, SolverOptions, Warning};
use std::f64::consts::PI;

/// The bound on |p₀ error| of a right answer (see the module comment).
const RIGHT: f64 = 0.02;

/// The warnings of a solve of `scene` and its p₀ error against Hertz.
fn outcome(scene: &Scene) -> (Vec<Warning>, f64) {
    let (p0, warnings) = p0_and_warnings(scene);
    (warnings, relative(p0, hertz_p0(scene)))
}

/// Hertz's p₀ for the disk of `scene` on its floor: rigid, or the block's
/// half space when there is a body "block".
fn hertz_p0(scene: &Scene) -> f64 {
    let disk = scene.bodies.iter().find(|b| b.name == "disk").unwrap();
    let radius = 0.2;
    let floor = match scene.bodies.iter().find(|b| b.name == "block") {
        Some(b) => Cylinder::HalfSpace(b.material),
        None => Cylinder::RigidPlane,
    };
    let load = 1.3e6 * PI * radius * radius;
    let disk = Cylinder::Elastic {
        radius,
        material: disk.material,
    };
    Hertz::new(disk, floor, load).p0
}

fn hertz(elements: usize) -> Scene {
    let mut s = companion::shipped("hertz.toml")
        .unwrap()
        .refined("disk", RefineSpec::iga(2, [elements, elements]))
        .unwrap();
    s.solver = SolverOptions::default();
    s.output = Default::default();
    s
}

fn disk_on_block(stiffness_ratio: f64) -> Scene {
    let mut s = companion::shipped("disk_on_block.toml").unwrap();
    s.body_mut("block").unwrap().material.young *= stiffness_ratio;
    s.output = Default::default();
    s
}

fn only(w: &[Warning]) -> &Warning {
    assert_eq!(w.len(), 1, "one warning expected: {w:?}");
    &w[0]
}

fn remedy(w: &Warning) -> PenaltyRemedy {
    match w {
        Warning::PenaltyBelowBound { remedy, .. }
        | Warning::PenaltyFarAboveBound { remedy, .. }
        | Warning::PenaltyLoose { remedy, .. } => *remedy,
        other => panic!("not a penalty warning: {other}"),
    }
}

/// Applies a penalty remedy to every pair of `scene`.
fn follow(mut scene: Scene, r: PenaltyRemedy) -> Scene {
    for n in scene.nitsche_mut() {
        match r {
            PenaltyRemedy::Factor(f) => n.penalty_factor = f,
            PenaltyRemedy::Sharp(f) => {
                n.penalty = iga_contact::contact::PenaltyKind::Sharp;
                n.penalty_factor = f;
            }
            PenaltyRemedy::SlaveModulus => n.modulus = iga_contact::contact::Modulus::Slave,
        }
    }
    scene
}

/// The scene under 8× load with the growth `growth` on n² (penalty factor 2).
fn heavy(n: usize, growth: Growth) -> Scene {
    let mut s = hertz(n).with_nitsche(|x| x.penalty_factor = 2.0);
    s.solver.growth = growth;
    common::scale_body_force(&mut s, 8.0);
    s
}

/// p₀ and the warnings of a solve of `scene`.
fn p0_and_warnings(scene: &Scene) -> (f64, Vec<Warning>) {
    let problem = scene.build().unwrap();
    let s = solve(&problem, &scene.solver).unwrap();
    let p0 = PressureProfile::dense(&problem, &s.full)
        .unwrap()
        .measures(0)
        .p0;
    (p0, s.warnings)
}
