//! The Taylor contact patch test: segment integration reproduces the exact
//! homogeneous state to round-off (for θ = 0, 1 and −1), Gauss integration
//! does not, and the study writes the same bytes on every run.

use iga_contact::benchmarks::{Taylor, TAYLOR_PRESSURE};
use iga_contact::contact::Integration;
use iga_contact::problem::Problem;
use iga_contact::solver::SolverOptions;
use iga_contact::studies::taylor::{
    exact_displacement, patch_errors, run, solve_case, PatchErrors, LOWER, UPPER,
};

const TOL: f64 = 1e-10;

fn errors(integration: Integration, theta: f64) -> PatchErrors {
    let setup = Taylor {
        integration,
        theta,
        ..Taylor::default()
    };
    solve_case(&setup, &SolverOptions::default())
        .unwrap_or_else(|e| panic!("{integration:?}, θ = {theta}: {e}"))
        .errors
}

fn assert_exact(e: &PatchErrors, what: &str) {
    assert!(e.max_rel_error_syy <= TOL, "{what}: σ_yy error {e:?}");
    assert!(e.max_rel_error_sxx <= TOL, "{what}: σ_xx error {e:?}");
    assert!(e.max_rel_error_sxy <= TOL, "{what}: σ_xy error {e:?}");
    assert!(
        (e.uy_top + 0.1).abs() <= TOL && e.uy_top_deviation <= TOL,
        "{what}: u_y(top) {e:?}"
    );
    assert!(
        (e.ux_right - 0.03).abs() <= TOL && e.ux_right_deviation <= TOL,
        "{what}: u_x(x = 1) {e:?}"
    );
    assert!(
        e.max_displacement_error <= TOL,
        "{what}: displacement {e:?}"
    );
    assert!(
        e.contact_force_rel_error <= TOL,
        "{what}: contact force {:?} against load {}",
        e.contact_force,
        TAYLOR_PRESSURE
    );
}

/// Total number of bulk Gauss points of both blocks.
fn bulk_points(p: &Problem) -> usize {
    p.bodies
        .iter()
        .map(|b| b.space.elements.len() * b.space.quad_order.pow(2))
        .sum()
}

/// The exact field interpolated at the control points: exact for these
/// affine blocks, since NURBS reproduce linear functions.
fn exact_full(p: &Problem) -> Vec<f64> {
    let mut full = vec![0.0; p.map.n_total()];
    for (bi, body) in p.bodies.iter().enumerate() {
        for (a, &x) in body.space.patch.points.iter().enumerate() {
            let u = exact_displacement(x);
            full[p.map.global(bi, a, 0)] = u[0];
            full[p.map.global(bi, a, 1)] = u[1];
        }
    }
    full
}

#[test]
fn the_exact_field_is_what_the_blocks_should_do() {
    assert_eq!(exact_displacement([1.0, 1.0]), [0.03, -0.1]);
    let p = Taylor::default().build().unwrap();
    let e = patch_errors(&p, &exact_full(&p)).unwrap();
    assert_eq!(e.gauss_points, bulk_points(&p));
    assert_eq!(e.gauss_points, (8 + 6) * 9);
    assert_exact(&e, "interpolated exact field");
}

#[test]
fn the_error_measures_notice_a_wrong_field() {
    let p = Taylor::default().build().unwrap();
    let mut full = exact_full(&p);
    // Nudge one interior control point of the upper block upwards.
    let patch = &p.bodies[UPPER].space.patch;
    let a = patch.index(2, 2);
    full[p.map.global(UPPER, a, 1)] += 1e-3;
    let e = patch_errors(&p, &full).unwrap();
    assert!(e.max_rel_error_syy > 1e-3, "{e:?}");
    assert!(e.max_displacement_error > 1e-5, "{e:?}");
    // A NaN anywhere must surface, not be swallowed by a max.
    full[p.map.global(LOWER, 0, 0)] = f64::NAN;
    assert!(patch_errors(&p, &full).unwrap().max_rel_error_syy.is_nan());
}

/// Consistency: the exact solution satisfies the discrete equations with
/// segment integration, and not with Gauss points that straddle the master
/// knots x = 0.25, 0.5, 0.75 inside the slave elements.
#[test]
fn segment_integration_is_consistent_and_gauss_is_not() {
    for (integration, exact) in [(Integration::Segment, true), (Integration::Gauss, false)] {
        for theta in [0.0, 1.0, -1.0] {
            let p = Taylor {
                integration,
                theta,
                ..Taylor::default()
            }
            .build()
            .unwrap();
            let u = p.map.restrict(&exact_full(&p));
            let r0 = norm(&p.residual(&vec![0.0; p.n()]).0);
            let (r, state) = p.residual(&u);
            let rel = norm(&r) / r0;
            assert_eq!(state.active, p.points.len());
            if exact {
                assert!(
                    rel <= 1e-12,
                    "{integration:?} θ = {theta}: ‖R(u_exact)‖/‖R(0)‖ = {rel:.3e}"
                );
            } else {
                assert!(
                    rel > 1e-4,
                    "{integration:?} θ = {theta}: ‖R(u_exact)‖/‖R(0)‖ = {rel:.3e}"
                );
            }
        }
    }
}

fn norm(v: &[f64]) -> f64 {
    v.iter().map(|x| x * x).sum::<f64>().sqrt()
}

#[test]
fn segment_integration_passes_the_patch_test() {
    let e = errors(Integration::Segment, 0.0);
    assert_eq!(e.gauss_points, (8 + 6) * 9);
    assert_exact(&e, "segment, θ = 0");
}

#[test]
fn symmetric_and_skew_symmetric_variants_pass_too() {
    for theta in [1.0, -1.0] {
        assert_exact(
            &errors(Integration::Segment, theta),
            &format!("segment, θ = {theta}"),
        );
    }
}

#[test]
fn gauss_integration_passes_only_approximately() {
    let e = errors(Integration::Gauss, 0.0);
    for (name, v) in [
        ("σ_yy", e.max_rel_error_syy),
        ("u_y(top)", e.uy_top_deviation / 0.1),
        ("u_x(x = 1)", e.ux_right_deviation / 0.03),
    ] {
        assert!(
            v.is_finite() && v > 1e-12 && v < 0.05,
            "{name}: {v:e} ({e:?})"
        );
    }
    // The slave side is still in equilibrium with the load: the contact
    // force is exact, only its distribution is not.
    assert!(e.contact_force_rel_error <= TOL, "{e:?}");
}

#[test]
fn the_study_writes_the_same_files_twice() {
    let base = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("taylor_study");
    let dirs = [base.join("a"), base.join("b")];
    let mut summaries = Vec::new();
    for d in &dirs {
        let _ = std::fs::remove_dir_all(d);
        summaries.push(run(d).unwrap());
    }
    assert_eq!(summaries[0], summaries[1]);
    let s = &summaries[0];
    assert!(s.segment.errors.max_rel_error_syy <= TOL);
    assert!(s.gauss.errors.max_rel_error_syy > 1e-12);

    let names = [
        "summary.csv",
        "summary.md",
        "iterations_segment.csv",
        "iterations_gauss.csv",
        "iterations.md",
        "mesh.svg",
        "displacement.svg",
        "error_syy_segment.svg",
        "error_syy_gauss.svg",
        "taylor.vtu",
    ];
    for n in names {
        let a = std::fs::read(dirs[0].join(n)).unwrap_or_else(|e| panic!("{n}: {e}"));
        let b = std::fs::read(dirs[1].join(n)).unwrap();
        assert!(!a.is_empty(), "{n} is empty");
        assert!(a == b, "{n} differs between two runs");
    }
    let csv = std::fs::read_to_string(dirs[0].join("summary.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "integration,iterations,max_rel_error_syy,uy_top");
    assert_eq!(lines.len(), 3);
    assert!(lines[1].starts_with("segment,") && lines[2].starts_with("gauss,"));
    let md = std::fs::read_to_string(dirs[0].join("summary.md")).unwrap();
    assert!(md.contains("0.13 %") && md.contains("| 6 |"), "{md}");
    // Nothing but the listed files (and no temporaries) is left behind.
    let mut left: Vec<String> = std::fs::read_dir(&dirs[0])
        .unwrap()
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    left.sort();
    let mut want: Vec<String> = names.iter().map(|s| s.to_string()).collect();
    want.sort();
    assert_eq!(left, want);
}
