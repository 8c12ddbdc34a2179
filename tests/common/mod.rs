//! Helpers shared by the integration tests.

#![allow(dead_code)] // each test file uses a different subset

use iga_contact::contact::{Integration, Theta};
use iga_contact::problem::Problem;
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::{solve, SolverKind, SolverOptions};
use std::path::PathBuf;

/// A shipped scene file, loaded.
pub fn scene(file: &str) -> Scene {
    Scene::shipped(file).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The Hertz scene with p = `degree` on `elements`² and the given θ.
pub fn hertz_scene(degree: usize, elements: usize, theta: Theta) -> Scene {
    let mut s = scene("hertz.toml");
    s.bodies[0].refine = Some(RefineSpec::iga(degree, [elements, elements]));
    for n in s.nitsche_mut() {
        n.theta = theta;
    }
    s
}

/// [`hertz_scene`], built.
pub fn hertz(degree: usize, elements: usize, theta: Theta) -> Problem {
    hertz_scene(degree, elements, theta)
        .build()
        .expect("the Hertz scene builds")
}

/// The Taylor scene with the given contact rule and θ.
pub fn taylor_scene(integration: Integration, theta: Theta) -> Scene {
    let mut s = scene("taylor.toml");
    for n in s.nitsche_mut() {
        n.integration = integration;
        n.theta = theta;
    }
    s
}

/// [`taylor_scene`], built.
pub fn taylor(integration: Integration, theta: Theta) -> Problem {
    taylor_scene(integration, theta)
        .build()
        .expect("the Taylor scene builds")
}

/// The binary of the chapter program `name` (built by `cargo test` next to
/// the test binaries, in the same profile).
pub fn example(name: &str) -> PathBuf {
    let exe = std::env::current_exe().expect("the test binary has a path");
    let profile = exe
        .parent()
        .and_then(|d| d.parent())
        .expect("target/<profile>/deps");
    profile.join("examples").join(name)
}

/// n deterministic pseudo-random values in [−½, ½) (a 64-bit LCG).
pub fn rough(n: usize, mut seed: u64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        })
        .collect()
}

/// The Newton solution of `p` plus `amplitude` · max|u| · `rough(n, seed)`.
pub fn perturbed_solution(p: &Problem, amplitude: f64, seed: u64) -> Vec<f64> {
    let s = solve(p, &SolverOptions::with_kind(SolverKind::Newton)).expect("converges");
    let umax = s.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    s.u.iter()
        .zip(rough(p.n(), seed))
        .map(|(v, e)| v + amplitude * umax * e)
        .collect()
}

pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}
