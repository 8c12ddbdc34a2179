//! The default solver: large initial gaps, zero load, the round-off
//! stopping rule, iteration counts, and why the tied start (17) is not the
//! default.

use iga_contact::assembly::Load;
mod common;

use common::HertzCase;
use iga_contact::contact::{ContactPair, Master};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry;
use iga_contact::material::{Material, Plane};
use iga_contact::nurbs::Side;
use iga_contact::problem::Problem;
use iga_contact::solver::history::Event;
use iga_contact::solver::trace::TraceProblem;
use iga_contact::solver::{
    solve, Growth, IterationSpace, OnStall, SolverKind, SolverOptions, Start, Warning,
};

const WIDTH: f64 = 1.0;
const HEIGHT: f64 = 0.5;
const PRESSURE: f64 = 1e7;

/// A block [0, 1] × [gap, gap + 0.5] held only by rollers on its left
/// edge (u_x = 0), pushed down by a pressure on its top, above the rigid
/// floor y = 0: only a rigid motion closes the gap.
fn block(gap: f64, elements: [usize; 2], pressure: f64) -> Problem {
    let patch = geometry::rectangle(0.0, gap, WIDTH, gap + HEIGHT)
        .unwrap()
        .k_refined(2, elements)
        .unwrap();
    let bodies = vec![Body {
        name: "block".into(),
        space: iga_contact::space::Space::new(patch, None).unwrap(),
        material: Material::new(1e9, 0.3, Plane::Strain).unwrap(),
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let mut b = DofMap::builder(&bodies);
    b.fix_side(0, Side::XiMin, 0, 0.0).unwrap();
    let map = b.build();
    let loads = [Load::Pressure {
        body: 0,
        side: Side::EtaMax,
        pressure,
    }];
    let floor = geometry::segment([-1.0, 0.0], [2.0, 0.0]).unwrap();
    let pair = ContactPair::new(0, Side::EtaMin, Master::Rigid(floor));
    Problem::new(bodies, map, &loads, vec![pair]).unwrap()
}

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

/// Why the tied start overshoots at high degree: its θ = 0 consistency
/// term nearly cancels the penalty on a mode of the far arc, where the
/// floor's normal is tangent to the disk; a larger penalty removes it.
#[test]
fn the_tied_kernel_is_weak_on_the_far_arc_for_the_empirical_penalty() {
    let weakest = |factor: f64| {
        let p = HertzCase {
            degree: 4,
            elements: 64,
            penalty_factor: factor,
            ..HertzCase::default()
        }
        .build()
        .unwrap();
        let t = TraceProblem::new(&p).unwrap();
        let svd = t.kernel(&vec![1.0; p.points.len()]).svd().unwrap();
        let ell = t.dim();
        let smin = svd.S().column_vector()[ell - 1];
        let s0 = t
            .condensation()
            .schur()
            .self_adjoint_eigenvalues(faer::Side::Lower)
            .unwrap()[0];
        // share of the weakest mode on the last fifth of the arc (ξ ≥ 0.8)
        let n0 = p.bodies[0].space.patch.n()[0];
        let mut free_to_cp = vec![0usize; p.n()];
        for g in 0..p.map.n_total() {
            if let Some(i) = p.map.free(g) {
                free_to_cp[i] = g / 2;
            }
        }
        let v = svd.V().col(ell - 1);
        let far: f64 = t
            .condensation()
            .layer()
            .iter()
            .enumerate()
            .filter(|&(_, &i)| 5 * (free_to_cp[i] % n0) >= 4 * n0)
            .map(|(k, _)| v[k] * v[k])
            .sum();
        (smin / s0, far)
    };
    let (ratio, far) = weakest(1.0);
    assert!(ratio < 0.5, "σ_min(tied)/λ_min(S₀) = {ratio:.3}");
    assert!(far > 0.9, "far-arc share {far:.3}");
    let (ratio, _) = weakest(3.0);
    assert!(
        ratio > 0.9,
        "penalty ×3: σ_min(tied)/λ_min(S₀) = {ratio:.3}"
    );
    // the default start never ties the far arc
    assert_eq!(SolverOptions::default().start, Start::Secant);
}

#[test]
fn the_layer_space_needs_the_factorise_once_kernels() {
    let p = block(0.1, [4, 2], PRESSURE);
    let opts = SolverOptions {
        space: IterationSpace::Trace,
        factorisation: iga_contact::solver::Factorisation::Lu,
        ..SolverOptions::default()
    };
    let err = solve(&p, &opts).expect_err("invalid combination");
    assert_eq!(err.kind(), iga_contact::ErrorKind::InvalidInput);
    assert!(err.to_string().contains("solver.space"), "{err}");
    // with the body space the same kernels work
    let body = SolverOptions {
        space: IterationSpace::Body,
        ..opts
    };
    assert!(solve(&p, &body).is_ok());
}

// The stability atlas's hard cases (`examples/stability`): each either
// converges, with a warning where the answer may mislead, or fails early
// with a reason that names the cause.

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
