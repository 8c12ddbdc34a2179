//! Degenerate but well-posed problems: no floating mode, no contact point,
//! no interior DOF, no load, no free DOF. Each reaches a dense or sparse
//! factorisation or eigenproblem with an empty or trivial input (the
//! floating guard's eigenproblem over zero modes, the condensation's
//! ordering of an empty interior, the trace kernel of a layer that is the
//! whole problem) and must give the exact answer, not a panic.

mod common;

use common::scene;
use iga_contact::nurbs::Side;
use iga_contact::post::contact_resultant;
use iga_contact::scene::{Component, RefineSpec, Scene, SupportAt};
use iga_contact::solver::{solve, Factorisation, IterationSpace, SolverKind, SolverOptions, Start};
use iga_contact::Error;

const DELTA: f64 = 1.0e-3;
const HEIGHT: f64 = 0.5;
const SIGMA: f64 = 1.0e6 / (1.0 - 0.3 * 0.3) * DELTA / HEIGHT;

/// Every way to run the solvers: both kinds and the uncorrected BFGS,
/// both starts, every factorisation, both spaces, and θ = 1 (whose
/// kernels are never symmetric positive definite: the LU path).
fn variants() -> Vec<(String, SolverOptions)> {
    let mut out = vec![("paper".to_string(), SolverOptions::paper())];
    for kind in [
        SolverKind::Bfgs,
        SolverKind::BfgsNoCorrection,
        SolverKind::Newton,
    ] {
        for start in [Start::Secant, Start::Tied] {
            for (factorisation, space) in [
                (Factorisation::Auto, IterationSpace::Auto),
                (Factorisation::Auto, IterationSpace::Body),
                (Factorisation::LowRank, IterationSpace::Body),
                (Factorisation::Lu, IterationSpace::Body),
            ] {
                out.push((
                    format!("{kind:?}, {start:?}, {factorisation:?}, {space:?}"),
                    SolverOptions {
                        kind,
                        start,
                        factorisation,
                        space,
                        ..SolverOptions::default()
                    },
                ));
            }
        }
    }
    out
}

/// The compression scene with its top lowered by `top`, its mesh and
/// floor replaced, and θ set.
fn block(top: f64, degree: usize, elements: [usize; 2], floor_y: f64, theta: i32) -> Scene {
    let text = std::fs::read_to_string(companion::shipped_path("block_compression.toml"))
        .unwrap()
        .replace(
            "from = [-0.5, 0.0], to = [1.5, 0.0]",
            &format!("from = [-0.5, {floor_y:?}], to = [1.5, {floor_y:?}]"),
        )
        .replace("value = -1.0e-3", &format!("value = {top:?}"));
    Scene::from_toml_str(&text)
        .unwrap()
        .refined("block", RefineSpec::iga(degree, elements))
        .unwrap()
        .with_nitsche(|n| {
            n.theta = iga_contact::contact::Theta::from_value(theta as f64).unwrap();
        })
}

/// What the block must do: a rigid motion by `shift` in y with no force,
/// or the uniform compression of the closed form.
enum Exact {
    Rigid(f64),
    Compressed,
}

fn check(name: &str, s: Scene, exact: Exact) {
    let p = s.build().unwrap();
    assert!(p.floating_modes().is_empty(), "{name}");
    for (how, opts) in variants() {
        let what = format!("{name}, {how}");
        let sol = solve(&p, &opts).unwrap_or_else(|e| panic!("{what}: {e}"));
        let f = contact_resultant(&p, &sol.full);
        let pts = &p.bodies[0].space.patch.points;
        match exact {
            Exact::Rigid(shift) => {
                assert_eq!(f, [0.0, 0.0], "{what}");
                for a in 0..pts.len() {
                    let u = [
                        sol.full[p.map.global(0, a, 0)],
                        sol.full[p.map.global(0, a, 1)],
                    ];
                    assert!(
                        u[0].abs() <= 1e-12 * DELTA && (u[1] - shift).abs() <= 1e-12 * DELTA,
                        "{what}: {u:?}"
                    );
                }
            }
            Exact::Compressed => {
                assert!((f[1] / SIGMA - 1.0).abs() <= 1e-10, "{what}: {f:?}");
                for (a, x) in pts.iter().enumerate() {
                    let uy = sol.full[p.map.global(0, a, 1)];
                    assert!(
                        (uy + DELTA * x[1] / HEIGHT).abs() <= 1e-10 * DELTA,
                        "{what}"
                    );
                }
            }
        }
    }
}

/// Supports hold the block, the top is pushed down onto the floor: the
/// floating guard has no mode to guard (its eigenproblem would be 0 × 0).
#[test]
fn a_block_held_by_supports_is_compressed_by_every_solver() {
    for theta in [-1, 0, 1] {
        check(
            &format!("θ = {theta}"),
            block(-DELTA, 2, [4, 1], 0.0, theta),
            Exact::Compressed,
        );
    }
}

/// One linear element, four free DOFs: the condensation's interior is a
/// single DOF (the top corner's u_x, which σ_n on the bottom does not
/// see) and the trace kernel is 3 × 3.
#[test]
fn a_single_element_is_the_smallest_problem() {
    let s = block(-DELTA, 1, [1, 1], 0.0, -1);
    let p = s.build().unwrap();
    assert_eq!((p.n(), p.layer().len()), (4, 3));
    check("1 element", s, Exact::Compressed);
}

/// The floor out of reach (below the block by more than δ, or off to the
/// side, where no slave point projects onto it and the pair has no
/// contact point at all): the block follows its top rigidly.
#[test]
fn an_unreached_floor_leaves_the_block_rigid() {
    check(
        "floor below",
        block(-DELTA, 2, [4, 1], -1.0, 0),
        Exact::Rigid(-DELTA),
    );
    let far = std::fs::read_to_string(companion::shipped_path("block_compression.toml"))
        .unwrap()
        .replace(
            "from = [-0.5, 0.0], to = [1.5, 0.0]",
            "from = [5.0, 0.0], to = [6.0, 0.0]",
        );
    let s = Scene::from_toml_str(&far).unwrap();
    assert!(s.build().unwrap().points.is_empty(), "no contact point");
    check("floor aside", s, Exact::Rigid(-DELTA));
}

/// Nothing moves: zero prescribed displacement and no load, so the
/// residual is zero at the start.
#[test]
fn zero_data_gives_zero_displacement() {
    check("zero", block(0.0, 2, [4, 1], 0.0, 0), Exact::Rigid(0.0));
}

/// Every DOF prescribed: refused as input, naming the supports.
#[test]
fn no_free_dof_is_refused_as_input() {
    let mut s = block(-DELTA, 1, [2, 1], 0.0, 0);
    let mut more = s.supports[0].clone();
    for (side, comp) in [
        (Side::EtaMin, Component::X),
        (Side::EtaMin, Component::Y),
        (Side::EtaMax, Component::X),
        (Side::XiMax, Component::X),
    ] {
        more.at = SupportAt::Side(side);
        more.component = comp;
        s.supports.push(more.clone());
    }
    let err = s.build().err().expect("nothing to solve");
    assert!(matches!(err, Error::InvalidInput { .. }), "{err}");
    assert!(err.to_string().contains("supports"), "{err}");
}

/// The scene file shipped for the benchmark is the one these tests vary.
#[test]
fn the_shipped_scene_is_the_compression_benchmark() {
    let s = scene("block_compression.toml");
    assert_eq!(s.supports[1].value, -DELTA);
}
