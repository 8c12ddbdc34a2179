//! Errors found by building or checking a scene, beside the table of
//! refused scenes: a free rigid motion, a folded map, a formulation the
//! mesh cannot carry, a degenerate slave side.

use crate::text::{one_body, shipped_text};
use iga_contact::scene::Scene;
use iga_contact::Error;

#[test]
fn check_finds_a_free_rotation_without_assembling() {
    // A quarter annulus bearing on a concentric one: the contact normals
    // are radial, so rotation about the common centre is never resisted.
    let text = include_str!("../fixtures/rotating_annuli.toml");
    let scene = Scene::from_toml_str(text).unwrap();
    let e = scene
        .check(&iga_contact::resources::Budget::from_machine())
        .unwrap_err();
    assert!(e.to_string().contains("rotate about (0, 0)"), "{e}");
}

#[test]
fn geometry_errors_name_the_body() {
    // A bow-tie control net: the map folds.
    let text = one_body(
        "{ nurbs = { degree = [1, 1], knots_xi = [0.0, 0.0, 1.0, 1.0], \
           knots_eta = [0.0, 0.0, 1.0, 1.0], \
           control_points = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] } }",
        "",
    )
    .replace("\"b\"", "\"bowtie\"");
    let scene = Scene::from_toml_str(&text).unwrap();
    // a fault of the input, found by `check` as well as by the build: the
    // key of the geometry and the body's name, not a failure of the run
    for e in [
        scene.build().err().expect("a folded map was accepted"),
        scene
            .check(&iga_contact::resources::Budget::from_machine())
            .expect_err("check accepted a folded map"),
    ] {
        let msg = e.to_string();
        let Error::InvalidInput { field, value, .. } = &e else {
            panic!("not an input error: {msg}");
        };
        assert_eq!(
            (field.as_str(), value.as_str()),
            ("body[0].geometry", "nurbs")
        );
        assert!(msg.contains("(body \"bowtie\")"), "{msg}");
        assert!(msg.contains("det J = 0"), "{msg}");
    }
}

/// `mixed` needs a continuous pressure space of degree p − 1 on the body's
/// knots: none at p = 1, a discontinuous one on a C⁰ Lagrange mesh. Both
/// are refused naming the formulation, and `local_mixed` runs on each.
#[test]
fn mixed_needs_degree_two_and_a_k_refined_body() {
    for refine in [
        "{ degree = 1, elements = [4, 1] }",
        "{ lagrange = 2, elements = [4, 1] }",
    ] {
        // the minimal scene (a block on a rigid floor), refined and
        // formulated as this case says
        let minimal = shipped_text("minimal.toml");
        let text = minimal.replace(
            "refine = { degree = 2, elements = [4, 1] }",
            &format!("refine = {refine}\nformulation = \"mixed\""),
        );
        assert!(
            text.contains("formulation"),
            "minimal.toml changed its refine line"
        );
        let Err(Error::InvalidInput { field, reason, .. }) = Scene::from_toml_str(&text) else {
            panic!("mixed accepted with refine = {refine}");
        };
        assert_eq!(field, "body[0].formulation", "{refine}: {reason}");
        assert!(reason.contains("local_mixed"), "{refine}: {reason}");
        let local = text.replace("\"mixed\"", "\"local_mixed\"");
        let run = Scene::from_toml_str(&local).and_then(|s| s.build());
        assert!(
            run.is_ok(),
            "{refine}: local_mixed refused: {:?}",
            run.err()
        );
    }
}

#[test]
fn a_degenerate_slave_side_is_not_reported_as_the_master() {
    // A quadratic bottom side whose first two control points coincide: its
    // tangent vanishes at t = 0, where the floor's end projects.
    let text = r#"
[[body]]
name = "pinched"
geometry = { nurbs = { degree = [2, 1], knots_xi = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0], knots_eta = [0.0, 0.0, 1.0, 1.0], control_points = [[0.0, 0.0], [0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 1.0], [1.0, 1.0]] } }
material = { young = 1.0e6, poisson = 0.3, plane = "strain" }

[[support]]
body = "pinched"
side = "xi_min"
component = "x"

[[contact]]
slave = "pinched"
slave_side = "eta_min"
master = { rigid_segment = { from = [-0.5, 0.0], to = [1.5, 0.0] } }
"#;
    let Err(e) = Scene::from_toml_str(text).and_then(|s| s.build()) else {
        panic!("a side with a vanishing tangent was accepted");
    };
    let msg = e.to_string();
    assert!(!msg.contains("master"), "{msg}");
    assert!(
        msg.contains("contact[0]: the slave side eta_min of body \"pinched\"")
            && msg.contains("degenerate"),
        "{msg}"
    );
}
