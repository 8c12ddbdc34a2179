//! The stability atlas's hard cases (`examples/stability`): each either
//! converges, with a warning where the answer may mislead, or fails early
//! with a reason that names the cause.

use crate::common::HertzCase;
use iga_contact::problem::Problem;
use iga_contact::solver::history::Event;
use iga_contact::solver::{solve, Growth, OnStall, SolverKind, SolverOptions, Warning};

/// Hertz 16×16 (p = 2) with Poisson's ratio `nu`.
fn hertz_nu(nu: f64) -> Problem {
    let mut s = HertzCase {
        elements: 16,
        ..HertzCase::default()
    }
    .scene();
    s.body_mut("disk").unwrap().material.poisson = nu;
    s.build().unwrap()
}

fn applied_and_contact(p: &Problem, full: &[f64]) -> (f64, f64) {
    let load = -iga_contact::post::applied_resultant(p).unwrap()[1];
    let force = iga_contact::post::contact_resultant(p, full)[1];
    (load, force)
}

/// At ν = 0.4999 every contact point is below the stability bound (γ of
/// Eq. (11) ignores λ), and the tangent need not be coercive: the plain
/// iteration from the balanced start (`growth = "full"`) stalls at a kink,
/// and the restart from the tied kernel finds a root; with the growth cut
/// (`growth = "auto"`) the first start reaches a root (another one: 7
/// active points against 10) without a restart.
#[test]
fn the_near_incompressible_disk_converges_after_a_restart() {
    let p = hertz_nu(0.4999);
    let with = |kind, growth| SolverOptions {
        growth,
        ..SolverOptions::with_kind(kind)
    };
    for (opts, restarts) in [
        (with(SolverKind::Bfgs, Growth::Auto), 0),
        (with(SolverKind::Newton, Growth::Auto), 0),
        (with(SolverKind::Bfgs, Growth::Full), 1),
        (with(SolverKind::Newton, Growth::Full), 1),
    ] {
        let kind = opts.kind;
        let s = solve(&p, &opts).unwrap();
        assert_eq!(
            s.history.count(|e| *e == Event::Restart),
            restarts,
            "{kind:?}"
        );
        assert!(s.history.len() <= 60, "{kind:?}: {}", s.history.len());
        let (load, force) = applied_and_contact(&p, &s.full);
        assert!((force - load).abs() <= 1e-8 * load, "{kind:?}");
        // every active point is below the bound, which the data keep;
        // the warning names the one cause, locking, whose remedy (the
        // mixed formulation) changes the bound too
        let st = iga_contact::post::penalty_stability(&p, &s.full)[0];
        assert!(
            st.active > 0 && st.active_below == st.active,
            "{kind:?}: {st:?}"
        );
        assert!(
            matches!(s.warnings[..], [Warning::NearlyIncompressible { .. }]),
            "{kind:?}: {:?}",
            s.warnings
        );
    }
    // without the restart the plain iteration stops early, saying why
    let err = solve(
        &p,
        &SolverOptions {
            on_stall: OnStall::Fail,
            ..with(SolverKind::Bfgs, Growth::Full)
        },
    )
    .unwrap_err();
    let text = err.to_string();
    assert!(
        text.contains("stalled") && text.contains("stability bound"),
        "{text}"
    );
    match err {
        iga_contact::Error::NotConverged { history, .. } => assert!(history.len() < 100),
        e => panic!("{e}"),
    }
}

/// θ = −1 is stable for any γ > 0: with γ at 10⁻³ and 10⁻⁴ of Eq. (11) it
/// converges near the paper's p₀. Its residual carries the round-off of
/// contact terms of size w|σ_n|/γ that cancel, which the stopping rule's
/// second floor counts (with the first alone it ran into the iteration limit).
#[test]
fn the_skew_variant_converges_with_a_tiny_penalty() {
    let p0 = |case: HertzCase| {
        let p = case.build().unwrap();
        let s = solve(&p, &SolverOptions::default()).unwrap();
        assert!(s.history.len() <= 12, "{}", s.history.len());
        iga_contact::post::PressureProfile::dense(&p, &s.full)
            .unwrap()
            .measures(0)
            .p0
    };
    let reference = p0(HertzCase::default());
    for factor in [1e-3, 1e-4] {
        let v = p0(HertzCase {
            theta: -1.0,
            penalty_factor: factor,
            ..HertzCase::default()
        });
        assert!((v / reference - 1.0).abs() < 0.01, "{factor}: {v}");
    }
}

/// θ = 0 with γ at 10⁻³ of Eq. (11): one step from the balanced start
/// lands on a genuine root of the discrete equations (the whole arc
/// active), and the solution says that every active point off the
/// disk's collapsed corner is below the stability bound.
#[test]
fn an_under_penalised_root_is_a_root_and_is_flagged() {
    let p = HertzCase {
        penalty_factor: 1e-3,
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    let s = solve(&p, &SolverOptions::default()).unwrap();
    let (r, state) = p.residual(&s.u);
    let norm = |v: &[f64]| v.iter().map(|x| x * x).sum::<f64>().sqrt();
    assert!(norm(&r) <= 1e-10 * norm(&p.rhs));
    assert_eq!(state.active, p.points.len());
    // every point is below the bound but those at the collapsed corner of
    // the disk, where the map is singular and the bound means nothing
    let regular = p.points.iter().filter(|cp| cp.regular).count();
    assert!(
        matches!(
            s.warnings.as_slice(),
            [Warning::PenaltyBelowBound { contact: 0, below, active, .. }]
                if *below == regular && *active == p.points.len()
        ),
        "{:?}",
        s.warnings
    );
}

/// At 10⁻⁸ of the load one quadrature point carries the disk: the disk
/// sinks until that point touches, whatever the load, and the dense
/// profile's p₀ is then the penalty bracket γ g₀ of that point, not a
/// pressure of the load. The solution says so.
#[test]
fn a_contact_zone_on_one_point_is_flagged() {
    let p = HertzCase {
        elements: 16,
        load_scale: 1e-8,
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    let s = solve(&p, &SolverOptions::default()).unwrap();
    assert_eq!(
        s.warnings,
        vec![Warning::UnresolvedContact {
            contact: 0,
            active: 1,
            elements: 1
        }]
    );
    let only = p.points.iter().find(|cp| cp.p(&s.full) <= 0.0).unwrap();
    let p0 = iga_contact::post::PressureProfile::dense(&p, &s.full)
        .unwrap()
        .measures(0)
        .p0;
    assert!((p0 / (only.gamma * only.g0) - 1.0).abs() < 0.01, "{p0}");
}

/// A hundred times the load presses the contact zone out to the far arc,
/// whose points are below the stability bound: both starts stall, and the
/// run fails after a few dozen iterations (not 300) saying so.
#[test]
fn a_huge_load_fails_early_with_its_reason() {
    let p = HertzCase {
        elements: 16,
        load_scale: 1e2,
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    let err = solve(&p, &SolverOptions::default()).unwrap_err();
    let text = err.to_string();
    assert!(text.contains("stalled"), "{text}");
    assert!(text.contains("stability bound"), "{text}");
    match err {
        iga_contact::Error::NotConverged { history, .. } => {
            assert!(history.len() < 100, "{}", history.len());
            assert_eq!(history.count(|e| *e == Event::Restart), 1);
        }
        e => panic!("{e}"),
    }
}

/// The paper's full-step BFGS at p = 3, 8²: an exact cycle of period 7,
/// named in the error with the advice to start from the secant kernel,
/// which, followed, converges.
#[test]
fn the_paper_iteration_at_p3_reports_its_cycle() {
    let p = HertzCase {
        degree: 3,
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    let paper = SolverOptions::paper();
    let err = solve(&p, &paper).unwrap_err();
    let text = err.to_string();
    assert!(text.contains("repeat with period 7"), "{text}");
    assert!(text.contains("solver.start = \"secant\""), "{text}");
    let advised = SolverOptions {
        start: iga_contact::solver::Start::Secant,
        ..paper
    };
    let s = solve(&p, &advised).unwrap_or_else(|e| panic!("advice followed: {e}"));
    assert!(s.history.len() < 50, "{}", s.history.len());
}

/// A penalty of 10⁻¹² of Eq. (11) barely holds the disk: it sinks by
/// orders of magnitude more than its size, and at that displacement the
/// round-off of K u alone is a few percent of the load. No iteration can
/// resolve ‖R‖ to rtol there, so the solve fails, saying so, with its
/// history, instead of calling the noise converged; every solver agrees.
#[test]
fn a_residual_the_round_off_cannot_resolve_is_not_convergence() {
    let p = HertzCase {
        penalty_factor: 1e-12,
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    for (name, opts) in [
        ("default", SolverOptions::default()),
        ("paper", SolverOptions::paper()),
        ("newton", SolverOptions::with_kind(SolverKind::Newton)),
    ] {
        match solve(&p, &opts) {
            Err(iga_contact::Error::NotConverged { diagnosis, history }) => {
                assert!(
                    matches!(
                        diagnosis.halt,
                        iga_contact::error::Halt::Unresolvable { .. }
                    ),
                    "{name}: {diagnosis}"
                );
                assert!(!history.is_empty(), "{name}");
            }
            Err(e) => panic!("{name}: {e}"),
            Ok(s) => {
                // a converged answer must meet the stopping rule it claims
                let last = s.history.rows.last().unwrap();
                assert!(
                    last.relative_residual <= opts.rtol,
                    "{name}: converged at relative residual {:.3e}, disk at u_y = {:.3e}",
                    last.relative_residual,
                    last.max_displacement
                );
            }
        }
    }
}
