//! The stiffer body as slave: named by the warning, with the swap (or the
//! biased form with the softer slave) as its advice, which fixes p₀.

use crate::common::swapped;
use crate::{disk_on_block, only, outcome, p0_and_warnings, RIGHT};
use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::post::relative;
use iga_contact::scene::Scene;
use iga_contact::solver::warning::STIFFER_SLAVE;
use iga_contact::solver::Warning;
use std::f64::consts::PI;

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
