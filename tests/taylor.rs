//! The Taylor contact patch test: segment integration reproduces the exact
//! homogeneous state to round-off (for θ = 0, 1 and −1), Gauss integration
//! does not, and the chapter program writes the same bytes on every run.

mod common;

use common::{example, taylor, taylor_scene};
use companion::taylor::{consistency, exact_full, patch_errors, Exact, PatchErrors};
use iga_contact::contact::{Integration, Theta};
use iga_contact::problem::Problem;
use iga_contact::solver::solve;

const TOL: f64 = 1e-10;

fn errors(integration: Integration, theta: Theta) -> PatchErrors {
    let scene = taylor_scene(integration, theta);
    let p = scene.build().unwrap();
    let s =
        solve(&p, &scene.solver).unwrap_or_else(|e| panic!("{integration:?}, θ = {theta}: {e}"));
    patch_errors(&p, &s.full, &Exact::of_problem(&p).unwrap()).unwrap()
}

fn assert_exact(e: &PatchErrors, what: &str) {
    for (name, v) in [
        ("σ_yy", e.syy),
        ("σ_xx", e.sxx),
        ("σ_xy", e.sxy),
        ("u_y(top)", (e.uy_top + 0.1).abs()),
        ("u_x(x = 1)", (e.ux_right - 0.03).abs()),
        ("displacement", e.displacement),
        ("contact force", e.force),
    ] {
        assert!(v <= TOL, "{what}: {name} error {v:e} ({e:?})");
    }
}

/// Total number of bulk Gauss points of both blocks.
fn bulk_points(p: &Problem) -> usize {
    p.bodies
        .iter()
        .map(|b| b.space.elements.len() * b.space.quad_order.pow(2))
        .sum()
}

#[test]
fn the_exact_field_is_what_the_blocks_should_do() {
    let p = taylor(Integration::Segment, Theta::Incomplete);
    let ex = Exact::of_problem(&p).unwrap();
    assert_eq!(ex.displacement([1.0, 1.0]), [0.03, -0.1]);
    let e = patch_errors(&p, &exact_full(&p, &ex), &ex).unwrap();
    assert_eq!(e.gauss_points, bulk_points(&p));
    assert_eq!(e.gauss_points, (8 + 6) * 9);
    assert_exact(&e, "interpolated exact field");
}

#[test]
fn the_error_measures_notice_a_wrong_field() {
    let p = taylor(Integration::Segment, Theta::Incomplete);
    let ex = Exact::of_problem(&p).unwrap();
    let mut full = exact_full(&p, &ex);
    // Nudge one interior control point of the upper block upwards.
    let patch = &p.bodies[1].space.patch;
    let a = patch.index(2, 2);
    full[p.map.global(1, a, 1)] += 1e-3;
    let e = patch_errors(&p, &full, &ex).unwrap();
    assert!(e.syy > 1e-3, "{e:?}");
    assert!(e.displacement > 1e-5, "{e:?}");
    // A NaN anywhere must surface, not be swallowed by a max.
    full[p.map.global(0, 0, 0)] = f64::NAN;
    assert!(patch_errors(&p, &full, &ex).unwrap().syy.is_nan());
}

/// Consistency: the exact solution satisfies the discrete equations with
/// segment integration, and not with Gauss points that straddle the master
/// knots x = 0.25, 0.5, 0.75 inside the slave elements.
#[test]
fn segment_integration_is_consistent_and_gauss_is_not() {
    for (integration, consistent) in [(Integration::Segment, true), (Integration::Gauss, false)] {
        for theta in Theta::ALL {
            let p = taylor(integration, theta);
            let rel = consistency(&p, &Exact::of_problem(&p).unwrap());
            let what = format!("{integration:?} θ = {theta}: ‖R(u_exact)‖/‖R(0)‖ = {rel:.3e}");
            assert_eq!(consistent, rel <= 1e-12, "{what}");
            assert!(consistent || rel > 1e-4, "{what}");
        }
    }
}

#[test]
fn segment_integration_passes_the_patch_test_for_every_theta() {
    for theta in Theta::ALL {
        let e = errors(Integration::Segment, theta);
        assert_eq!(e.gauss_points, (8 + 6) * 9);
        assert_exact(&e, &format!("segment, θ = {theta}"));
    }
}

#[test]
fn gauss_integration_passes_only_approximately() {
    let e = errors(Integration::Gauss, Theta::Incomplete);
    for (name, v) in [
        ("σ_yy", e.syy),
        ("u_y(top)", (e.uy_top + 0.1).abs() / 0.1),
        ("u_x(x = 1)", (e.ux_right - 0.03).abs() / 0.03),
    ] {
        assert!(
            v.is_finite() && v > 1e-12 && v < 0.05,
            "{name}: {v:e} ({e:?})"
        );
    }
    // The slave side is still in equilibrium with the load: the contact
    // force is exact, only its distribution is not.
    assert!(e.force <= TOL, "{e:?}");
}

/// The chapter program writes the same bytes on every run, and exactly
/// the columns other tools read.
#[test]
fn the_chapter_program_writes_the_same_files_twice() {
    let base = std::path::Path::new(env!("CARGO_TARGET_TMPDIR")).join("taylor_chapter");
    let dirs = [base.join("a"), base.join("b")];
    for d in &dirs {
        let _ = std::fs::remove_dir_all(d);
        let status = std::process::Command::new(example("taylor"))
            .arg("--out")
            .arg(d)
            .status()
            .expect("the taylor example runs");
        assert!(status.success());
    }
    let listing = |d: &std::path::Path| {
        let mut v: Vec<String> = std::fs::read_dir(d)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        v.sort();
        v
    };
    let names = listing(&dirs[0]);
    assert_eq!(names, listing(&dirs[1]));
    for n in [
        "summary.csv",
        "facts.txt",
        "mesh.svg",
        "error_syy_gauss.svg",
        "taylor.vtu",
    ] {
        assert!(names.iter().any(|m| m == n), "{n} missing: {names:?}");
    }
    for n in &names {
        let a = std::fs::read(dirs[0].join(n)).unwrap();
        assert!(!a.is_empty(), "{n} is empty");
        assert!(
            a == std::fs::read(dirs[1].join(n)).unwrap(),
            "{n} differs between two runs"
        );
    }
    let csv = std::fs::read_to_string(dirs[0].join("summary.csv")).unwrap();
    let lines: Vec<&str> = csv.lines().collect();
    assert_eq!(lines[0], "integration,iterations,max_rel_error_syy,uy_top");
    assert_eq!(lines.len(), 3);
    assert!(lines[1].starts_with("segment,") && lines[2].starts_with("gauss,"));
}

/// The unbiased form (each block the slave once, half weight) passes the
/// patch test exactly too, with either modulus in the penalty.
#[test]
fn the_unbiased_form_passes_the_patch_test() {
    use iga_contact::contact::{Modulus, Sides};
    for theta in Theta::ALL {
        for modulus in [Modulus::Slave, Modulus::Max] {
            let scene = taylor_scene(Integration::Segment, theta).with_nitsche(|n| {
                n.sides = Sides::Unbiased;
                n.modulus = modulus;
            });
            let p = scene.build().unwrap();
            let s = solve(&p, &scene.solver).unwrap();
            let e = patch_errors(&p, &s.full, &Exact::of_problem(&p).unwrap()).unwrap();
            assert_exact(&e, &format!("unbiased, {modulus:?}, θ = {theta}"));
        }
    }
}
