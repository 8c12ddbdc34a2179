//! The shipped scenes (`data/scenes/`): each parses and builds, round-trips
//! through TOML, and agrees with what it stands for.

use crate::text::{shipped_text, BASE};
use iga_contact::scene::Scene;
use iga_contact::solver;
use std::path::Path;

#[test]
fn base_scene_is_valid_and_builds() {
    let scene = Scene::from_toml_str(BASE).unwrap();
    scene.build().unwrap();
}

#[test]
fn every_shipped_scene_parses_and_builds() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            scene
                .build()
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            n += 1;
        }
    }
    assert!(n >= 4, "expected at least the four shipped scenes");
}

#[test]
fn shipped_scenes_round_trip_through_toml() {
    for name in [
        "taylor.toml",
        "hertz.toml",
        "hertz_fem_q2.toml",
        "minimal.toml",
    ] {
        let scene = Scene::from_toml_str(&shipped_text(name)).unwrap();
        let text = toml::to_string(&scene).unwrap();
        let again = Scene::from_toml_str(&text).unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        assert_eq!(scene, again, "{name}");
    }
}

/// The Taylor scene as shipped passes the patch test: u_y = −0.1 on top.
#[test]
fn the_taylor_scene_passes_the_patch_test() {
    let scene = Scene::from_toml_str(&shipped_text("taylor.toml")).unwrap();
    let a = scene.build().unwrap();
    let sa = solver::solve(&a, &scene.solver).unwrap();
    let patch = &a.bodies[1].space.patch;
    for cp in patch.side_indices(iga_contact::nurbs::Side::EtaMax) {
        let uy = a.map.cp_displacement(&sa.full, 1, cp)[1];
        assert!((uy + 0.1).abs() < 1e-10, "u_y(top) = {uy}");
    }
}

/// The FEM Q2 scene is the IGA scene with a Lagrange mesh: same contact
/// force, and the DOF count of a Q2 mesh of 8² elements.
#[test]
fn the_fem_scene_differs_from_the_iga_scene_only_in_its_mesh() {
    let iga = Scene::from_toml_str(&shipped_text("hertz.toml")).unwrap();
    let fem = Scene::from_toml_str(&shipped_text("hertz_fem_q2.toml")).unwrap();
    let mut same = fem.clone();
    same.bodies[0].refine = iga.bodies[0].refine.clone();
    same.title = iga.title.clone();
    same.output = iga.output.clone();
    assert_eq!(same, iga);
    let (a, b) = (iga.build().unwrap(), fem.build().unwrap());
    assert_eq!(
        b.n(),
        2 * (17 * 17) - 17,
        "Q2 on 8²: 17 × 17 nodes, u_x = 0 on 17"
    );
    // each balances its own load; the loads differ by the Q2 geometry's
    // error in the disk's area
    for (p, scene) in [(&a, &iga), (&b, &fem)] {
        let f =
            iga_contact::post::contact_resultant(p, &solver::solve(p, &scene.solver).unwrap().full);
        let load = iga_contact::post::applied_resultant(p).unwrap();
        assert!(
            (f[1] + load[1]).abs() <= 1e-8 * load[1].abs(),
            "{f:?} vs {load:?}"
        );
    }
    let (la, lb) = (
        iga_contact::post::applied_resultant(&a).unwrap()[1],
        iga_contact::post::applied_resultant(&b).unwrap()[1],
    );
    assert!((la - lb).abs() <= 1e-5 * la.abs(), "{la} vs {lb}");
}
