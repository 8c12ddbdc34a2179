//! Hertz contact of a disk on a rigid plane: solver agreement, equilibrium,
//! accuracy against Hertz, mesh convergence and the floating-body error.

use iga_contact::benchmarks::{Hertz, HertzAnalytic};
use iga_contact::problem::Problem;
use iga_contact::solver::{solve, Solution, SolverKind, SolverOptions};
use iga_contact::studies::hertz::{
    applied_force, measure, measure_signed, pressure_profile, problem, SAMPLES_PER_ELEMENT,
};
use iga_contact::Error;

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

fn solved(p: &Problem, kind: SolverKind) -> Solution {
    solve(p, &SolverOptions::with_kind(kind)).unwrap_or_else(|e| panic!("{kind:?}: {e}"))
}

/// BFGS (with the correction) and Newton reach the same discrete solution,
/// and the floor carries exactly the weight of the half disk.
fn check_agreement(degree: usize, elements: usize) {
    let p = problem(degree, elements).unwrap();
    let b = solved(&p, SolverKind::Bfgs);
    let n = solved(&p, SolverKind::Newton);
    let diff: Vec<f64> = b.u.iter().zip(&n.u).map(|(x, y)| x - y).collect();
    let rel = norm(&diff) / norm(&n.u);
    assert!(
        rel <= 1e-8,
        "p = {degree}, {elements}²: ‖u_bfgs − u_newton‖/‖u‖ = {rel:.3e}"
    );
    let half_load = HertzAnalytic::new().load / 2.0;
    for (name, s) in [("bfgs", &b), ("newton", &n)] {
        let f = p.contact_force(&s.full);
        let err = (f[1] - half_load).abs() / half_load;
        assert!(
            err <= 1e-8,
            "p = {degree}, {elements}², {name}: contact force {} against P/2 = {half_load}: {err:.3e}",
            f[1]
        );
        assert!(f[0] == 0.0, "a rigid floor y = 0 pushes vertically only");
    }
    eprintln!(
        "p = {degree}, {elements}²: BFGS {} it ({} corrections), Newton {} it, rel. diff {rel:.2e}",
        b.history.len(),
        b.history.corrections(),
        n.history.len()
    );
}

#[test]
fn bfgs_and_newton_agree_and_balance_the_load_p2() {
    for n in [8, 16, 32, 64] {
        check_agreement(2, n);
    }
}

#[test]
fn bfgs_and_newton_agree_and_balance_the_load_p3() {
    for n in [8, 16, 32] {
        check_agreement(3, n);
    }
}

#[test]
fn the_discrete_load_is_half_the_disk_weight() {
    let half_load = HertzAnalytic::new().load / 2.0;
    for n in [8, 32] {
        let f = applied_force(&problem(2, n).unwrap());
        assert!(
            (f - half_load).abs() <= 1e-8 * half_load,
            "{n}²: {f} against {half_load}"
        );
    }
}

/// The paper's headline mesh against the closed-form Hertz values. The
/// tolerances (3 % on p₀, 4 % on a) hold for the discretisation itself,
/// not only for one solver: see the chapter for why Hertz is only
/// asymptotic here.
#[test]
fn hertz_8x8_p2_is_within_3_percent_in_p0_and_4_percent_in_a() {
    let p = problem(2, 8).unwrap();
    let s = solved(&p, SolverKind::Bfgs);
    let (p0, a) = measure(&p, &s.full, SAMPLES_PER_ELEMENT).unwrap();
    let exact = HertzAnalytic::new();
    let e_p0 = (p0 - exact.p0) / exact.p0;
    let e_a = (a - exact.half_width) / exact.half_width;
    eprintln!(
        "8×8, p = 2: p0 = {p0:.6e} ({:+.3} %), a = {a:.6e} ({:+.3} %)",
        100.0 * e_p0,
        100.0 * e_a
    );
    assert!(e_p0.abs() <= 0.03, "p0 error {:.3} %", 100.0 * e_p0);
    assert!(e_a.abs() <= 0.04, "half-width error {:.3} %", 100.0 * e_a);
}

/// The dense profile is a pressure: non-negative, zero beyond the
/// half-width and positive inside it.
#[test]
fn the_dense_profile_is_consistent_with_the_measured_half_width() {
    let p = problem(2, 16).unwrap();
    let s = solved(&p, SolverKind::Newton);
    let prof = pressure_profile(&p, &s.full, SAMPLES_PER_ELEMENT).unwrap();
    assert_eq!(prof.len(), 16 * SAMPLES_PER_ELEMENT);
    assert!(prof.windows(2).all(|w| w[0].0 <= w[1].0), "sorted by x");
    assert!(prof.iter().all(|&(_, q)| q >= 0.0));
    let (p0, a) = measure(&p, &s.full, SAMPLES_PER_ELEMENT).unwrap();
    assert_eq!(p0, prof.iter().map(|s| s.1).fold(0.0, f64::max));
    for &(x, q) in &prof {
        if x > a {
            assert_eq!(q, 0.0, "pressure {q} at x = {x} beyond a = {a}");
        }
    }
    assert!(prof.iter().filter(|s| s.0 < a).all(|s| s.1 > 0.0));
}

#[test]
fn measure_interpolates_where_the_bracket_changes_sign() {
    let signed = [
        (0.0, -3.0),
        (1.0, -2.0),
        (2.0, -1.0),
        (3.0, 1.0),
        (4.0, 3.0),
    ];
    assert_eq!(measure_signed(&signed), (3.0, 2.5));
    assert_eq!(measure_signed(&[(0.0, 1.0), (1.0, 2.0)]), (0.0, 0.0));
    assert_eq!(measure_signed(&[(0.0, -1.0), (1.0, -2.0)]), (2.0, 1.0));
}

/// Refining the p = 2 mesh moves p₀ and a toward a fine p = 3 solution:
/// the errors against it fall from 8² to 16² to 32².
#[test]
fn refinement_converges_toward_the_fine_reference() {
    let rp = problem(3, 64).unwrap();
    let rs = solved(&rp, SolverKind::Newton);
    let (p0_ref, a_ref) = measure(&rp, &rs.full, SAMPLES_PER_ELEMENT).unwrap();
    let errs: Vec<(f64, f64)> = [8, 16, 32]
        .iter()
        .map(|&n| {
            let p = problem(2, n).unwrap();
            let s = solved(&p, SolverKind::Bfgs);
            let (p0, a) = measure(&p, &s.full, SAMPLES_PER_ELEMENT).unwrap();
            (((p0 - p0_ref) / p0_ref).abs(), ((a - a_ref) / a_ref).abs())
        })
        .collect();
    eprintln!("errors (p0, a) against p = 3, 64², for 8², 16², 32²: {errs:?}");
    for w in errs.windows(2) {
        assert!(w[1].0 < w[0].0, "p0 errors {errs:?}");
        assert!(w[1].1 < w[0].1, "half-width errors {errs:?}");
    }
}

/// Gravity reversed: the disk is pulled off the floor, nothing holds it,
/// and the solver must say so instead of panicking or iterating forever.
#[test]
fn a_floating_disk_is_a_clear_error() {
    let p = Hertz::default()
        .build_with(Hertz::material(), -1.0)
        .expect("the set-up itself is valid");
    for kind in [SolverKind::Bfgs, SolverKind::Newton] {
        match solve(&p, &SolverOptions::with_kind(kind)) {
            Ok(s) => panic!(
                "{kind:?} claims convergence in {} iterations",
                s.history.len()
            ),
            Err(e) => {
                let msg = e.to_string();
                assert!(
                    matches!(e, Error::Floating(_))
                        || msg.contains("float")
                        || msg.contains("active set empty"),
                    "{kind:?}: {msg}"
                );
                assert!(
                    msg.contains("float") && msg.contains("active set"),
                    "{kind:?}: the message should name the floating body and the empty active set: {msg}"
                );
            }
        }
    }
}
