//! The kernels (17)–(18) factorised on their own, two exact ways: sparse LU
//! of the assembled matrix, and Cholesky of its symmetric positive definite
//! part with the Sherman–Morrison–Woodbury correction of the trace rows;
//! and the whole-body solves of both against the factorise-once default
//! (tests/condense.rs checks the condensation itself).

mod common;

use common::{assert_same_iteration, perturbed_solution, rough};
use common::{HertzCase, TaylorCase};
use iga_contact::contact::Integration;
use iga_contact::linsolve::{mul, mul_transpose, Factor, FactorError, Factoriser, Method};
use iga_contact::problem::{Kernel, Problem};
use iga_contact::solver::history::Event;
use iga_contact::solver::kernel::{factor_kernel, Factorisation};
use iga_contact::solver::{solve, SolverKind, SolverOptions};

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn hertz(elements: usize, theta: f64) -> Problem {
    HertzCase {
        elements,
        theta,
        ..HertzCase::default()
    }
    .build()
    .unwrap()
}

/// A displacement near the solution with a mixed active set.
fn mixed_iterate(p: &Problem) -> Vec<f64> {
    let u = perturbed_solution(p, 1e-3, 3);
    let active = p.active_points(&u);
    assert!(active > 0 && active < p.points.len(), "active {active}");
    u
}

fn diff(a: &[f64], b: &[f64]) -> f64 {
    let d: Vec<f64> = a.iter().zip(b).map(|(x, y)| x - y).collect();
    norm(&d) / norm(b)
}

#[test]
fn the_split_reassembles_the_kernel() {
    for theta in [0.0, -1.0] {
        let p = hertz(8, theta);
        let u = mixed_iterate(&p);
        let mut ranks = Vec::new();
        for kind in [Kernel::Tied, Kernel::Secant(&u)] {
            let split = p.kernel_split(kind).unwrap().expect("θ ≤ 0 splits");
            let v = rough(p.n(), 11);
            let mut got = mul(&split.spd, &v);
            for (g, c) in got
                .iter_mut()
                .zip(mul(&split.u, &mul_transpose(&split.v, &v)))
            {
                *g += c;
            }
            let want = mul(&p.kernel(kind).unwrap(), &v);
            assert!(
                diff(&got, &want) <= 1e-13,
                "θ = {theta}: {:.2e}",
                diff(&got, &want)
            );
            // the non-symmetric part lives on the trace: a thin layer
            assert!(
                split.rank() * 5 < p.n(),
                "θ = {theta}: k = {}",
                split.rank()
            );
            ranks.push(split.rank());
        }
        // θ = 0: the rows R of the active trace; θ ≠ 0: rows and columns, 2|R|
        let trace = |k: usize| if theta == 0.0 { k } else { k / 2 };
        assert!(
            trace(ranks[1]) < trace(ranks[0]),
            "θ = {theta}: ranks {ranks:?}"
        );
        assert_eq!(ranks[0], if theta == 0.0 { 8 + 2 } else { 2 * (8 + 2) });
    }
}

#[test]
fn the_low_rank_solve_equals_lu() {
    for theta in [0.0, -1.0] {
        let p = hertz(16, theta);
        let u = mixed_iterate(&p);
        for kind in [Kernel::Tied, Kernel::Secant(&u)] {
            let mut fac = Factoriser::default();
            let mut events = Vec::new();
            let low =
                factor_kernel(&p, &mut fac, kind, Factorisation::LowRank, &mut events).unwrap();
            assert!(events.is_empty(), "θ = {theta}: {events:?}");
            assert!(
                matches!(low, Factor::LowRank(_)),
                "θ = {theta}: Auto takes the low-rank path"
            );
            let lu = factor_kernel(&p, &mut fac, kind, Factorisation::Lu, &mut events).unwrap();
            assert!(matches!(lu, Factor::Lu(_)));
            let b = rough(p.n(), 5);
            let (x_low, x_lu) = (low.solve(&b).unwrap(), lu.solve(&b).unwrap());
            assert!(
                diff(&x_low, &x_lu) <= 1e-10,
                "θ = {theta}: {:.2e}",
                diff(&x_low, &x_lu)
            );
            let k = p.kernel(kind).unwrap();
            let res: Vec<f64> = mul(&k, &x_low).iter().zip(&b).map(|(a, c)| a - c).collect();
            assert!(
                norm(&res) <= 1e-10 * norm(&b),
                "θ = {theta}: {:.2e}",
                norm(&res) / norm(&b)
            );
        }
    }
}

/// Why θ = 1 gets no Cholesky path although its kernel is symmetric: at
/// the empirical penalty, and even at 100 times it, the symmetric Nitsche
/// tied kernel of the Hertz disk is indefinite.
#[test]
fn the_symmetric_theta_one_kernel_is_indefinite() {
    for factor in [1.0, 100.0] {
        let p = HertzCase {
            elements: 8,
            theta: 1.0,
            penalty_factor: factor,
            ..HertzCase::default()
        }
        .build()
        .unwrap();
        let k = p.kernel(Kernel::Tied).unwrap();
        let err = Factoriser::default()
            .factor(&k, Method::Cholesky)
            .err()
            .expect("indefinite");
        assert!(
            matches!(err, FactorError::NotPositiveDefinite { .. }),
            "{err}"
        );
    }
}

#[test]
fn theta_one_falls_back_to_lu() {
    let p = hertz(8, 1.0);
    assert!(p.kernel_split(Kernel::Tied).unwrap().is_none());
    let mut events = Vec::new();
    let f = factor_kernel(
        &p,
        &mut Factoriser::default(),
        Kernel::Tied,
        Factorisation::Auto,
        &mut events,
    )
    .unwrap();
    assert!(matches!(f, Factor::Lu(_)));
    assert!(events.is_empty(), "LU by design is no fallback: {events:?}");
}

#[test]
fn a_floating_secant_kernel_is_not_taken_by_cholesky() {
    // lifted clear of the floor: no active point, S = K is singular
    let p = HertzCase {
        elements: 4,
        lift: 0.01,
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    let u = vec![0.0; p.n()];
    assert_eq!(p.active_points(&u), 0);
    let split = p.kernel_split(Kernel::Secant(&u)).unwrap().unwrap();
    assert_eq!(split.rank(), 0);
    let err = Factoriser::default()
        .factor_low_rank(&split.spd, &split.u, &split.v)
        .err()
        .expect("a singular S is refused");
    assert!(err.lu_may_help(), "LU takes over: {err}");
    // through the solvers' entry point the refusal is logged, and LU runs
    let mut events = Vec::new();
    let _ = factor_kernel(
        &p,
        &mut Factoriser::default(),
        Kernel::Secant(&u),
        Factorisation::LowRank,
        &mut events,
    );
    assert_eq!(events, vec![Event::KernelLuFallback]);
}

#[test]
fn a_stiff_upper_block_needs_refinement_and_stays_exact() {
    // a contrast of 10⁴ makes S much worse conditioned than the kernel
    let p = TaylorCase {
        integration: Integration::Segment,
        contrast: 1e4,
        ..TaylorCase::default()
    }
    .build()
    .unwrap();
    // the damped BFGS over the whole body, as before the condensation
    let body = SolverOptions {
        line_search_after: 0,
        ..SolverOptions::paper()
    };
    let s = solve(
        &p,
        &SolverOptions {
            factorisation: Factorisation::LowRank,
            ..body
        },
    )
    .unwrap();
    assert!(s.history.count(|e| *e == Event::KernelRefined) >= 1);
    let lu = solve(
        &p,
        &SolverOptions {
            factorisation: Factorisation::Lu,
            ..body
        },
    )
    .unwrap();
    assert!(diff(&s.u, &lu.u) <= 1e-9, "{:.2e}", diff(&s.u, &lu.u));
}

#[test]
fn both_factorisations_give_the_same_solutions() {
    let taylor = TaylorCase {
        integration: Integration::Segment,
        ..TaylorCase::default()
    }
    .build()
    .unwrap();
    let cases = [
        ("hertz 8²", hertz(8, 0.0)),
        ("hertz 8², θ = −1", hertz(8, -1.0)),
        ("taylor", taylor),
    ];
    let damped = SolverOptions {
        line_search_after: 0,
        ..SolverOptions::paper()
    };
    let newton = SolverOptions {
        kind: SolverKind::Newton,
        ..damped
    };
    for (name, p) in cases {
        for (label, opts) in [("bfgs", damped), ("newton", newton)] {
            let run = |how| {
                solve(
                    &p,
                    &SolverOptions {
                        factorisation: how,
                        ..opts
                    },
                )
                .unwrap()
            };
            let lu = run(Factorisation::Lu);
            for how in [Factorisation::Auto, Factorisation::LowRank] {
                let a = run(how);
                assert!(
                    diff(&a.u, &lu.u) <= 1e-10,
                    "{name} {label} {how:?}: {:.2e}",
                    diff(&a.u, &lu.u)
                );
                assert_same_iteration(&a.history, &lu.history, &format!("{name} {label} {how:?}"));
            }
        }
    }
}

/// The Cholesky path of the symmetric part alone, for contrast: the
/// assembled θ = 0 kernel is not symmetric, so Cholesky of it would solve
/// a different system.
#[test]
fn cholesky_of_the_assembled_kernel_would_be_wrong() {
    let p = hertz(8, 0.0);
    let k = p.kernel(Kernel::Tied).unwrap();
    let b = rough(p.n(), 9);
    // Cholesky reads one triangle: it either meets a non-positive pivot or
    // solves the symmetric matrix of that triangle, which is not K
    match Factoriser::default().factor(&k, Method::Cholesky) {
        Err(e) => assert!(
            matches!(
                e,
                iga_contact::linsolve::FactorError::NotPositiveDefinite { .. }
            ),
            "{e}"
        ),
        Ok(f) => {
            let x = f.solve(&b).unwrap();
            let res: Vec<f64> = mul(&k, &x).iter().zip(&b).map(|(a, c)| a - c).collect();
            assert!(norm(&res) > 1e-6 * norm(&b), "the kernel looked symmetric");
        }
    }
}
