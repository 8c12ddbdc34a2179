//! Prescribed displacements as a loading: supports with `value = …` drive
//! the contact problem with no load at all, and no body keeps a rigid
//! mode for contact to hold.

mod common;

use common::scene;
use iga_contact::post::{contact_resultant, PressureProfile};
use iga_contact::scene::{RefineSpec, Scene};
use iga_contact::solver::{solve, SolverKind, SolverOptions};

/// The shipped compression scene's data: E, ν, H and δ.
const YOUNG: f64 = 1.0e6;
const POISSON: f64 = 0.3;
const HEIGHT: f64 = 0.5;
const WIDTH: f64 = 1.0;
const DELTA: f64 = 1.0e-3;

/// The solvers every prescribed-displacement scene must pass: the default,
/// semismooth Newton, and the paper's BFGS over the whole body.
fn solvers() -> Vec<(&'static str, SolverOptions)> {
    vec![
        ("default", SolverOptions::default()),
        ("newton", SolverOptions::with_kind(SolverKind::Newton)),
        ("paper", SolverOptions::paper()),
    ]
}

fn compression(degree: usize, elements: [usize; 2], top: f64) -> Scene {
    let mut s = scene("block_compression.toml")
        .refined("block", RefineSpec::iga(degree, elements))
        .unwrap();
    s.supports[1].value = top;
    s
}

/// A block on a frictionless rigid floor, its top lowered by δ, sides
/// free: the exact solution is the uniform plane-strain state
/// σ_yy = −E/(1 − ν²)·δ/H, σ_xx = 0, with u_y = −δ y/H and
/// u_x = ν/(1 − ν)·δ x/H (the left side on rollers). It is linear, so
/// every degree and mesh holds it exactly and Nitsche's method is
/// consistent with it (zero gap, P = σ_n): the discrete solution is exact
/// to round-off, here checked to 1e-10 in the pressure at the 20 sample
/// points of every slave element, the contact resultant and every
/// control-point displacement.
#[test]
fn a_prescribed_top_displacement_compresses_the_block_exactly() {
    let sigma_yy = -YOUNG / (1.0 - POISSON * POISSON) * DELTA / HEIGHT;
    for (degree, elements) in [(1, [3, 2]), (2, [4, 1]), (3, [5, 3])] {
        let p = compression(degree, elements, -DELTA).build().unwrap();
        assert!(
            p.floating_modes().is_empty(),
            "the supports hold every rigid motion"
        );
        for (name, opts) in solvers() {
            let what = format!("p = {degree}, {elements:?}, {name}");
            let s = solve(&p, &opts).unwrap_or_else(|e| panic!("{what}: {e}"));
            let profile = PressureProfile::dense(&p, &s.full).unwrap();
            for sample in profile.samples() {
                // the pressure on the floor is −σ_yy
                let err = (sample.pressure() + sigma_yy).abs() / sigma_yy.abs();
                assert!(
                    err <= 1e-10,
                    "{what}: pressure at x = {:?}: {err:.1e}",
                    sample.x
                );
            }
            let f = contact_resultant(&p, &s.full);
            assert!(
                f[0].abs() <= 1e-10 * sigma_yy.abs() * WIDTH,
                "{what}: {f:?}"
            );
            assert!(
                (f[1] + sigma_yy * WIDTH).abs() <= 1e-10 * sigma_yy.abs() * WIDTH,
                "{what}: {f:?}"
            );
            let pts = &p.bodies[0].space.patch.points;
            for (a, x) in pts.iter().enumerate() {
                let exact = [
                    POISSON / (1.0 - POISSON) * DELTA * x[0] / HEIGHT,
                    -DELTA * x[1] / HEIGHT,
                ];
                for comp in 0..2 {
                    let u = s.full[p.map.global(0, a, comp)];
                    assert!(
                        (u - exact[comp]).abs() <= 1e-10 * DELTA,
                        "{what}: control point {a}, component {comp}: {u} vs {}",
                        exact[comp]
                    );
                }
            }
        }
    }
}

/// The top lifted instead: the floor cannot pull, so the block follows
/// its top as a rigid body, with no stress and no contact force.
#[test]
fn a_lifted_top_takes_the_block_off_the_floor() {
    let p = compression(2, [4, 1], DELTA).build().unwrap();
    for (name, opts) in solvers() {
        let s = solve(&p, &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
        let f = contact_resultant(&p, &s.full);
        assert_eq!(f, [0.0, 0.0], "{name}");
        for a in 0..p.bodies[0].space.patch.points.len() {
            let u = [s.full[p.map.global(0, a, 0)], s.full[p.map.global(0, a, 1)]];
            assert!(u[0].abs() <= 1e-12 * DELTA, "{name}: {u:?}");
            assert!((u[1] - DELTA).abs() <= 1e-12 * DELTA, "{name}: {u:?}");
        }
    }
}

/// Lamé's cylinder under internal pressure on the exact quarter annulus,
/// held by its symmetry supports only, with its outer arc as the slave
/// side of a contact pair against a floor it never reaches: the contact
/// solve needs no floating mode, ends with every point open, and returns
/// the linear elastic solution of the same mesh, which converges to Lamé's
/// (the example `lame` measures the rates; here the displacement at the
/// inner arc, the largest, is within 1e-3 of Lamé's on 8², where the
/// energy error of p = 2 is of order 1e-4).
#[test]
fn the_annulus_held_by_supports_alone_is_lames() {
    let text = r#"
[[body]]
name = "annulus"
geometry = { quarter_annulus = { inner_radius = 1.0, outer_radius = 2.0 } }
refine = { degree = 2, elements = [8, 8] }
material = { young = 1.0e5, poisson = 0.3, plane = "strain" }

[[support]]
body = "annulus"
side = "xi_min"
component = "y"

[[support]]
body = "annulus"
side = "xi_max"
component = "x"

[[load]]
pressure = { body = "annulus", side = "eta_min", pressure = 100.0 }

[[contact]]
slave = "annulus"
slave_side = "eta_max"
master = { rigid_segment = { from = [-1.0, -0.5], to = [3.0, -0.5] } }
"#;
    let p = Scene::from_toml_str(text).unwrap().build().unwrap();
    assert!(p.floating_modes().is_empty());
    // the inner radius's exact radial displacement (Lamé, plane strain)
    let (a, b, e, nu, q) = (1.0f64, 2.0f64, 1.0e5, 0.3, 100.0);
    let c = q * a * a / (b * b - a * a);
    let u_r = |r: f64| (1.0 + nu) / e * c * ((1.0 - 2.0 * nu) * r + b * b / r);
    let mut reference: Option<Vec<f64>> = None;
    for (name, opts) in solvers() {
        let s = solve(&p, &opts).unwrap_or_else(|e| panic!("{name}: {e}"));
        assert_eq!(p.active_points(&s.u), 0, "{name}");
        assert!(s.warnings.is_empty(), "{name}: {:?}", s.warnings);
        // with every point open the answer is K u = f, whatever the solver
        match &reference {
            None => reference = Some(s.full.clone()),
            Some(r) => {
                let d = s
                    .full
                    .iter()
                    .zip(r)
                    .map(|(x, y)| (x - y).abs())
                    .fold(0.0, f64::max);
                assert!(d <= 1e-10 * u_r(a), "{name}: {d:.1e}");
            }
        }
        let pts = &p.bodies[0].space.patch.points;
        // the inner arc's end points lie on it (interpolatory corners)
        for (k, x) in pts.iter().enumerate() {
            let r = x[0].hypot(x[1]);
            if (r - a).abs() < 1e-12 && (x[0] == 0.0 || x[1] == 0.0) {
                let u = [s.full[p.map.global(0, k, 0)], s.full[p.map.global(0, k, 1)]];
                let radial = (u[0] * x[0] + u[1] * x[1]) / r;
                assert!(
                    (radial / u_r(a) - 1.0).abs() < 1e-3,
                    "{name}: {radial} vs {}",
                    u_r(a)
                );
            }
        }
    }
}
