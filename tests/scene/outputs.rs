//! What a run writes and reports: lean (nothing that was not asked for),
//! atomic (a failing run leaves the earlier results), and well-formed (no
//! negative zeros, escaped titles, a figure even without regular samples).

use crate::rejected::rejects;
use crate::text::{block_on_floor, shipped_text, BASE, HELD};
use companion::hertz as setup;
use iga_contact::post::{PressureProfile, PROFILE_SAMPLES_PER_ELEMENT};
use iga_contact::report::atomic::{read_manifest, MANIFEST};
use iga_contact::scene::{files, RefineSpec, Scene};
use iga_contact::solver::{self, SolverOptions};
use iga_contact::Error;
use std::path::{Path, PathBuf};

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

#[test]
fn summary_survives_solver_limits_beyond_toml_integers() {
    let dir = tmp("summary-usize-max");
    let mut scene = Scene::from_toml_str(&shipped_text("minimal.toml")).unwrap();
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

#[test]
fn hertz_run_writes_everything_it_asks_for() {
    let dir = tmp("hertz-run");
    let scene = Scene::from_toml_str(&shipped_text("hertz.toml")).unwrap();
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

#[test]
fn a_scene_without_outputs_writes_nothing() {
    let dir = tmp("no-outputs");
    let scene = Scene::from_toml_str(&shipped_text("minimal.toml")).unwrap();
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
    let text = block_on_floor(HELD).replace("pressure = 1.0e4", "pressure = 0.0")
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
    Scene::from_toml_str(&shipped_text("hertz.toml"))
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
    let text = shipped_text("hertz.toml").replace(
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
