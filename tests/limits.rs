//! No scene inside the documented limits (`MAX_DEGREE`, `MAX_ELEMENTS`)
//! ends with a signal or a backtrace under an 8 GiB address-space limit:
//! each either answers, or is refused with exit code 2 and one `error:`
//! line before anything large is allocated, or fails with exit code 1 and
//! one `error:` line (an allocation failure included).

use iga_contact::scene::{MAX_DEGREE, MAX_ELEMENTS};
use std::os::unix::process::CommandExt;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_iga-contact");
const LIMIT: u64 = 8 << 30;

fn workdir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("limits-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the CLI with its address space limited to [`LIMIT`].
fn limited(dir: &Path, args: &[&str]) -> Output {
    let mut cmd = Command::new(BIN);
    cmd.args(args).current_dir(dir);
    // SAFETY: setrlimit is async-signal-safe, as pre_exec requires.
    unsafe {
        cmd.pre_exec(|| {
            let lim = libc::rlimit {
                rlim_cur: LIMIT,
                rlim_max: LIMIT,
            };
            if libc::setrlimit(libc::RLIMIT_AS, &lim) != 0 {
                return Err(std::io::Error::last_os_error());
            }
            Ok(())
        });
    }
    cmd.output().expect("the binary runs")
}

fn scene(geometry: &str, refine: &str, extra: &str) -> String {
    format!(
        r#"
[[body]]
name = "b"
geometry = {geometry}
refine = {refine}
material = {{ young = 1.0e6, poisson = 0.3, plane = "strain" }}
{extra}
[[support]]
body = "b"
side = "xi_min"
component = "x"

[[load]]
body_force = {{ body = "b", force = [0.0, -1.0] }}

[[contact]]
slave = "b"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-2.0, 0.0], to = [2.0, 0.0] }} }}

[output]
summary = true
vtu = true
vtu_subdivisions = 64
"#
    )
}

#[track_caller]
fn assert_clean(o: &Output, what: &str) {
    let err = String::from_utf8_lossy(&o.stderr);
    let code = o
        .status
        .code()
        .unwrap_or_else(|| panic!("{what}: ended by a signal ({:?}); stderr: {err}", o.status));
    assert!(
        !err.contains("backtrace") && !err.contains("panicked"),
        "{what}: {err}"
    );
    match code {
        0 => assert!(err.trim().is_empty(), "{what}: {err}"),
        1 | 2 => {
            let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
            assert_eq!(lines.len(), 1, "{what}: {err}");
            assert!(lines[0].starts_with("error: "), "{what}: {err}");
        }
        c => panic!("{what}: exit code {c}: {err}"),
    }
}

#[test]
fn scenes_at_the_documented_maxima_end_cleanly_under_8_gib() {
    let dir = workdir("maxima");
    let (p, n) = (MAX_DEGREE, MAX_ELEMENTS);
    let geometries = [
        "{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }",
        "{ half_disk = { center = [0.0, 0.2], radius = 0.2 } }",
        "{ quarter_annulus = { inner_radius = 0.5, outer_radius = 1.0 } }",
    ];
    let refinements = [
        format!("{{ degree = {p}, elements = [{n}, {n}] }}"),
        format!("{{ degree = {p}, elements = [{n}, 1] }}"),
        format!("{{ degree = {p}, elements = [1, {n}] }}"),
        format!("{{ degree = {p}, elements = [64, 64] }}"),
        format!("{{ degree = 1, elements = [{n}, {n}] }}"),
        format!("{{ lagrange = 4, elements = [{n}, {n}] }}"),
    ];
    let mut count = 0;
    for g in geometries {
        for r in &refinements {
            for extra in ["", "quadrature = 30"] {
                let name = format!("case{count}.toml");
                std::fs::write(dir.join(&name), scene(g, r, extra)).unwrap();
                for cmd in ["check", "run"] {
                    let o = limited(&dir, &[cmd, &name]);
                    assert_clean(&o, &format!("{cmd} {g} {r} {extra}"));
                    // These are all far beyond 8 GiB: refused up front.
                    assert_eq!(o.status.code(), Some(2), "{cmd} {g} {r}");
                }
                count += 1;
            }
        }
    }
    assert!(!dir.join("out").exists(), "a refused run wrote outputs");
}

#[test]
fn an_allocation_failure_is_one_error_line_not_an_abort() {
    // A budget far above the limit lets a run start that cannot fit: the
    // allocator then fails, and the process must still end cleanly.
    let dir = workdir("allocation");
    let text = scene(
        "{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }",
        "{ degree = 10, elements = [64, 64] }",
        "",
    );
    std::fs::write(dir.join("big.toml"), text).unwrap();
    let o = limited(&dir, &["run", "big.toml", "--max-memory", "1T"]);
    assert_clean(&o, "run beyond the address-space limit");
    assert_eq!(o.status.code(), Some(1));
    let err = String::from_utf8_lossy(&o.stderr);
    assert!(err.contains("out of memory"), "{err}");
}
