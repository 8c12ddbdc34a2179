//! Scene files: parsing, validation (one test per rule, each checking that
//! the error names the key path and the value), the shipped scenes, and
//! lean, atomic output.

#[path = "../examples/common/hertz.rs"]
mod setup;

use iga_contact::post::{PressureProfile, PROFILE_SAMPLES_PER_ELEMENT};
use iga_contact::report::atomic::{read_manifest, MANIFEST};
use iga_contact::scene::{files, Scene};
use iga_contact::solver::{self, SolverOptions};
use iga_contact::Error;
use std::path::{Path, PathBuf};

/// A small valid scene with two bodies, every kind of load and both kinds
/// of master, on which the validation tests make one change each.
const BASE: &str = r#"
title = "base"

[[body]]
name = "lower"
geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }
refine = { degree = 2, elements = [2, 1] }
material = { young = 1.0e9, poisson = 0.3, plane = "stress" }

[[body]]
name = "upper"
geometry = { rectangle = { x0 = 0.0, y0 = 0.5, x1 = 1.0, y1 = 1.0 } }
refine = { degree = 2, elements = [1, 1] }
material = { young = 1.0e9, poisson = 0.3, plane = "stress" }

[[support]]
body = "lower"
side = "eta_min"
component = "y"
value = 0.0

[[support]]
body = "lower"
side = "xi_min"
component = "x"

[[support]]
body = "upper"
side = "xi_min"
component = "x"

[[load]]
pressure = { body = "upper", side = "eta_max", pressure = 1.0e8 }

[[load]]
body_force = { body = "upper", force = [0.0, -1.0] }

[[load]]
traction = { body = "upper", side = "xi_max", traction = [0.0, 0.0] }

[[contact]]
slave = "upper"
slave_side = "eta_min"
master = { body = "lower", side = "eta_max" }

[solver]
kind = "bfgs"
rtol = 1e-10
"#;

/// A single body with a geometry given as a TOML inline table.
fn one_body(geometry: &str, refine: &str) -> String {
    format!(
        r#"
[[body]]
name = "b"
geometry = {geometry}
{refine}
material = {{ young = 1.0, poisson = 0.3, plane = "strain" }}

[[support]]
body = "b"
side = "eta_min"
component = "y"

[[support]]
body = "b"
side = "eta_min"
component = "x"
"#
    )
}

fn base_with(from: &str, to: &str) -> String {
    assert!(BASE.contains(from), "the base scene lacks {from:?}");
    BASE.replacen(from, to, 1)
}

/// Asserts that `text` fails with an invalid-input error naming `path` and
/// showing `value`, and returns the message.
#[track_caller]
fn rejects(text: &str, path: &str, value: &str) -> String {
    let err = match Scene::from_toml_str(text) {
        Ok(s) => match s.build() {
            Ok(_) => panic!("accepted a scene that should fail at `{path}`"),
            Err(e) => e,
        },
        Err(e) => e,
    };
    let msg = err.to_string();
    match &err {
        Error::InvalidInput {
            field, value: v, ..
        } => {
            assert_eq!(field, path, "wrong key path in: {msg}");
            assert_eq!(v, value, "wrong value in: {msg}");
        }
        other => panic!("expected invalid input at `{path}`, got: {other}"),
    }
    assert!(msg.contains(&format!("`{path}` = {value}")), "{msg}");
    msg
}

fn tmp(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("scene-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// The files of an output directory, without the manifest of the set.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .map(|rd| {
            rd.map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
                .filter(|n| n != MANIFEST)
                .collect()
        })
        .unwrap_or_default();
    v.sort();
    v
}

fn scene_file(name: &str) -> String {
    let path = Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenes")
        .join(name);
    std::fs::read_to_string(path).unwrap()
}

// ---------------------------------------------------------------------------
// The shipped scenes
// ---------------------------------------------------------------------------

#[test]
fn base_scene_is_valid_and_builds() {
    let scene = Scene::from_toml_str(BASE).unwrap();
    scene.build().unwrap();
}

#[test]
fn every_shipped_scene_parses_and_builds() {
    let dir = Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes");
    let mut n = 0;
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "toml") {
            let scene = Scene::load(&path).unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            scene
                .build()
                .unwrap_or_else(|e| panic!("{}: {e}", path.display()));
            n += 1;
        }
    }
    assert!(n >= 4, "expected at least the four shipped scenes");
}

#[test]
fn shipped_scenes_round_trip_through_toml() {
    for name in [
        "taylor.toml",
        "hertz.toml",
        "hertz_fem_q2.toml",
        "minimal.toml",
    ] {
        let scene = Scene::from_toml_str(&scene_file(name)).unwrap();
        let text = toml::to_string(&scene).unwrap();
        let again = Scene::from_toml_str(&text).unwrap_or_else(|e| panic!("{name}: {e}\n{text}"));
        assert_eq!(scene, again, "{name}");
    }
}

#[test]
fn the_kernel_factorisation_is_chosen_in_the_solver_table() {
    let text = base_with("kind = \"bfgs\"", "kind = \"bfgs\"\nfactorisation = \"lu\"");
    let scene = Scene::from_toml_str(&text).unwrap();
    assert_eq!(scene.solver.factorisation, solver::Factorisation::Lu);
    let scene = Scene::from_toml_str(&base_with("", "")).unwrap();
    assert_eq!(scene.solver.factorisation, solver::Factorisation::Auto);
}

#[test]
fn summary_survives_solver_limits_beyond_toml_integers() {
    let dir = tmp("summary-usize-max");
    let mut scene = Scene::from_toml_str(&scene_file("minimal.toml")).unwrap();
    scene.solver.line_search_after = usize::MAX;
    scene.output.summary = true;
    scene.run(&dir).unwrap();
    let summary: toml::Table =
        toml::from_str(&std::fs::read_to_string(dir.join(files::SUMMARY)).unwrap()).unwrap();
    assert_eq!(
        summary["solver"]["line_search_after"].as_integer(),
        Some(i64::MAX)
    );
}

/// The Taylor scene as shipped passes the patch test: u_y = −0.1 on top.
#[test]
fn the_taylor_scene_passes_the_patch_test() {
    let scene = Scene::from_toml_str(&scene_file("taylor.toml")).unwrap();
    let a = scene.build().unwrap();
    let sa = solver::solve(&a, &scene.solver).unwrap();
    let patch = &a.bodies[1].space.patch;
    for cp in patch.side_indices(iga_contact::nurbs::Side::EtaMax) {
        let uy = a.map.cp_displacement(&sa.full, 1, cp)[1];
        assert!((uy + 0.1).abs() < 1e-10, "u_y(top) = {uy}");
    }
}

/// The FEM Q2 scene is the IGA scene with a Lagrange mesh: same contact
/// force, and the DOF count of a Q2 mesh of 8² elements.
#[test]
fn the_fem_scene_differs_from_the_iga_scene_only_in_its_mesh() {
    let iga = Scene::from_toml_str(&scene_file("hertz.toml")).unwrap();
    let fem = Scene::from_toml_str(&scene_file("hertz_fem_q2.toml")).unwrap();
    let mut same = fem.clone();
    same.bodies[0].refine = iga.bodies[0].refine.clone();
    same.title = iga.title.clone();
    same.output = iga.output.clone();
    assert_eq!(same, iga);
    let (a, b) = (iga.build().unwrap(), fem.build().unwrap());
    assert_eq!(
        b.n(),
        2 * (17 * 17) - 17,
        "Q2 on 8²: 17 × 17 nodes, u_x = 0 on 17"
    );
    // each balances its own load; the loads differ by the Q2 geometry's
    // error in the disk's area
    for (p, scene) in [(&a, &iga), (&b, &fem)] {
        let f =
            iga_contact::post::contact_resultant(p, &solver::solve(p, &scene.solver).unwrap().full);
        let load = iga_contact::post::applied_resultant(p).unwrap();
        assert!(
            (f[1] + load[1]).abs() <= 1e-8 * load[1].abs(),
            "{f:?} vs {load:?}"
        );
    }
    let (la, lb) = (
        iga_contact::post::applied_resultant(&a).unwrap()[1],
        iga_contact::post::applied_resultant(&b).unwrap()[1],
    );
    assert!((la - lb).abs() <= 1e-5 * la.abs(), "{la} vs {lb}");
}

#[test]
fn hertz_run_writes_everything_it_asks_for() {
    let dir = tmp("hertz-run");
    let scene = Scene::from_toml_str(&scene_file("hertz.toml")).unwrap();
    let report = scene.run(&dir).unwrap();
    let mut expected = [
        files::ITERATIONS,
        files::PRESSURE_PROFILE,
        files::FIGURE,
        files::VTU,
        files::SUMMARY,
    ]
    .map(String::from)
    .to_vec();
    expected.sort();
    assert_eq!(listing(&dir), expected);
    assert_eq!(report.files.len(), 5);
    // The manifest lists exactly the committed files.
    assert_eq!(read_manifest(&dir).unwrap(), expected);
    // Equilibrium: the floor carries the applied load.
    let applied = report.applied_force.unwrap();
    assert!((report.contact_force[1] + applied[1]).abs() < 1e-8 * applied[1].abs());
    let summary: toml::Table =
        toml::from_str(&std::fs::read_to_string(dir.join(files::SUMMARY)).unwrap()).unwrap();
    assert_eq!(
        summary["iterations"].as_integer().unwrap() as usize,
        report.iterations
    );
    // p0 and half_width of the pair are the post-processing layer's, on the
    // same solution, and within a few per cent of Hertz.
    let pair = &summary["contact"].as_array().unwrap()[0];
    let (p0, a) = (
        pair["p0"].as_float().unwrap(),
        pair["half_width"].as_float().unwrap(),
    );
    let problem = scene.build().unwrap();
    let solution = solver::solve(&problem, &scene.solver).unwrap();
    let m = PressureProfile::dense(&problem, &solution.full)
        .unwrap()
        .measures(0);
    assert_eq!((p0, a), (m.p0, m.half_width));
    let exact = setup::analytic(&scene).unwrap();
    assert!(
        (p0 / exact.p0 - 1.0).abs() < 0.03,
        "p0 {p0} vs {}",
        exact.p0
    );
    assert!(
        (a / exact.half_width - 1.0).abs() < 0.04,
        "a {a} vs {}",
        exact.half_width
    );
    // The profile file is the dense profile, whose peak is p0.
    let csv = std::fs::read_to_string(dir.join(files::PRESSURE_PROFILE)).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("pair,x,y,bracket,pressure,regular"));
    let rows: Vec<f64> = lines
        .map(|l| l.split(',').nth(4).unwrap().parse::<f64>().unwrap())
        .collect();
    assert_eq!(rows.len(), 8 * PROFILE_SAMPLES_PER_ELEMENT);
    assert_eq!(rows.iter().copied().fold(0.0, f64::max), p0);
    let svg = std::fs::read_to_string(dir.join(files::FIGURE)).unwrap();
    assert!(svg.starts_with("<svg") || svg.contains("<svg"));
}

// ---------------------------------------------------------------------------
// Lean, atomic output
// ---------------------------------------------------------------------------

#[test]
fn a_scene_without_outputs_writes_nothing() {
    let dir = tmp("no-outputs");
    let scene = Scene::from_toml_str(&scene_file("minimal.toml")).unwrap();
    assert!(scene.output.is_empty());
    let report = scene.run(&dir).unwrap();
    assert!(report.files.is_empty());
    assert!(
        report.applied_force.is_none(),
        "summary data computed anyway"
    );
    assert!(!dir.exists(), "the output directory was created");
    let line = report.to_string();
    assert!(
        !line.contains('\n') && line.contains("no outputs requested"),
        "{line}"
    );
}

/// A converged run whose answer may not be the wanted one says so in its
/// report (the atlas's case: Hertz 8×8, θ = 0, penalty factor 10⁻³,
/// where the solver converges to a p₀ far off the reference); the report
/// line itself stays one line of facts, the tool printing each warning on
/// a line of its own.
#[test]
fn a_run_below_the_stability_bound_reports_its_warning() {
    let dir = tmp("warned");
    let mut scene = Scene::shipped("hertz.toml").unwrap();
    scene.nitsche_mut().for_each(|n| n.penalty_factor = 1e-3);
    scene.solver = SolverOptions::default();
    scene.output = Default::default();
    let report = scene.run(&dir).unwrap();
    assert!(matches!(
        report.warnings.as_slice(),
        [solver::Warning::PenaltyBelowBound { pair: 0, .. }]
    ));
    let line = report.to_string();
    assert!(!line.contains('\n') && !line.contains("warning"), "{line}");
    let text = report.warnings[0].to_string();
    assert!(
        text.starts_with("contact[0]: ") && text.contains("stability bound"),
        "{text}"
    );
    assert!(line.ends_with("no outputs requested"), "{line}");
    assert!(report.warnings[0].to_string().contains("stability bound"));
    // at the empirical penalty the same run carries no warning
    let mut fine = Scene::shipped("hertz.toml").unwrap();
    fine.solver = SolverOptions::default();
    fine.output = Default::default();
    assert!(fine.run(&dir).unwrap().warnings.is_empty());
}

#[test]
fn a_scene_asking_only_for_iterations_writes_only_that() {
    let dir = tmp("only-iterations");
    let text = format!("{BASE}\n[output]\niterations = true\n");
    let scene = Scene::from_toml_str(&text).unwrap();
    let report = scene.run(&dir).unwrap();
    assert_eq!(listing(&dir), vec![files::ITERATIONS.to_string()]);
    assert_eq!(report.files, vec![dir.join(files::ITERATIONS)]);
    let csv = std::fs::read_to_string(dir.join(files::ITERATIONS)).unwrap();
    assert!(csv.starts_with("iteration,residual"));
    assert_eq!(csv.lines().count(), report.iterations + 1);
}

#[test]
fn a_failing_run_leaves_earlier_results_and_no_partial_files() {
    let dir = tmp("failing-run");
    let outputs =
        "\n[output]\niterations = true\nsummary = true\nvtu = true\nvtu_subdivisions = 1\n";
    let good = Scene::from_toml_str(&format!("{BASE}{outputs}")).unwrap();
    good.run(&dir).unwrap();
    let before = listing(&dir);
    let contents: Vec<Vec<u8>> = before
        .iter()
        .map(|f| std::fs::read(dir.join(f)).unwrap())
        .collect();
    assert_eq!(before.len(), 3);

    // Same scene, different title (so every file would change), and a
    // solver that cannot converge in one iteration: the paper's tied start
    // glues the upper block at an initial gap.
    let bad_text = format!("{BASE}{outputs}")
        .replacen("title = \"base\"", "title = \"changed\"", 1)
        .replacen(
            "y0 = 0.5, x1 = 1.0, y1 = 1.0",
            "y0 = 0.6, x1 = 1.0, y1 = 1.1",
            1,
        )
        .replacen(
            "rtol = 1e-10",
            "rtol = 1e-10\nmax_iter = 1\nstart = \"tied\"",
            1,
        );
    let bad = Scene::from_toml_str(&bad_text).unwrap();
    let err = bad.run(&dir).unwrap_err();
    assert!(
        matches!(err, Error::NotConverged { .. }),
        "expected a solver failure, got {err}"
    );
    assert_eq!(listing(&dir), before, "files appeared or vanished");
    for (f, c) in before.iter().zip(&contents) {
        assert_eq!(
            &std::fs::read(dir.join(f)).unwrap(),
            c,
            "{f} was overwritten"
        );
    }

    // An invalid scene fails before anything is touched, too.
    let invalid = bad_text.replacen("max_iter = 1", "max_iter = 0", 1);
    rejects(&invalid, "solver.max_iter", "0");
    assert_eq!(listing(&dir), before);
}

#[test]
fn summary_and_pressure_profile_without_vtu() {
    let dir = tmp("summary-profile");
    let text = format!("{BASE}\n[output]\nsummary = true\npressure_profile = true\n");
    let report = Scene::from_toml_str(&text).unwrap().run(&dir).unwrap();
    assert_eq!(
        listing(&dir),
        vec![
            files::PRESSURE_PROFILE.to_string(),
            files::SUMMARY.to_string()
        ]
    );
    // Taylor-like block: the contact force balances pressure and weight.
    let applied = report.applied_force.unwrap();
    assert!((applied[1] + 1e8 + 0.5).abs() < 1e-3, "{applied:?}");
    assert!((report.contact_force[1] + applied[1]).abs() < 1e-6 * 1e8);
    let csv = std::fs::read_to_string(dir.join(files::PRESSURE_PROFILE)).unwrap();
    for l in csv.lines().skip(1) {
        let p: f64 = l.split(',').nth(4).unwrap().parse().unwrap();
        assert!((p / 1e8 - 1.0).abs() < 1e-6, "{l}");
    }
}

// ---------------------------------------------------------------------------
// Syntax and shape errors
// ---------------------------------------------------------------------------

#[test]
fn syntax_error_names_line_and_column() {
    let text = base_with("rtol = 1e-10", "rtol = 1e-10 2");
    let line = 1 + text.lines().position(|l| l.contains("1e-10 2")).unwrap();
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(msg.contains(&format!("`line {line}, column ")), "{msg}");
    assert!(msg.contains("= rtol = 1e-10 2:"), "{msg}");
    assert!(msg.contains("not valid TOML"), "{msg}");
}

#[test]
fn unknown_top_level_key_is_rejected_with_its_path() {
    let text = format!("{BASE}\n[outputs]\nvtu = true\n");
    let msg = rejects(&text, "outputs", "{ vtu = true }");
    assert!(msg.contains("unknown field `outputs`"), "{msg}");
}

#[test]
fn unknown_nested_key_is_rejected_with_its_path() {
    let text = base_with("poisson = 0.3,", "poisson = 0.3, nu = 0.3,");
    let msg = rejects(&text, "body[0].material.nu", "0.3");
    assert!(msg.contains("unknown field `nu`"), "{msg}");
    let text = base_with("x1 = 1.0, y1 = 0.5", "x1 = 1.0, y1 = 0.5, z1 = 2");
    rejects(&text, "body[0].geometry.rectangle.z1", "2");
    let text = base_with("side = \"eta_max\" }", "side = \"eta_max\", rigid = true }");
    rejects(&text, "contact[0].master.rigid", "true");
    let text = base_with("rtol = 1e-10", "rtol = 1e-10\ntolerance = 1");
    rejects(&text, "solver.tolerance", "1");
    let text = format!("{BASE}\n[output]\nvtk = true\n");
    rejects(&text, "output.vtk", "true");
}

#[test]
fn type_errors_name_their_path() {
    let text = base_with(
        "young = 1.0e9, poisson = 0.3",
        "young = \"big\", poisson = 0.3",
    );
    let msg = rejects(&text, "body[0].material.young", "\"big\"");
    assert!(msg.contains("expected f64"), "{msg}");
    let text = base_with("elements = [2, 1]", "elements = [2, -1]");
    rejects(&text, "body[0].refine.elements[1]", "-1");
    let text = base_with("elements = [2, 1]", "elements = [2]");
    rejects(&text, "body[0].refine.elements", "[2]");
    let text = base_with("kind = \"bfgs\"", "kind = \"lbfgs\"");
    rejects(&text, "solver.kind", "\"lbfgs\"");
    let text = base_with(
        "kind = \"bfgs\"",
        "kind = \"bfgs\"\nfactorisation = \"cholesky\"",
    );
    rejects(&text, "solver.factorisation", "\"cholesky\"");
    let text = base_with("plane = \"stress\"", "plane = \"strainn\"");
    rejects(&text, "body[0].material.plane", "\"strainn\"");
}

#[test]
fn unknown_geometry_kind_is_rejected() {
    let text = base_with("{ rectangle = {", "{ square = {");
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(msg.contains("`body[0].geometry`"), "{msg}");
    assert!(msg.contains("unknown variant `square`"), "{msg}");
}

#[test]
fn invalid_side_name_is_rejected() {
    let text = base_with("slave_side = \"eta_min\"", "slave_side = \"bottom\"");
    let msg = rejects(&text, "contact[0].slave_side", "\"bottom\"");
    assert!(msg.contains("eta_min"), "{msg}");
    let text = base_with("side = \"eta_min\"", "side = \"south\"");
    rejects(&text, "support[0].side", "\"south\"");
}

#[test]
fn missing_required_key_names_its_table() {
    let text = base_with("name = \"lower\"\n", "");
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(
        msg.contains("`body[0]`") && msg.contains("missing field `name`"),
        "{msg}"
    );
}

#[test]
fn unreadable_file_is_invalid_input() {
    let err = Scene::load("/nonexistent/scene.toml").unwrap_err();
    assert!(matches!(err, Error::InvalidInput { .. }), "{err}");
    assert!(err.to_string().contains("/nonexistent/scene.toml"));
}

// ---------------------------------------------------------------------------
// Validation rules, one test each
// ---------------------------------------------------------------------------

#[test]
fn young_modulus_must_be_positive() {
    let text = base_with("young = 1.0e9", "young = -1.0");
    rejects(&text, "body[0].material.young", "-1");
    let text = base_with("young = 1.0e9", "young = 0.0");
    rejects(&text, "body[0].material.young", "0");
}

#[test]
fn poisson_ratio_must_lie_in_range() {
    let text = base_with("poisson = 0.3", "poisson = 0.5");
    rejects(&text, "body[0].material.poisson", "0.5");
    let text = base_with("poisson = 0.3", "poisson = -1.0");
    rejects(&text, "body[0].material.poisson", "-1");
}

#[test]
fn numbers_must_be_finite() {
    let text = base_with("young = 1.0e9", "young = inf");
    rejects(&text, "body[0].material.young", "inf");
    let text = base_with("x0 = 0.0, y0 = 0.0", "x0 = nan, y0 = 0.0");
    rejects(&text, "body[0].geometry.rectangle.x0", "NaN");
    let text = base_with("value = 0.0", "value = -inf");
    rejects(&text, "support[0].value", "-inf");
}

#[test]
fn refine_degree_must_lie_in_range() {
    let text = base_with(
        "degree = 2, elements = [2, 1]",
        "degree = 0, elements = [2, 1]",
    );
    rejects(&text, "body[0].refine.degree", "0");
    let text = base_with(
        "degree = 2, elements = [2, 1]",
        "degree = 11, elements = [2, 1]",
    );
    rejects(&text, "body[0].refine.degree", "11");
}

#[test]
fn refine_degree_cannot_lower_the_geometry_degree() {
    let text = one_body(
        "{ half_disk = { center = [0.0, 0.2], radius = 0.2 } }",
        "refine = { degree = 1, elements = [2, 2] }",
    );
    let msg = rejects(&text, "body[0].refine.degree", "1");
    assert!(msg.contains("lagrange"), "{msg}");
}

#[test]
fn elements_must_lie_in_range() {
    let text = base_with("elements = [2, 1]", "elements = [2, 0]");
    rejects(&text, "body[0].refine.elements[1]", "0");
    let text = base_with("elements = [2, 1]", "elements = [5000, 1]");
    rejects(&text, "body[0].refine.elements[0]", "5000");
}

#[test]
fn lagrange_degree_must_lie_in_range() {
    let text = base_with(
        "degree = 2, elements = [2, 1]",
        "lagrange = 5, elements = [2, 1]",
    );
    rejects(&text, "body[0].refine.lagrange", "5");
    let text = base_with(
        "degree = 2, elements = [2, 1]",
        "lagrange = 0, elements = [2, 1]",
    );
    rejects(&text, "body[0].refine.lagrange", "0");
}

#[test]
fn refine_needs_exactly_one_of_degree_and_lagrange() {
    let text = base_with(
        "degree = 2, elements = [2, 1]",
        "degree = 2, lagrange = 2, elements = [2, 1]",
    );
    rejects(&text, "body[0].refine.degree", "2");
    let text = base_with("degree = 2, elements = [2, 1]", "elements = [2, 1]");
    rejects(&text, "body[0].refine", "elements = [2, 1]");
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
fn quadrature_order_must_lie_in_range() {
    let text = base_with(
        "plane = \"stress\" }\n\n[[body]]",
        "plane = \"stress\" }\nquadrature = 0\n\n[[body]]",
    );
    rejects(&text, "body[0].quadrature", "0");
}

#[test]
fn radii_must_be_positive() {
    let text = one_body(
        "{ half_disk = { center = [0.0, 0.2], radius = -0.2 } }",
        "refine = { degree = 2, elements = [2, 2] }",
    );
    rejects(&text, "body[0].geometry.half_disk.radius", "-0.2");
    let text = one_body("{ full_disk = { center = [0.0, 0.0], radius = 0.0 } }", "");
    rejects(&text, "body[0].geometry.full_disk.radius", "0");
    let text = one_body(
        "{ full_disk = { center = [0.0, 0.0], radius = 1e308 } }",
        "",
    );
    rejects(&text, "body[0].geometry.full_disk.radius", "1e308");
    let text = one_body(
        "{ quarter_annulus = { inner_radius = -1.0, outer_radius = 2.0 } }",
        "",
    );
    rejects(&text, "body[0].geometry.quarter_annulus.inner_radius", "-1");
}

#[test]
fn annulus_outer_radius_must_exceed_inner() {
    let text = one_body(
        "{ quarter_annulus = { inner_radius = 2.0, outer_radius = 1.0 } }",
        "",
    );
    rejects(&text, "body[0].geometry.quarter_annulus.outer_radius", "1");
}

#[test]
fn disk_center_must_be_finite() {
    let text = one_body("{ full_disk = { center = [inf, 0.0], radius = 1.0 } }", "");
    rejects(&text, "body[0].geometry.full_disk.center[0]", "inf");
}

#[test]
fn rectangle_must_have_positive_extent() {
    let text = base_with("x1 = 1.0, y1 = 0.5", "x1 = -1.0, y1 = 0.5");
    rejects(&text, "body[0].geometry.rectangle.x1", "-1");
    let text = base_with("x1 = 1.0, y1 = 0.5", "x1 = 1.0, y1 = 0.0");
    rejects(&text, "body[0].geometry.rectangle.y1", "0");
}

#[test]
fn quadrilateral_must_be_convex_and_counter_clockwise() {
    let ok = one_body(
        "{ quadrilateral = { corners = [[0.0, 0.0], [2.0, 0.0], [1.5, 1.0], [0.2, 1.2]] } }",
        "refine = { degree = 2, elements = [2, 2] }",
    );
    Scene::from_toml_str(&ok).unwrap().build().unwrap();
    let clockwise = one_body(
        "{ quadrilateral = { corners = [[0.0, 0.0], [0.2, 1.2], [1.5, 1.0], [2.0, 0.0]] } }",
        "",
    );
    rejects(
        &clockwise,
        "body[0].geometry.quadrilateral.corners[0]",
        "[0.0, 0.0]",
    );
    let dart = one_body(
        "{ quadrilateral = { corners = [[0.0, 0.0], [2.0, 0.0], [0.5, 0.5], [0.0, 2.0]] } }",
        "",
    );
    rejects(
        &dart,
        "body[0].geometry.quadrilateral.corners[2]",
        "[0.5, 0.5]",
    );
}

fn nurbs_body(knots_xi: &str, control_points: &str, weights: &str) -> String {
    one_body(
        &format!(
            "{{ nurbs = {{ degree = [1, 1], knots_xi = {knots_xi}, knots_eta = [0.0, 0.0, 1.0, 1.0], \
             control_points = {control_points}{weights} }} }}"
        ),
        "refine = { degree = 2, elements = [2, 2] }",
    )
}

const SQUARE: &str = "[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [1.0, 1.0]]";

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
fn nurbs_weights_must_be_positive() {
    let text = nurbs_body(
        "[0.0, 0.0, 1.0, 1.0]",
        SQUARE,
        ", weights = [1.0, 1.0, 0.0, 1.0]",
    );
    rejects(&text, "body[0].geometry.nurbs.weights[2]", "0");
    let text = nurbs_body(
        "[0.0, 0.0, 1.0, 1.0]",
        SQUARE,
        ", weights = [1.0, 1.0, 1.0]",
    );
    rejects(&text, "body[0].geometry.nurbs.weights", "3 weights");
}

#[test]
fn nurbs_knots_must_be_open() {
    let text = nurbs_body("[0.0, 0.5, 1.0, 1.0]", SQUARE, "");
    let msg = rejects(&text, "body[0].geometry.nurbs.knots_xi[0]", "0");
    assert!(msg.contains("open"), "{msg}");
}

#[test]
fn nurbs_knots_must_be_non_decreasing() {
    let text = nurbs_body(
        "[0.0, 0.0, 0.7, 0.3, 1.0, 1.0]",
        "[[0.0, 0.0], [0.3, 0.0], [0.7, 0.0], [1.0, 0.0], [0.0, 1.0], [0.3, 1.0], [0.7, 1.0], [1.0, 1.0]]",
        "",
    );
    let msg = rejects(&text, "body[0].geometry.nurbs.knots_xi[3]", "0.3");
    assert!(msg.contains("non-decreasing"), "{msg}");
}

#[test]
fn nurbs_knots_must_be_finite() {
    let text = nurbs_body("[0.0, 0.0, nan, 1.0, 1.0]", SQUARE, "");
    rejects(&text, "body[0].geometry.nurbs.knots_xi[2]", "NaN");
}

#[test]
fn nurbs_degree_must_lie_in_range() {
    let text = nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, "").replacen(
        "degree = [1, 1]",
        "degree = [0, 1]",
        1,
    );
    rejects(&text, "body[0].geometry.nurbs.degree[0]", "0");
    let text = nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, "").replacen(
        "degree = [1, 1]",
        "degree = [1, 12]",
        1,
    );
    rejects(&text, "body[0].geometry.nurbs.degree[1]", "12");
}

#[test]
fn nurbs_control_net_must_match_the_knots() {
    let text = nurbs_body(
        "[0.0, 0.0, 1.0, 1.0]",
        "[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]",
        "",
    );
    rejects(&text, "body[0].geometry.nurbs.control_points", "3 points");
    let text = nurbs_body(
        "[0.0, 0.0, 1.0, 1.0]",
        "[[0.0, 0.0], [1.0, 0.0], [0.0, inf], [1.0, 1.0]]",
        "",
    );
    rejects(&text, "body[0].geometry.nurbs.control_points[2][1]", "inf");
}

#[test]
fn a_scene_needs_a_body() {
    let msg = Scene::from_toml_str("title = \"empty\"\n")
        .unwrap_err()
        .to_string();
    assert!(msg.contains("`body` = []"), "{msg}");
}

#[test]
fn body_names_must_be_unique() {
    let text = base_with("name = \"upper\"", "name = \"lower\"");
    let msg = rejects(&text, "body[1].name", "\"lower\"");
    assert!(msg.contains("body[0]"), "{msg}");
}

#[test]
fn body_names_must_not_be_empty() {
    let text = base_with("name = \"upper\"", "name = \"  \"");
    rejects(&text, "body[1].name", "\"  \"");
}

#[test]
fn supports_must_refer_to_existing_bodies() {
    let text = base_with(
        "body = \"lower\"\nside = \"eta_min\"",
        "body = \"floor\"\nside = \"eta_min\"",
    );
    let msg = rejects(&text, "support[0].body", "\"floor\"");
    assert!(msg.contains("lower, upper"), "{msg}");
}

#[test]
fn loads_must_refer_to_existing_bodies() {
    let text = base_with(
        "pressure = { body = \"upper\"",
        "pressure = { body = \"top\"",
    );
    rejects(&text, "load[0].pressure.body", "\"top\"");
    let text = base_with(
        "body_force = { body = \"upper\"",
        "body_force = { body = \"x\"",
    );
    rejects(&text, "load[1].body_force.body", "\"x\"");
    let text = base_with("traction = { body = \"upper\"", "traction = { body = \"y\"");
    rejects(&text, "load[2].traction.body", "\"y\"");
}

#[test]
fn load_values_must_be_finite() {
    let text = base_with("pressure = 1.0e8", "pressure = nan");
    rejects(&text, "load[0].pressure.pressure", "NaN");
    let text = base_with("force = [0.0, -1.0]", "force = [0.0, -inf]");
    rejects(&text, "load[1].body_force.force[1]", "-inf");
    let text = base_with("traction = [0.0, 0.0]", "traction = [inf, 0.0]");
    rejects(&text, "load[2].traction.traction[0]", "inf");
}

#[test]
fn contact_slave_must_exist() {
    let text = base_with("slave = \"upper\"", "slave = \"top\"");
    rejects(&text, "contact[0].slave", "\"top\"");
}

#[test]
fn contact_master_body_must_exist_and_differ_from_the_slave() {
    let text = base_with("master = { body = \"lower\"", "master = { body = \"floor\"");
    rejects(&text, "contact[0].master.body", "\"floor\"");
    let text = base_with("master = { body = \"lower\"", "master = { body = \"upper\"");
    let msg = rejects(&text, "contact[0].master.body", "\"upper\"");
    assert!(msg.contains("self-contact"), "{msg}");
}

#[test]
fn contact_master_needs_a_side_or_a_segment() {
    let text = base_with(
        "master = { body = \"lower\", side = \"eta_max\" }",
        "master = { body = \"lower\" }",
    );
    rejects(&text, "contact[0].master.side", "(absent)");
    let text = base_with(
        "master = { body = \"lower\", side = \"eta_max\" }",
        "master = {}",
    );
    rejects(&text, "contact[0].master", "{}");
    let text = base_with(
        "master = { body = \"lower\", side = \"eta_max\" }",
        "master = { body = \"lower\", side = \"eta_max\", rigid_segment = { from = [0.0, 0.0], to = [1.0, 0.0] } }",
    );
    rejects(&text, "contact[0].master", "rigid_segment and body");
}

#[test]
fn rigid_segment_must_be_finite_and_non_degenerate() {
    let rigid = |seg: &str| {
        base_with(
            "master = { body = \"lower\", side = \"eta_max\" }",
            &format!("master = {{ rigid_segment = {seg} }}"),
        )
    };
    rejects(
        &rigid("{ from = [0.0, nan], to = [1.0, 0.5] }"),
        "contact[0].master.rigid_segment.from[1]",
        "NaN",
    );
    rejects(
        &rigid("{ from = [0.5, 0.5], to = [0.5, 0.5] }"),
        "contact[0].master.rigid_segment.to",
        "[0.5, 0.5]",
    );
    // A valid rigid floor under the upper block builds.
    Scene::from_toml_str(&rigid("{ from = [-1.0, 0.5], to = [2.0, 0.5] }"))
        .unwrap()
        .build()
        .unwrap();
}

#[test]
fn contact_sides_must_not_be_collapsed() {
    // A triangle: the η = 1 side of this bilinear patch is a single point.
    let tri = "{ nurbs = { degree = [1, 1], knots_xi = [0.0, 0.0, 1.0, 1.0], \
               knots_eta = [0.0, 0.0, 1.0, 1.0], \
               control_points = [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.5, 1.0]] } }";
    let text = format!(
        "{}\n[[contact]]\nslave = \"b\"\nslave_side = \"eta_max\"\n\
         master = {{ rigid_segment = {{ from = [0.0, 2.0], to = [1.0, 2.0] }} }}\n",
        one_body(tri, "refine = { degree = 2, elements = [2, 2] }")
    );
    let msg = rejects(&text, "contact[0].slave_side", "eta_max");
    assert!(msg.contains("collapsed"), "{msg}");
}

#[test]
fn theta_must_be_one_zero_or_minus_one() {
    let text = base_with(
        "side = \"eta_max\" }\n",
        "side = \"eta_max\" }\nnitsche = { theta = 0.5 }\n",
    );
    rejects(&text, "contact[0].nitsche.theta", "0.5");
    let text = base_with(
        "side = \"eta_max\" }\n",
        "side = \"eta_max\" }\nnitsche = { theta = nan }\n",
    );
    rejects(&text, "contact[0].nitsche.theta", "nan");
    for ok in ["1", "0", "-1"] {
        let text = base_with(
            "side = \"eta_max\" }\n",
            &format!("side = \"eta_max\" }}\nnitsche = {{ theta = {ok} }}\n"),
        );
        Scene::from_toml_str(&text).unwrap();
    }
}

#[test]
fn penalty_factor_must_be_positive() {
    let text = base_with(
        "side = \"eta_max\" }\n",
        "side = \"eta_max\" }\nnitsche = { penalty_factor = 0 }\n",
    );
    rejects(&text, "contact[0].nitsche.penalty_factor", "0");
    let text = base_with(
        "side = \"eta_max\" }\n",
        "side = \"eta_max\" }\nnitsche = { penalty_factor = -2.5 }\n",
    );
    rejects(&text, "contact[0].nitsche.penalty_factor", "-2.5");
}

#[test]
fn gauss_points_must_lie_in_range() {
    let text = base_with(
        "side = \"eta_max\" }\n",
        "side = \"eta_max\" }\nnitsche = { gauss_points = 0 }\n",
    );
    rejects(&text, "contact[0].nitsche.gauss_points", "0");
}

#[test]
fn solver_tolerances_must_lie_in_the_unit_interval() {
    let text = base_with("rtol = 1e-10", "rtol = 0.0");
    rejects(&text, "solver.rtol", "0");
    let text = base_with("rtol = 1e-10", "rtol = 1e-10\nutol = 1.0");
    rejects(&text, "solver.utol", "1");
    let text = base_with("rtol = 1e-10", "rtol = 1e-10\ncurvature_tol = nan");
    rejects(&text, "solver.curvature_tol", "NaN");
}

#[test]
fn solver_iteration_limit_must_be_positive() {
    let text = base_with("rtol = 1e-10", "rtol = 1e-10\nmax_iter = 0");
    rejects(&text, "solver.max_iter", "0");
}

#[test]
fn vtu_subdivisions_must_lie_in_range() {
    let text = format!("{BASE}\n[output]\nvtu = true\nvtu_subdivisions = 0\n");
    rejects(&text, "output.vtu_subdivisions", "0");
}

#[test]
fn pressure_outputs_need_a_contact_pair() {
    let text = one_body(
        "{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }",
        "",
    ) + "\n[output]\npressure_profile = true\n";
    rejects(&text, "output.pressure_profile", "true");
    let text = one_body(
        "{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }",
        "",
    ) + "\n[output]\nfigures = true\n";
    rejects(&text, "output.figures", "true");
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

// ---------------------------------------------------------------------------
// Well-posedness: rigid modes, quadrature, input scales
// ---------------------------------------------------------------------------

/// A block on a rigid floor with the given supports (TOML tables).
fn block_on_floor(supports: &str) -> String {
    format!(
        r#"
[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 }} }}
refine = {{ degree = 2, elements = [2, 2] }}
material = {{ young = 1.0e6, poisson = 0.3, plane = "strain" }}
{supports}
[[load]]
pressure = {{ body = "block", side = "eta_max", pressure = 1.0e4 }}

[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-0.5, 0.0], to = [1.5, 0.0] }} }}
"#
    )
}

#[test]
fn a_body_free_to_slide_along_the_contact_surface_is_rejected() {
    let msg = rejects(&block_on_floor(""), "body[0]", "\"block\"");
    assert!(msg.contains("slide along (1, 0)"), "{msg}");
    assert!(
        msg.contains("contact normals") && msg.contains("[[support]]"),
        "{msg}"
    );
    // Loaded or not.
    let unloaded = block_on_floor("").replace("pressure = 1.0e4", "pressure = 0.0");
    rejects(&unloaded, "body[0]", "\"block\"");
    // A support that holds the sliding makes it well posed.
    let held = "[[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n";
    Scene::from_toml_str(&block_on_floor(held))
        .unwrap()
        .build()
        .unwrap();
}

#[test]
fn the_upper_taylor_block_without_its_side_support_is_named() {
    let text = base_with(
        "[[support]]\nbody = \"upper\"\nside = \"xi_min\"\ncomponent = \"x\"\n",
        "",
    );
    let msg = rejects(&text, "body[1]", "\"upper\"");
    assert!(msg.contains("slide along (1, 0)"), "{msg}");
}

#[test]
fn a_body_free_to_rotate_about_a_curved_contact_surface_is_rejected() {
    // A quarter annulus bearing on a concentric one: the contact normals
    // are radial, so rotation about the common centre is never resisted.
    let text = include_str!("fixtures/rotating_annuli.toml");
    let msg = rejects(text, "body[1]", "\"inner\"");
    assert!(msg.contains("rotate about (0, 0)"), "{msg}");
    // `check` finds it too, without assembling anything.
    let scene = Scene::from_toml_str(text).unwrap();
    let e = scene
        .check(&iga_contact::resources::Budget::from_machine())
        .unwrap_err();
    assert!(e.to_string().contains("rotate about (0, 0)"), "{e}");
}

#[test]
fn a_body_with_neither_support_nor_contact_is_rejected() {
    let text = one_body(
        "{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }",
        "",
    )
    .replace(
        "[[support]]\nbody = \"b\"\nside = \"eta_min\"\ncomponent = \"x\"\n",
        "",
    );
    let msg = rejects(&text, "body[0]", "\"b\"");
    assert!(
        msg.contains("slide along (1, 0)") && msg.contains("no contact"),
        "{msg}"
    );
}

#[test]
fn quadrature_below_the_degree_needs_is_refused_unless_allowed() {
    let text = base_with(
        "plane = \"stress\" }\n\n[[body]]",
        "plane = \"stress\" }\nquadrature = 2\n\n[[body]]",
    );
    let msg = rejects(&text, "body[0].quadrature", "2");
    assert!(
        msg.contains("3 Gauss points") && msg.contains("allow_underintegration = true"),
        "{msg}"
    );
    let allowed = format!("allow_underintegration = true\n{text}");
    Scene::from_toml_str(&allowed).unwrap().build().unwrap();
    // p + 1 is accepted as it is.
    let text = base_with(
        "plane = \"stress\" }\n\n[[body]]",
        "plane = \"stress\" }\nquadrature = 3\n\n[[body]]",
    );
    Scene::from_toml_str(&text).unwrap();

    let text = base_with(
        "side = \"eta_max\" }\n",
        "side = \"eta_max\" }\nnitsche = { gauss_points = 2 }\n",
    );
    let msg = rejects(&text, "contact[0].nitsche.gauss_points", "2");
    assert!(msg.contains("allow_underintegration"), "{msg}");
    Scene::from_toml_str(&format!("allow_underintegration = true\n{text}")).unwrap();
}

/// Largest |σ_yy / σ_exact − 1| of the Taylor scene over a 5 × 5 sampling
/// of every element, with the given body and contact quadrature.
/// `None` if the solve fails.
fn taylor_syy_error(quadrature: usize, gauss_points: usize) -> Option<f64> {
    let text = format!(
        "allow_underintegration = true\n{}",
        scene_file("taylor.toml")
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

#[test]
fn input_scales_beyond_double_precision_are_named_as_such() {
    let text =
        block_on_floor("[[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n");
    let tiny = text.replace("young = 1.0e6", "young = 1e-300");
    let msg = rejects(&tiny, "body[0].material.young", "1e-300");
    assert!(msg.contains("underflows"), "{msg}");
    assert!(!msg.contains("diverged"), "{msg}");
    let huge = text.replace("pressure = 1.0e4", "pressure = 1e200");
    let msg = rejects(&huge, "load[0].pressure.pressure", "1e200");
    assert!(msg.contains("overflows"), "{msg}");
    // A soft material under a large load: the displacements overflow.
    let soft = text
        .replace("young = 1.0e6", "young = 1e-100")
        .replace("pressure = 1.0e4", "pressure = 1e100");
    let msg = rejects(&soft, "load[0].pressure.pressure", "1e100");
    assert!(msg.contains("displacements would be of order"), "{msg}");
    // A geometry too large to differentiate over.
    let big = one_body(
        "{ full_disk = { center = [0.0, 0.0], radius = 1e200 } }",
        "",
    );
    let msg = rejects(&big, "body[0].geometry.full_disk.radius", "1e200");
    assert!(msg.contains("overflows"), "{msg}");
}

#[test]
fn geometry_errors_name_the_body() {
    // A bow-tie control net: the map folds.
    let text = one_body(
        "{ nurbs = { degree = [1, 1], knots_xi = [0.0, 0.0, 1.0, 1.0], \
           knots_eta = [0.0, 0.0, 1.0, 1.0], \
           control_points = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] } }",
        "",
    )
    .replace("\"b\"", "\"bowtie\"");
    let Err(e) = Scene::from_toml_str(&text).unwrap().build() else {
        panic!("a folded map was accepted");
    };
    let msg = e.to_string();
    assert!(matches!(e, Error::Geometry(_)), "{msg}");
    assert!(msg.contains("body[0] (\"bowtie\")"), "{msg}");
}

#[test]
fn a_degenerate_slave_side_is_not_reported_as_the_master() {
    // A quadratic bottom side whose first two control points coincide: its
    // tangent vanishes at t = 0, where the floor's end projects.
    let text = r#"
[[body]]
name = "pinched"
geometry = { nurbs = { degree = [2, 1], knots_xi = [0.0, 0.0, 0.0, 1.0, 1.0, 1.0], knots_eta = [0.0, 0.0, 1.0, 1.0], control_points = [[0.0, 0.0], [0.0, 0.0], [1.0, 0.0], [0.0, 1.0], [0.5, 1.0], [1.0, 1.0]] } }
material = { young = 1.0e6, poisson = 0.3, plane = "strain" }

[[support]]
body = "pinched"
side = "xi_min"
component = "x"

[[contact]]
slave = "pinched"
slave_side = "eta_min"
master = { rigid_segment = { from = [-0.5, 0.0], to = [1.5, 0.0] } }
"#;
    let Err(e) = Scene::from_toml_str(text).and_then(|s| s.build()) else {
        panic!("a side with a vanishing tangent was accepted");
    };
    let msg = e.to_string();
    assert!(!msg.contains("master"), "{msg}");
    assert!(
        msg.contains("contact[0]: the slave side eta_min of body \"pinched\"")
            && msg.contains("degenerate"),
        "{msg}"
    );
}

// ---------------------------------------------------------------------------
// What outputs write
// ---------------------------------------------------------------------------

/// Every number-like token of `text` that is a negative zero.
fn negative_zeros(text: &str) -> Vec<String> {
    text.split(|c: char| c.is_whitespace() || ",;=[]{}\"<>".contains(c))
        .filter(|t| t.starts_with('-'))
        .filter(|t| t.parse::<f64>().is_ok_and(|v| v == 0.0))
        .map(String::from)
        .collect()
}

#[test]
fn a_zero_load_run_reports_residual_zero_and_no_output_has_negative_zeros() {
    let dir = tmp("zero-load");
    let held = "[[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n";
    let text = block_on_floor(held).replace("pressure = 1.0e4", "pressure = 0.0")
        + "\n[output]\nsummary = true\npressure_profile = true\nvtu = true\niterations = true\n";
    Scene::from_toml_str(&text).unwrap().run(&dir).unwrap();
    let summary: toml::Table =
        toml::from_str(&std::fs::read_to_string(dir.join(files::SUMMARY)).unwrap()).unwrap();
    assert_eq!(
        summary["relative_residual"].as_float(),
        Some(0.0),
        "{summary}"
    );
    for f in listing(&dir) {
        let text = std::fs::read_to_string(dir.join(&f)).unwrap();
        assert!(
            negative_zeros(&text).is_empty(),
            "{f}: {:?}",
            negative_zeros(&text)
        );
    }
    // A loaded run: pressures of open points are zero, never −0.
    let dir = tmp("no-negative-zeros");
    Scene::from_toml_str(&scene_file("hertz.toml"))
        .unwrap()
        .run(&dir)
        .unwrap();
    for f in listing(&dir) {
        let text = std::fs::read_to_string(dir.join(&f)).unwrap();
        assert!(
            negative_zeros(&text).is_empty(),
            "{f}: {:?}",
            negative_zeros(&text)
        );
    }
}

#[test]
fn titles_with_control_characters_still_give_well_formed_xml() {
    let dir = tmp("xml-title");
    let text = scene_file("hertz.toml").replace(
        "title = \"Hertz contact, IGA p = 2, 8 × 8\"",
        "title = \"nul \\u0000, bell \\u0007, <tag> & \\\"quotes\\\" \\u001b[31m\"",
    );
    let scene = Scene::from_toml_str(&text).unwrap();
    assert!(scene.title.as_deref().unwrap().contains('\u{0}'));
    scene.run(&dir).unwrap();
    for f in [files::FIGURE, files::VTU] {
        let xml = std::fs::read_to_string(dir.join(f)).unwrap();
        if let Err(e) = roxmltree::Document::parse(&xml) {
            panic!("{f} is not well-formed XML: {e}");
        }
    }
    let svg = std::fs::read_to_string(dir.join(files::FIGURE)).unwrap();
    assert!(svg.contains("&lt;tag&gt; &amp;"), "markup not escaped");
}
