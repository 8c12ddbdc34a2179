//! Running the `iga-contact` binary as a child process under resource
//! limits, with its exit status, peak memory and messages; and the scenes
//! the campaign feeds it.

use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Stdio};
use std::sync::OnceLock;
use std::time::{Duration, Instant};

/// The CLI binary of this build (checked once to be newer than the sources).
pub fn binary() -> &'static Path {
    static BIN: OnceLock<PathBuf> = OnceLock::new();
    BIN.get_or_init(|| {
        crate::cli_binary().unwrap_or_else(|e| {
            eprintln!("reliability: {e}");
            std::process::exit(2)
        })
    })
}

/// Limits and timing of one child run.
#[derive(Clone, Copy, Default)]
pub struct Launch {
    /// RLIMIT_AS in bytes.
    pub address_space: Option<u64>,
    /// RLIMIT_FSIZE in bytes (a stand-in for a full disk).
    pub file_size: Option<u64>,
    /// Seconds before the harness sends SIGKILL (counted as a time-out).
    pub timeout: f64,
    /// Send this signal after this many seconds.
    pub signal: Option<(i32, f64)>,
}

#[derive(Debug)]
pub struct Outcome {
    pub code: Option<i32>,
    pub signal: Option<i32>,
    /// Peak resident memory (`ru_maxrss` from `wait4`), bytes.
    pub peak_bytes: f64,
    pub seconds: f64,
    pub stdout: String,
    pub stderr: String,
    pub timed_out: bool,
}

impl Outcome {
    /// Exit code 0 and nothing but `warning:` lines on stderr, or
    /// 1/2/130/143 with exactly one `error:` line; no backtrace.
    pub fn clean(&self) -> bool {
        let lines: Vec<&str> = self
            .stderr
            .lines()
            .filter(|l| !l.trim().is_empty())
            .collect();
        let no_trace = !self.stderr.contains("backtrace") && !self.stderr.contains("panicked");
        no_trace
            && match self.code {
                // warnings (one line each) are all an answer may print
                Some(0) => lines.iter().all(|l| l.starts_with("warning: ")),
                // one error line, last, after the warnings known before
                // the failure (a penalty below its bound may be why)
                Some(1 | 2 | 130 | 143) => {
                    lines.last().is_some_and(|l| l.starts_with("error: "))
                        && lines[..lines.len() - 1]
                            .iter()
                            .all(|l| l.starts_with("warning: "))
                }
                _ => false,
            }
    }

    /// The error line without `error: ` and the scene file's name.
    pub fn message(&self) -> String {
        let m = self
            .stderr
            .lines()
            .rfind(|l| l.starts_with("error: "))
            .unwrap_or(self.stderr.trim());
        let m = m.strip_prefix("error: ").unwrap_or(m);
        m.split_once(".toml: ")
            .map_or(m, |(_, rest)| rest)
            .to_string()
    }

    /// The exit code, or the signal that ended the process.
    pub fn status(&self) -> String {
        match (self.code, self.signal) {
            (Some(c), _) => c.to_string(),
            (None, Some(libc::SIGKILL)) => "SIGKILL".into(),
            (None, Some(s)) => format!("signal {s}"),
            _ => "?".into(),
        }
    }
}

fn read_all(mut r: impl std::io::Read + Send + 'static) -> std::thread::JoinHandle<String> {
    std::thread::spawn(move || {
        let mut s = String::new();
        let _ = r.read_to_string(&mut s);
        s
    })
}

/// Runs `iga-contact ARGS` in `dir` under the limits of `how`.
pub fn launch(dir: &Path, args: &[&str], how: Launch) -> Outcome {
    let mut cmd = Command::new(binary());
    cmd.args(args)
        .current_dir(dir)
        .stdout(Stdio::piped())
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
    let stdout = read_all(child.stdout.take().expect("piped"));
    let stderr = read_all(child.stderr.take().expect("piped"));
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
        stdout: stdout.join().unwrap_or_default(),
        stderr: stderr.join().unwrap_or_default(),
        timed_out,
    }
}

// ---------------------------------------------------------------------------
// Scenes
// ---------------------------------------------------------------------------

/// The geometries of the campaign: (label, `geometry` value).
pub const SHAPES: [(&str, &str); 5] = [
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

/// One body resting on a rigid floor under its weight, held sideways on
/// `xi_min`.
pub fn body_scene(title: &str, geometry: &str, refine: &str, extra: &str, output: &str) -> String {
    floor_scene(
        title,
        geometry,
        refine,
        extra,
        &support("side = \"xi_min\""),
        "slave_side = \"eta_min\"",
        output,
    )
}

/// A body of several patches for the campaign: it names boundaries, not
/// sides, and a full disk is held by points.
pub struct MultiPatchShape {
    pub name: &'static str,
    pub geometry: &'static str,
    /// Where it is held in x: `boundary = …` or `point = …` lines, one
    /// support each.
    pub held: &'static [&'static str],
    /// The boundary that rests on the floor.
    pub slave: &'static str,
}

/// The multi-patch geometries of the campaign: the half disk of four
/// patches on its symmetry line, and the full disk of five held at two
/// points of its vertical centre line (as the shipped `disk_full.toml`).
pub const MULTIPATCH_SHAPES: [MultiPatchShape; 2] = [
    MultiPatchShape {
        name: "half disk of 4 patches",
        geometry: "{ half_disk_4 = { center = [0.0, 0.2], radius = 0.2 } }",
        held: &["boundary = \"straight\""],
        slave: "arc_lower",
    },
    MultiPatchShape {
        name: "disk of 5 patches",
        geometry: "{ disk_5 = { center = [0.0, 0.2], radius = 0.2, layout = \"diagonal\" } }",
        held: &["point = [0.0, 0.31313708498984763]", "point = [0.0, 0.4]"],
        slave: "arc_lower",
    },
];

/// [`body_scene`] for a body of several patches.
pub fn multipatch_scene(
    title: &str,
    shape: &MultiPatchShape,
    refine: &str,
    output: &str,
) -> String {
    let held: String = shape.held.iter().map(|h| support(h)).collect();
    floor_scene(
        title,
        shape.geometry,
        refine,
        "",
        &held,
        &format!("slave_boundary = \"{}\"", shape.slave),
        output,
    )
}

/// A `[[support]]` of body `b` in x, at `at` (a `side`, `boundary` or
/// `point` line).
fn support(at: &str) -> String {
    format!("[[support]]\nbody = \"b\"\n{at}\ncomponent = \"x\"\n\n")
}

/// Body `b` on a rigid floor under its weight, with its supports and the
/// key of its slave side or boundary.
fn floor_scene(
    title: &str,
    geometry: &str,
    refine: &str,
    extra: &str,
    supports: &str,
    slave: &str,
    output: &str,
) -> String {
    format!(
        r#"title = "{title}"
[[body]]
name = "b"
geometry = {geometry}
{refine}
material = {{ young = 2.0e7, poisson = 0.3, plane = "strain" }}
{extra}
{supports}[[load]]
body_force = {{ body = "b", force = [0.0, -1.3e6] }}

[[contact]]
slave = "b"
{slave}
master = {{ rigid_segment = {{ from = [-2.0, 0.0], to = [2.0, 0.0] }} }}

{output}"#
    )
}

/// `refine = { degree = p, elements = [a, b] }`.
pub fn refine(degree: usize, elements: [usize; 2]) -> String {
    format!(
        "refine = {{ degree = {degree}, elements = [{}, {}] }}",
        elements[0], elements[1]
    )
}

/// A mesh as the tables write it: `64²` or `4096 × 1`.
pub fn mesh(elements: [usize; 2]) -> String {
    if elements[0] == elements[1] {
        format!("{}²", elements[0])
    } else {
        format!("{} × {}", elements[0], elements[1])
    }
}

/// Every output a scene can ask for.
pub const ALL_OUTPUTS: &str =
    "[output]\niterations = true\npressure_profile = true\nsummary = true\n\
                               figures = true\nvtu = true\n";

/// The commit measured, `+` marking uncommitted changes.
pub fn commit() -> String {
    let git = |args: &[&str]| {
        std::process::Command::new("git")
            .args(args)
            .current_dir(crate::source_root())
            .output()
            .ok()
            .filter(|o| o.status.success())
            .map(|o| String::from_utf8_lossy(&o.stdout).trim().to_string())
    };
    match (
        git(&["rev-parse", "--short", "HEAD"]),
        git(&["status", "--porcelain", "--untracked-files=no"]),
    ) {
        (Some(h), Some(s)) if s.is_empty() => h,
        (Some(h), Some(_)) => format!("{h}+"),
        _ => "unknown".into(),
    }
}
