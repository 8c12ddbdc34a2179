//! Scene files: parsing, validation (one table of refused scenes, each row
//! checking that the error names the key path and the value), the shipped
//! scenes, and lean, atomic output.

use companion::hertz as setup;

use iga_contact::post::{PressureProfile, PROFILE_SAMPLES_PER_ELEMENT};
use iga_contact::report::atomic::{read_manifest, MANIFEST};
use iga_contact::scene::{files, RefineSpec, Scene};
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

/// Asserts that `text` fails, parsing or building, with an invalid-input
/// error naming `path` and showing `value` (a row of [`rejected`]).
#[track_caller]
fn rejects(text: &str, path: &'static str, value: &'static str) {
    if let Some(why) = reject(text, path, value).failure() {
        panic!("`{path}`: {why}");
    }
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
    assert_eq!(lines.next(), Some("contact,x,y,bracket,pressure,regular"));
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
    let mut scene = companion::shipped("hertz.toml").unwrap();
    scene.nitsche_mut().for_each(|n| n.penalty_factor = 1e-3);
    scene.solver = SolverOptions::default();
    scene.output = Default::default();
    let report = scene.run(&dir).unwrap();
    assert!(matches!(
        report.warnings.as_slice(),
        [solver::Warning::PenaltyBelowBound { contact: 0, .. }]
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
    let mut fine = companion::shipped("hertz.toml").unwrap();
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
// Syntax errors and errors beside the table below
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

/// An inline table left open: TOML finds the error at the start of the
/// next line, but the brace was left open on this one, which the message
/// names (inline tables do not go on to the next line; a multi-line array
/// keeps the line TOML gives).
#[test]
fn an_unclosed_inline_table_is_named_on_its_own_line() {
    let text = base_with("y1 = 0.5 } }", "y1 = 0.5 }");
    let line = 1 + text.lines().position(|l| l.contains("y1 = 0.5 }")).unwrap();
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(msg.contains(&format!("`line {line}, column ")), "{msg}");
    assert!(msg.contains("not closed on it"), "{msg}");
    let array = "title = \"t\"\nv = [\n  1,\n  2\n  3,\n]\n";
    let msg = Scene::from_toml_str(array).unwrap_err().to_string();
    assert!(!msg.contains("not closed on it"), "{msg}");
}

#[test]
fn unknown_geometry_kind_is_rejected() {
    let text = base_with("{ rectangle = {", "{ square = {");
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(msg.contains("`body[0].geometry`"), "{msg}");
    assert!(msg.contains("unknown variant `square`"), "{msg}");
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
// Accepted scenes beside the rejected ones
// ---------------------------------------------------------------------------

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
fn a_support_that_holds_the_sliding_makes_the_block_well_posed() {
    Scene::from_toml_str(&block_on_floor(HELD))
        .unwrap()
        .build()
        .unwrap();
}

#[test]
fn check_finds_a_free_rotation_without_assembling() {
    // A quarter annulus bearing on a concentric one: the contact normals
    // are radial, so rotation about the common centre is never resisted.
    let text = include_str!("fixtures/rotating_annuli.toml");
    let scene = Scene::from_toml_str(text).unwrap();
    let e = scene
        .check(&iga_contact::resources::Budget::from_machine())
        .unwrap_err();
    assert!(e.to_string().contains("rotate about (0, 0)"), "{e}");
}

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

// ---------------------------------------------------------------------------
// Rejected scenes: one table, one row per refused case
// ---------------------------------------------------------------------------

/// A scene that must be refused, by parsing or by building: the key path
/// and the value the error names, and what its message says (and does
/// not).
struct Reject {
    text: String,
    path: &'static str,
    value: &'static str,
    says: &'static [&'static str],
    lacks: &'static [&'static str],
}

/// A row of [`rejected`].
fn reject(text: impl Into<String>, path: &'static str, value: &'static str) -> Reject {
    Reject {
        text: text.into(),
        path,
        value,
        says: &[],
        lacks: &[],
    }
}

impl Reject {
    /// Fragments the message must contain.
    fn says(self, says: &'static [&'static str]) -> Self {
        Self { says, ..self }
    }

    /// Fragments the message must not contain.
    fn lacks(self, lacks: &'static [&'static str]) -> Self {
        Self { lacks, ..self }
    }

    /// Why this row fails, if it does.
    fn failure(&self) -> Option<String> {
        let (path, value) = (self.path, self.value);
        let err = match Scene::from_toml_str(&self.text).and_then(|s| s.build()) {
            Ok(_) => return Some("accepted".into()),
            Err(e) => e,
        };
        let msg = err.to_string();
        let Error::InvalidInput {
            field, value: v, ..
        } = &err
        else {
            return Some(format!("not invalid input: {msg}"));
        };
        if field != path || v != value {
            return Some(format!("names `{field}` = {v}: {msg}"));
        }
        if !msg.contains(&format!("`{path}` = {value}")) {
            return Some(format!("does not show `{path}` = {value}: {msg}"));
        }
        let missing: Vec<_> = self.says.iter().filter(|s| !msg.contains(*s)).collect();
        let present: Vec<_> = self.lacks.iter().filter(|s| msg.contains(*s)).collect();
        (!missing.is_empty() || !present.is_empty())
            .then(|| format!("lacks {missing:?}, has {present:?}: {msg}"))
    }
}

/// `BASE` with the contact pair's Nitsche table set to `{ set }`.
fn nitsche(set: &str) -> String {
    base_with(
        "side = \"eta_max\" }\n",
        &format!("side = \"eta_max\" }}\nnitsche = {{ {set} }}\n"),
    )
}

/// `BASE` with the contact pair's master set to `master`.
fn master(master: &str) -> String {
    base_with(
        "master = { body = \"lower\", side = \"eta_max\" }",
        &format!("master = {master}"),
    )
}

/// `BASE` with `degree = 2, elements = [2, 1]` of the lower body's refine
/// table replaced.
fn refine(to: &str) -> String {
    base_with("degree = 2, elements = [2, 1]", to)
}

/// `BASE` with a line added to the lower body's table.
fn lower_body(line: &str) -> String {
    base_with(
        "plane = \"stress\" }\n\n[[body]]",
        &format!("plane = \"stress\" }}\n{line}\n\n[[body]]"),
    )
}

/// A single body with no refinement and geometry `geometry`.
fn plain_body(geometry: &str) -> String {
    one_body(geometry, "")
}

/// A triangle: the η = 1 side of this bilinear patch is a single point.
const TRIANGLE: &str = "{ nurbs = { degree = [1, 1], knots_xi = [0.0, 0.0, 1.0, 1.0], \
                        knots_eta = [0.0, 0.0, 1.0, 1.0], \
                        control_points = [[0.0, 0.0], [1.0, 0.0], [0.5, 1.0], [0.5, 1.0]] } }";

const HELD: &str = "[[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n";

/// Every refused scene: the rules of the shape (unknown keys, types,
/// either-or tables), of the values, of well-posedness and of the scales
/// double precision carries. Adding a rule's case is adding a row.
// One row a line where it fits, so that the table reads as one.
#[rustfmt::skip]
fn rejected() -> Vec<Reject> {
    let nurbs_square = |degree: &str| {
        nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, "").replacen("degree = [1, 1]", degree, 1)
    };
    let held = block_on_floor(HELD);
    vec![
        // unknown keys
        reject(format!("{BASE}\n[outputs]\nvtu = true\n"), "outputs", "{ vtu = true }")
            .says(&["unknown field `outputs`"]),
        reject(base_with("poisson = 0.3,", "poisson = 0.3, nu = 0.3,"), "body[0].material.nu", "0.3")
            .says(&["unknown field `nu`"]),
        reject(base_with("x1 = 1.0, y1 = 0.5", "x1 = 1.0, y1 = 0.5, z1 = 2"), "body[0].geometry.rectangle.z1", "2"),
        reject(base_with("side = \"eta_max\" }", "side = \"eta_max\", rigid = true }"), "contact[0].master.rigid", "true"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\ntolerance = 1"), "solver.tolerance", "1"),
        reject(format!("{BASE}\n[output]\nvtk = true\n"), "output.vtk", "true"),
        // types
        reject(base_with("young = 1.0e9, poisson = 0.3", "young = \"big\", poisson = 0.3"), "body[0].material.young", "\"big\"")
            .says(&["expected a number"])
            .lacks(&["f64"]),
        // serde's type names do not reach the user
        reject(base_with("geometry = { rectangle = { x0 = 0.0", "geometry = { full_disk = { center = [0.0, 0.0], radius = 1.0 }, rectangle = { x0 = 0.0"), "body[0].geometry", "{ full_disk = { center = [0.0, 0.0], radius = 1.0 }, rectangle = { x0 = 0.0, x1 …")
            .says(&["name exactly one kind"]).lacks(&["element"]),
        reject(base_with("refine = { degree = 2, elements = [2, 1] }", "refine = 3"), "body[0].refine", "3").says(&["expected a table"]).lacks(&["struct", "RefineSpec"]),
        reject(refine("degree = 1.5, elements = [2, 1]"), "body[0].refine.degree", "1.5").says(&["non-negative integer"]).lacks(&["usize"]),
        reject(refine("degree = 2, elements = [2, -1]"), "body[0].refine.elements[1]", "-1"),
        reject(refine("degree = 2, elements = [2]"), "body[0].refine.elements", "[2]"),
        reject(base_with("kind = \"bfgs\"", "kind = \"lbfgs\""), "solver.kind", "\"lbfgs\""),
        reject(base_with("kind = \"bfgs\"", "kind = \"bfgs\"\nfactorisation = \"cholesky\""), "solver.factorisation", "\"cholesky\""),
        reject(base_with("plane = \"stress\"", "plane = \"strainn\""), "body[0].material.plane", "\"strainn\""),
        reject(base_with("slave_side = \"eta_min\"", "slave_side = \"bottom\""), "contact[0].slave_side", "\"bottom\"")
            .says(&["eta_min"]),
        reject(base_with("side = \"eta_min\"", "side = \"south\""), "support[0].side", "\"south\""),
        // materials and finite numbers
        reject(base_with("young = 1.0e9", "young = -1.0"), "body[0].material.young", "-1"),
        reject(base_with("young = 1.0e9", "young = 0.0"), "body[0].material.young", "0"),
        reject(base_with("poisson = 0.3", "poisson = 0.5"), "body[0].material.poisson", "0.5"),
        reject(base_with("poisson = 0.3", "poisson = -1.0"), "body[0].material.poisson", "-1"),
        reject(base_with("young = 1.0e9", "young = inf"), "body[0].material.young", "inf"),
        reject(base_with("x0 = 0.0, y0 = 0.0", "x0 = nan, y0 = 0.0"), "body[0].geometry.rectangle.x0", "NaN"),
        reject(base_with("value = 0.0", "value = -inf"), "support[0].value", "-inf"),
        // refinement
        reject(refine("degree = 0, elements = [2, 1]"), "body[0].refine.degree", "0"),
        reject(refine("degree = 11, elements = [2, 1]"), "body[0].refine.degree", "11"),
        reject(
            one_body("{ half_disk = { center = [0.0, 0.2], radius = 0.2 } }", "refine = { degree = 1, elements = [2, 2] }"),
            "body[0].refine.degree",
            "1",
        )
        .says(&["lagrange"]),
        reject(refine("degree = 2, elements = [2, 0]"), "body[0].refine.elements[1]", "0"),
        reject(refine("degree = 2, elements = [5000, 1]"), "body[0].refine.elements[0]", "5000"),
        reject(refine("lagrange = 5, elements = [2, 1]"), "body[0].refine.lagrange", "5"),
        reject(refine("lagrange = 0, elements = [2, 1]"), "body[0].refine.lagrange", "0"),
        reject(refine("degree = 2, lagrange = 2, elements = [2, 1]"), "body[0].refine.degree", "2"),
        reject(refine("elements = [2, 1]"), "body[0].refine", "elements = [2, 1]"),
        reject(lower_body("quadrature = 0"), "body[0].quadrature", "0"),
        // geometry
        reject(
            one_body("{ half_disk = { center = [0.0, 0.2], radius = -0.2 } }", "refine = { degree = 2, elements = [2, 2] }"),
            "body[0].geometry.half_disk.radius",
            "-0.2",
        ),
        reject(plain_body("{ full_disk = { center = [0.0, 0.0], radius = 0.0 } }"), "body[0].geometry.full_disk.radius", "0"),
        reject(plain_body("{ full_disk = { center = [0.0, 0.0], radius = 1e308 } }"), "body[0].geometry.full_disk.radius", "1e308"),
        reject(
            plain_body("{ quarter_annulus = { inner_radius = -1.0, outer_radius = 2.0 } }"),
            "body[0].geometry.quarter_annulus.inner_radius",
            "-1",
        ),
        reject(
            plain_body("{ quarter_annulus = { inner_radius = 2.0, outer_radius = 1.0 } }"),
            "body[0].geometry.quarter_annulus.outer_radius",
            "1",
        ),
        reject(plain_body("{ full_disk = { center = [inf, 0.0], radius = 1.0 } }"), "body[0].geometry.full_disk.center[0]", "inf"),
        reject(base_with("x1 = 1.0, y1 = 0.5", "x1 = -1.0, y1 = 0.5"), "body[0].geometry.rectangle.x1", "-1"),
        reject(base_with("x1 = 1.0, y1 = 0.5", "x1 = 1.0, y1 = 0.0"), "body[0].geometry.rectangle.y1", "0"),
        reject(
            plain_body("{ quadrilateral = { corners = [[0.0, 0.0], [0.2, 1.2], [1.5, 1.0], [2.0, 0.0]] } }"),
            "body[0].geometry.quadrilateral.corners[0]",
            "[0.0, 0.0]",
        ),
        reject(
            plain_body("{ quadrilateral = { corners = [[0.0, 0.0], [2.0, 0.0], [0.5, 0.5], [0.0, 2.0]] } }"),
            "body[0].geometry.quadrilateral.corners[2]",
            "[0.5, 0.5]",
        ),
        // NURBS patches
        reject(nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, ", weights = [1.0, 1.0, 0.0, 1.0]"), "body[0].geometry.nurbs.weights[2]", "0"),
        reject(nurbs_body("[0.0, 0.0, 1.0, 1.0]", SQUARE, ", weights = [1.0, 1.0, 1.0]"), "body[0].geometry.nurbs.weights", "3 weights"),
        reject(nurbs_body("[0.0, 0.5, 1.0, 1.0]", SQUARE, ""), "body[0].geometry.nurbs.knots_xi[0]", "0").says(&["open"]),
        reject(
            nurbs_body(
                "[0.0, 0.0, 0.7, 0.3, 1.0, 1.0]",
                "[[0.0, 0.0], [0.3, 0.0], [0.7, 0.0], [1.0, 0.0], [0.0, 1.0], [0.3, 1.0], [0.7, 1.0], [1.0, 1.0]]",
                "",
            ),
            "body[0].geometry.nurbs.knots_xi[3]",
            "0.3",
        )
        .says(&["non-decreasing"]),
        reject(nurbs_body("[0.0, 0.0, nan, 1.0, 1.0]", SQUARE, ""), "body[0].geometry.nurbs.knots_xi[2]", "NaN"),
        reject(nurbs_square("degree = [0, 1]"), "body[0].geometry.nurbs.degree[0]", "0"),
        reject(nurbs_square("degree = [1, 12]"), "body[0].geometry.nurbs.degree[1]", "12"),
        reject(
            nurbs_body("[0.0, 0.0, 1.0, 1.0]", "[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]", ""),
            "body[0].geometry.nurbs.control_points",
            "3 points",
        ),
        reject(
            nurbs_body("[0.0, 0.0, 1.0, 1.0]", "[[0.0, 0.0], [1.0, 0.0], [0.0, inf], [1.0, 1.0]]", ""),
            "body[0].geometry.nurbs.control_points[2][1]",
            "inf",
        ),
        // bodies and the names that refer to them
        reject("title = \"empty\"\n", "body", "[]"),
        reject(base_with("name = \"upper\"", "name = \"lower\""), "body[1].name", "\"lower\"").says(&["body[0]"]),
        reject(base_with("name = \"upper\"", "name = \"  \""), "body[1].name", "\"  \""),
        reject(
            base_with("body = \"lower\"\nside = \"eta_min\"", "body = \"floor\"\nside = \"eta_min\""),
            "support[0].body",
            "\"floor\"",
        )
        .says(&["lower, upper"]),
        reject(base_with("pressure = { body = \"upper\"", "pressure = { body = \"top\""), "load[0].pressure.body", "\"top\""),
        reject(base_with("body_force = { body = \"upper\"", "body_force = { body = \"x\""), "load[1].body_force.body", "\"x\""),
        reject(base_with("traction = { body = \"upper\"", "traction = { body = \"y\""), "load[2].traction.body", "\"y\""),
        reject(base_with("pressure = 1.0e8", "pressure = nan"), "load[0].pressure.pressure", "NaN"),
        reject(base_with("force = [0.0, -1.0]", "force = [0.0, -inf]"), "load[1].body_force.force[1]", "-inf"),
        reject(base_with("traction = [0.0, 0.0]", "traction = [inf, 0.0]"), "load[2].traction.traction[0]", "inf"),
        // contact pairs
        reject(base_with("slave = \"upper\"", "slave = \"top\""), "contact[0].slave", "\"top\""),
        reject(master("{ body = \"floor\", side = \"eta_max\" }"), "contact[0].master.body", "\"floor\""),
        reject(master("{ body = \"upper\", side = \"eta_max\" }"), "contact[0].master.body", "\"upper\"").says(&["self-contact"]),
        reject(master("{ body = \"lower\" }"), "contact[0].master.side", "(absent)"),
        reject(master("{}"), "contact[0].master", "{}"),
        reject(
            master("{ body = \"lower\", side = \"eta_max\", rigid_segment = { from = [0.0, 0.0], to = [1.0, 0.0] } }"),
            "contact[0].master",
            "rigid_segment and body",
        ),
        reject(
            master("{ rigid_segment = { from = [0.0, nan], to = [1.0, 0.5] } }"),
            "contact[0].master.rigid_segment.from[1]",
            "NaN",
        ),
        reject(
            master("{ rigid_segment = { from = [0.5, 0.5], to = [0.5, 0.5] } }"),
            "contact[0].master.rigid_segment.to",
            "[0.5, 0.5]",
        ),
        // a floor from right to left is a ceiling: the slave lies inside it
        reject(
            master("{ rigid_segment = { from = [2.0, 0.5], to = [-1.0, 0.5] } }"),
            "contact[0].master",
            "the rigid curve from [2.0, 0.5] to [-1.0, 0.5]",
        )
        .says(&["points away from the master", "swap `from` and `to`"]),
        // the same contact twice: each would carry half of the pressure
        reject(
            base_with(
                "[solver]",
                "[[contact]]\nslave = \"upper\"\nslave_side = \"eta_min\"\nmaster = { body = \"lower\", side = \"eta_max\" }\n\n[solver]",
            ),
            "contact[1]",
            "slave \"upper\" against the master of contact[0]",
        )
        .says(&["the pressure is shared between them"]),
        // the same interface again with the roles swapped
        reject(
            base_with(
                "[solver]",
                "[[contact]]\nslave = \"lower\"\nslave_side = \"eta_max\"\nmaster = { body = \"upper\", side = \"eta_min\" }\n\n[solver]",
            ),
            "contact[1]",
            "slave \"lower\" against the slave of contact[0]",
        )
        .says(&["sides = \"unbiased\""]),
        // two floors on one line that overlap: the same obstacle twice
        reject(
            master("{ rigid_segment = { from = [-1.0, 0.5], to = [2.0, 0.5] } }").replacen(
                "[solver]",
                "[[contact]]\nslave = \"upper\"\nslave_side = \"eta_min\"\nmaster = { rigid_segment = { from = [0.5, 0.5], to = [3.0, 0.5] } }\n\n[solver]",
                1,
            ),
            "contact[1]",
            "slave \"upper\" against the master of contact[0]",
        ),
        // a parallel floor just below the first: the first hides it
        reject(
            master("{ rigid_segment = { from = [-1.0, 0.5], to = [2.0, 0.5] } }").replacen(
                "[solver]",
                "[[contact]]\nslave = \"upper\"\nslave_side = \"eta_min\"\nmaster = { rigid_segment = { from = [-1.0, 0.4999], to = [2.0, 0.4999] } }\n\n[solver]",
                1,
            ),
            "contact[1]",
            "slave \"upper\" against the master of contact[0]",
        )
        .says(&["one hides the other"]),
        // the lower block's bottom faces away from the upper block
        reject(
            master("{ body = \"lower\", side = \"eta_min\" }"),
            "contact[0]",
            "body \"upper\" against side eta_min of body \"lower\"",
        )
        .says(&["face each other"]),
        reject(
            format!(
                "{}\n[[contact]]\nslave = \"b\"\nslave_side = \"eta_max\"\n\
                 master = {{ rigid_segment = {{ from = [0.0, 2.0], to = [1.0, 2.0] }} }}\n",
                one_body(TRIANGLE, "refine = { degree = 2, elements = [2, 2] }")
            ),
            "contact[0].slave_side",
            "eta_max",
        )
        .says(&["collapsed"]),
        reject(nitsche("theta = 0.5"), "contact[0].nitsche.theta", "0.5"),
        reject(nitsche("theta = nan"), "contact[0].nitsche.theta", "nan"),
        reject(nitsche("penalty_factor = 0"), "contact[0].nitsche.penalty_factor", "0"),
        reject(nitsche("penalty_factor = -2.5"), "contact[0].nitsche.penalty_factor", "-2.5"),
        reject(nitsche("penalty_factor = 1e300"), "contact[0].nitsche.penalty_factor", "1e300").says(&["round-off"]),
        reject(nitsche("penalty_factor = 1e-13"), "contact[0].nitsche.penalty_factor", "1e-13"),
        reject(nitsche("gauss_points = 0"), "contact[0].nitsche.gauss_points", "0"),
        // solver and outputs
        reject(base_with("rtol = 1e-10", "rtol = 0.0"), "solver.rtol", "0"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\nutol = 1.0"), "solver.utol", "1"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\ncurvature_tol = nan"), "solver.curvature_tol", "NaN"),
        reject(base_with("rtol = 1e-10", "rtol = 1e-10\nmax_iter = 0"), "solver.max_iter", "0"),
        reject(format!("{BASE}\n[output]\nvtu = true\nvtu_subdivisions = 0\n"), "output.vtu_subdivisions", "0"),
        reject(
            plain_body("{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }") + "\n[output]\npressure_profile = true\n",
            "output.pressure_profile",
            "true",
        ),
        reject(
            plain_body("{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }") + "\n[output]\nfigures = true\n",
            "output.figures",
            "true",
        ),
        // rigid modes nothing holds
        reject(block_on_floor(""), "body[0]", "\"block\"")
            .says(&["slide along (1, 0)", "contact normals", "[[support]]"]),
        reject(block_on_floor("").replace("pressure = 1.0e4", "pressure = 0.0"), "body[0]", "\"block\""),
        reject(
            base_with("[[support]]\nbody = \"upper\"\nside = \"xi_min\"\ncomponent = \"x\"\n", ""),
            "body[1]",
            "\"upper\"",
        )
        .says(&["slide along (1, 0)"]),
        reject(include_str!("fixtures/rotating_annuli.toml"), "body[1]", "\"inner\"").says(&["rotate about (0, 0)"]),
        reject(
            plain_body("{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }")
                .replace("[[support]]\nbody = \"b\"\nside = \"eta_min\"\ncomponent = \"x\"\n", ""),
            "body[0]",
            "\"b\"",
        )
        .says(&["slide along (1, 0)", "no contact"]),
        // under-integration
        reject(lower_body("quadrature = 2"), "body[0].quadrature", "2")
            .says(&["3 Gauss points", "allow_underintegration = true"]),
        reject(nitsche("gauss_points = 2"), "contact[0].nitsche.gauss_points", "2").says(&["allow_underintegration"]),
        // scales beyond double precision
        reject(held.replace("young = 1.0e6", "young = 1e-300"), "body[0].material.young", "1e-300")
            .says(&["underflows"])
            .lacks(&["diverged"]),
        reject(held.replace("pressure = 1.0e4", "pressure = 1e200"), "load[0].pressure.pressure", "1e200").says(&["overflows"]),
        reject(
            held.replace("young = 1.0e6", "young = 1e-100").replace("pressure = 1.0e4", "pressure = 1e100"),
            "load[0].pressure.pressure",
            "1e100",
        )
        .says(&["displacements would be of order"]),
        reject(plain_body("{ full_disk = { center = [0.0, 0.0], radius = 1e200 } }"), "body[0].geometry.full_disk.radius", "1e200")
            .says(&["overflows"]),
    ]
}

#[test]
fn every_rejected_scene_names_its_key_value_and_reason() {
    let rows = rejected();
    let failures: Vec<String> = rows
        .iter()
        .enumerate()
        .filter_map(|(i, r)| {
            r.failure()
                .map(|why| format!("row {i}, `{}`: {why}", r.path))
        })
        .collect();
    assert!(
        failures.is_empty(),
        "{} of {} rows failed:\n{}",
        failures.len(),
        rows.len(),
        failures.join("\n")
    );
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
fn geometry_errors_name_the_body() {
    // A bow-tie control net: the map folds.
    let text = one_body(
        "{ nurbs = { degree = [1, 1], knots_xi = [0.0, 0.0, 1.0, 1.0], \
           knots_eta = [0.0, 0.0, 1.0, 1.0], \
           control_points = [[0.0, 0.0], [1.0, 0.0], [1.0, 1.0], [0.0, 1.0]] } }",
        "",
    )
    .replace("\"b\"", "\"bowtie\"");
    let scene = Scene::from_toml_str(&text).unwrap();
    // a fault of the input, found by `check` as well as by the build: the
    // key of the geometry and the body's name, not a failure of the run
    for e in [
        scene.build().err().expect("a folded map was accepted"),
        scene
            .check(&iga_contact::resources::Budget::from_machine())
            .expect_err("check accepted a folded map"),
    ] {
        let msg = e.to_string();
        let Error::InvalidInput { field, value, .. } = &e else {
            panic!("not an input error: {msg}");
        };
        assert_eq!(
            (field.as_str(), value.as_str()),
            ("body[0].geometry", "nurbs")
        );
        assert!(msg.contains("(body \"bowtie\")"), "{msg}");
        assert!(msg.contains("det J = 0"), "{msg}");
    }
}

/// `mixed` needs a continuous pressure space of degree p − 1 on the body's
/// knots: none at p = 1, a discontinuous one on a C⁰ Lagrange mesh. Both
/// are refused naming the formulation, and `local_mixed` runs on each.
#[test]
fn mixed_needs_degree_two_and_a_k_refined_body() {
    for refine in [
        "{ degree = 1, elements = [4, 1] }",
        "{ lagrange = 2, elements = [4, 1] }",
    ] {
        // the minimal scene (a block on a rigid floor), refined and
        // formulated as this case says
        let minimal = std::fs::read_to_string(
            Path::new(env!("CARGO_MANIFEST_DIR")).join("data/scenes/minimal.toml"),
        )
        .unwrap();
        let text = minimal.replace(
            "refine = { degree = 2, elements = [4, 1] }",
            &format!("refine = {refine}\nformulation = \"mixed\""),
        );
        assert!(
            text.contains("formulation"),
            "minimal.toml changed its refine line"
        );
        let Err(Error::InvalidInput { field, reason, .. }) = Scene::from_toml_str(&text) else {
            panic!("mixed accepted with refine = {refine}");
        };
        assert_eq!(field, "body[0].formulation", "{refine}: {reason}");
        assert!(reason.contains("local_mixed"), "{refine}: {reason}");
        let local = text.replace("\"mixed\"", "\"local_mixed\"");
        let run = Scene::from_toml_str(&local).and_then(|s| s.build());
        assert!(
            run.is_ok(),
            "{refine}: local_mixed refused: {:?}",
            run.err()
        );
    }
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

#[test]
fn a_slave_side_of_singular_elements_only_still_gets_its_figure() {
    // hertz.toml on one element: the one slave element touches the disk's
    // singular corner, so no profile sample is regular; the solve is not
    // thrown away for the figure, which draws the brackets and says so
    let mut scene = companion::shipped("hertz.toml")
        .unwrap()
        .refined("disk", RefineSpec::iga(2, [1, 1]))
        .unwrap();
    scene.output = iga_contact::scene::OutputSpec {
        figures: true,
        pressure_profile: true,
        ..Default::default()
    };
    let dir = std::env::temp_dir().join(format!("iga-one-element-{}", std::process::id()));
    scene.run(&dir).unwrap();
    let svg = std::fs::read_to_string(dir.join("pressure_profile.svg")).unwrap();
    assert!(svg.contains("singular map: brackets, not pressures"));
    let csv = std::fs::read_to_string(dir.join("pressure_profile.csv")).unwrap();
    assert!(csv.lines().skip(1).all(|l| l.ends_with(",0")), "{csv}");
    let _ = std::fs::remove_dir_all(&dir);
}
