//! Large initial gaps and zero load: a block and a lifted disk land on the
//! floor in few iterations (the paper's iteration leaves the block
//! hovering), and a problem without load converges in no iteration.

use crate::common::{self, HertzCase};
use crate::{block, HEIGHT, PRESSURE, WIDTH};
use iga_contact::solver::{solve, IterationSpace, SolverKind, SolverOptions};

#[test]
fn a_block_above_the_floor_closes_gaps_up_to_its_height() {
    let load = PRESSURE * WIDTH;
    for ratio in [0.2, 1.0] {
        let p = block(ratio * HEIGHT, [6, 3], PRESSURE);
        for (name, opts) in [
            ("default", SolverOptions::default()),
            ("newton", SolverOptions::with_kind(SolverKind::Newton)),
            (
                "default, body",
                SolverOptions {
                    space: IterationSpace::Body,
                    ..SolverOptions::default()
                },
            ),
        ] {
            let s = solve(&p, &opts).unwrap_or_else(|e| panic!("gap {ratio}·h, {name}: {e}"));
            assert!(
                s.history.len() <= 6,
                "gap {ratio}·h, {name}: {} iterations",
                s.history.len()
            );
            let f = iga_contact::post::contact_resultant(&p, &s.full);
            assert!(
                (f[1] - load).abs() <= 1e-8 * load,
                "gap {ratio}·h, {name}: contact force {} against the load {load}",
                f[1]
            );
            // the block came down by the gap (plus its compression)
            let top = s
                .full
                .iter()
                .skip(1)
                .step_by(2)
                .fold(0.0f64, |m, v| m.min(*v));
            assert!(
                top < -ratio * HEIGHT,
                "gap {ratio}·h, {name}: u_y min {top}"
            );
        }
    }
}

/// A curved body too: the Hertz disk lifted by 0.2 and 1.0 times its
/// diameter lands on the floor with the unlifted iteration count.
#[test]
fn a_lifted_disk_lands_on_the_floor() {
    let load = common::vertical_load(&HertzCase::default().build().unwrap());
    let on_floor = solve(
        &HertzCase::default().build().unwrap(),
        &SolverOptions::default(),
    )
    .unwrap()
    .history
    .len();
    for lift in [0.08, 0.4] {
        let p = HertzCase {
            lift,
            ..HertzCase::default()
        }
        .build()
        .unwrap();
        for kind in [SolverKind::Bfgs, SolverKind::Newton] {
            let s = solve(&p, &SolverOptions::with_kind(kind)).unwrap();
            assert!(s.history.len() <= on_floor + 1, "lift {lift}, {kind:?}");
            let f = iga_contact::post::contact_resultant(&p, &s.full)[1];
            assert!(
                (f - load).abs() <= 1e-8 * load,
                "lift {lift}, {kind:?}: {f}"
            );
        }
    }
}

/// The paper's iteration cannot: its tied start glues the block at its
/// gap, the block then hovers (no active point, ‖R‖ = ‖R₀‖) while BFGS
/// moves it in small rigid steps, and the first correction is allowed only
/// after 8 iterations — too late. While it hovers, the secant pair's
/// y = ΔR is round-off alone, so how many steps hover before one diverges
/// depends on the last bits of the factorisation (the order of the
/// Cholesky factor changes it); the first step, from the tied start, always
/// hovers.
#[test]
fn the_paper_iteration_leaves_a_block_hovering_above_a_large_gap() {
    let p = block(0.2 * HEIGHT, [6, 3], PRESSURE);
    let err = solve(&p, &SolverOptions::paper()).expect_err("the paper's iteration fails");
    let iga_contact::Error::NotConverged { history, .. } = err else {
        panic!("{err}")
    };
    let hovering = history
        .rows
        .iter()
        .take_while(|r| r.active_points == 0)
        .collect::<Vec<_>>();
    assert!(!hovering.is_empty(), "the first step lands");
    assert!(hovering
        .iter()
        .all(|r| (r.relative_residual - 1.0).abs() < 1e-9));
}

#[test]
fn a_problem_without_load_converges_in_no_iteration() {
    let p = block(0.1, [4, 2], 0.0);
    for kind in [SolverKind::Bfgs, SolverKind::Newton] {
        let s = solve(&p, &SolverOptions::with_kind(kind)).unwrap();
        assert_eq!(s.history.len(), 0, "{kind:?}");
        assert_eq!(s.history.initial_residual, 0.0);
        assert_eq!(s.history.last_relative_residual(), 0.0);
        assert!(s.u.iter().all(|&v| v == 0.0));
    }
}
