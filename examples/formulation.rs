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
//! - `disk_5_net.svg`: the disk as five patches without a singular point
//!   (`geometry::disk_5`, the Hertz disk's centre and radius): each patch's
//!   boundary, control net and parametric directions, and the weights;
//! - `half_disk_4_net.svg`: the half disk of four patches as
//!   `hertz_multipatch.toml` builds it (`geometry::half_disk_4`), drawn the
//!   same way;
//! - `contact_sketch.svg`: slave points of that half disk, lifted above a
//!   curved rigid master, projected onto it by the contact code: slave point,
//!   projection, normals and gap of Eqs. (4)–(5);
//!
//! and the facts the chapter quotes about the two bodies of several patches:
//! how many patches, control points (all, and distinct: matching
//! interfaces share theirs) and matching interfaces, the range of the
//! weights, and |det J| sampled densely over every patch, corners included.
//!
//! ```text
//! cargo run --release --example formulation
//! ```

use companion::chapter::Chapter;
use companion::facts::Facts;
use companion::figures::{basis_figure, contact_sketch, control_net_figure, multipatch_figure};
use iga_contact::contact::{contact_points, ContactPair, Integration, Master};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry;
use iga_contact::interface::{self, Interface};
use iga_contact::nurbs::{KnotVector, NurbsCurve, NurbsPatch, Side};
use iga_contact::report::table::Format;
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

/// Parameter samples per direction and patch for the extremes of det J:
/// both ends included, so the corners, where a one-patch disk is singular,
/// are among them.
const DET_SAMPLES: usize = 201;

/// Records, under `prefix`, what the chapter says of a body of several
/// patches: patches, control points (all and distinct), matching
/// interfaces, the smallest and largest weight, how many patches are
/// left-handed, and min |det J| over its largest value.
fn multipatch_facts(
    facts: &mut Facts,
    prefix: &str,
    patches: &[NurbsPatch],
) -> iga_contact::Result<()> {
    let key = |name: &str| format!("{prefix}_{name}");
    let all: Vec<[f64; 2]> = patches.iter().flat_map(|p| p.points.clone()).collect();
    let size = patches.iter().map(interface::extent).fold(0.0, f64::max);
    let mut distinct: Vec<[f64; 2]> = Vec::new();
    for p in &all {
        if !distinct
            .iter()
            .any(|q| (p[0] - q[0]).hypot(p[1] - q[1]) <= 1e-12 * size)
        {
            distinct.push(*p);
        }
    }
    let mut interfaces = 0;
    for (a, pa) in patches.iter().enumerate() {
        for pb in &patches[a + 1..] {
            for sa in Side::ALL {
                for sb in Side::ALL {
                    if let Interface::Matching(_) = interface::matching(pa, sa, pb, sb, size) {
                        interfaces += 1;
                    }
                }
            }
        }
    }
    let weights = || patches.iter().flat_map(|p| p.weights.iter().copied());
    let (mut det_min, mut det_max, mut left) = (f64::INFINITY, 0.0f64, 0);
    for patch in patches {
        let (mut lo, mut hi) = (f64::INFINITY, f64::NEG_INFINITY);
        let at = |d: usize, k: usize| {
            let kv = &patch.knots[d];
            kv.first() + (kv.last() - kv.first()) * k as f64 / (DET_SAMPLES - 1) as f64
        };
        for i in 0..DET_SAMPLES {
            for j in 0..DET_SAMPLES {
                let m = patch.jacobian(at(0, i), at(1, j));
                let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
                lo = lo.min(det);
                hi = hi.max(det);
            }
        }
        // one sign over the whole patch, or the map folds or degenerates
        if lo <= 0.0 && hi >= 0.0 {
            return Err(iga_contact::Error::invalid(
                prefix,
                format!("det J from {lo} to {hi}"),
                "changes sign or vanishes on a patch",
            ));
        }
        if hi < 0.0 {
            left += 1;
            (lo, hi) = (-hi, -lo);
        }
        det_min = det_min.min(lo);
        det_max = det_max.max(hi);
    }
    facts.count(&key("patches"), patches.len())?;
    facts.count(&key("points"), all.len())?;
    facts.count(&key("distinct_points"), distinct.len())?;
    facts.count(&key("interfaces"), interfaces)?;
    facts.count(&key("left_handed"), left)?;
    facts.number(
        &key("w_min"),
        weights().fold(f64::INFINITY, f64::min),
        Format::Fixed(4),
    )?;
    facts.number(
        &key("w_max"),
        weights().fold(0.0, f64::max),
        Format::Fixed(4),
    )?;
    facts.number(&key("det_ratio"), det_min / det_max, Format::Fixed(3))?;
    println!(
        "{prefix}: {} patches, {} control points ({} distinct), {interfaces} matching interfaces, \
         {left} left-handed, |det J| from {det_min:.4e} to {det_max:.4e} m²",
        patches.len(),
        all.len(),
        distinct.len()
    );
    Ok(())
}

fn run() -> iga_contact::Result<()> {
    let mut chapter = Chapter::from_args("formulation")?;
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

    // The bodies of several patches: the half disk as the multi-patch Hertz
    // scene builds it, and the five-patch disk it is the right half of.
    let multi = companion::shipped("hertz_multipatch.toml")?;
    let spec = &multi.bodies[0].geometry;
    let GeometrySpec::HalfDisk4 { center, radius } = *spec else {
        unreachable!("the multi-patch Hertz scene is a four-patch half disk")
    };
    let half_4 = spec
        .multipatch()
        .expect("half_disk_4 is a multi-patch kind")?;
    let disk_5 = geometry::disk_5(center, radius)?;
    multipatch_figure(
        out("disk_5_net.svg"),
        "The disk as five patches: boundaries, control nets, weights",
        &disk_5.patches,
    )?;
    multipatch_figure(
        out("half_disk_4_net.svg"),
        "The half disk as four patches (hertz_multipatch.toml)",
        &half_4.patches,
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
    multipatch_facts(chapter.facts(), "disk5", &disk_5.patches)?;
    multipatch_facts(chapter.facts(), "half4", &half_4.patches)?;
    chapter.facts().count("det_samples", DET_SAMPLES)?;
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
