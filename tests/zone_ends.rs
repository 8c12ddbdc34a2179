//! Where a contact zone ends without the bracket changing sign, and what
//! its half-width is then: only an end of the slave side on a symmetry line
//! (a straight side held normal to itself, as the Hertz half disk's
//! diameter) is the zone's centre. A zone that stops where the master runs
//! out, or at an edge of the body, is a whole zone, and its half-width is
//! half its extent.
//!
//! The scenes: a 1 × 0.5 block pushed 1 mm down by its top onto a rigid
//! floor, which is flat, so the zone is wherever the floor is. Before the
//! fix a block on a floor [0.25, 0.75] reported `half_width = 0.5` (the
//! slave side's ends taken for the zone's), twice the 0.25 of its zone.

use iga_contact::post::PressureProfile;
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, Warning};

/// The block on a floor from `from` to `to` (x, at y = 0), its top pushed
/// down and held in x; `roller` puts its left side on rollers (u_x = 0),
/// the symmetry support of a half model.
fn block(from: f64, to: f64, roller: bool) -> Scene {
    let roller = if roller {
        "[[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n"
    } else {
        "[[support]]\nbody = \"block\"\nside = \"eta_max\"\ncomponent = \"x\"\n"
    };
    let text = format!(
        r#"
title = "block on a floor"
[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 }} }}
refine = {{ degree = 2, elements = [8, 2] }}
material = {{ young = 1.0e6, poisson = 0.3, plane = "strain" }}
{roller}
[[support]]
body = "block"
side = "eta_max"
component = "y"
value = -1.0e-3
[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [{from:?}, 0.0], to = [{to:?}, 0.0] }} }}
"#
    );
    Scene::from_toml_str(&text).unwrap()
}

/// The half-width of contact 0 of `scene` and whether the zone was warned
/// as running off the end of its slave side.
fn half_width(scene: &Scene) -> (f64, bool) {
    let problem = scene.build().unwrap();
    let s = solve(&problem, &scene.solver).unwrap();
    let m = PressureProfile::dense(&problem, &s.full)
        .unwrap()
        .measures_joined(problem.contacts.pieces(0));
    assert_eq!(m.zones, 1);
    let warned = s
        .warnings
        .iter()
        .any(|w| matches!(w, Warning::ZoneAtSideEnd { .. }));
    (m.half_width, warned)
}

/// The zone is the floor's extent under the block: the samples stop where
/// the master does, and that end is no centre. (Old code: 0.5, 0.5, 0.5.)
#[test]
fn a_zone_that_ends_with_the_master_is_a_whole_zone() {
    for (from, to, roller, a) in [
        // a floor shorter than the block, inside it
        (0.25, 0.75, false, 0.25),
        // the floor ends under the block, which it overhangs on the left
        (-0.5, 0.5, false, 0.25),
        // the block a symmetric half, the floor under its right half: the
        // zone [0.5, 1] is away from the symmetry line
        (0.5, 1.5, true, 0.25),
    ] {
        let (half, warned) = half_width(&block(from, to, roller));
        assert!((half - a).abs() <= 1e-9, "floor [{from}, {to}]: {half}");
        // the slave side does not run on past a corner: nothing to warn
        assert!(!warned, "floor [{from}, {to}]");
    }
}

/// A zone from the symmetry line of a half model is half of its mirrored
/// whole: its extent is the half-width, where it stops at the master's
/// end as where it stops at the body's corner (Old code: 0.5 and 0.5.)
#[test]
fn a_zone_from_a_symmetry_line_is_a_half() {
    // the floor ends at x = 0.5: the mirrored zone is [−0.5, 0.5]
    let (half, warned) = half_width(&block(-0.5, 0.5, true));
    assert!((half - 0.5).abs() <= 1e-9, "{half}");
    assert!(!warned);
    // the floor under the whole block: the mirrored zone is [−1, 1], and
    // without the rollers (the top held in x) the zone [0, 1] is whole
    let (half, _) = half_width(&block(-0.5, 1.5, true));
    assert!((half - 1.0).abs() <= 1e-9, "{half}");
    let (half, _) = half_width(&block(-0.5, 1.5, false));
    assert!((half - 0.5).abs() <= 1e-9, "{half}");
}

/// The shipped half models measure from their symmetry line: the Hertz
/// disk's diameter, the two cylinders' common diameter (though the lower
/// disk's arc, the master, ends on it as well), and the block held on
/// rollers, whose zone covers the bottom of a block 2 wide. The first two
/// keep the half-widths they had before the fix (the block had 0.5).
#[test]
fn shipped_half_models_measure_from_their_symmetry_line() {
    for (file, before) in [
        ("hertz.toml", 0.047110855600004),
        ("two_cylinders.toml", 0.040178031292192),
    ] {
        let (half, _) = half_width(&companion::shipped(file).unwrap());
        assert!((half / before - 1.0).abs() <= 1e-9, "{file}: {half}");
    }
    let (half, _) = half_width(&companion::shipped("block_compression.toml").unwrap());
    assert!((half - 1.0).abs() <= 1e-9, "{half}");
}
