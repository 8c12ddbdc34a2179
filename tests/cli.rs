//! The command-line interface: exit codes (0 ok, 1 failure, 2 invalid
//! input), one `error:` line on stderr, and lean output.

use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_iga-contact");

fn scene(name: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenes")
        .join(name)
}

/// A fresh, empty working directory for one test.
fn workdir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("cli-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

fn run(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .expect("the binary runs")
}

fn stderr(o: &Output) -> String {
    String::from_utf8_lossy(&o.stderr).into_owned()
}

fn stdout(o: &Output) -> String {
    String::from_utf8_lossy(&o.stdout).into_owned()
}

/// Exactly one non-empty stderr line, starting with `error:`.
#[track_caller]
fn single_error_line(o: &Output) -> String {
    let err = stderr(o);
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert_eq!(lines.len(), 1, "stderr: {err}");
    assert!(lines[0].starts_with("error: "), "stderr: {err}");
    lines[0].to_string()
}

const INVALID: &str = r#"
[[body]]
name = "block"
geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }
material = { young = -5.0, poisson = 0.3, plane = "strain" }
"#;

#[test]
fn invalid_scene_exits_with_2_and_one_error_line_naming_the_key() {
    let dir = workdir("invalid");
    std::fs::write(dir.join("bad.toml"), INVALID).unwrap();
    for cmd in ["run", "check"] {
        let o = run(&dir, &[cmd, "bad.toml"]);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {}", stderr(&o));
        let line = single_error_line(&o);
        assert!(line.contains("bad.toml"), "{line}");
        assert!(line.contains("`body[0].material.young` = -5"), "{line}");
        assert!(stdout(&o).is_empty());
    }
    assert!(!dir.join("out").exists(), "a failed run created outputs");
}

/// The block of [`block`] made a quadratic patch whose middle control
/// point is pulled out past the right side: det J < 0 near it, between the
/// nodes, so no corner test sees it. `check` finds it as `run` does: an
/// input error (exit 2) naming the geometry, before any solve.
fn folded() -> String {
    block(2, [4, 1], "1.0e6", "1.0e4").replace(
        "geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }",
        "geometry = { nurbs = { degree = [2, 2], knots_xi = [0, 0, 0, 1, 1, 1], \
         knots_eta = [0, 0, 0, 1, 1, 1], control_points = [[0.0, 0.0], [0.5, 0.0], \
         [1.0, 0.0], [0.0, 0.25], [1.6, 0.6], [1.0, 0.25], [0.0, 0.5], [0.5, 0.5], \
         [1.0, 0.5]] } }",
    )
}

#[test]
fn a_folded_map_is_an_input_error_found_by_check() {
    let dir = workdir("folded");
    let text = folded();
    assert!(text.contains("nurbs"), "the block's geometry line changed");
    std::fs::write(dir.join("folded.toml"), text).unwrap();
    for cmd in ["check", "run"] {
        let o = run(&dir, &[cmd, "folded.toml"]);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {}", stderr(&o));
        let line = single_error_line(&o);
        assert!(line.contains("`body[0].geometry` = nurbs"), "{line}");
        assert!(line.contains("not invertible"), "{line}");
    }
    assert!(!dir.join("out").exists(), "a refused run created outputs");
}

#[test]
fn unknown_key_exits_with_2() {
    let dir = workdir("unknown-key");
    let text = INVALID.replace("young = -5.0", "young = 5.0, colour = \"red\"");
    std::fs::write(dir.join("typo.toml"), text).unwrap();
    let o = run(&dir, &["check", "typo.toml"]);
    assert_eq!(o.status.code(), Some(2));
    let line = single_error_line(&o);
    assert!(line.contains("`body[0].material.colour`"), "{line}");
}

#[test]
fn toml_syntax_error_exits_with_2() {
    let dir = workdir("syntax");
    std::fs::write(dir.join("broken.toml"), "[[body]\nname = \"x\"\n").unwrap();
    let o = run(&dir, &["check", "broken.toml"]);
    assert_eq!(o.status.code(), Some(2));
    let line = single_error_line(&o);
    assert!(line.contains("line 1"), "{line}");
}

#[test]
fn missing_scene_file_exits_with_2() {
    let dir = workdir("missing");
    let o = run(&dir, &["run", "nowhere.toml"]);
    assert_eq!(o.status.code(), Some(2));
    let line = single_error_line(&o);
    assert!(line.contains("nowhere.toml"), "{line}");
}

#[test]
fn minimal_scene_runs_and_writes_nothing() {
    let dir = workdir("minimal");
    let path = scene("minimal.toml");
    let o = run(&dir, &["run", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    assert_eq!(out.lines().count(), 1, "{out}");
    assert!(out.contains("converged"), "{out}");
    assert!(stderr(&o).is_empty(), "{}", stderr(&o));
    // No outputs requested: not even the default `out/minimal` directory.
    assert!(!dir.join("out").exists());
}

#[test]
fn check_builds_without_solving() {
    let dir = workdir("check");
    for name in [
        "taylor.toml",
        "hertz.toml",
        "hertz_fem_q2.toml",
        "minimal.toml",
    ] {
        let path = scene(name);
        let o = run(&dir, &["check", path.to_str().unwrap()]);
        assert_eq!(o.status.code(), Some(0), "{name}: {}", stderr(&o));
        assert!(stdout(&o).contains("ok"), "{}", stdout(&o));
    }
    assert!(!dir.join("out").exists(), "check wrote files");
}

#[test]
fn run_writes_to_the_default_directory_named_after_the_scene() {
    let dir = workdir("default-out");
    let path = scene("taylor.toml");
    let o = run(&dir, &["run", path.to_str().unwrap()]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = dir.join("out").join("taylor");
    for f in ["iterations.csv", "summary.toml", "solution.vtu"] {
        assert!(out.join(f).is_file(), "missing {f}");
    }
}

#[test]
fn run_honours_out() {
    let dir = workdir("explicit-out");
    let path = scene("taylor.toml");
    let o = run(
        &dir,
        &["run", path.to_str().unwrap(), "--out", "results/here"],
    );
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(dir.join("results/here/summary.toml").is_file());
    assert!(!dir.join("out").exists());
}

#[test]
fn solver_failure_exits_with_1() {
    let dir = workdir("solver-failure");
    let text = std::fs::read_to_string(scene("hertz.toml"))
        .unwrap()
        .replace("max_iter = 300", "max_iter = 1");
    std::fs::write(dir.join("short.toml"), text).unwrap();
    let o = run(&dir, &["run", "short.toml"]);
    assert_eq!(o.status.code(), Some(1), "{}", stderr(&o));
    let line = single_error_line(&o);
    assert!(line.contains("iteration limit"), "{line}");
    assert!(!dir.join("out").exists(), "a failed run wrote files");
}

/// Regenerating the book is the book's own tool (`book/companion`, binary
/// `reproduce`), not a command of the binary: asking for it is a usage
/// error like any unknown command.
#[test]
fn reproduce_is_not_a_command_of_the_binary() {
    let dir = workdir("reproduce-gone");
    let o = run(&dir, &["reproduce", "--only", "hertz"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let line = single_error_line(&o);
    assert!(line.contains("'reproduce'"), "{line}");
    assert!(
        line.contains("cargo run --release --bin reproduce"),
        "{line}"
    );
}

/// Every usage error is one `error:` line naming what is wrong (exit 2),
/// while `--help` and `--version` still print in full (exit 0).
#[test]
fn usage_errors_are_one_line_naming_the_argument() {
    let dir = workdir("usage");
    for (args, names) in [
        (&["frobnicate"][..], "frobnicate"),
        (&["run"][..], "<SCENE>"),
        (&["check"][..], "<SCENE>"),
        (&["run", "a.toml", "b.toml"][..], "'b.toml'"),
        (&["run", "a.toml", "--bogus"][..], "--bogus"),
        (&["run", "a.toml", "--max-memory"][..], "--max-memory"),
        (&["check", "a.toml", "--all"][..], "--all"),
        (&[][..], "commands: run, check;"),
    ] {
        let o = run(&dir, args);
        assert_eq!(o.status.code(), Some(2), "{args:?}: {}", stderr(&o));
        let line = single_error_line(&o);
        assert!(line.contains(names), "{args:?}: {line}");
        assert!(stdout(&o).is_empty(), "{args:?}");
    }
    for args in [&["--help"][..], &["run", "--help"][..], &["--version"][..]] {
        let o = run(&dir, args);
        assert_eq!(o.status.code(), Some(0), "{args:?}: {}", stderr(&o));
        assert!(stderr(&o).is_empty(), "{args:?}: {}", stderr(&o));
    }
    assert!(stdout(&run(&dir, &["run", "--help"])).contains("--max-memory"));
}

/// A run with a warning: the run line tells the files and where they
/// went, and each cause is one `warning:` line on stderr, told once.
#[test]
fn a_warned_run_prints_its_files_then_one_line_per_warning() {
    let dir = workdir("warned-run");
    // Hertz 8×8 with θ = 0 and a penalty far below its bound, solved by
    // the default solver (which converges there, see tests/scene/outputs.rs).
    let hertz = std::fs::read_to_string(scene("hertz.toml")).unwrap();
    let text = format!(
        "{}\n[output]\niterations = true\npressure_profile = true\nsummary = true\n",
        hertz.split("# ANCHOR: solver").next().unwrap()
    )
    .replace("penalty_factor = 1.0", "penalty_factor = 1e-3");
    std::fs::write(dir.join("weak.toml"), text).unwrap();
    let o = run(&dir, &["run", "weak.toml", "--out", "res"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    let out = stdout(&o);
    let lines: Vec<&str> = out.lines().collect();
    assert_eq!(lines.len(), 1, "{out}");
    assert!(lines[0].ends_with("; wrote 3 files to res"), "{out}");
    assert!(!lines[0].contains("warning"), "{out}");
    let err = stderr(&o);
    let warnings: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    assert!(!warnings.is_empty(), "no warning: {err}");
    assert!(
        warnings
            .iter()
            .all(|l| l.starts_with("warning: weak.toml: ")),
        "{err}"
    );
    // the penalty of contact[0] below its bound: one line, not two
    let penalty = warnings
        .iter()
        .filter(|l| l.contains("stability bound"))
        .count();
    assert_eq!(penalty, 1, "{err}");
}

/// A block on a rigid floor with the given degree, elements and material.
fn block(degree: usize, elements: [usize; 2], young: &str, pressure: &str) -> String {
    format!(
        r#"
[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 }} }}
refine = {{ degree = {degree}, elements = [{}, {}] }}
material = {{ young = {young}, poisson = 0.3, plane = "strain" }}

[[support]]
body = "block"
side = "xi_min"
component = "x"

[[load]]
pressure = {{ body = "block", side = "eta_max", pressure = {pressure} }}

[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-0.5, 0.0], to = [1.5, 0.0] }} }}
"#,
        elements[0], elements[1]
    )
}

#[test]
fn input_scale_overflow_and_underflow_are_reported_as_such() {
    let dir = workdir("scales");
    for (name, young, pressure, key, word) in [
        (
            "tiny.toml",
            "1e-300",
            "1.0e4",
            "body[0].material.young",
            "underflows",
        ),
        (
            "huge.toml",
            "1.0e6",
            "1e200",
            "load[0].pressure.pressure",
            "overflows",
        ),
    ] {
        std::fs::write(dir.join(name), block(2, [2, 2], young, pressure)).unwrap();
        for cmd in ["check", "run"] {
            let o = run(&dir, &[cmd, name]);
            assert_eq!(o.status.code(), Some(2), "{cmd} {name}: {}", stderr(&o));
            let line = single_error_line(&o);
            assert!(line.contains(key) && line.contains(word), "{line}");
            assert!(!line.contains("diverged"), "{line}");
        }
    }
}

#[test]
fn a_scene_over_the_memory_budget_is_refused_naming_the_field() {
    let dir = workdir("budget");
    std::fs::write(
        dir.join("big.toml"),
        block(10, [4096, 4096], "1.0e6", "1.0e4"),
    )
    .unwrap();
    for cmd in ["check", "run"] {
        let o = run(&dir, &[cmd, "big.toml"]);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {}", stderr(&o));
        let line = single_error_line(&o);
        assert!(
            line.contains("`body[0].refine.elements` = [4096, 4096]")
                && line.contains("memory budget"),
            "{line}"
        );
    }
    // --max-memory moves the budget both ways.
    std::fs::write(dir.join("small.toml"), block(2, [4, 4], "1.0e6", "1.0e4")).unwrap();
    let o = run(&dir, &["check", "small.toml", "--max-memory", "1M"]);
    assert_eq!(o.status.code(), Some(2), "{}", stderr(&o));
    let line = single_error_line(&o);
    assert!(line.contains("set by --max-memory"), "{line}");
    let o = run(&dir, &["check", "small.toml", "--max-memory", "2G"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
    assert!(stdout(&o).contains("a run needs about"), "{}", stdout(&o));
    let o = run(&dir, &["check", "small.toml", "--max-memory", "lots"]);
    assert_eq!(o.status.code(), Some(2));
    assert!(single_error_line(&o).contains("--max-memory"));
}

/// Where the VTU's samples set the peak, the refusal names the key that
/// sets their number, with its value as written, and the budget that the
/// run without them fits in admits it once the subdivisions are lowered.
#[test]
fn a_vtu_over_the_budget_is_refused_naming_its_subdivisions() {
    let dir = workdir("vtu-budget");
    let with = |s: usize| {
        block(2, [64, 64], "1.0e6", "1.0e4")
            + &format!("\n[output]\nvtu = true\nvtu_subdivisions = {s}\n")
    };
    let peak = |s: usize| {
        iga_contact::scene::Scene::from_toml_str(&with(s))
            .unwrap()
            .estimate()
            .unwrap()
            .peak_bytes()
    };
    let (low, high) = (peak(2), peak(64));
    assert!(
        high > 4.0 * low,
        "the samples do not set the peak: {low:.3e} {high:.3e}"
    );
    let budget = format!("{}M", ((low * high).sqrt() / 1048576.0).round());
    std::fs::write(dir.join("fine.toml"), with(64)).unwrap();
    std::fs::write(dir.join("coarse.toml"), with(2)).unwrap();
    for cmd in ["check", "run"] {
        let o = run(&dir, &[cmd, "fine.toml", "--max-memory", &budget]);
        assert_eq!(o.status.code(), Some(2), "{cmd}: {}", stderr(&o));
        let line = single_error_line(&o);
        assert!(line.contains("`output.vtu_subdivisions` = 64"), "{line}");
        assert!(line.contains("sample points"), "{line}");
    }
    let o = run(&dir, &["check", "coarse.toml", "--max-memory", &budget]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}

#[test]
fn check_at_the_documented_maxima_answers_without_assembling() {
    let dir = workdir("maxima");
    for (name, degree, elements) in [
        ("d10_64x64.toml", 10, [64, 64]),
        ("d10_4096x1.toml", 10, [4096, 1]),
        ("d2_4096x1.toml", 2, [4096, 1]),
        ("d1_4096x4096.toml", 1, [4096, 4096]),
    ] {
        std::fs::write(dir.join(name), block(degree, elements, "1.0e6", "1.0e4")).unwrap();
        let o = run(&dir, &["check", name, "--max-memory", "8G"]);
        match o.status.code() {
            Some(0) => assert!(stdout(&o).contains("ok ("), "{name}: {}", stdout(&o)),
            Some(2) => assert!(single_error_line(&o).contains("memory budget"), "{name}"),
            other => panic!("{name}: exit {other:?}: {}", stderr(&o)),
        }
    }
}

/// Runs the binary and returns its peak resident memory (`VmHWM`, which
/// `wait4` reports as `ru_maxrss`), in bytes.
fn peak_of_run(dir: &Path, args: &[&str]) -> f64 {
    #[allow(clippy::zombie_processes)] // reaped by wait4 below, for its rusage
    let child = Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the binary runs");
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value for wait4 to fill in.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: waits for our own child; status and usage are valid out-pointers.
    let r = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    assert_eq!(r, child.id() as i32);
    assert!(
        libc::WIFEXITED(status) && libc::WEXITSTATUS(status) == 0,
        "{args:?}: {status}"
    );
    usage.ru_maxrss as f64 * 1024.0
}

/// The estimate follows the measured peak within a factor 1.5 either way,
/// on a scene whose factorisation sets the peak (p = 2, 128²) and on ones
/// where the contact couplings do (high degree); the full ladder is the
/// memory table of the chapter "Reliability" (`examples/memory_table.rs`).
#[test]
fn the_memory_estimate_is_within_one_and_a_half_of_the_measured_peak() {
    let dir = workdir("memory-estimate");
    for (p, m) in [(2, 128), (6, 32), (10, 8)] {
        let text = block(p, [m, m], "1.0e6", "1.0e4") + "\n[output]\nsummary = true\n";
        let name = format!("p{p}_{m}.toml");
        std::fs::write(dir.join(&name), &text).unwrap();
        let estimate = iga_contact::scene::Scene::from_toml_str(&text)
            .unwrap()
            .estimate()
            .unwrap()
            .peak_bytes();
        let peak = peak_of_run(&dir, &["run", &name, "--out", "out", "--max-memory", "1T"]);
        let ratio = estimate / peak;
        eprintln!("p = {p}, {m}²: estimate {estimate:.3e} B, peak {peak:.3e} B, ratio {ratio:.2}");
        assert!((1.0 / 1.5..=1.5).contains(&ratio), "p = {p}, {m}²: {ratio}");
    }
    // Hertz p = 2 on 512² (without the VTU) needs about 3 GB: a budget of
    // 4 GiB admits it.
    let hertz = std::fs::read_to_string(scene("hertz.toml"))
        .unwrap()
        .replace("elements = [8, 8]", "elements = [512, 512]")
        .replace("vtu = true ", "vtu = false");
    std::fs::write(dir.join("hertz512.toml"), hertz).unwrap();
    let o = run(&dir, &["check", "hertz512.toml", "--max-memory", "4G"]);
    assert_eq!(o.status.code(), Some(0), "{}", stderr(&o));
}
