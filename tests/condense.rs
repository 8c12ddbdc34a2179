//! Factorise once, condense onto the contact layer: the condensed residual
//! and kernels against the assembled full-space ones, and condensed solves
//! against full-space LU solves (the path of the paper's iteration before
//! the condensation).

mod common;

use common::{assert_same_iteration, perturbed_solution, rough};
use common::{HertzCase, TaylorCase};
use iga_contact::contact::nitsche::heaviside;
use iga_contact::contact::Integration;
use iga_contact::linsolve::{mul, Factoriser, Method};
use iga_contact::problem::{Kernel, Problem};
use iga_contact::solver::trace::{DenseLu, TraceProblem};
use iga_contact::solver::{
    solve, Factorisation, IterationSpace, Solution, SolverKind, SolverOptions,
};

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn diff(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(&d) / norm(b)
}

fn hertz(degree: usize, elements: usize, theta: f64) -> Problem {
    HertzCase {
        degree,
        elements,
        theta,
        ..HertzCase::default()
    }
    .build()
    .unwrap()
}

fn taylor(theta: f64) -> Problem {
    TaylorCase {
        theta,
        integration: Integration::Segment,
        ..TaylorCase::default()
    }
    .build()
    .unwrap()
}

/// The layer part of a free vector.
fn on_layer(t: &TraceProblem, free: &[f64]) -> Vec<f64> {
    t.condensation().layer().iter().map(|&i| free[i]).collect()
}

#[test]
fn the_condensed_residual_is_the_full_residual_of_the_recovered_body() {
    for (name, p) in [("hertz", hertz(2, 8, 0.0)), ("taylor", taylor(0.0))] {
        let t = TraceProblem::new(&p).unwrap();
        let u_l = on_layer(&t, &perturbed_solution(&p, 1e-3, 5));
        let u = t.recover(&u_l);
        let (full, state) = p.residual(&u);
        let (trace, tstate, floor) = t.residual_forced(&u_l, &[]);
        assert_eq!(state.active, tstate.active, "{name}");
        // the interior is relaxed: R_I = 0 up to round-off
        let layer = t.condensation().layer();
        let mut interior = full.clone();
        for &i in layer {
            interior[i] = 0.0;
        }
        let scale = norm(&p.rhs);
        assert!(
            norm(&interior) <= 1e-10 * scale,
            "{name}: R_I {:.2e}",
            norm(&interior) / scale
        );
        let d = diff(&trace, &on_layer(&t, &full));
        assert!(d <= 1e-8, "{name}: R̂ against R_L: {d:.2e}");
        assert!(
            floor.typical > 0.0 && floor.typical <= floor.cancelling,
            "{name}: floor {floor:?}"
        );
        assert!(floor.cancelling < 1e-10 * scale, "{name}: floor {floor:?}");
    }
}

/// T(H) is the Schur complement of the assembled kernel on the layer,
/// for every θ and for the tied and a mixed secant activity.
#[test]
fn the_trace_kernel_is_the_schur_complement_of_the_full_kernel() {
    for theta in [0.0, 1.0, -1.0] {
        let p = hertz(2, 4, theta);
        let t = TraceProblem::new(&p).unwrap();
        let u = perturbed_solution(&p, 1e-3, 3);
        let mixed: Vec<f64> = p.p_values(&u).into_iter().map(heaviside).collect();
        assert!(mixed.contains(&0.0) && mixed.contains(&1.0));
        for h in [vec![1.0; p.points.len()], mixed] {
            let k = p.kernel(Kernel::Activity(&h)).unwrap().to_dense();
            let layer = t.condensation().layer();
            let interior: Vec<usize> = (0..p.n()).filter(|i| !layer.contains(i)).collect();
            let sub = |r: &[usize], c: &[usize]| {
                faer::Mat::from_fn(r.len(), c.len(), |i, j| k[(r[i], c[j])])
            };
            use faer::linalg::solvers::Solve;
            let x = sub(&interior, &interior)
                .partial_piv_lu()
                .solve(sub(&interior, layer));
            let want = sub(layer, layer) - sub(layer, &interior) * &x;
            let got = t.kernel(&h);
            let err = (&got - &want).norm_max() / want.norm_max();
            assert!(err <= 1e-10, "θ = {theta}: {err:.2e}");
        }
    }
}

/// A full-space kernel solve through the condensation (forward pass, dense
/// layer solve, backward pass) equals LU of the assembled kernel.
#[test]
fn kernel_solves_through_the_condensation_equal_lu() {
    for theta in [0.0, 1.0, -1.0] {
        for (name, p) in [
            ("hertz 16²", hertz(2, 16, theta)),
            ("taylor", taylor(theta)),
        ] {
            let t = TraceProblem::new(&p).unwrap();
            let u = perturbed_solution(&p, 1e-3, 9);
            for kind in [Kernel::Tied, Kernel::Secant(&u)] {
                let h: Vec<f64> = match kind {
                    Kernel::Secant(v) => p.p_values(v).into_iter().map(heaviside).collect(),
                    _ => vec![1.0; p.points.len()],
                };
                let b = rough(p.n(), 21);
                let x = t
                    .solve_full(&DenseLu::new(&t.kernel(&h)).unwrap(), &b)
                    .unwrap();
                let k = p.kernel(kind).unwrap();
                let lu = Factoriser::default().factor(&k, Method::Lu).unwrap();
                let want = lu.solve(&b).unwrap();
                assert!(
                    diff(&x, &want) <= 1e-10,
                    "{name} θ = {theta}: {:.2e}",
                    diff(&x, &want)
                );
                let res: Vec<f64> = mul(&k, &x).iter().zip(&b).map(|(a, c)| a - c).collect();
                assert!(norm(&res) <= 1e-10 * norm(&b), "{name} θ = {theta}");
            }
        }
    }
}

fn run(p: &Problem, opts: SolverOptions) -> Solution {
    solve(p, &opts).unwrap_or_else(|e| panic!("{opts:?}: {e}"))
}

/// The solutions of the condensed solvers equal those of the full-space
/// paths of before (the paper's BFGS and Newton over every DOF with LU
/// kernels) to 1e-10, on the small Hertz and Taylor ladders, every θ.
#[test]
fn condensed_solves_equal_full_space_lu_solves() {
    let mut cases: Vec<(String, Problem)> = Vec::new();
    for (degree, elements) in [(2, 8), (2, 16), (2, 32), (3, 8), (3, 16)] {
        cases.push((
            format!("hertz p={degree} {elements}²"),
            hertz(degree, elements, 0.0),
        ));
    }
    for theta in [0.0, 1.0, -1.0] {
        cases.push((format!("hertz 8², θ = {theta}"), hertz(2, 8, theta)));
        cases.push((format!("taylor θ = {theta}"), taylor(theta)));
    }
    let lu = |o: SolverOptions| SolverOptions {
        factorisation: Factorisation::Lu,
        ..o
    };
    for (name, p) in &cases {
        let reference = run(p, lu(SolverOptions::with_kind(SolverKind::Newton)));
        assert!(!reference.on_trace);
        let mut runs = vec![
            ("default", SolverOptions::default()),
            ("newton", SolverOptions::with_kind(SolverKind::Newton)),
        ];
        // the paper's full-step BFGS from the tied start does not converge
        // at p = 3, nor for θ = 1 (an indefinite tied kernel) on Hertz
        if !name.contains("p=3") && !name.contains("hertz 8², θ = 1") {
            runs.extend([
                (
                    "paper on the trace",
                    SolverOptions {
                        space: IterationSpace::Auto,
                        ..SolverOptions::paper()
                    },
                ),
                ("paper, body", SolverOptions::paper()),
                ("paper, LU", lu(SolverOptions::paper())),
            ]);
        }
        for (label, o) in runs {
            let s = solve(p, &o).unwrap_or_else(|e| panic!("{name}, {label}: {e}"));
            let d = diff(&s.u, &reference.u);
            assert!(d <= 1e-10, "{name}, {label}: {d:.2e}");
        }
    }
}

/// Over the whole body, the factorise-once kernels reproduce the paper's
/// iteration of the per-kernel factorisations row by row (Table 2).
#[test]
fn the_body_space_history_matches_the_per_kernel_factorisations() {
    for (name, p) in [("hertz 8²", hertz(2, 8, 0.0)), ("taylor", taylor(0.0))] {
        let once = run(&p, SolverOptions::paper());
        for how in [Factorisation::Lu, Factorisation::LowRank] {
            let other = run(
                &p,
                SolverOptions {
                    factorisation: how,
                    ..SolverOptions::paper()
                },
            );
            assert_same_iteration(&once.history, &other.history, &format!("{name} {how:?}"));
        }
    }
}
