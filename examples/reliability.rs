//! Writes `RELIABILITY_NOTES.md`: the figures of the robustness work, all
//! measured in this run of the `iga-contact` binary.
//!
//! 1. `check` at the documented maxima (times);
//! 2. the memory estimate against measured peaks (`wait4` → `ru_maxrss`);
//! 3. a campaign of valid-but-hard scenes under an 8 GiB address-space
//!    limit (every outcome counted: no signal, no backtrace);
//! 4. fault injection into the output transaction: a full disk at every
//!    file, unwritable locations, SIGKILL spread over a run, SIGINT and
//!    SIGTERM, concurrent runs into one directory.
//!
//! `cargo build --release && cargo run --release --example reliability [-- OUT.md]`
//! (about ten minutes on two cores).

use iga_contact::report::atomic;
use iga_contact::report::chapter::Chapter;
use iga_contact::resources::human_bytes;
use iga_contact::scene::Scene;
use std::collections::BTreeMap;
use std::fmt::Write as _;
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::time::{Duration, Instant};

// ---------------------------------------------------------------------------
// Running the CLI as a child
// ---------------------------------------------------------------------------

/// The CLI binary beside this example's directory (target/release).
fn binary() -> PathBuf {
    let exe = std::env::current_exe().expect("own path");
    exe.parent()
        .and_then(Path::parent)
        .expect("target dir")
        .join("iga-contact")
}

/// Limits and timing of one child run.
#[derive(Clone, Copy, Default)]
struct Launch {
    /// RLIMIT_AS in bytes.
    address_space: Option<u64>,
    /// RLIMIT_FSIZE in bytes (a stand-in for a full disk).
    file_size: Option<u64>,
    /// Seconds before the harness sends SIGKILL (counted as a time-out).
    timeout: f64,
    /// Send this signal after `signal_after` seconds.
    signal: Option<(i32, f64)>,
}

#[derive(Debug)]
struct Outcome {
    code: Option<i32>,
    signal: Option<i32>,
    peak_bytes: f64,
    seconds: f64,
    stderr: String,
    timed_out: bool,
}

impl Outcome {
    /// Exit code 0, or 1/2 with exactly one `error:` line and no backtrace.
    fn clean(&self) -> bool {
        let lines: Vec<&str> = self
            .stderr
            .lines()
            .filter(|l| !l.trim().is_empty())
            .collect();
        let no_trace = !self.stderr.contains("backtrace") && !self.stderr.contains("panicked");
        no_trace
            && match self.code {
                Some(0) => lines.is_empty(),
                Some(1 | 2 | 130 | 143) => lines.len() == 1 && lines[0].starts_with("error: "),
                _ => false,
            }
    }
}

fn launch(dir: &Path, args: &[&str], how: Launch) -> Outcome {
    let mut cmd = Command::new(binary());
    cmd.args(args)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped());
    let (asl, fsl) = (how.address_space, how.file_size);
    // SAFETY: only setrlimit, which is async-signal-safe, runs in the child.
    unsafe {
        cmd.pre_exec(move || {
            for (res, v) in [(libc::RLIMIT_AS, asl), (libc::RLIMIT_FSIZE, fsl)] {
                if let Some(v) = v {
                    let lim = libc::rlimit {
                        rlim_cur: v,
                        rlim_max: v,
                    };
                    if libc::setrlimit(res, &lim) != 0 {
                        return Err(std::io::Error::last_os_error());
                    }
                }
            }
            Ok(())
        });
    }
    let start = Instant::now();
    #[allow(clippy::zombie_processes)] // reaped by wait4 below, for its rusage
    let mut child = cmd.spawn().expect("the CLI starts");
    let pid = child.id() as i32;
    let mut stderr = child.stderr.take().expect("piped");
    let reader = std::thread::spawn(move || {
        let mut s = String::new();
        let _ = std::io::Read::read_to_string(&mut stderr, &mut s);
        s
    });
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value for wait4 to fill in.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    let mut timed_out = false;
    let mut signalled = false;
    loop {
        // SAFETY: polls our own child; status and usage are valid out-pointers.
        let r = unsafe { libc::wait4(pid, &mut status, libc::WNOHANG, &mut usage) };
        if r == pid {
            break;
        }
        let t = start.elapsed().as_secs_f64();
        if let Some((sig, after)) = how.signal {
            if !signalled && t >= after {
                // SAFETY: signals our own child.
                unsafe { libc::kill(pid, sig) };
                signalled = true;
            }
        }
        if how.timeout > 0.0 && t > how.timeout && !timed_out {
            // SAFETY: kills our own child.
            unsafe { libc::kill(pid, libc::SIGKILL) };
            timed_out = true;
        }
        std::thread::sleep(Duration::from_micros(500));
    }
    let seconds = start.elapsed().as_secs_f64();
    let (code, signal) = if libc::WIFEXITED(status) {
        (Some(libc::WEXITSTATUS(status)), None)
    } else {
        (None, Some(libc::WTERMSIG(status)))
    };
    Outcome {
        code,
        signal,
        peak_bytes: usage.ru_maxrss as f64 * 1024.0,
        seconds,
        stderr: reader.join().unwrap_or_default(),
        timed_out,
    }
}

// ---------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------

const SHAPES: [(&str, &str); 5] = [
    (
        "rectangle",
        "{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }",
    ),
    (
        "half disk",
        "{ half_disk = { center = [0.0, 0.2], radius = 0.2 } }",
    ),
    (
        "quarter annulus",
        "{ quarter_annulus = { inner_radius = 0.5, outer_radius = 1.0 } }",
    ),
    (
        "quadrilateral",
        "{ quadrilateral = { corners = [[0.0, 0.0], [1.0, 0.1], [0.9, 0.6], [0.1, 0.5]] } }",
    ),
    (
        "NURBS, 2 × 2 spans",
        "{ nurbs = { degree = [2, 2], knots_xi = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], \
         knots_eta = [0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], control_points = [\
         [0.0, 0.0], [0.3, 0.0], [0.7, 0.0], [1.0, 0.0], \
         [0.0, 0.2], [0.3, 0.2], [0.7, 0.2], [1.0, 0.2], \
         [0.0, 0.4], [0.3, 0.4], [0.7, 0.4], [1.0, 0.4], \
         [0.0, 0.5], [0.3, 0.5], [0.7, 0.5], [1.0, 0.5]] } }",
    ),
];

/// One body resting on a rigid floor, held sideways on `xi_min`.
fn body_scene(title: &str, geometry: &str, refine: &str, extra: &str, output: &str) -> String {
    format!(
        r#"title = "{title}"
[[body]]
name = "b"
geometry = {geometry}
{refine}
material = {{ young = 2.0e7, poisson = 0.3, plane = "strain" }}
{extra}
[[support]]
body = "b"
side = "xi_min"
component = "x"

[[load]]
body_force = {{ body = "b", force = [0.0, -1.3e6] }}

[[contact]]
slave = "b"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-2.0, 0.0], to = [2.0, 0.0] }} }}

{output}"#
    )
}

const ALL_OUTPUTS: &str = "[output]\niterations = true\npressure_profile = true\nsummary = true\n\
                           figures = true\nvtu = true\n";

// ---------------------------------------------------------------------------
// 1. check at the documented maxima
// ---------------------------------------------------------------------------

fn check_times(work: &Path, md: &mut String) {
    let rect = SHAPES[0].1;
    let cases = [
        (10, [64, 64]),
        (10, [4096, 1]),
        (2, [4096, 1]),
        (10, [4096, 4096]),
        (1, [4096, 4096]),
    ];
    md.push_str(
        "| scene (rectangle on a rigid floor) | `check`, s | exit | answer |\n|---|---|---|---|\n",
    );
    for (p, e) in cases {
        let text = body_scene(
            "maxima",
            rect,
            &format!(
                "refine = {{ degree = {p}, elements = [{}, {}] }}",
                e[0], e[1]
            ),
            "",
            "",
        );
        let path = work.join("maxima.toml");
        std::fs::write(&path, text).unwrap();
        let o = launch(work, &["check", "maxima.toml"], Launch::default());
        let answer = if o.code == Some(0) {
            "ok (estimate printed)".to_string()
        } else {
            let e = o.stderr.trim();
            let at = e.find("the run would need").unwrap_or(0);
            e[at..].chars().take(60).collect::<String>() + "…"
        };
        let _ = writeln!(
            md,
            "| degree {p}, elements {e:?} | {:.2} | {} | {answer} |",
            o.seconds,
            o.code.map_or("signal".into(), |c| c.to_string())
        );
    }
}

// ---------------------------------------------------------------------------
// 2. memory estimate against measured peaks
// ---------------------------------------------------------------------------

fn calibration(work: &Path, md: &mut String) -> f64 {
    let (rect, disk) = (SHAPES[0].1, SHAPES[1].1);
    // (label, geometry, degree, elements, contact keys, output keys)
    type Case<'a> = (&'a str, &'a str, usize, [usize; 2], &'a str, &'a str);
    let cases: Vec<Case> = vec![
        ("rectangle", rect, 1, [256, 256], "", ""),
        ("rectangle", rect, 1, [512, 512], "", ""),
        ("rectangle", rect, 2, [128, 128], "", ""),
        ("rectangle", rect, 2, [256, 256], "", ""),
        ("rectangle", rect, 3, [128, 128], "", ""),
        ("rectangle", rect, 4, [64, 64], "", ""),
        ("rectangle", rect, 4, [1024, 1], "", ""),
        ("rectangle", rect, 6, [48, 48], "", ""),
        ("rectangle", rect, 8, [24, 24], "", ""),
        ("rectangle", rect, 10, [16, 16], "", ""),
        ("rectangle", rect, 10, [24, 24], "", ""),
        (
            "rectangle, VTU ×16",
            rect,
            2,
            [64, 64],
            "",
            "vtu_subdivisions = 16",
        ),
        ("half disk", disk, 2, [128, 128], "", ""),
        (
            "half disk, VTU ×8",
            disk,
            3,
            [64, 64],
            "",
            "vtu_subdivisions = 8",
        ),
        ("half disk", disk, 5, [32, 32], "", ""),
        (
            "rectangle, θ = 1 (LU)",
            rect,
            2,
            [128, 128],
            "theta = 1",
            "",
        ),
        ("half disk, θ = 1 (LU)", disk, 4, [48, 48], "theta = 1", ""),
        ("rectangle, θ = −1", rect, 3, [96, 96], "theta = -1", ""),
        (
            "rectangle, LU forced",
            rect,
            1,
            [256, 256],
            "",
            "[solver]\nfactorisation = \"lu\"",
        ),
    ];
    md.push_str(
        "| scene | degree | elements | DOFs | non-zeros | estimate | measured peak | measured / estimate | s |\n\
         |---|---|---|---|---|---|---|---|---|\n",
    );
    let mut worst: f64 = 0.0;
    for (label, geometry, p, e, contact, tail) in cases {
        let output = format!(
            "[output]\nsummary = true\nvtu = {}\n{tail}\n",
            tail.contains("vtu")
        );
        let mut text = body_scene(
            label,
            geometry,
            &format!(
                "refine = {{ degree = {p}, elements = [{}, {}] }}",
                e[0], e[1]
            ),
            "",
            &output,
        );
        if !contact.is_empty() {
            text = text.replace(
                "to = [2.0, 0.0] } }\n",
                &format!("to = [2.0, 0.0] }} }}\n{contact}\n"),
            );
        }
        let est = Scene::from_toml_str(&text)
            .and_then(|s| s.estimate())
            .expect("a valid scene")
            .peak_bytes();
        std::fs::write(work.join("calibration.toml"), &text).unwrap();
        let o = launch(
            work,
            &[
                "run",
                "calibration.toml",
                "--out",
                "calibration-out",
                "--max-memory",
                "1T",
            ],
            Launch::default(),
        );
        let s = Scene::from_toml_str(&text).unwrap().estimate().unwrap();
        let ratio = o.peak_bytes / est;
        worst = worst.max(ratio);
        let _ = writeln!(
            md,
            "| {label} | {p} | {e:?} | {:.0} | {:.2e} | {} | {} | {ratio:.2} | {:.1} |",
            s.dofs,
            s.nonzeros,
            human_bytes(est),
            human_bytes(o.peak_bytes),
            o.seconds
        );
    }
    worst
}

// ---------------------------------------------------------------------------
// 3. valid but hard scenes under 8 GiB
// ---------------------------------------------------------------------------

#[derive(Default)]
struct Tally {
    scenes: usize,
    launches: usize,
    by_code: BTreeMap<String, usize>,
    unclean: Vec<String>,
    slowest_check: f64,
    /// Exit-1 messages (scene file names stripped), with counts.
    failures: BTreeMap<String, usize>,
    /// Scenes whose run the harness stopped.
    stopped: Vec<String>,
}

impl Tally {
    fn record(&mut self, what: &str, o: &Outcome) {
        self.launches += 1;
        let key = if o.timed_out {
            "stopped by the harness after the time limit (no crash)".to_string()
        } else if let Some(s) = o.signal {
            format!("ended by signal {s}")
        } else {
            match o.code {
                Some(0) => "exit 0 (answered)".into(),
                Some(1) => "exit 1 (clean failure, one error line)".into(),
                Some(2) => "exit 2 (clean refusal, one error line)".into(),
                Some(c) => format!("exit {c}"),
                None => "unknown".into(),
            }
        };
        *self.by_code.entry(key).or_default() += 1;
        if o.code == Some(1) {
            let m = o.stderr.trim();
            let m = m.split_once(".toml: ").map_or(m, |(_, rest)| rest);
            let m: String = m.chars().take(90).collect();
            *self.failures.entry(format!("{what}: `{m}…`")).or_default() += 1;
        }
        if o.timed_out {
            self.stopped.push(what.to_string());
        }
        if !o.timed_out && !o.clean() {
            self.unclean
                .push(format!("{what}: {:?} {}", o.code, o.stderr.trim()));
        }
    }
}

fn campaign(work: &Path) -> Tally {
    const LIMIT: u64 = 8 << 30;
    let limited = |timeout| Launch {
        address_space: Some(LIMIT),
        timeout,
        ..Launch::default()
    };
    let mut refinements = vec!["".to_string()];
    for p in [2, 5, 10] {
        for e in [[1, 1], [64, 64], [4096, 1], [1, 4096], [4096, 4096]] {
            refinements.push(format!(
                "refine = {{ degree = {p}, elements = [{}, {}] }}",
                e[0], e[1]
            ));
        }
    }
    for e in [[1024, 1024], [4096, 4096]] {
        refinements.push(format!(
            "refine = {{ degree = 1, elements = [{}, {}] }}",
            e[0], e[1]
        ));
    }
    for q in [1, 4] {
        for e in [[64, 64], [4096, 4096]] {
            refinements.push(format!(
                "refine = {{ lagrange = {q}, elements = [{}, {}] }}",
                e[0], e[1]
            ));
        }
    }
    let outputs = [
        "".to_string(),
        ALL_OUTPUTS.to_string(),
        format!("{ALL_OUTPUTS}vtu_subdivisions = 64\n"),
    ];
    let mut tally = Tally::default();
    let mut k = 0;
    let mut scenes: Vec<String> = Vec::new();
    let mut labels: Vec<String> = Vec::new();
    let output_names = ["no outputs", "all outputs", "all outputs, VTU ×64"];
    for (shape, g) in SHAPES {
        for r in &refinements {
            for (o, on) in outputs.iter().zip(output_names) {
                scenes.push(body_scene("campaign", g, r, "", o));
                let r = r.trim_start_matches("refine = ").replace(['{', '}'], "");
                let r = if r.is_empty() { "as given".into() } else { r };
                labels.push(format!("{shape}, {}, {on}", r.trim()));
            }
        }
    }
    // Extremes of other keys.
    let rect = SHAPES[0].1;
    let deg10 = "refine = { degree = 10, elements = [64, 64] }";
    scenes.push(body_scene("q30", rect, deg10, "quadrature = 30", ""));
    scenes.push(body_scene(
        "q30 small",
        rect,
        "refine = { degree = 10, elements = [4, 4] }",
        "quadrature = 30",
        ALL_OUTPUTS,
    ));
    let many: String = (0..40)
        .map(|i| {
            format!(
                "[[body]]\nname = \"b{i}\"\ngeometry = {{ rectangle = {{ x0 = {i}.0, y0 = 0.0, x1 = {i}.5, y1 = 0.5 }} }}\n\
                 refine = {{ degree = 4, elements = [64, 64] }}\n\
                 material = {{ young = 1.0e6, poisson = 0.3, plane = \"strain\" }}\n\
                 [[support]]\nbody = \"b{i}\"\nside = \"eta_min\"\ncomponent = \"x\"\n\
                 [[support]]\nbody = \"b{i}\"\nside = \"eta_min\"\ncomponent = \"y\"\n"
            )
        })
        .collect();
    scenes.push(many);
    let knots: Vec<String> = (1..2000)
        .map(|i| format!("{}", i as f64 / 2000.0))
        .collect();
    let nurbs_long = format!(
        "{{ nurbs = {{ degree = [1, 1], knots_xi = [0.0, 0.0, {}, 1.0, 1.0], knots_eta = [0.0, 0.0, 1.0, 1.0], control_points = [{}] }} }}",
        knots.join(", "),
        (0..2)
            .flat_map(|j| (0..2001).map(move |i| format!("[{}, {}]", i as f64 / 2000.0, j as f64 * 0.5)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    scenes.push(body_scene(
        "long NURBS",
        &nurbs_long,
        "refine = { degree = 10, elements = [4096, 4096] }",
        "",
        "",
    ));
    scenes.push(body_scene("nul \\u0000 <&>", rect, "", "", ALL_OUTPUTS));
    scenes.push(body_scene("tiny E", rect, "", "", "").replace("young = 2.0e7", "young = 1e-300"));
    scenes.push(
        body_scene("huge load", rect, "", "", "")
            .replace("force = [0.0, -1.3e6]", "force = [0.0, -1e200]"),
    );
    scenes.push(body_scene("zero load", rect, "", "", ALL_OUTPUTS).replace("-1.3e6", "0.0"));
    scenes.push(
        body_scene(
            "unsupported",
            rect,
            "refine = { degree = 2, elements = [4, 4] }",
            "",
            "",
        )
        .replace(
            "[[support]]\nbody = \"b\"\nside = \"xi_min\"\ncomponent = \"x\"\n",
            "",
        ),
    );
    while labels.len() < scenes.len() {
        labels.push(format!("extreme scene {}", labels.len() + 1));
    }
    for (text, label) in scenes.iter().zip(&labels) {
        let name = format!("c{k}.toml");
        std::fs::write(work.join(&name), text).unwrap();
        tally.scenes += 1;
        let c = launch(work, &["check", &name], limited(30.0));
        tally.slowest_check = tally.slowest_check.max(c.seconds);
        tally.record(&format!("check: {label}"), &c);
        let r = launch(
            work,
            &["run", &name, "--out", "campaign-out"],
            limited(30.0),
        );
        tally.record(&format!("run: {label}"), &r);
        k += 1;
    }
    tally
}

// ---------------------------------------------------------------------------
// 4. fault injection
// ---------------------------------------------------------------------------

type Set = BTreeMap<String, Vec<u8>>;

struct Fixture {
    dir: PathBuf,
    out: PathBuf,
    old: Set,
    new: Set,
    seconds: f64,
}

impl Fixture {
    fn new(work: &Path, name: &str, elements: usize, subdivisions: usize) -> Self {
        let dir = work.join(name);
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        let refine = format!("refine = {{ degree = 2, elements = [{elements}, {elements}] }}");
        let output = format!("{ALL_OUTPUTS}vtu_subdivisions = {subdivisions}\n");
        for t in ["old", "new"] {
            let text = body_scene(t, SHAPES[0].1, &refine, "", &output);
            std::fs::write(dir.join(format!("{t}.toml")), text).unwrap();
        }
        let o = launch(
            &dir,
            &["run", "new.toml", "--out", "reference"],
            Launch::default(),
        );
        assert!(o.code == Some(0), "{}", o.stderr);
        let new = atomic::snapshot(&dir.join("reference")).unwrap();
        let mut f = Self {
            out: dir.join("out"),
            dir,
            old: Set::new(),
            new,
            seconds: o.seconds,
        };
        f.reset();
        f.old = atomic::snapshot(&f.out).unwrap();
        f
    }

    fn reset(&self) {
        let o = launch(
            &self.dir,
            &["run", "old.toml", "--out", "out"],
            Launch::default(),
        );
        assert!(o.code == Some(0), "{}", o.stderr);
    }

    fn run_new(&self, how: Launch) -> Outcome {
        launch(&self.dir, &["run", "new.toml", "--out", "out"], how)
    }

    /// "old", "new" or "MIXED".
    fn state(&self) -> &'static str {
        let now = atomic::snapshot(&self.out).unwrap_or_default();
        if now == self.old {
            "old"
        } else if now == self.new {
            "new"
        } else {
            "MIXED"
        }
    }

    fn staging(&self) -> usize {
        atomic::staging_entries(&self.out).len()
    }
}

fn chattr(flag: &str, path: &Path) -> bool {
    Command::new("chattr")
        .arg(flag)
        .arg(path)
        .stderr(Stdio::null())
        .status()
        .is_ok_and(|s| s.success())
}

fn faults(work: &Path, md: &mut String) -> usize {
    let mut mixed = 0;
    let f = Fixture::new(work, "faults", 24, 12);
    let sizes: Vec<(String, usize)> = f.new.iter().map(|(n, b)| (n.clone(), b.len())).collect();
    let _ = writeln!(
        md,
        "The fixture: a rectangle, degree 2, 24 × 24 elements, every output (VTU with 12 \
         subdivisions); one clean run takes {:.2} s and writes {} files ({}).\n",
        f.seconds,
        sizes.len(),
        sizes
            .iter()
            .map(|(n, b)| format!("`{n}` {}", human_bytes(*b as f64)))
            .collect::<Vec<_>>()
            .join(", ")
    );
    md.push_str("| fault | trials | exit codes | output afterwards | staging left | after the next run |\n|---|---|---|---|---|---|\n");
    let mut row =
        |md: &mut String, fault: &str, outcomes: &[(Outcome, &'static str, usize)], next: &str| {
            let mut codes: BTreeMap<String, usize> = BTreeMap::new();
            let mut states: BTreeMap<&str, usize> = BTreeMap::new();
            let mut left = 0;
            for (o, s, l) in outcomes {
                let c = match (o.code, o.signal) {
                    (Some(c), _) => c.to_string(),
                    (None, Some(9)) => "SIGKILL".into(),
                    (None, Some(s)) => format!("signal {s}"),
                    _ => "?".into(),
                };
                *codes.entry(c).or_default() += 1;
                *states.entry(s).or_default() += 1;
                left += usize::from(*l > 0);
                if *s == "MIXED" {
                    mixed += 1;
                }
            }
            let fmt = |m: &BTreeMap<_, usize>| {
                m.iter()
                    .map(|(k, v)| format!("{k} × {v}"))
                    .collect::<Vec<_>>()
                    .join(", ")
            };
            let _ = writeln!(
                md,
                "| {fault} | {} | {} | {} | {left} | {next} |",
                outcomes.len(),
                fmt(&codes),
                fmt(&states.iter().map(|(k, v)| (k.to_string(), *v)).collect())
            );
        };

    // A full disk at every file: a file-size limit one byte below each size.
    let mut out = Vec::new();
    let mut limits: Vec<u64> = sizes.iter().map(|(_, b)| *b as u64 - 1).collect();
    limits.sort();
    limits.dedup();
    for limit in limits {
        let o = f.run_new(Launch {
            file_size: Some(limit),
            ..Launch::default()
        });
        let s = f.state();
        out.push((o, s, f.staging()));
    }
    row(
        md,
        "full disk (file-size limit just below each output's size)",
        &out,
        "—",
    );

    // Unwritable locations (immutable attribute; needs root and ext4).
    if chattr("+i", &f.out) {
        let o = f.run_new(Launch::default());
        let s = f.state();
        let l = f.staging();
        chattr("-i", &f.out);
        row(
            md,
            "output directory immutable (cannot be swapped)",
            &[(o, s, l)],
            "—",
        );
        let parent = f.dir.clone();
        let _ = chattr("+i", &parent);
        let o = f.run_new(Launch::default());
        let s = f.state();
        let l = f.staging();
        chattr("-i", &parent);
        row(
            md,
            "parent directory immutable (no staging possible): refused before the solve",
            &[(o, s, l)],
            "—",
        );
        let file = f.out.join("summary.toml");
        chattr("+i", &file);
        let o = f.run_new(Launch::default());
        let s = f.state();
        let l = f.staging();
        // The immutable file left with the earlier set, into the staging
        // directory beside the target: release it there.
        for entry in atomic::staging_entries(&f.out) {
            chattr("-i", &entry.join("summary.toml"));
        }
        chattr("-i", &file);
        let next = f.run_new(Launch::default());
        let next = format!("exit {:?}, staging left {}", next.code, f.staging());
        row(
            md,
            "one earlier output file immutable (cannot be deleted)",
            &[(o, s, l)],
            &next,
        );
        f.reset();
    } else {
        md.push_str(
            "| unwritable locations | 0 | (chattr unavailable: not run as root on ext4) | | | |\n",
        );
    }

    // SIGKILL spread over a whole run.
    let mut out = Vec::new();
    let mut cleaned = 0;
    let kills = 40;
    for k in 0..kills {
        let after = f.seconds * 1.1 * k as f64 / (kills - 1) as f64;
        let o = f.run_new(Launch {
            signal: Some((libc::SIGKILL, after)),
            ..Launch::default()
        });
        let s = f.state();
        let l = f.staging();
        out.push((o, s, l));
        f.reset();
        cleaned += usize::from(f.staging() == 0);
    }
    row(
        md,
        &format!("SIGKILL at {kills} moments spread over a run (parse … commit)"),
        &out,
        &format!("staging removed in {cleaned} of {kills}"),
    );

    // SIGINT and SIGTERM.
    for (sig, name) in [(libc::SIGINT, "SIGINT"), (libc::SIGTERM, "SIGTERM")] {
        let mut out = Vec::new();
        for k in 1..=10 {
            let after = f.seconds * k as f64 / 10.0;
            let o = f.run_new(Launch {
                signal: Some((sig, after)),
                ..Launch::default()
            });
            let s = f.state();
            let l = f.staging();
            out.push((o, s, l));
            f.reset();
        }
        row(
            md,
            &format!("{name} at 10 moments spread over a run"),
            &out,
            "—",
        );
    }

    // Two different scenes into one directory at once.
    let small = Fixture::new(work, "concurrent", 8, 2);
    let mut out = Vec::new();
    for _ in 0..30 {
        let a = std::thread::spawn({
            let dir = small.dir.clone();
            move || {
                launch(
                    &dir,
                    &["run", "old.toml", "--out", "out"],
                    Launch::default(),
                )
            }
        });
        let b = small.run_new(Launch::default());
        let a = a.join().unwrap();
        let s = small.state();
        let l = small.staging();
        out.push((if a.code == Some(0) { b } else { a }, s, l));
    }
    row(
        md,
        "two different scenes run at once into one `--out` (rounds)",
        &out,
        "—",
    );
    mixed
}

// ---------------------------------------------------------------------------

fn fuzz_counts() -> (u32, usize) {
    let src = std::fs::read_to_string(Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fuzz.rs"))
        .unwrap_or_default();
    let mut total = 0;
    let mut groups = 0;
    for part in src.split("proptest_config(config(").skip(1) {
        let n: String = part
            .chars()
            .take_while(|c| c.is_ascii_digit() || *c == '_')
            .collect();
        total += n.replace('_', "").parse::<u32>().unwrap_or(0);
        groups += 1;
    }
    (total, groups)
}

fn main() {
    // fail fast: the chapter folder must take the report before ten minutes of work
    let mut chapter =
        Chapter::from_args("reliability").expect("the chapter folder takes the outputs");
    let work = std::env::temp_dir().join(format!("reliability-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    let t0 = Instant::now();
    let mut md = String::new();

    md.push_str("## `check` at the documented maxima\n\n");
    md.push_str(
        "`MAX_DEGREE` = 10, `MAX_ELEMENTS` = 4096 per direction. `check` validates, estimates \
         the memory of a run from the knot vectors alone, refines the geometry, checks the \
         Jacobian at every quadrature point, builds the contact points and checks the rigid \
         modes — it assembles nothing. Before refinement ran in linear time, the degree-10 \
         cases ended with SIGABRT (`memory allocation of … bytes failed`), because refinement \
         solved a dense collocation system.\n\n",
    );
    check_times(&work, &mut md);

    md.push_str("\n## The memory estimate against measured peaks\n\n");
    md.push_str(
        "Each scene is run by `iga-contact run` as a child process; its peak resident memory is \
         `ru_maxrss` from `wait4`. The estimate is `Scene::estimate` (see `src/resources.rs` for \
         the model); the default budget it is checked against is 75% of the physical memory \
         (`/proc/meminfo`), or 80% of an address-space limit, and `--max-memory` overrides it.\n\n",
    );
    let worst = calibration(&work, &mut md);
    let _ = writeln!(
        md,
        "\nLargest measured / estimate: **{worst:.2}** (the estimate is above every measured \
         peak; it is most generous for large low-degree meshes, where it assumes both \
         displacement components on the contact trace).\n"
    );

    md.push_str("## Valid but hard scenes under an 8 GiB address-space limit\n\n");
    let tally = campaign(&work);
    let (fuzz, groups) = fuzz_counts();
    let _ = writeln!(
        md,
        "{} scenes — 5 geometries (rectangle, half disk, quarter annulus, quadrilateral, a \
         NURBS patch) × 22 refinements (none; degree 2, 5, 10 on [1, 1], [64, 64], [4096, 1], \
         [1, 4096], [4096, 4096]; degree 1 on [1024, 1024] and [4096, 4096]; Lagrange 1 and 4 \
         on [64, 64] and [4096, 4096]) × 3 output sets (none, all, all with 64 VTU \
         subdivisions), plus extremes (quadrature 30 at degree 10, 40 bodies, a NURBS with \
         2000 knot spans refined to the maxima, a title with control characters, E = 1e-300, a \
         load of 1e200, zero load, an unsupported body) — each given to `check` and to `run` \
         with `RLIMIT_AS` = 8 GiB and a 30 s limit: {} launches.\n",
        tally.scenes, tally.launches
    );
    md.push_str("| outcome | launches |\n|---|---|\n");
    for (k, v) in &tally.by_code {
        let _ = writeln!(md, "| {k} | {v} |");
    }
    let _ = writeln!(
        md,
        "\nEnded by a signal, with a backtrace, or with other than one `error:` line: **{}**. \
         Slowest `check`: {:.2} s.\n",
        tally.unclean.len(),
        tally.slowest_check
    );
    for u in &tally.unclean {
        let _ = writeln!(md, "- {u}");
    }
    md.push_str("The clean failures (exit 1):\n\n");
    for (m, n) in &tally.failures {
        let times = if *n > 1 {
            format!(" ({n} ×)")
        } else {
            String::new()
        };
        let _ = writeln!(md, "- {m}{times}");
    }
    md.push_str(
        "\nThe runs stopped by the harness (accepted by the estimate, still computing):\n\n",
    );
    for m in &tally.stopped {
        let _ = writeln!(md, "- {m}");
    }
    md.push('\n');
    let _ = writeln!(
        md,
        "Invalid input is covered separately: `tests/fuzz.rs` feeds {fuzz} generated inputs in \
         {groups} families (arbitrary text, TOML-like text, text and structural mutations and \
         numeric perturbations of the shipped scenes, knot vectors, patches, builders, \
         refinement) through parsing and building on every `cargo test`, and requires every \
         error to be one line naming a scene key; `tests/scene.rs` has one test per \
         validation rule.\n"
    );

    md.push_str("## Faults injected into the output transaction\n\n");
    md.push_str(
        "A run stages its files in `.NAME.staging-ID` beside `--out`, then swaps that directory \
         in with `renameat2(RENAME_EXCHANGE)` and deletes the earlier set \
         (`report::atomic::OutputSet`). After every fault below the output directory is \
         compared byte for byte with the earlier set (`old`) and the complete new set \
         (`new`); `MIXED` would be anything else.\n\n",
    );
    let mixed = faults(&work, &mut md);
    let _ = writeln!(
        md,
        "\nMixed outputs observed: **{mixed}**. A file-size limit (`RLIMIT_FSIZE`, with SIGXFSZ \
         ignored so the write fails with EFBIG) stands in for a full disk: the outputs smaller \
         than the limit were staged, the first larger one failed. An immutable earlier file \
         (the `chattr +i` row) cannot be deleted even by root: the new set is committed, the \
         earlier directory stays beside the target as staging until the file is released, \
         and the next run removes it.\n"
    );
    let _ = writeln!(md, "Whole run: {:.0} s.", t0.elapsed().as_secs_f64());
    let _ = std::fs::remove_dir_all(&work);
    let written = chapter.text("report.md", &md).and_then(|()| {
        chapter.timed("report.md");
        chapter.facts().count("mixed_outputs", mixed)?;
        chapter.finish()
    });
    match written {
        Ok(()) => println!("wrote book/src/generated/reliability/report.md"),
        Err(e) => {
            eprintln!("reliability: {e}");
            std::process::exit(1);
        }
    }
}
