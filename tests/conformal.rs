//! Conformal contact (issue 19): the half annulus, one patch with exact
//! arcs and a Jacobian of one sign; its scene key, validated like the
//! other geometries (one `error:` line naming the key path and value);
//! the compound cylinder against Lamé's interface pressure on non-matching
//! meshes; and the shipped pin in a ring, which `check` and `run` pass
//! without a warning.

mod common;

use iga_contact::geometry::half_annulus;
use iga_contact::nurbs::Side;
use iga_contact::post::PressureProfile;
use iga_contact::scene::{GeometrySpec, RefineSpec, Scene};
use iga_contact::solver::solve;
use std::path::Path;
use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_iga-contact");

fn det(j: [[f64; 2]; 2]) -> f64 {
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

#[test]
fn half_annulus_arcs_are_circles_and_det_j_has_one_sign() {
    let (c, r_in, r_out) = ([0.25, -1.5], 0.7, 1.9);
    let exact = half_annulus(c, r_in, r_out).unwrap();
    for patch in [
        exact.clone(),
        exact.k_refined(2, [4, 3]).unwrap(),
        exact.k_refined(4, [7, 2]).unwrap(),
    ] {
        let (mut positive, mut negative) = (0, 0);
        for i in 0..=400 {
            let xi = i as f64 / 400.0;
            for (eta, r) in [(0.0, r_in), (1.0, r_out)] {
                let x = patch.point(xi, eta);
                let d = (x[0] - c[0]).hypot(x[1] - c[1]);
                assert!((d - r).abs() < 1e-12, "ξ = {xi}, η = {eta}: |x − c| = {d}");
                assert!(x[0] >= c[0] - 1e-12, "the half x ≥ cx: {x:?}");
            }
            for j in 0..=20 {
                // the double knot at ξ = 1/2 is evaluated from either side
                for xi in [xi, (xi - 1e-9).max(0.0)] {
                    let d = det(patch.jacobian(xi, j as f64 / 20.0));
                    if d > 0.0 {
                        positive += 1;
                    } else if d < 0.0 {
                        negative += 1;
                    }
                }
            }
        }
        assert!(positive == 0 && negative > 0, "{positive} {negative}");
        // the cuts lie on x = cx, below and above the centre
        for (side, sign) in [(Side::XiMin, -1.0), (Side::XiMax, 1.0)] {
            for t in [0.0, 0.5, 1.0] {
                let [xi, eta] = patch.side_point(side, t);
                let x = patch.point(xi, eta);
                assert!((x[0] - c[0]).abs() < 1e-12);
                assert!(sign * (x[1] - c[1]) >= r_in - 1e-12, "{side:?} {x:?}");
            }
        }
    }
}

#[test]
fn half_annulus_area_is_half_the_annulus() {
    let (r_in, r_out) = (1.0, 3.0);
    let patch = half_annulus([0.0, 0.0], r_in, r_out)
        .unwrap()
        .k_refined(2, [3, 2])
        .unwrap();
    let space = iga_contact::space::Space::new(patch, Some(6)).unwrap();
    let area = common::area(&space);
    let exact = std::f64::consts::PI * (r_out * r_out - r_in * r_in) / 2.0;
    assert!((area - exact).abs() < 1e-12 * exact, "{area} vs {exact}");
}

#[test]
fn half_annulus_builder_refuses_bad_radii() {
    for (r_in, r_out) in [
        (0.0, 1.0),
        (-1.0, 1.0),
        (1.0, 1.0),
        (2.0, 1.0),
        (f64::NAN, 1.0),
    ] {
        assert!(
            half_annulus([0.0, 0.0], r_in, r_out).is_err(),
            "{r_in} {r_out}"
        );
    }
    assert!(half_annulus([f64::INFINITY, 0.0], 1.0, 2.0).is_err());
}

fn one_body(geometry: &str) -> String {
    format!(
        "[[body]]\nname = \"ring\"\ngeometry = {geometry}\n\
         material = {{ young = 1.0e9, poisson = 0.3, plane = \"strain\" }}\n\
         [[support]]\nbody = \"ring\"\nside = \"eta_max\"\ncomponent = \"x\"\n\
         [[support]]\nbody = \"ring\"\nside = \"eta_max\"\ncomponent = \"y\"\n"
    )
}

/// Every bad value is refused in one `error:` line that names the key path
/// and the value, from the library and from the command line.
#[test]
fn half_annulus_key_is_validated_with_one_error_line() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("conformal-errors");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    let key = "body[0].geometry.half_annulus";
    for (geometry, field, value) in [
        (
            "{ half_annulus = { center = [0.0, 0.0], inner_radius = -1.0, outer_radius = 2.0 } }",
            "inner_radius",
            "-1",
        ),
        (
            "{ half_annulus = { center = [0.0, 0.0], inner_radius = 2.0, outer_radius = 1.0 } }",
            "outer_radius",
            "1",
        ),
        (
            "{ half_annulus = { center = [0.0, 0.0], inner_radius = 1.0, outer_radius = 1.0 } }",
            "outer_radius",
            "1",
        ),
        (
            "{ half_annulus = { center = [0.0, 0.0], inner_radius = 0.0, outer_radius = 1.0 } }",
            "inner_radius",
            "0",
        ),
        (
            "{ half_annulus = { center = [1e308, 0.0], inner_radius = 1.0, outer_radius = 1e308 } }",
            "outer_radius",
            "1e308",
        ),
    ] {
        let text = one_body(geometry);
        let e = Scene::from_toml_str(&text).unwrap_err().to_string();
        assert!(e.contains(&format!("{key}.{field}")), "{geometry}: {e}");
        let path = dir.join("bad.toml");
        std::fs::write(&path, &text).unwrap();
        let out = Command::new(BIN)
            .args(["check", path.to_str().unwrap()])
            .output()
            .unwrap();
        assert_eq!(out.status.code(), Some(2), "{geometry}");
        let stderr = String::from_utf8_lossy(&out.stderr);
        let lines: Vec<&str> = stderr.lines().filter(|l| !l.trim().is_empty()).collect();
        assert_eq!(lines.len(), 1, "{stderr}");
        assert!(lines[0].starts_with("error:"), "{stderr}");
        assert!(
            lines[0].contains(&format!("{key}.{field}")) && lines[0].contains(value),
            "{geometry}: {stderr}"
        );
    }
    // an unknown key of the table is refused by name
    let e = Scene::from_toml_str(&one_body(
        "{ half_annulus = { center = [0.0, 0.0], inner_radius = 1.0, outer_radius = 2.0, radius = 3.0 } }",
    ))
    .unwrap_err()
    .to_string();
    assert!(e.contains("radius"), "{e}");
    // a good one builds, and its sides are its own (one patch)
    let good = one_body(
        "{ half_annulus = { center = [0.0, 0.0], inner_radius = 1.0, outer_radius = 2.0 } }",
    );
    let scene = Scene::from_toml_str(&good).unwrap();
    assert_eq!(scene.bodies[0].geometry.kind(), "half_annulus");
    assert!(scene.bodies[0].geometry.multipatch().is_none());
    scene.build().unwrap();
}

/// Lamé's interface pressure of the shipped compound cylinder, plane
/// strain (the chapter derives it).
fn lame(scene: &Scene) -> f64 {
    let radii = |k: usize| match scene.bodies[k].geometry {
        GeometrySpec::QuarterAnnulus {
            inner_radius,
            outer_radius,
        } => (inner_radius, outer_radius),
        _ => unreachable!(),
    };
    let ((a, b), (_, c)) = (radii(0), radii(1));
    let p = 1.0e8;
    let (m1, m2) = (scene.bodies[0].material, scene.bodies[1].material);
    let (e1, n1, e2, n2) = (m1.young, m1.poisson, m2.young, m2.poisson);
    let load = 2.0 * (1.0 - n1 * n1) * p * a * a / (e1 * (b * b - a * a));
    let inner = (1.0 + n1) * ((1.0 - 2.0 * n1) * b * b + a * a) / (e1 * (b * b - a * a));
    let outer = (1.0 + n2) * ((1.0 - 2.0 * n2) * b * b + c * c) / (e2 * (c * c - b * b));
    load / (inner + outer)
}

/// The chapter's compound cylinder, beside its program.
fn compound_path() -> std::path::PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("examples/pin_ring/compound_cylinder.toml")
}

/// The largest relative deviation of the dense contact pressure from q.
fn compound_error(k: usize) -> f64 {
    let scene = Scene::load(compound_path())
        .unwrap()
        .refined("inner", RefineSpec::iga(2, [3 * k, k]))
        .unwrap()
        .refined("outer", RefineSpec::iga(2, [2 * k, k]))
        .unwrap();
    let q = lame(&scene);
    let problem = scene.build().unwrap();
    let solution = solve(&problem, &scene.solver).unwrap();
    assert!(solution.warnings.is_empty(), "{:?}", solution.warnings);
    let profile = PressureProfile::dense(&problem, &solution.full).unwrap();
    profile
        .samples()
        .iter()
        .map(|s| (s.pressure() - q).abs() / q)
        .fold(0.0, f64::max)
}

#[test]
fn compound_cylinder_pressure_converges_to_lame_on_non_matching_meshes() {
    let errors: Vec<f64> = [1, 2, 4, 8].into_iter().map(compound_error).collect();
    for w in errors.windows(2) {
        // at least second order (h², the degree's rate) on every rung
        assert!(w[1] < w[0] / 4.0, "{errors:?}");
    }
    assert!(errors[3] < 1e-4, "{errors:?}");
}

#[test]
fn pin_ring_checks_and_runs_without_a_warning() {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join("conformal-pin");
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    for scene in [companion::shipped_path("pin_ring.toml"), compound_path()] {
        let file = scene.file_name().unwrap().to_owned();
        for args in [
            vec!["check", scene.to_str().unwrap()],
            vec![
                "run",
                scene.to_str().unwrap(),
                "--out",
                dir.join(file).to_str().unwrap(),
            ],
        ] {
            let out = Command::new(BIN).args(&args).output().unwrap();
            let stderr = String::from_utf8_lossy(&out.stderr);
            assert!(out.status.success(), "{args:?}: {stderr}");
            assert!(stderr.trim().is_empty(), "{args:?} warns: {stderr}");
        }
    }
    // the pin presses on the lower half of the bore only, in one zone,
    // and the contact carries the load
    let scene = companion::shipped("pin_ring.toml").unwrap();
    let problem = scene.build().unwrap();
    let solution = solve(&problem, &scene.solver).unwrap();
    let profile = PressureProfile::dense(&problem, &solution.full).unwrap();
    let m = profile.measures_joined(0..problem.pairs.len());
    assert_eq!(m.zones, 1);
    assert!(m.peak_at[1] < -0.049, "peak at {:?}", m.peak_at);
    for s in profile.samples() {
        if s.x[1] > 0.001 {
            assert_eq!(s.pressure(), 0.0, "pressed above the centre at {:?}", s.x);
        }
    }
    let [_, fy] = iga_contact::post::contact_resultant(&problem, &solution.full);
    let [_, ly] = iga_contact::post::applied_resultant(&problem).unwrap();
    assert!(((fy + ly) / ly).abs() < 1e-10, "{fy} {ly}");
}
