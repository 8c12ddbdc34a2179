//! Scale invariance: a scene written in other units is the same problem,
//! so it must take the same iterations to the same answer. Every shipped
//! scene is rescaled exactly — lengths by L, moduli and tractions by s,
//! body forces by s/L, prescribed displacements by L — and solved for
//! L = 1e-9 … 1e9 and s = 1e-6 … 1e12 (and both at once); the iteration
//! count, the warnings and the solution (u/L, p₀/s) must match the unit
//! scene's to 1e-8.
//!
//! Before the rigid modes were judged in a dimensionless basis, Hertz 16²
//! failed for L ≤ 1e-5 and L ≥ 1e6 with both solvers: the x translation,
//! held by the symmetry support, was counted as floating once the
//! rotation's size² outweighed it by 1e10.

use iga_contact::post::PressureProfile;
use iga_contact::scene::Scene;
use iga_contact::solver::{solve, SolverKind, SolverOptions};
use toml::Value;

/// How a key's value scales: as a length, a stress, or a force per volume.
#[derive(Clone, Copy)]
enum Unit {
    Length,
    Stress,
    ForcePerVolume,
}

fn unit_of(key: &str) -> Option<Unit> {
    match key {
        "center" | "radius" | "inner_radius" | "outer_radius" | "x0" | "y0" | "x1" | "y1"
        | "corners" | "control_points" | "from" | "to" | "value" | "point" => Some(Unit::Length),
        "young" | "pressure" | "traction" => Some(Unit::Stress),
        "force" => Some(Unit::ForcePerVolume),
        _ => None,
    }
}

fn scale_numbers(v: &mut Value, by: f64) {
    match v {
        Value::Float(x) => *x *= by,
        Value::Integer(i) => *v = Value::Float(*i as f64 * by),
        Value::Array(a) => a.iter_mut().for_each(|x| scale_numbers(x, by)),
        _ => {}
    }
}

fn rescale(v: &mut Value, length: f64, stiffness: f64) {
    match v {
        Value::Table(t) => {
            for (key, value) in t.iter_mut() {
                match unit_of(key) {
                    // `pressure` names both a load kind (a table) and its value.
                    Some(unit) if !value.is_table() => scale_numbers(
                        value,
                        match unit {
                            Unit::Length => length,
                            Unit::Stress => stiffness,
                            Unit::ForcePerVolume => stiffness / length,
                        },
                    ),
                    _ => rescale(value, length, stiffness),
                }
            }
        }
        Value::Array(a) => a.iter_mut().for_each(|x| rescale(x, length, stiffness)),
        _ => {}
    }
}

/// The shipped scene `file` in units where one length is `length` and one
/// stress `stiffness`, with `solver` if given instead of the scene's own.
fn scaled(file: &str, length: f64, stiffness: f64, solver: Option<SolverKind>) -> Scene {
    let text = std::fs::read_to_string(companion::shipped_path(file)).unwrap();
    let mut value: Value = toml::from_str(&text).unwrap();
    rescale(&mut value, length, stiffness);
    if let Some(t) = value.as_table_mut() {
        t.remove("output");
        if let Some(kind) = solver {
            t.remove("solver");
            let mut scene = Scene::from_toml_str(&toml::to_string(&value).unwrap()).unwrap();
            scene.solver = SolverOptions {
                kind,
                ..SolverOptions::default()
            };
            return scene;
        }
    }
    Scene::from_toml_str(&toml::to_string(&value).unwrap()).unwrap()
}

/// What must not depend on the units: iterations, warnings (by kind), the
/// solution in units of L, and p₀ in units of s.
struct Answer {
    iterations: usize,
    warnings: Vec<String>,
    u: Vec<f64>,
    p0: Option<f64>,
}

fn answer(scene: &Scene, length: f64, stiffness: f64) -> Answer {
    let problem = scene.build().unwrap();
    let solution = solve(&problem, &scene.solver)
        .unwrap_or_else(|e| panic!("L = {length:e}, s = {stiffness:e}: {e}"));
    let p0 = (!problem.points.is_empty()).then(|| {
        PressureProfile::dense(&problem, &solution.full)
            .unwrap()
            .measures(0)
            .p0
            / stiffness
    });
    Answer {
        iterations: solution.history.rows.len(),
        warnings: solution
            .warnings
            .iter()
            .map(|w| format!("{:?}", std::mem::discriminant(w)))
            .collect(),
        u: solution.full.iter().map(|x| x / length).collect(),
        p0,
    }
}

fn assert_same(reference: &Answer, got: &Answer, what: &str) {
    assert_eq!(
        reference.iterations, got.iterations,
        "{what}: iterations differ"
    );
    assert_eq!(reference.warnings, got.warnings, "{what}: warnings differ");
    let size = reference.u.iter().fold(0.0_f64, |m, x| m.max(x.abs()));
    let off = reference
        .u
        .iter()
        .zip(&got.u)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(off <= 1e-8 * size, "{what}: |Δ(u/L)| = {off:e} of {size:e}");
    if let (Some(a), Some(b)) = (reference.p0, got.p0) {
        assert!(
            (a - b).abs() <= 1e-8 * a.abs(),
            "{what}: p₀/s = {b:e} against {a:e}"
        );
    }
}

fn sweep(file: &str, solver: Option<SolverKind>) {
    let reference = answer(&scaled(file, 1.0, 1.0, solver), 1.0, 1.0);
    let decades = |lo: i32, hi: i32| (lo..=hi).map(|k| 10f64.powi(k));
    let cases = decades(-9, 9)
        .map(|l| (l, 1.0))
        .chain(decades(-6, 12).map(|s| (1.0, s)))
        .chain([(1e-9, 1e12), (1e9, 1e-6), (1e-6, 1e-6), (1e6, 1e9)]);
    for (length, stiffness) in cases {
        let got = answer(&scaled(file, length, stiffness, solver), length, stiffness);
        assert_same(
            &reference,
            &got,
            &format!("{file} ({solver:?}), L = {length:e}, s = {stiffness:e}"),
        );
    }
}

#[test]
fn hertz_with_the_papers_solver_is_the_same_in_any_units() {
    sweep("hertz.toml", None);
}

#[test]
fn hertz_with_the_default_solver_and_newton_is_the_same_in_any_units() {
    sweep("hertz.toml", Some(SolverKind::Bfgs));
    sweep("hertz.toml", Some(SolverKind::Newton));
}

#[test]
fn a_disk_on_a_block_is_the_same_in_any_units() {
    sweep("disk_on_block.toml", None);
}

/// Bodies of several patches, a slave boundary over patches, point
/// supports (the patch corner nearest a point, found to a tolerance
/// relative to the body's size) and the Lagrange mesh.
#[test]
fn multi_patch_bodies_point_supports_and_lagrange_meshes_are_the_same_in_any_units() {
    sweep("hertz_multipatch.toml", None);
    sweep("disk_full.toml", None);
    sweep("hertz_fem_q2.toml", None);
}

#[test]
fn two_cylinders_are_the_same_in_any_units() {
    sweep("two_cylinders.toml", None);
}

/// Conformal contact: a pin in a half annulus (a multi-patch slave on a
/// one-patch master, both elastic, touching along the whole interface
/// before the load).
#[test]
fn a_pin_in_a_ring_is_the_same_in_any_units() {
    sweep("pin_ring.toml", None);
}

#[test]
fn the_taylor_patch_test_is_the_same_in_any_units() {
    sweep("taylor.toml", None);
}

#[test]
fn a_block_pressed_down_is_the_same_in_any_units() {
    sweep("block_compression.toml", None);
}

#[test]
fn every_key_is_the_same_in_any_units() {
    sweep("every_key.toml", None);
    sweep("minimal.toml", None);
}

/// The chapter "Reliability" says each shipped scene is swept: a scene
/// added to `data/scenes/` without a sweep here fails this test.
#[test]
fn every_shipped_scene_is_swept() {
    let source = include_str!("scale.rs");
    let dir = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes");
    let mut missing = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name.ends_with(".toml") && !source.contains(&format!("sweep(\"{name}\"")) {
            missing.push(name);
        }
    }
    assert!(
        missing.is_empty(),
        "shipped scenes with no sweep: {missing:?}"
    );
}
