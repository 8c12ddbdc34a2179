//! Helpers shared by the integration tests.

#![allow(dead_code)] // each test file uses a different subset

pub mod affine;
pub mod block;

use iga_contact::assembly::Load;
use iga_contact::contact::{Integration, Theta};
use iga_contact::problem::Problem;
use iga_contact::scene::{GeometrySpec, RefineSpec, Scene, SlaveAt};
use iga_contact::solver::history::History;
use iga_contact::solver::{solve, SolverKind, SolverOptions};
use std::path::PathBuf;

/// `s` with the slave and master of its first contact swapped (on the
/// disk on the block: the block's top as slave, the disk as master).
pub fn swapped(mut s: Scene) -> Scene {
    let c = &mut s.contacts[0];
    let iga_contact::scene::MasterSpec::Body { body, side } = c.master.clone() else {
        panic!("the first contact has a rigid master: nothing to swap");
    };
    let SlaveAt::Side(slave_side) = std::mem::replace(&mut c.slave_at, SlaveAt::Side(side)) else {
        panic!("the first contact's slave is a boundary: no side to swap");
    };
    c.master = iga_contact::scene::MasterSpec::Body {
        body: std::mem::replace(&mut c.slave, body),
        side: slave_side,
    };
    s
}

/// A shipped scene file, loaded.
pub fn scene(file: &str) -> Scene {
    companion::shipped(file).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// The text of a shipped scene file, for tests that edit it before parsing.
pub fn shipped_text(file: &str) -> String {
    std::fs::read_to_string(companion::shipped_path(file)).unwrap_or_else(|e| panic!("{file}: {e}"))
}

/// Multiplies the vertical body force of `s` by `factor` (the heavy-load
/// cases of the Hertz scenes).
pub fn scale_body_force(s: &mut Scene, factor: f64) {
    for l in &mut s.loads {
        if let Load::BodyForce { force, .. } = l {
            force[1] *= factor;
        }
    }
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

/// Asserts that `a` and `b` record the same iteration: the same active
/// points and events row by row, residuals to 1e-4 (rows at the round-off
/// floor excepted). The last row, a confirmation at the round-off floor,
/// may come one iteration apart.
#[allow(dead_code)] // not every test crate compares histories
pub fn assert_same_iteration(a: &History, b: &History, what: &str) {
    let (la, lb) = (a.len(), b.len());
    assert!(la.abs_diff(lb) <= 1, "{what}: {la} against {lb} iterations");
    for (x, y) in a.rows.iter().zip(&b.rows).take(la.min(lb) - 1) {
        assert_eq!(
            x.active_points, y.active_points,
            "{what}, row {}",
            x.iteration
        );
        assert_eq!(x.events, y.events, "{what}, row {}", x.iteration);
        let rel = (x.residual - y.residual).abs() / y.residual.max(1e-300);
        assert!(
            rel <= 1e-4 || y.relative_residual < 1e-9,
            "{what}, row {}: residuals {:.6e} and {:.6e}",
            x.iteration,
            x.residual,
            y.residual
        );
    }
}

/// A Hertz case built from `data/scenes/hertz.toml` with the fields the
/// tests vary (the scene's values otherwise).
#[derive(Clone, Debug)]
pub struct HertzCase {
    pub degree: usize,
    pub elements: usize,
    pub theta: f64,
    pub penalty_factor: f64,
    pub integration: Integration,
    /// An isoparametric Lagrange mesh of this degree instead of IGA.
    pub lagrange: Option<usize>,
    /// The disk lifted above the floor by this much (negative: into it).
    pub lift: f64,
    /// The body force multiplied by this.
    pub load_scale: f64,
}

impl Default for HertzCase {
    fn default() -> Self {
        Self {
            degree: 2,
            elements: 8,
            theta: 0.0,
            penalty_factor: 1.0,
            integration: Integration::Gauss,
            lagrange: None,
            lift: 0.0,
            load_scale: 1.0,
        }
    }
}

impl HertzCase {
    pub fn scene(&self) -> Scene {
        let n = [self.elements, self.elements];
        let refine = match self.lagrange {
            Some(q) => RefineSpec::lagrange(q, n),
            None => RefineSpec::iga(self.degree, n),
        };
        let mut s = scene("hertz.toml")
            .refined("disk", refine)
            .unwrap()
            .with_nitsche(|n| {
                n.theta = Theta::from_value(self.theta).expect("θ ∈ {1, 0, −1}");
                n.penalty_factor = self.penalty_factor;
                n.integration = self.integration;
            });
        if let GeometrySpec::HalfDisk { center, .. } = &mut s.bodies[0].geometry {
            center[1] += self.lift;
        }
        for l in &mut s.loads {
            if let Load::BodyForce { force, .. } = l {
                force.iter_mut().for_each(|f| *f *= self.load_scale);
            }
        }
        s
    }

    pub fn build(&self) -> iga_contact::Result<Problem> {
        self.scene().build()
    }
}

/// A Taylor case built from `data/scenes/taylor.toml`.
#[derive(Clone, Debug)]
pub struct TaylorCase {
    pub theta: f64,
    pub penalty_factor: f64,
    pub integration: Integration,
    /// The upper block lifted by this much (negative: into the lower one).
    pub gap: f64,
    /// The upper block's Young's modulus multiplied by this.
    pub contrast: f64,
}

impl Default for TaylorCase {
    fn default() -> Self {
        Self {
            theta: 0.0,
            penalty_factor: 1.0,
            integration: Integration::Segment,
            gap: 0.0,
            contrast: 1.0,
        }
    }
}

impl TaylorCase {
    pub fn scene(&self) -> Scene {
        let mut s = scene("taylor.toml").with_nitsche(|n| {
            n.theta = Theta::from_value(self.theta).expect("θ ∈ {1, 0, −1}");
            n.penalty_factor = self.penalty_factor;
            n.integration = self.integration;
        });
        if let GeometrySpec::Rectangle { y0, y1, .. } = &mut s.bodies[1].geometry {
            *y0 += self.gap;
            *y1 += self.gap;
        }
        s.bodies[1].material.young *= self.contrast;
        s
    }

    pub fn build(&self) -> iga_contact::Result<Problem> {
        self.scene().build()
    }
}

/// The vertical load the contact must carry (the applied resultant, up).
pub fn vertical_load(p: &Problem) -> f64 {
    -iga_contact::post::applied_resultant(p).unwrap()[1]
}

/// The area of a patch by its own quadrature: the sum of the weights
/// (which carry det J) over every element.
pub fn area(space: &iga_contact::space::Space) -> f64 {
    space
        .elements
        .iter()
        .flat_map(|e| space.quadrature(e).unwrap())
        .map(|q| q.weight)
        .sum()
}
