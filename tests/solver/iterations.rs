//! The stopping rule is attainable at the round-off floor, and the default
//! solver's iteration counts stay small (Hertz meshes, the disk on a block).

use crate::common::HertzCase;
use iga_contact::solver::{solve, Growth, IterationSpace, SolverKind, SolverOptions};

/// A tolerance no floating-point evaluation of R can meet still ends in
/// convergence, at the round-off floor, and the solution is the one a
/// reachable tolerance gives.
#[test]
fn the_stopping_rule_is_attainable_at_the_round_off_floor() {
    let p = HertzCase {
        elements: 16,
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    let usual = solve(&p, &SolverOptions::default()).unwrap();
    for space in [IterationSpace::Auto, IterationSpace::Body] {
        let strict = SolverOptions {
            rtol: 1e-300,
            utol: 1e-300,
            space,
            ..SolverOptions::default()
        };
        let s = solve(&p, &strict).unwrap_or_else(|e| panic!("{space:?}: {e}"));
        let last = s.history.rows.last().unwrap();
        assert!(
            last.relative_residual < 1e-11,
            "{space:?}: {}",
            last.relative_residual
        );
        assert!(s.history.len() <= usual.history.len() + 2, "{space:?}");
        let d: f64 =
            s.u.iter()
                .zip(&usual.u)
                .map(|(a, b)| (a - b).powi(2))
                .sum::<f64>()
                .sqrt()
                / usual.u.iter().map(|a| a * a).sum::<f64>().sqrt();
        assert!(d <= 1e-11, "{space:?}: {d:.2e}");
    }
}

/// The default solver's iteration count stays flat over the small Hertz
/// meshes (the example `solver_scaling` continues to 512²).
#[test]
fn the_default_solver_needs_few_iterations_on_hertz() {
    let mut counts = Vec::new();
    for (degree, elements) in [(2, 8), (2, 16), (2, 32), (2, 64), (3, 16), (4, 16)] {
        let p = HertzCase {
            degree,
            elements,
            ..HertzCase::default()
        }
        .build()
        .unwrap();
        let s = solve(&p, &SolverOptions::default()).unwrap();
        assert!(s.on_trace);
        counts.push(s.history.len());
    }
    assert!(counts.iter().all(|&c| c <= 8), "{counts:?}");
}

/// The disk on an elastic block (stiffness ratio 1, the shipped scene) at
/// a strong penalty: the balanced start lies far below the root's zone and
/// the plain iteration (`growth = "full"`) walks down to it from a first
/// step at about twice its size, one or two points per step (27 and 29
/// iterations on 32² at factors 20 and 30). With the growth cut
/// (`growth = "auto"`, the default) both solvers reach the same
/// root in at most 10, and p₀ agrees with the plain iteration's to 1e-8.
#[test]
fn the_disk_on_a_block_takes_its_active_set_in_few_iterations() {
    for (n, factor) in [(32, 20.0), (32, 30.0), (64, 20.0)] {
        let p = companion::shipped("disk_on_block.toml")
            .unwrap()
            .refined("disk", iga_contact::scene::RefineSpec::iga(2, [n, n]))
            .unwrap()
            .refined("block", iga_contact::scene::RefineSpec::iga(2, [2 * n, n]))
            .unwrap()
            .with_nitsche(|x| x.penalty_factor = factor)
            .build()
            .unwrap();
        let p0 = |s: &iga_contact::solver::Solution| {
            iga_contact::post::PressureProfile::dense(&p, &s.full)
                .unwrap()
                .measures(0)
                .p0
        };
        let plain = solve(
            &p,
            &SolverOptions {
                growth: Growth::Full,
                ..SolverOptions::default()
            },
        )
        .unwrap();
        assert!(
            plain.history.len() > 10,
            "{n}² {factor}: {}",
            plain.history.len()
        );
        for kind in [SolverKind::Bfgs, SolverKind::Newton] {
            let opts = SolverOptions {
                growth: Growth::Auto,
                ..SolverOptions::with_kind(kind)
            };
            let s = solve(&p, &opts).unwrap();
            assert!(
                s.history.len() <= 10,
                "{n}² factor {factor} {kind:?}: {} iterations",
                s.history.len()
            );
            assert_eq!(
                s.history.rows.last().unwrap().active_points,
                plain.history.rows.last().unwrap().active_points
            );
            let (a, b) = (p0(&s), p0(&plain));
            assert!(
                (a / b - 1.0).abs() <= 1e-8,
                "{n}² {factor} {kind:?}: {a} vs {b}"
            );
        }
    }
}
