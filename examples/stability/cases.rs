//! "Axes and references": every case of the atlas, a change of a shipped
//! scene, axis by axis.

use crate::{setup, Case, Metric};
use iga_contact::assembly::Load;
use iga_contact::contact::{Integration, PenaltyKind, Theta};
use iga_contact::error::Result;
use iga_contact::report::table::Format;
use iga_contact::scene::{GeometrySpec, RefineSpec, Scene};

/// The penalty factors of the penalty axis.
pub fn factors() -> impl Iterator<Item = f64> {
    (-4..=6).map(|k| 10f64.powi(k))
}

pub fn hertz(p: usize, n: usize) -> Result<Scene> {
    setup::scene(setup::iga(p, n))
}

fn taylor() -> Result<Scene> {
    companion::shipped("taylor.toml")
}

/// Every Nitsche parameter group of a scene, set by `f`.
fn with(mut scene: Scene, f: impl Fn(&mut iga_contact::scene::NitscheSpec)) -> Scene {
    scene.nitsche_mut().for_each(f);
    scene
}

/// The scene's loads scaled by `s`.
fn scaled(mut scene: Scene, s: f64) -> Scene {
    for l in &mut scene.loads {
        match l {
            Load::BodyForce { force, .. }
            | Load::Traction {
                traction: force, ..
            } => force.iter_mut().for_each(|f| *f *= s),
            Load::Pressure { pressure, .. } => *pressure *= s,
        }
    }
    scene
}

/// The disk lifted by `lift` above the floor (negative: into it).
fn lifted_disk(mut scene: Scene, lift: f64) -> Scene {
    if let GeometrySpec::HalfDisk { center, .. } = &mut scene.bodies[0].geometry {
        center[1] += lift;
    }
    scene
}

/// The upper Taylor block lifted by `gap` (negative: into the lower one).
fn lifted_block(mut scene: Scene, gap: f64) -> Scene {
    if let GeometrySpec::Rectangle { y0, y1, .. } = &mut scene.bodies[1].geometry {
        *y0 += gap;
        *y1 += gap;
    }
    scene
}

// ANCHOR: cases
/// The safety factor over the stability bound of the sharp-penalty cases.
pub const SHARP_SAFETY: f64 = 2.0;

pub fn cases(reference_8x8: f64, reference_fine: f64) -> Result<Vec<Case>> {
    let taylor_stress = Metric::UniformStress(-1e8);
    let case = |name: String, scene: Scene, metric| {
        let n = scene.contacts[0].nitsche;
        Case {
            name,
            theta: n.theta,
            penalty_factor: n.penalty_factor,
            scene,
            metric,
        }
    };
    let mut out = Vec::new();
    for theta in Theta::ALL {
        for f in factors() {
            let set = |n: &mut iga_contact::scene::NitscheSpec| {
                n.theta = theta;
                n.penalty_factor = f;
            };
            let name = Format::Sci(0).render(f).replace('−', "-");
            out.push(case(
                format!("hertz_8x8_penalty_{name}"),
                with(hertz(2, 8)?, set),
                Metric::PeakPressure(reference_8x8),
            ));
            out.push(case(
                format!("taylor_penalty_{name}"),
                with(taylor()?, set),
                taylor_stress,
            ));
        }
    }
    for k in [-6, -4, -2, 0, 2, 4, 6] {
        let c = 10f64.powi(k);
        let mut s = taylor()?;
        s.body_mut("upper")?.material.young *= c;
        out.push(case(format!("taylor_contrast_1e{k}"), s, taylor_stress));
    }
    for nu in [0.3, 0.45, 0.49, 0.499, 0.4999] {
        let mut s = hertz(2, 16)?;
        s.body_mut("disk")?.material.poisson = nu;
        let p0 = setup::analytic(&s)?.p0;
        out.push(case(
            format!("hertz_16x16_nu_{nu}"),
            s,
            Metric::PeakPressure(p0),
        ));
    }
    // The same ν with the penalty held above the stability bound (the sharp
    // penalty, safety factor SHARP_SAFETY): what is left of the error is the
    // discretisation's, locking included.
    for nu in [0.3, 0.45, 0.49, 0.499, 0.4999] {
        let mut s = hertz(2, 16)?;
        s.body_mut("disk")?.material.poisson = nu;
        let p0 = setup::analytic(&s)?.p0;
        let s = with(s, |n| {
            n.penalty = PenaltyKind::Sharp;
            n.penalty_factor = SHARP_SAFETY;
        });
        out.push(case(
            format!("hertz_16x16_nu_{nu}_sharp"),
            s,
            Metric::PeakPressure(p0),
        ));
    }
    for k in [-8, -6, -4, -2, 0, 1, 2, 3] {
        let s = scaled(hertz(2, 16)?, 10f64.powi(k));
        let p0 = setup::analytic(&s)?.p0;
        out.push(case(
            format!("hertz_16x16_load_1e{k}"),
            s,
            Metric::PeakPressure(p0),
        ));
    }
    let gaps = [
        (
            "taylor_open_gap_unloaded",
            scaled(lifted_block(taylor()?, 1e-2), 0.0),
            Metric::NoContact,
        ),
        (
            "taylor_gap_closed_by_load",
            lifted_block(taylor()?, 1e-3),
            taylor_stress,
        ),
        (
            "taylor_initial_penetration",
            lifted_block(taylor()?, -1e-3),
            taylor_stress,
        ),
        (
            "hertz_lifted_and_pulled_up",
            scaled(lifted_disk(hertz(2, 8)?, 1e-2), -1.0),
            Metric::NoContact,
        ),
        (
            "hertz_lifted_then_falls",
            lifted_disk(hertz(2, 8)?, 1e-4),
            Metric::PeakPressure(reference_8x8),
        ),
        (
            "hertz_initial_penetration",
            lifted_disk(hertz(2, 8)?, -1e-4),
            Metric::PeakPressure(reference_8x8),
        ),
    ];
    for (name, scene, metric) in gaps {
        out.push(case(name.into(), scene, metric));
    }
    // The mesh and degree axis is measured against the converged solution
    // of this disk (the Hertz chapter's fine reference), not against Hertz's
    // formula, which approximates the finite disk.
    for degree in 1..=5 {
        for n in [1, 4, 16] {
            // degree 1: the isoparametric Q1 interpolant (NURBS cannot go below the circle's 2)
            let refine = match degree {
                1 => RefineSpec::lagrange(1, [n, n]),
                p => RefineSpec::iga(p, [n, n]),
            };
            let s = setup::scene(refine)?;
            out.push(case(
                format!("hertz_p{degree}_{n}x{n}"),
                s,
                Metric::PeakPressure(reference_fine),
            ));
        }
    }
    for n in [128, 256] {
        out.push(case(
            format!("hertz_p2_{n}x{n}"),
            hertz(2, n)?,
            Metric::PeakPressure(reference_fine),
        ));
    }
    let gauss = with(taylor()?, |n| n.integration = Integration::Gauss);
    out.push(case(
        "taylor_gauss_integration".into(),
        gauss,
        taylor_stress,
    ));
    Ok(out)
}
// ANCHOR_END: cases
