//! The figures of the formulation chapters, in `book/src/generated/formulation/`:
//!
//! - `basis_bspline.svg`: the quadratic B-splines of the knot vector that
//!   "NURBS fields" uses, {0, 0, 0, ¼, ½, ½, 1, 1, 1} (C¹ at ¼, C⁰ at ½);
//! - `basis_nurbs.svg`: the rational basis of the same knots with two weights
//!   changed, over the B-splines it is built from;
//! - `half_disk_net.svg`: the Hertz half disk as `geometry::half_disk` builds
//!   it (one element), its control net and weights;
//! - `half_disk_net_p2.svg`: the same disk k-refined to p = 2 with 2 × 2
//!   elements, the way the Hertz benchmark refines it;
//! - `contact_sketch.svg`: slave points of that half disk, lifted above a
//!   curved rigid master, projected onto it by the contact code: slave point,
//!   projection, normals and gap of Eqs. (4)–(5).
//!
//! ```text
//! cargo run --release --example formulation
//! ```

use companion::chapter::Chapter;
use companion::figures::{basis_figure, contact_sketch, control_net_figure};
use iga_contact::contact::{contact_points, ContactPair, Integration, Master};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry;
use iga_contact::nurbs::{KnotVector, NurbsCurve, Side};
use iga_contact::scene::{GeometrySpec, RefineSpec};
use iga_contact::space::Space;
use std::process::ExitCode;

/// A circular arc of radius `r` about `c` from angle `from` to `to` (radians,
/// at most 180° apart) as a quadratic NURBS curve.
fn arc(c: [f64; 2], r: f64, from: f64, to: f64) -> iga_contact::Result<NurbsCurve> {
    let half = 0.5 * (to - from);
    let mid = 0.5 * (from + to);
    let at = |t: f64, s: f64| [c[0] + s * t.cos(), c[1] + s * t.sin()];
    NurbsCurve::new(
        KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2)?,
        vec![at(from, r), at(mid, r / half.cos()), at(to, r)],
        vec![1.0, half.cos(), 1.0],
    )
}

fn run() -> iga_contact::Result<()> {
    let chapter = Chapter::from_args("formulation")?;
    let out = |file: &str| chapter.path(file);

    let knots = KnotVector::new(vec![0.0, 0.0, 0.0, 0.25, 0.5, 0.5, 1.0, 1.0, 1.0], 2)?;
    basis_figure(
        out("basis_bspline.svg"),
        "Quadratic B-splines, Ξ = {0, 0, 0, ¼, ½, ½, 1, 1, 1}",
        &knots,
        None,
    )?;
    let weights = [1.0, 1.0, 3.0, 1.0, 0.5, 1.0];
    basis_figure(
        out("basis_nurbs.svg"),
        "Rational basis with weights w = (1, 1, 3, 1, 0.5, 1)",
        &knots,
        Some(&weights),
    )?;

    let scene = companion::shipped("hertz.toml")?;
    let GeometrySpec::HalfDisk { center, radius: r } = scene.bodies[0].geometry else {
        unreachable!("the Hertz scene is a half disk")
    };
    let coarse = geometry::half_disk(center, r)?;
    control_net_figure(
        out("half_disk_net.svg"),
        "The half disk as built: one element, weights at the control points",
        &coarse,
    )?;
    let material = scene.bodies[0].material;
    let refined = scene
        .refined("disk", RefineSpec::iga(2, [2, 2]))?
        .build()?
        .bodies[0]
        .space
        .patch
        .clone();
    control_net_figure(
        out("half_disk_net_p2.svg"),
        "k-refined to p = 2 with 2 × 2 elements",
        &refined,
    )?;

    // The same half disk, lifted 15 % of its radius above a rigid master that
    // bulges upwards (the top of a disk of radius 2R): every Gauss point of
    // the slave arc is projected by the contact code.
    let lift = 0.15 * r;
    let slave = refined.transformed(|p| [p[0], p[1] + lift]);
    let master = arc(
        [0.0, -2.0 * r],
        2.0 * r,
        94f64.to_radians(),
        62f64.to_radians(),
    )?;
    let bodies = vec![Body {
        name: "disk".into(),
        space: Space::new(slave.clone(), None)?,
        material,
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let map = DofMap::builder(&bodies).build();
    let mut pair = ContactPair::new(0, Side::EtaMin, Master::Rigid(master.clone()));
    pair.nitsche.integration = Integration::Gauss;
    let points = contact_points(&bodies, &map, &[pair])?;
    let highlight = points.len() * 3 / 4;
    contact_sketch(
        out("contact_sketch.svg"),
        "Slave points projected on a curved master",
        &slave.side_curve(Side::EtaMin),
        &master,
        &points,
        highlight,
    )?;
    let cp = &points[highlight];
    println!(
        "contact sketch: {} slave points; highlighted x¹ = ({:.4}, {:.4}), n¹ = ({:.4}, {:.4}), g₀ = {:.5} m",
        points.len(),
        cp.x[0],
        cp.x[1],
        cp.normal[0],
        cp.normal[1],
        cp.g0
    );
    println!("written to {}", chapter.dir().display());
    chapter.finish()
}

fn main() -> ExitCode {
    match run() {
        Ok(()) => ExitCode::SUCCESS,
        Err(e) => {
            eprintln!("formulation: {e}");
            ExitCode::FAILURE
        }
    }
}
