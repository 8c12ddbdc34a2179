//! Multi-patch keys, checked: patch sides, boundaries, masters and point
//! supports refused with one error line; point supports at patch corners
//! hold the body; a ceiling under a climbing boundary is refused; the
//! locking advice for a multi-patch body is refinement, not `mixed`.

use crate::common::shipped_text;
use crate::{rel, R};
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, Warning};
use std::f64::consts::PI;

#[test]
fn multi_patch_keys_are_checked_with_one_error_line() {
    let base = shipped_text("hertz_multipatch.toml");
    let cases = [
        // a patch side on a body of several patches
        (
            "boundary = \"straight\"",
            "side = \"xi_min\"",
            "support[0].side",
        ),
        // a boundary the builder does not define
        (
            "slave_boundary = \"arc_lower\"",
            "slave_boundary = \"rim\"",
            "contact[0].slave_boundary",
        ),
        // a multi-patch body as master: refused with the swap as advice
        (
            "master = { rigid_segment = { from = [-0.2, 0.0], to = [0.4, 0.0] } }",
            "master = { body = \"disk\", side = \"eta_min\" }",
            "contact[0].master.body",
        ),
        // a point support off the patch corners: the centre
        (
            "boundary = \"straight\"",
            "point = [0.05, 0.2]",
            "support[0].point",
        ),
    ];
    for (from, to, field) in cases {
        let text = base.replacen(from, to, 1);
        let e = Scene::from_toml_str(&text)
            .and_then(|s| s.build().map(|_| ()))
            .expect_err(to);
        let msg = e.to_string();
        assert!(msg.contains(field), "{to}: {msg}");
        if field.ends_with("master.body") {
            assert!(msg.contains("make the multi-patch body the slave"), "{msg}");
        }
        assert!(!msg.contains('\n'), "{msg}");
    }
    // a traction on a patch side of the multi-patch body: refused with
    // advice a load can follow (a load has no `boundary` key)
    let text = format!(
        "{base}\n[[load]]\ntraction = {{ body = \"disk\", side = \"eta_max\", traction = [0.0, -1.0] }}\n"
    );
    let msg = Scene::from_toml_str(&text)
        .and_then(|s| s.build().map(|_| ()))
        .expect_err("a traction on a multi-patch body")
        .to_string();
    assert!(msg.contains("load[1].traction.side"), "{msg}");
    assert!(
        msg.contains("body_force") && !msg.contains("`boundary`"),
        "{msg}"
    );
}

#[test]
fn point_supports_at_patch_corners_hold_the_body() {
    // the straight side held by two point supports in x at patch corners
    // (the core's corners on the diameter) instead of the whole side: the
    // body is still held (the well-posedness check passes) and in x only
    // there, so the contact force balances the load
    let base = shipped_text("hertz_multipatch.toml");
    let text = base.replacen(
        "boundary = \"straight\"\ncomponent = \"x\"\nvalue = 0.0",
        "point = [0.0, 0.12]\ncomponent = \"x\"\n\n[[support]]\nbody = \"disk\"\npoint = [0.0, 0.28]\ncomponent = \"x\"",
        1,
    );
    assert_ne!(text, base);
    let scene = Scene::from_toml_str(&text).unwrap();
    let problem = scene.build().unwrap();
    let sol = solve(&problem, &scene.solver).unwrap();
    let f = iga_contact::post::contact_resultant(&problem, &sol.full);
    let load = 1.3e6 * PI * R * R / 2.0;
    assert!(rel(f[1], load) < 1e-8, "{f:?}");
    // without supports the x slide of the whole body, all its patches
    // together, is free: refused, naming the body
    let mut none = Scene::from_toml_str(&base).unwrap();
    none.supports.clear();
    let e = none.build().err().expect("refused");
    assert!(
        e.to_string().contains("body[0]") && e.to_string().contains("slide"),
        "{e}"
    );
}

#[test]
fn a_ceiling_under_a_boundary_that_climbs_the_sides_is_refused() {
    // disk_5 in the axes layout: `arc_lower` runs from 135° through the
    // bottom to 45°, so its ends face upwards. Under a floor drawn from
    // right to left (a ceiling: the obstacle above y = 0 holds the whole
    // disk) every point starts closed and the upper ends face the
    // obstacle; the lower two thirds face away and carry the refusal.
    let base = shipped_text("disk_full.toml");
    let axes = base.replacen("layout = \"diagonal\"", "layout = \"axes\"", 1);
    let drop_supports = |t: &str| {
        t.split("[[support]]")
            .enumerate()
            .map(|(i, part)| {
                if i == 0 {
                    part.to_string()
                } else {
                    // keep what follows the support's three lines
                    part.splitn(5, '\n').nth(4).unwrap_or("").to_string()
                }
            })
            .collect::<String>()
    };
    let axes = drop_supports(&axes);
    assert!(!axes.contains("component"), "{axes}");
    let ceiling = axes.replacen(
        "from = [-0.4, 0.0], to = [0.4, 0.0]",
        "from = [0.4, 0.0], to = [-0.4, 0.0]",
        1,
    );
    let e = Scene::from_toml_str(&ceiling)
        .and_then(|s| s.build().map(|_| ()))
        .expect_err("a ceiling holding the disk");
    let msg = e.to_string();
    assert!(msg.contains("`contact[0].master`"), "{msg}");
    assert!(msg.contains("from [0.4, 0.0] to [-0.4, 0.0]"), "{msg}");
    assert!(msg.contains("swap `from` and `to`"), "{msg}");
    // the floor as drawn in the shipped file passes this check: what stops
    // the build (if anything) is no longer the contact's direction
    if let Err(e) = Scene::from_toml_str(&axes).and_then(|s| s.build().map(|_| ())) {
        assert!(!e.to_string().contains("contact[0].master"), "{e}");
    }
}

#[test]
fn a_locking_multi_patch_body_is_told_to_refine_not_to_go_mixed() {
    // the mixed formulation is refused on a body of several patches, so
    // the locking warning of one may only advise the finer mesh
    let base = shipped_text("hertz_multipatch.toml");
    let nu = base.replacen("poisson = 0.1", "poisson = 0.4999", 1);
    assert_ne!(nu, base);
    let report = Scene::from_toml_str(&nu)
        .unwrap()
        .check(&iga_contact::resources::Budget::from_machine())
        .unwrap();
    let locking: Vec<String> = report
        .warnings
        .iter()
        .filter(|w| matches!(w, Warning::NearlyIncompressible { .. }))
        .map(|w| w.to_string())
        .collect();
    assert_eq!(locking.len(), 1, "{:?}", report.warnings);
    assert!(
        locking[0].contains("refine it to at least"),
        "{}",
        locking[0]
    );
    assert!(!locking[0].contains("set formulation"), "{}", locking[0]);
    // the advice the warning does not give is indeed refused
    let mixed = nu.replacen("material = {", "formulation = \"mixed\"\nmaterial = {", 1);
    let e = Scene::from_toml_str(&mixed)
        .and_then(|s| s.build().map(|_| ()))
        .expect_err("mixed on a multi-patch body");
    assert!(e.to_string().contains("one-patch bodies only"), "{e}");
}
