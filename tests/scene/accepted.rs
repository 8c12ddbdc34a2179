//! Accepted scenes beside the rejected ones: each case next to a refused
//! one builds, and the defaults are the paper's choices.

use crate::text::{
    base_with, block_on_floor, master, nitsche, nurbs_body, one_body, BASE, HELD, SQUARE,
};
use iga_contact::scene::Scene;
use iga_contact::solver::{self, SolverOptions};

#[test]
fn the_kernel_factorisation_is_chosen_in_the_solver_table() {
    let text = base_with("kind = \"bfgs\"", "kind = \"bfgs\"\nfactorisation = \"lu\"");
    let scene = Scene::from_toml_str(&text).unwrap();
    assert_eq!(scene.solver.factorisation, solver::Factorisation::Lu);
    let scene = Scene::from_toml_str(&base_with("", "")).unwrap();
    assert_eq!(scene.solver.factorisation, solver::Factorisation::Auto);
}

#[test]
fn lagrange_refinement_builds_a_fem_mesh() {
    let text = base_with(
        "degree = 2, elements = [2, 1]",
        "lagrange = 1, elements = [3, 2]",
    );
    let p = Scene::from_toml_str(&text).unwrap().build().unwrap();
    assert_eq!(p.bodies[0].space.patch.degree(), [1, 1]);
    assert_eq!(p.bodies[0].space.n_elements(), [3, 2]);
}

#[test]
fn a_convex_counter_clockwise_quadrilateral_builds() {
    let ok = one_body(
        "{ quadrilateral = { corners = [[0.0, 0.0], [2.0, 0.0], [1.5, 1.0], [0.2, 1.2]] } }",
        "refine = { degree = 2, elements = [2, 2] }",
    );
    Scene::from_toml_str(&ok).unwrap().build().unwrap();
}

#[test]
fn a_valid_nurbs_patch_builds() {
    let text = nurbs_body(
        "[0.0, 0.0, 1.0, 1.0]",
        SQUARE,
        ", weights = [1.0, 2.0, 1.0, 1.0]",
    );
    let p = Scene::from_toml_str(&text).unwrap().build().unwrap();
    assert_eq!(p.bodies[0].space.n_elements(), [2, 2]);
}

#[test]
fn a_rigid_floor_under_the_upper_block_builds() {
    Scene::from_toml_str(&master(
        "{ rigid_segment = { from = [-1.0, 0.5], to = [2.0, 0.5] } }",
    ))
    .unwrap()
    .build()
    .unwrap();
}

#[test]
fn theta_is_one_zero_or_minus_one() {
    for ok in ["1", "0", "-1"] {
        Scene::from_toml_str(&nitsche(&format!("theta = {ok}"))).unwrap();
    }
}

#[test]
fn defaults_are_the_papers_choices() {
    let scene = Scene::from_toml_str(BASE).unwrap();
    let c = &scene.contacts[0].nitsche;
    assert_eq!(c.theta, iga_contact::contact::Theta::Incomplete);
    assert_eq!(c.penalty_factor, 1.0);
    assert_eq!(c.integration, iga_contact::contact::Integration::Segment);
    assert_eq!(c.gauss_points, None);
    assert!(scene.output.is_empty());
    assert_eq!(scene.solver, SolverOptions::default());
}

#[test]
fn a_support_that_holds_the_sliding_makes_the_block_well_posed() {
    Scene::from_toml_str(&block_on_floor(HELD))
        .unwrap()
        .build()
        .unwrap();
}

#[test]
fn two_floors_side_by_side_under_one_slave_side_are_two_contacts() {
    // one line, one direction, no overlap: the slave side meets each floor
    // on its own stretch, so the contacts do not repeat one another
    let floor = |from: f64, to: f64| {
        format!("{{ rigid_segment = {{ from = [{from:?}, 0.5], to = [{to:?}, 0.5] }} }}")
    };
    let text = master(&floor(-1.0, 0.5)).replacen(
        "[solver]",
        &format!(
            "[[contact]]\nslave = \"upper\"\nslave_side = \"eta_min\"\nmaster = {}\n\n[solver]",
            floor(0.5, 3.0)
        ),
        1,
    );
    let scene = Scene::from_toml_str(&text).unwrap();
    let problem = scene.build().unwrap();
    assert_eq!(problem.contacts.len(), 2);
}
