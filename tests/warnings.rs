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

mod common;
use common::swapped;
use iga_contact::material::Formulation;
use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::post::{relative, PressureProfile};
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::warning::{PenaltyRemedy, SideEnd, STIFFER_SLAVE};
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

/// Disk on a block 10⁴ times stiffer, the block as slave: p₀ far off, and
/// the warning names the disk as the slave to choose; so chosen, silent
/// and right.
#[test]
fn the_stiffer_slave_is_warned_and_swapping_fixes_it() {
    let bad = swapped(disk_on_block(1e4));
    let (w, error) = outcome(&bad);
    assert!(error > 0.5, "p₀ {error:+.3}");
    match only(&w) {
        Warning::StifferSlave { slave, master, .. } => {
            assert_eq!((slave.as_str(), master.as_str()), ("block", "disk"));
        }
        other => panic!("{other}"),
    }
    assert!(w[0].to_string().contains("make \"disk\" the slave"));
    let (w, error) = outcome(&disk_on_block(1e4));
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
}

/// The shipped two cylinders (the upper, softer, one the slave; the lower
/// five times stiffer) with the roles swapped: p₀ +31 % and silent before
/// the threshold came down from 10 to [`STIFFER_SLAVE`]; now warned, and the
/// advised swap (the shipped scene) is silent and within 3 % of Hertz for
/// two cylinders (its upper disk on 8×8 is 2 % off).
#[test]
fn a_slave_a_few_times_stiffer_is_warned() {
    let shipped = companion::shipped("two_cylinders.toml").unwrap();
    let p0_error = |s: &Scene| {
        let (p0, w) = p0_and_warnings(s);
        let body = |name: &str| s.bodies.iter().find(|b| b.name == name).unwrap();
        let hertz = Hertz::new(
            Cylinder::Elastic {
                radius: 0.2,
                material: body("upper").material,
            },
            Cylinder::Elastic {
                radius: 0.4,
                material: body("lower").material,
            },
            1.3e6 * PI * 0.2 * 0.2,
        );
        (w, relative(p0, hertz.p0))
    };
    let mut good = shipped;
    good.output = Default::default();
    let bad = swapped(good.clone());
    let (w, error) = p0_error(&bad);
    assert!(error > 0.2, "p₀ {error:+.3}");
    match only(&w) {
        Warning::StifferSlave {
            slave,
            master,
            contrast,
            ..
        } => {
            assert_eq!((slave.as_str(), master.as_str()), ("lower", "upper"));
            assert!(*contrast > STIFFER_SLAVE && *contrast < 10.0, "{contrast}");
        }
        other => panic!("{other}"),
    }
    let (w, error) = p0_error(&good);
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < 0.03, "p₀ {error:+.4}");
}

/// The unbiased form between a disk and a block 10⁴ times stiffer: its
/// mirrored half has the block as slave, whatever the scene names, and
/// over-penalises the disk. On the shipped meshes (p = 2) p₀ is off by
/// more than a right answer may be (+2.7 %, about three times the biased
/// form's +0.9 %). The warning names the block as the stiffer slave and
/// advises the biased form with the disk as slave; so set, the run is
/// silent and right.
#[test]
fn the_unbiased_form_with_a_stiff_body_is_warned_and_the_biased_form_fixes_it() {
    let unbiased = |s: Scene| s.with_nitsche(|n| n.sides = iga_contact::contact::Sides::Unbiased);
    // named either way round, the warning names the block
    for bad in [
        unbiased(disk_on_block(1e4)),
        unbiased(swapped(disk_on_block(1e4))),
    ] {
        let w = Scene::check(&bad, &iga_contact::resources::Budget::from_machine())
            .unwrap()
            .warnings;
        match only(&w) {
            Warning::StifferSlave { slave, master, .. } => {
                assert_eq!((slave.as_str(), master.as_str()), ("block", "disk"));
            }
            other => panic!("{other}"),
        }
        assert!(
            w[0].to_string()
                .contains("sides = \"biased\" with \"disk\" the slave"),
            "{}",
            w[0]
        );
    }
    let (w, unbiased_error) = outcome(&unbiased(disk_on_block(1e4)));
    assert!(matches!(only(&w), Warning::StifferSlave { .. }));
    let (w, biased_error) = outcome(&disk_on_block(1e4));
    assert!(w.is_empty(), "{w:?}");
    assert!(biased_error.abs() < RIGHT, "p₀ {biased_error:+.4}");
    assert!(
        unbiased_error.abs() > RIGHT && unbiased_error.abs() > 2.0 * biased_error.abs(),
        "unbiased {unbiased_error:+.4}, biased {biased_error:+.4}"
    );
}

/// The two halves of the unbiased form each carry half the weight, and add
/// to one penalty γ on one gap: the over-penalty scale is that of the whole
/// weight. At the shipped factor the unbiased disk on a block of its own
/// stiffness is silent, as the biased one is, and agrees with it; at factor
/// 100 it is warned, and the advised factor silences it and agrees again.
/// (Hertz's half space is no reference for a block of the disk's size and
/// stiffness, so the biased form on the same meshes is.)
#[test]
fn the_unbiased_penalty_is_judged_against_the_whole_weight() {
    let (reference, w) = p0_and_warnings(&disk_on_block(1.0));
    assert!(w.is_empty(), "{w:?}");
    let off = |s: &Scene| {
        let (p0, w) = p0_and_warnings(s);
        (w, relative(p0, reference))
    };
    let unbiased =
        disk_on_block(1.0).with_nitsche(|n| n.sides = iga_contact::contact::Sides::Unbiased);
    let (w, error) = off(&unbiased);
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
    let bad = unbiased.with_nitsche(|n| n.penalty_factor = 100.0);
    let (w, error) = off(&bad);
    eprintln!("unbiased, factor 100: p₀ {error:+.4} against the biased form");
    assert!(error.abs() > 5.0 * RIGHT, "p₀ {error:+.4}");
    assert!(matches!(only(&w), Warning::PenaltyFarAboveBound { .. }));
    let r = remedy(&w[0]);
    let (w, error) = off(&follow(bad, r));
    assert!(w.is_empty(), "{r:?}: {w:?}");
    assert!(error.abs() < RIGHT, "{r:?}: p₀ {error:+.4}");
}

/// Penalty factor 100 on a rigid floor, 32×32: over-penalised; the advised
/// factor brings it back.
#[test]
fn over_penalisation_is_warned_and_the_advised_factor_fixes_it() {
    let bad = hertz(32).with_nitsche(|n| n.penalty_factor = 100.0);
    let (w, error) = outcome(&bad);
    assert!(error > 0.05, "p₀ {error:+.4}");
    assert!(matches!(only(&w), Warning::PenaltyFarAboveBound { .. }));
    let r = remedy(&w[0]);
    assert!(matches!(r, PenaltyRemedy::Factor(f) if f < 1.0), "{r:?}");
    let (w, error) = outcome(&follow(bad, r));
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
}

/// `modulus = "max"` between a disk and a block 100 times stiffer (32×32 on
/// 64×32): the block's modulus over-penalises the disk; the warning says
/// to take the slave's.
#[test]
fn modulus_max_is_warned_and_the_slave_modulus_fixes_it() {
    let mut bad =
        disk_on_block(100.0).with_nitsche(|n| n.modulus = iga_contact::contact::Modulus::Max);
    bad.body_mut("disk").unwrap().refine = Some(RefineSpec::iga(2, [32, 32]));
    bad.body_mut("block").unwrap().refine = Some(RefineSpec::iga(2, [64, 32]));
    let (w, error) = outcome(&bad);
    assert!(error > 0.1, "p₀ {error:+.4}");
    assert_eq!(remedy(only(&w)), PenaltyRemedy::SlaveModulus);
    assert!(w[0].to_string().contains("modulus = \"slave\""));
    let (w, error) = outcome(&follow(bad, PenaltyRemedy::SlaveModulus));
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
}

/// θ = 1 at the empirical penalty on 16×16 lies below its bound, at the
/// active points and at inactive ones near the corner (θ > 0 keeps
/// −(θ/γ) w σ_n σ_nᵀ there); one factor cannot lift those without
/// over-penalising the zone, so the advice is the sharp penalty, which
/// silences the warning and is right.
#[test]
fn a_penalty_below_the_bound_is_warned_and_the_advised_factor_fixes_it() {
    let bad = hertz(16).with_nitsche(|n| n.theta = iga_contact::contact::Theta::Symmetric);
    let (w, _) = outcome(&bad);
    assert!(matches!(only(&w), Warning::PenaltyBelowBound { .. }));
    let r = remedy(&w[0]);
    assert!(matches!(r, PenaltyRemedy::Sharp(f) if f >= 1.0), "{r:?}");
    let (w, error) = outcome(&follow(bad, r));
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
}

/// ν = 0.49 in plane strain on 16×16 locks (θ = −1, whose stability does
/// not depend on the penalty, so that only locking is at stake); the
/// advised refinement is silent and right.
#[test]
fn locking_is_warned_and_the_advised_refinement_fixes_it() {
    let nearly = |elements: usize| {
        let mut s = hertz(elements).with_nitsche(|n| n.theta = iga_contact::contact::Theta::Skew);
        s.body_mut("disk").unwrap().material.poisson = 0.49;
        s
    };
    let (w, error) = outcome(&nearly(16));
    assert!(error > 0.1, "p₀ {error:+.4}");
    let elements = match only(&w) {
        Warning::NearlyIncompressible { elements, .. } => *elements,
        other => panic!("{other}"),
    };
    assert!(elements > 16);
    let (w, error) = outcome(&nearly(elements));
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
    // plane stress does not lock: no warning at any ν
    let mut stress = nearly(16);
    stress.body_mut("disk").unwrap().material.plane = iga_contact::material::Plane::Stress;
    let problem = stress.build().unwrap();
    assert!(iga_contact::solver::warning::setup_warnings(
        &problem.bodies,
        &problem.pairs,
        &problem.contacts
    )
    .is_empty());
}

/// On a Lagrange (C⁰) mesh the displacement formulation locks as the spline
/// one does, but `mixed` is refused there: the warning advises the local
/// mixed formulation, Q1/P0, which does not lock on a C⁰ mesh and is not
/// warned for it. Q1 on 32², ν = 0.49999: +71 % and warned; so set, the
/// locking warning is gone and p₀ is right.
#[test]
fn locking_on_a_lagrange_mesh_advises_the_local_mixed_formulation() {
    let q1 = |formulation: Formulation| {
        let mut s = companion::shipped("hertz.toml")
            .unwrap()
            .refined("disk", RefineSpec::lagrange(1, [32, 32]))
            .unwrap();
        s.solver = SolverOptions::default();
        s.output = Default::default();
        let disk = s.body_mut("disk").unwrap();
        disk.material.poisson = 0.49999;
        disk.formulation = formulation;
        s
    };
    let locks = |w: &[Warning]| {
        w.iter()
            .any(|w| matches!(w, Warning::NearlyIncompressible { .. }))
    };
    let (w, error) = outcome(&q1(Formulation::Displacement));
    assert!(error > 0.3, "p₀ {error:+.4}");
    let warning = w
        .iter()
        .find(|w| matches!(w, Warning::NearlyIncompressible { .. }))
        .expect("locking warned");
    assert!(
        warning
            .to_string()
            .contains("formulation = \"local_mixed\""),
        "{warning}"
    );
    let (w, error) = outcome(&q1(Formulation::LocalMixed));
    assert!(!locks(&w), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
}

/// Under eight times the load (penalty factor 2, which keeps every regular
/// element above its bound: at factor 1 the element next to the corner is
/// just below it, and that warning comes first) the zone of the 32×32 disk
/// reaches the end of its slave side, the collapsed corner of the
/// nine-point disk where the boundary goes on smoothly: warned, once. A flat block on a floor (Taylor),
/// whose zone ends at the body's corners, and the symmetry end of the
/// Hertz half disk are not. This load has two roots: the plain iteration
/// (`growth = "full"`) ends on one whose zone (86 points) has the corner's
/// point active; the default's cut growth ends on one whose zone runs on to
/// 94 points and leaves the corner open, unwarned (which of the two is
/// right: [`where_the_growths_part_the_wrong_or_doubtful_root_is_warned`]).
#[test]
fn a_zone_that_reaches_the_end_of_the_slave_side_is_warned() {
    let mut heavy = hertz(32).with_nitsche(|n| n.penalty_factor = 2.0);
    heavy.solver.growth = iga_contact::solver::Growth::Full;
    for l in &mut heavy.loads {
        if let iga_contact::assembly::Load::BodyForce { force, .. } = l {
            force[1] *= 8.0;
        }
    }
    let problem = heavy.build().unwrap();
    let s = solve(&problem, &heavy.solver).unwrap();
    let at_end: Vec<_> = s
        .warnings
        .iter()
        .filter(|w| {
            matches!(
                w,
                Warning::ZoneAtSideEnd {
                    end: SideEnd::End,
                    ..
                }
            )
        })
        .collect();
    assert_eq!(at_end.len(), 1, "{:?}", s.warnings);
    for scene in [hertz(16), {
        let mut t = companion::shipped("taylor.toml").unwrap();
        t.output = Default::default();
        t
    }] {
        let problem = scene.build().unwrap();
        let s = solve(&problem, &scene.solver).unwrap();
        assert!(
            !s.warnings
                .iter()
                .any(|w| matches!(w, Warning::ZoneAtSideEnd { .. })),
            "{:?}",
            s.warnings
        );
    }
}

/// One cause, one line: the penalty below its bound is reported once by
/// `check` and once by `run`, each with one remedy, and the run's summary
/// carries the same line.
#[test]
fn one_cause_gives_one_warning_line_with_one_remedy() {
    let dir = std::env::temp_dir().join(format!("iga-warnings-{}", std::process::id()));
    std::fs::create_dir_all(&dir).unwrap();
    // the shipped Hertz scene with θ = 1 and the library's default solver
    let text = std::fs::read_to_string(companion::shipped_path("hertz.toml")).unwrap();
    let (head, tail) = text.split_at(text.find("[solver]").unwrap());
    let text = format!("{head}{}", &tail[tail.find("[output]").unwrap()..])
        .replace("nitsche = { theta = 0,", "nitsche = { theta = 1,");
    let path = dir.join("below.toml");
    std::fs::write(&path, text).unwrap();
    for cmd in ["check", "run"] {
        let mut c = std::process::Command::new(env!("CARGO_BIN_EXE_iga-contact"));
        c.args([cmd, path.to_str().unwrap()]);
        if cmd == "run" {
            c.arg("--out").arg(dir.join("out"));
        }
        let o = c.output().unwrap();
        let stderr = String::from_utf8_lossy(&o.stderr);
        let lines: Vec<_> = stderr
            .lines()
            .filter(|l| l.starts_with("warning: "))
            .collect();
        assert_eq!(lines.len(), 1, "{cmd}: {stderr}");
        assert_eq!(
            lines[0].matches("set contact[0]").count(),
            1,
            "{}",
            lines[0]
        );
        assert!(!lines[0].contains(" or "), "{}", lines[0]);
        if cmd == "run" {
            let summary = std::fs::read_to_string(dir.join("out/summary.toml")).unwrap();
            let t: toml::Table = toml::from_str(&summary).unwrap();
            let w = t["warnings"].as_array().unwrap();
            assert_eq!(w.len(), 1);
            assert!(lines[0].ends_with(w[0].as_str().unwrap()), "{}", lines[0]);
        }
    }
    let _ = std::fs::remove_dir_all(&dir);
}

/// θ = −1 is stable for any γ, but at 10⁻⁵ of Eq. (11) on the coarse
/// p = 3 8² disk its p₀ is +5.6 % off Hertz (it was +2.3 % at 10⁻¹): the
/// loose-penalty warning says so, and the factor it advises is silent and
/// right. Without the warning the campaign of the reliability chapter
/// counted this as a silent wrong answer.
#[test]
fn a_loose_skew_penalty_is_warned_and_the_advised_factor_fixes_it() {
    let mut bad = hertz(8).with_nitsche(|n| {
        n.theta = iga_contact::contact::Theta::Skew;
        n.penalty_factor = 1e-5;
    });
    bad.body_mut("disk").unwrap().refine = Some(RefineSpec::iga(3, [8, 8]));
    let (w, error) = outcome(&bad);
    assert!(error > 0.05, "p₀ {error:+.4}");
    assert!(matches!(only(&w), Warning::PenaltyLoose { .. }), "{w:?}");
    let (w, error) = outcome(&follow(bad, remedy(&w[0])));
    assert!(w.is_empty(), "{w:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.4}");
}

/// The scene under 8× load with the growth `growth` on n² (penalty factor 2).
fn heavy(n: usize, growth: Growth) -> Scene {
    let mut s = hertz(n).with_nitsche(|x| x.penalty_factor = 2.0);
    s.solver.growth = growth;
    for l in &mut s.loads {
        if let iga_contact::assembly::Load::BodyForce { force, .. } = l {
            force[1] *= 8.0;
        }
    }
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

/// Where the default (`growth = "auto"`) and the plain iteration
/// (`growth = "full"`) end on different roots, the wrong or doubtful one is
/// warned.
///
/// Hertz under 8× load at penalty factor 2: on 32² the plain iteration ends
/// on a root with the collapsed corner's point active (det J = 0 there, so
/// its bracket is not a contact pressure), p₀ 4.6 % below the default's;
/// the default's root lies on the mesh sequence (its p₀ within 0.2 % of the
/// 64² one, where the plain iteration's 64² root is again the corner's). The
/// corner root carries the zone-at-side-end warning, the default's none.
///
/// ν = 0.4999: the two roots differ (7 and 10 active points), and both carry
/// the locking warning; following it (`formulation = "mixed"`) both growths
/// reach the same root, which the finer mesh confirms.
#[test]
fn where_the_growths_part_the_wrong_or_doubtful_root_is_warned() {
    let at_end = |w: &[Warning]| {
        w.iter()
            .any(|w| matches!(w, Warning::ZoneAtSideEnd { singular: true, .. }))
    };
    let (auto32, w) = p0_and_warnings(&heavy(32, Growth::Auto));
    assert!(!at_end(&w), "{w:?}");
    let (auto64, w) = p0_and_warnings(&heavy(64, Growth::Auto));
    assert!(!at_end(&w), "{w:?}");
    assert!(relative(auto32, auto64).abs() < 2e-3, "{auto32} {auto64}");
    let (full32, w) = p0_and_warnings(&heavy(32, Growth::Full));
    assert!(at_end(&w), "{w:?}");
    assert!(relative(full32, auto64) < -0.03, "{full32} {auto64}");

    let nearly = |n: usize, growth: Growth, formulation: Formulation| {
        let mut s = hertz(n);
        s.solver.growth = growth;
        let disk = s.body_mut("disk").unwrap();
        disk.material.poisson = 0.4999;
        disk.formulation = formulation;
        p0_and_warnings(&s)
    };
    let locks = |w: &[Warning]| {
        w.iter()
            .any(|w| matches!(w, Warning::NearlyIncompressible { .. }))
    };
    let (a, wa) = nearly(16, Growth::Auto, Formulation::Displacement);
    let (b, wb) = nearly(16, Growth::Full, Formulation::Displacement);
    assert!(relative(a, b).abs() > 0.01, "{a} {b}");
    assert!(locks(&wa) && locks(&wb), "{wa:?} {wb:?}");
    let (a, wa) = nearly(16, Growth::Auto, Formulation::Mixed);
    let (b, wb) = nearly(16, Growth::Full, Formulation::Mixed);
    assert!(!locks(&wa) && !locks(&wb), "{wa:?} {wb:?}");
    assert!(relative(a, b).abs() < 1e-8, "{a} {b}");
    let (fine, _) = nearly(32, Growth::Auto, Formulation::Mixed);
    assert!(relative(a, fine).abs() < 0.01, "{a} {fine}");
}

/// Two cylinders with ν = 0.4999 on the upper, slave one (8²): the
/// displacement formulation locks, and its penalty, judged on the locked
/// stress, falls below the bound too. Only the locking warning is given,
/// before and after the solve: following a penalty advice computed on the
/// locked stress together with the locking advice gave p₀ 3.2 times too
/// high. Followed (`formulation = "mixed"`), no warning is left; p₀ is
/// that of the mixed formulation on 32² to 5 % (4.7 % measured: the coarse
/// mixed mesh's own error at this ν; on 16² it is 0.03 %), where the locked
/// answer is 61 % high.
#[test]
fn a_locking_slave_is_warned_of_locking_alone_and_the_advice_suffices() {
    let scene = |n: usize, formulation: Formulation| {
        let mut s = companion::shipped("two_cylinders.toml")
            .unwrap()
            .refined("upper", RefineSpec::iga(2, [n, n]))
            .unwrap();
        let upper = s.body_mut("upper").unwrap();
        upper.material.poisson = 0.4999;
        upper.formulation = formulation;
        s
    };
    let locked = scene(8, Formulation::Displacement);
    let only_locking = |w: &[Warning]| matches!(w, [Warning::NearlyIncompressible { body, .. }] if body == "upper");
    let report = locked
        .check(&iga_contact::resources::Budget::from_machine())
        .unwrap();
    assert!(only_locking(&report.warnings), "{:?}", report.warnings);
    let (p_locked, w) = p0_and_warnings(&locked);
    assert!(only_locking(&w), "{w:?}");
    let (reference, _) = p0_and_warnings(&scene(32, Formulation::Mixed));
    let (p_mixed, w) = p0_and_warnings(&scene(8, Formulation::Mixed));
    assert!(w.is_empty(), "{w:?}");
    assert!(
        relative(p_mixed, reference).abs() < 0.05,
        "{p_mixed} vs {reference}"
    );
    let (p_16, _) = p0_and_warnings(&scene(16, Formulation::Mixed));
    assert!(
        relative(p_16, reference).abs() < 1e-3,
        "{p_16} vs {reference}"
    );
    assert!(
        relative(p_locked, reference).abs() > 0.25,
        "{p_locked} vs {reference}"
    );
}

#[test]
fn a_slave_that_closes_where_it_faces_away_is_warned_and_the_advice_fixes_it() {
    // the full disk's upper half as the slave against the floor under it:
    // open at the start (its gaps run down through the disk), it closes
    // once the disk has fallen its diameter, where its normals point up,
    // away from the floor; only that warning is given (the penalty counted
    // on such gaps would be advice that leaves the answer as wrong)
    let shipped = companion::shipped("disk_full.toml").unwrap();
    let mut upper = shipped.clone();
    upper.contacts[0].slave_boundary = Some("arc_upper".into());
    upper.output = Default::default();
    let problem = upper.build().unwrap();
    let sol = solve(&problem, &upper.solver).unwrap();
    assert!(
        matches!(&sol.warnings[..], [Warning::ClosedFacingAway { contact: 0, away, active, .. }] if away == active && *active > 0),
        "{:?}",
        sol.warnings
    );
    let text = sol.warnings[0].to_string();
    assert!(text.contains("faces away from its master"), "{text}");
    // followed: the side of the disk that faces the floor
    let mut lower = upper.clone();
    lower.contacts[0].slave_boundary = Some("arc_lower".into());
    let (warnings, error) = outcome(&lower);
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.3e} off Hertz");
}

#[test]
fn a_slave_side_edge_on_to_its_master_is_warned_and_the_advice_fixes_it() {
    // the block's right side as the slave against the floor under it: the
    // block sinks until the side's lowest points pass the floor; the
    // bottom, which faces the floor, carries the uniform pressure
    let text = String::from(
        "title = \"block side against floor\"\n\
           [[body]]\nname = \"block\"\n\
           geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }\n\
           refine = { degree = 2, elements = [4, 16] }\n\
           material = { young = 1.0e7, poisson = 0.3, plane = \"strain\" }\n\
           [[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n\
           [[load]]\npressure = { body = \"block\", side = \"eta_max\", pressure = 1.0e4 }\n\
           [[contact]]\nslave = \"block\"\nslave_side = \"xi_max\"\n\
           master = { rigid_segment = { from = [-0.5, 0.0], to = [1.5, 0.0] } }\n",
    );
    let solved = |text: &str| {
        let scene = Scene::from_toml_str(text).unwrap();
        let problem = scene.build().unwrap();
        let sol = solve(&problem, &scene.solver).unwrap();
        let f = iga_contact::post::contact_resultant(&problem, &sol.full);
        (sol.warnings, f)
    };
    let (w, _) = solved(&text);
    assert!(
        w.iter()
            .any(|w| matches!(w, Warning::ClosedFacingAway { .. })),
        "{w:?}"
    );
    // the side tilted 6° from upright grazes the floor: warned too
    let tilted = text.replace(
        "geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }",
        "geometry = { quadrilateral = { corners = [[0.0, 0.0], [1.0, 0.0], [1.05, 0.5], [0.0, 0.5]] } }",
    );
    assert_ne!(tilted, text);
    let (w, _) = solved(&tilted);
    assert!(
        w.iter()
            .any(|w| matches!(w, Warning::ClosedFacingAway { .. })),
        "{w:?}"
    );
    // followed: the bottom; that side's own penalty warning is then
    // followed too (its factor is judged on real gaps now)
    let bottom = text.replace("slave_side = \"xi_max\"", "slave_side = \"eta_min\"");
    let (w, _) = solved(&bottom);
    let factor = match &w[..] {
        [Warning::PenaltyBelowBound {
            remedy: PenaltyRemedy::Factor(f),
            ..
        }] => *f,
        [] => 1.0,
        other => panic!("{other:?}"),
    };
    let (w, f) = solved(&format!(
        "{bottom}nitsche = {{ penalty_factor = {factor:?} }}\n"
    ));
    assert!(w.is_empty(), "{w:?}");
    assert!((f[1] - 1.0e4).abs() < 1e-8 * 1.0e4, "{f:?}");
}
