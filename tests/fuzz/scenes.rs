//! The shipped scenes the mutations start from, and what every scene input
//! must do: parse, build when valid and small, and never panic; every error
//! names a place in the scene.

use iga_contact::scene::{GeometrySpec, Scene};

pub const SCENES: [&str; 4] = [
    include_str!("../../data/scenes/taylor.toml"),
    include_str!("../../data/scenes/hertz.toml"),
    include_str!("../../data/scenes/hertz_fem_q2.toml"),
    include_str!("../../data/scenes/minimal.toml"),
];

/// Scenes small enough to build in a millisecond or so.
fn small(scene: &Scene) -> bool {
    let ok_quad = |q: Option<usize>| q.is_none_or(|q| q <= 8);
    scene.bodies.iter().all(|b| {
        let geometry_ok = match &b.geometry {
            GeometrySpec::Nurbs(n) => {
                n.degree.iter().all(|&p| p <= 4)
                    && n.knots_xi.len() <= 24
                    && n.knots_eta.len() <= 24
            }
            _ => true,
        };
        let refine_ok = b
            .refine
            .as_ref()
            .is_none_or(|r| r.elements().iter().all(|&n| n <= 8) && r.degree() <= 4);
        geometry_ok && refine_ok && ok_quad(b.quadrature)
    }) && scene
        .contacts
        .iter()
        .all(|c| ok_quad(c.nitsche.gauss_points))
        && scene.bodies.len() <= 4
}

/// Top-level keys of a scene, and the names of non-key locations.
const ROOTS: [&str; 10] = [
    "title",
    "allow_underintegration",
    "body",
    "support",
    "load",
    "contact",
    "solver",
    "output",
    "scene",
    "line",
];

/// An error names a place in the scene: a key path below a top-level key
/// (`body[0].geometry.full_disk.radius`), a line of the text, or the scene.
fn assert_names_a_scene_key(e: &iga_contact::Error) {
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "multi-line error: {msg}");
    if let iga_contact::Error::InvalidInput { field, reason, .. } = e {
        // An unknown key is named where the text has it.
        let root = field.split(['.', '[', ' ']).next().unwrap_or("");
        assert!(
            ROOTS.contains(&root) || reason.starts_with("unknown field"),
            "`{field}` is not a scene key path: {msg}"
        );
    }
}

/// Parses, and builds what validates and is small. Must not panic, and
/// every error must name a scene key.
pub fn parse_and_build(text: &str) {
    match Scene::from_toml_str(text) {
        Ok(scene) => {
            if small(&scene) {
                if let Err(e) = scene.build() {
                    assert_names_a_scene_key(&e);
                }
            }
        }
        Err(e) => assert_names_a_scene_key(&e),
    }
}
