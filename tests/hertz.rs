//! Hertz contact of a disk on a rigid plane: solver agreement, equilibrium,
//! accuracy against Hertz, mesh convergence and the floating-body error.

mod common;
use companion::hertz as setup;

use common::{hertz, hertz_scene, norm};
use iga_contact::assembly::Load;
use iga_contact::contact::Theta;
use iga_contact::post::{self, relative, PressureProfile, PROFILE_SAMPLES_PER_ELEMENT};
use iga_contact::problem::Problem;
use iga_contact::solver::{solve, Solution, SolverKind, SolverOptions};
use iga_contact::Error;

fn solved(p: &Problem, kind: SolverKind) -> Solution {
    solve(p, &SolverOptions::with_kind(kind)).unwrap_or_else(|e| panic!("{kind:?}: {e}"))
}

fn half_load() -> f64 {
    setup::analytic(&hertz_scene(2, 8, Theta::Incomplete))
        .unwrap()
        .load
        / 2.0
}

/// BFGS (with the correction) and Newton reach the same discrete solution,
/// and the floor carries exactly the weight of the half disk.
fn check_agreement(degree: usize, elements: usize) {
    let p = hertz(degree, elements, Theta::Incomplete);
    let b = solved(&p, SolverKind::Bfgs);
    let n = solved(&p, SolverKind::Newton);
    let diff: Vec<f64> = b.u.iter().zip(&n.u).map(|(x, y)| x - y).collect();
    let rel = norm(&diff) / norm(&n.u);
    assert!(
        rel <= 1e-8,
        "p = {degree}, {elements}²: ‖u_bfgs − u_newton‖/‖u‖ = {rel:.3e}"
    );
    let half_load = half_load();
    for (name, s) in [("bfgs", &b), ("newton", &n)] {
        let f = post::contact_resultant(&p, &s.full);
        let err = (f[1] - half_load).abs() / half_load;
        assert!(
            err <= 1e-8,
            "p = {degree}, {elements}², {name}: contact force {} against P/2 = {half_load}: {err:.3e}",
            f[1]
        );
        assert!(f[0] == 0.0, "a rigid floor y = 0 pushes vertically only");
    }
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
    let half_load = half_load();
    for n in [8, 32] {
        let f = -post::applied_resultant(&hertz(2, n, Theta::Incomplete)).unwrap()[1];
        assert!(
            (f - half_load).abs() <= 1e-8 * half_load,
            "{n}²: {f} against {half_load}"
        );
    }
}

/// The paper's headline mesh against the converged solution of the same
/// finite disk (p = 3 on 64², whose own distance from Hertz's half-plane
/// formula is the finite disk's, not the mesh's). Measured: p₀ +1.4 %,
/// −0.58 %, −0.21 % and a +5.6 %, +2.4 %, +0.92 % on 8², 16², 32²: each
/// halving of h divides both errors by 2.3 to 2.8. The test asks for at
/// least 2 (the rate of a quantity read off a kink of the pressure, which
/// the L² rate p + 1 does not govern) and bounds 8² at about 1.4× its
/// errors.
#[test]
fn hertz_8x8_p2_is_within_its_discretisation_error_of_the_converged_disk() {
    let measure = |p: usize, n: usize| {
        let problem = hertz(p, n, Theta::Incomplete);
        let s = solved(&problem, SolverKind::Bfgs);
        PressureProfile::dense(&problem, &s.full)
            .unwrap()
            .measures(0)
    };
    let reference = measure(3, 64);
    let errors: Vec<(f64, f64)> = [8, 16, 32]
        .iter()
        .map(|&n| {
            let m = measure(2, n);
            (
                relative(m.p0, reference.p0),
                relative(m.half_width, reference.half_width),
            )
        })
        .collect();
    let (e_p0, e_a) = errors[0];
    assert!(e_p0.abs() <= P0_8X8, "p0 error {:.3} %", 100.0 * e_p0);
    assert!(e_a.abs() <= A_8X8, "half-width error {:.3} %", 100.0 * e_a);
    assert!(
        errors
            .windows(2)
            .all(|w| w[0].0.abs() >= 2.0 * w[1].0.abs() && w[0].1.abs() >= 2.0 * w[1].1.abs()),
        "the errors do not halve with h: {errors:?}"
    );
    // and the converged disk sits where the chapter says: a little above
    // Hertz's half-plane p₀ (the finite disk is stiffer than a half-plane)
    let exact = setup::analytic(&hertz_scene(3, 64, Theta::Incomplete)).unwrap();
    let offset = relative(reference.p0, exact.p0);
    assert!(offset > 0.0 && offset < 0.03, "reference vs Hertz {offset}");
}

const P0_8X8: f64 = 0.02;
const A_8X8: f64 = 0.08;

/// The dense profile is a pressure: non-negative, zero beyond the
/// half-width and positive inside it; its peak is p₀.
#[test]
fn the_dense_profile_is_consistent_with_the_measured_half_width() {
    let p = hertz(2, 16, Theta::Incomplete);
    let s = solved(&p, SolverKind::Newton);
    let prof = PressureProfile::dense(&p, &s.full).unwrap();
    let samples = prof.pair(0);
    assert_eq!(samples.len(), 16 * PROFILE_SAMPLES_PER_ELEMENT);
    assert!(
        samples.windows(2).all(|w| w[0].x[0] <= w[1].x[0]),
        "ordered along the floor"
    );
    assert!(samples.iter().all(|q| q.pressure() >= 0.0));
    let m = prof.measures(0);
    assert_eq!(
        m.p0,
        samples.iter().map(|q| q.pressure()).fold(0.0, f64::max)
    );
    for q in samples {
        if q.x[0] > m.half_width {
            assert_eq!(
                q.pressure(),
                0.0,
                "pressure at x = {} beyond a = {}",
                q.x[0],
                m.half_width
            );
        } else {
            assert!(
                q.pressure() > 0.0,
                "no pressure at x = {} inside a = {}",
                q.x[0],
                m.half_width
            );
        }
    }
}

/// The half-width converges as the profile is sampled more densely (the
/// root of the bracket is interpolated linearly, an O(h²) error), and at
/// the dense profile's sampling it is settled far below the discretisation
/// error of the 8×8 mesh.
#[test]
fn the_half_width_converges_with_the_sampling() {
    let p = hertz(2, 8, Theta::Incomplete);
    let s = solved(&p, SolverKind::Newton);
    let a = |n| {
        PressureProfile::sample(&p, &s.full, n)
            .unwrap()
            .measures(0)
            .half_width
    };
    let (a10, a20, a30) = (a(10), a(PROFILE_SAMPLES_PER_ELEMENT), a(30));
    let (d1, d2) = (relative(a10, a30).abs(), relative(a20, a30).abs());
    assert!(d2 < 0.5 * d1, "{a10} {a20} {a30}");
    assert!(d2 < 5e-4, "{a20} vs {a30}");
}

/// Refining the p = 2 mesh moves p₀ and a toward a fine p = 3 solution:
/// the errors against it fall from 8² to 16² to 32².
#[test]
fn refinement_converges_toward_the_fine_reference() {
    let measure = |p: &Problem, kind| {
        let s = solved(p, kind);
        PressureProfile::dense(p, &s.full).unwrap().measures(0)
    };
    let r = measure(&hertz(3, 64, Theta::Incomplete), SolverKind::Newton);
    let errs: Vec<(f64, f64)> = [8, 16, 32]
        .iter()
        .map(|&n| {
            let m = measure(&hertz(2, n, Theta::Incomplete), SolverKind::Bfgs);
            (
                relative(m.p0, r.p0).abs(),
                relative(m.half_width, r.half_width).abs(),
            )
        })
        .collect();
    for w in errs.windows(2) {
        assert!(w[1].0 < w[0].0, "p0 errors {errs:?}");
        assert!(w[1].1 < w[0].1, "half-width errors {errs:?}");
    }
}

/// Gravity reversed: the disk is pulled off the floor, nothing holds it,
/// and the solver must say so instead of panicking or iterating forever.
#[test]
fn a_floating_disk_is_a_clear_error() {
    let mut scene = hertz_scene(2, 8, Theta::Incomplete);
    for l in &mut scene.loads {
        if let Load::BodyForce { force, .. } = l {
            force[1] = -force[1];
        }
    }
    let p = scene.build().expect("the set-up itself is valid");
    for kind in [SolverKind::Bfgs, SolverKind::Newton] {
        match solve(&p, &SolverOptions::with_kind(kind)) {
            Ok(s) => panic!(
                "{kind:?} claims convergence in {} iterations",
                s.history.len()
            ),
            Err(e) => {
                let msg = e.to_string();
                assert!(
                    matches!(e, Error::Floating(_)) || msg.contains("float"),
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
