//! The memory estimate counts the DOFs the solve has: `check` printed an
//! estimate built on 200 DOFs for the Hertz scene whose solve has 190 (the
//! diameter's 10 supported components), and counted the control points a
//! multi-patch body's matching interfaces share once per patch.

mod common;
use iga_contact::scene::Scene;

/// The estimate's DOFs and the solve's free DOFs of `scene`.
fn counts(scene: &Scene) -> (f64, usize) {
    let estimate = scene.estimate().unwrap();
    let problem = scene.build().unwrap();
    (estimate.dofs, problem.map.n_free())
}

#[test]
fn the_estimate_counts_the_free_dofs_of_every_shipped_scene() {
    let dir = companion::shipped_path("");
    let mut files: Vec<_> = std::fs::read_dir(&dir)
        .unwrap()
        .map(|e| e.unwrap().path())
        .filter(|p| p.extension().is_some_and(|x| x == "toml"))
        .collect();
    files.sort();
    assert!(files.len() >= 10, "{files:?}");
    for f in files {
        let scene = Scene::load(&f).unwrap();
        let (estimated, solved) = counts(&scene);
        assert_eq!(estimated, solved as f64, "{}", f.display());
    }
}

/// Supports that overlap (two sides through one corner holding the same
/// component, one side holding both) and a point support on a corner that
/// patches share are each counted once.
#[test]
fn overlapping_supports_and_shared_corners_are_counted_once() {
    let block = |supports: &str| {
        Scene::from_toml_str(&format!(
            r#"
title = "block"
[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 }} }}
refine = {{ degree = 3, elements = [5, 3] }}
material = {{ young = 1.0e6, poisson = 0.3, plane = "strain" }}
{supports}
[[load]]
pressure = {{ body = "block", side = "eta_max", pressure = 1.0e3 }}
[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-0.5, 0.0], to = [1.5, 0.0] }} }}
"#
        ))
        .unwrap()
    };
    let support = |side: &str, comp: &str| {
        format!("[[support]]\nbody = \"block\"\nside = \"{side}\"\ncomponent = \"{comp}\"\n")
    };
    let held = [
        support("xi_min", "x") + &support("eta_max", "x"),
        support("xi_min", "x") + &support("xi_min", "y"),
        support("xi_min", "x")
            + "[[support]]\nbody = \"block\"\npoint = [0.0, 0.5]\ncomponent = \"x\"\n",
    ];
    for s in held {
        let (estimated, solved) = counts(&block(&s));
        assert_eq!(estimated, solved as f64, "{s}");
    }
    // the full five-patch disk held at two points of its centre line,
    // whose corners three patches share
    let mut disk = common::scene("disk_full.toml");
    disk.output = Default::default();
    for n in [2, 5] {
        disk.bodies[0].refine = Some(iga_contact::scene::RefineSpec::iga(3, [n, n]));
        let (estimated, solved) = counts(&disk);
        assert_eq!(estimated, solved as f64, "{n}");
    }
}
