//! Quadrature: under-integration is accepted when allowed, and the Taylor
//! patch test is exact at the minimum rule and not below it.

use crate::text::{lower_body, nitsche, shipped_text};
use iga_contact::scene::Scene;
use iga_contact::solver;

#[test]
fn underintegration_is_accepted_when_allowed() {
    let text = lower_body("quadrature = 2");
    let allowed = format!("allow_underintegration = true\n{text}");
    Scene::from_toml_str(&allowed).unwrap().build().unwrap();
    // p + 1 is accepted as it is.
    Scene::from_toml_str(&lower_body("quadrature = 3")).unwrap();
    let text = nitsche("gauss_points = 2");
    Scene::from_toml_str(&format!("allow_underintegration = true\n{text}")).unwrap();
}

/// Largest |σ_yy / σ_exact − 1| of the Taylor scene over a 5 × 5 sampling
/// of every element, with the given body and contact quadrature.
/// `None` if the solve fails.
fn taylor_syy_error(quadrature: usize, gauss_points: usize) -> Option<f64> {
    let text = format!(
        "allow_underintegration = true\n{}",
        shipped_text("taylor.toml")
    )
    .replace(
        "plane = \"stress\" }\n",
        &format!("plane = \"stress\" }}\nquadrature = {quadrature}\n"),
    )
    .replace(
        "integration = \"segment\" }",
        &format!("integration = \"segment\", gauss_points = {gauss_points} }}"),
    );
    let scene = Scene::from_toml_str(&text).unwrap();
    let problem = scene.build().unwrap();
    let solution = solver::solve(&problem, &scene.solver).ok()?;
    let mesh =
        iga_contact::report::vtu::sample_bodies(&problem.bodies, &problem.map, &solution.full, 4)
            .unwrap();
    let stress = mesh.field("stress").unwrap();
    Some(
        stress
            .values
            .chunks(3)
            .map(|s| (s[1] / -1e8 - 1.0).abs())
            .fold(0.0, f64::max),
    )
}

#[test]
fn the_taylor_patch_test_is_exact_at_the_minimum_quadrature() {
    // Degree 2: the minimum is p + 1 = 3 points for the bodies and the contact.
    let at_minimum = taylor_syy_error(3, 3).expect("solves at the minimum");
    assert!(
        at_minimum < 1e-9,
        "σ_yy off by {at_minimum:e} at the minimum"
    );
    // Below it, hourglass modes: no solution, or a wrong stress field.
    let one_point = taylor_syy_error(1, 3);
    assert!(
        one_point.is_none_or(|e| e > 1e-2),
        "σ_yy off by only {one_point:?} with one point"
    );
    eprintln!("Taylor σ_yy error: {at_minimum:.1e} at (3, 3), {one_point:?} at (1, 3)");
}
