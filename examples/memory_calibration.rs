//! Calibrates the memory estimate of `resources.rs` against measured peaks.
//!
//! Runs `iga-contact run` on blocks and half disks from degree 1 to 10 as
//! child processes, reads each child's peak resident memory from `wait4`
//! (`ru_maxrss`), and compares it with `Scene::estimate`. The estimate is
//! meant to stay above every measured peak; the printed table (Markdown)
//! shows by how much.
//!
//! `cargo build --release && cargo run --release --example memory_calibration`

use iga_contact::resources::human_bytes;
use iga_contact::scene::Scene;
use std::path::{Path, PathBuf};
use std::process::Command;
use std::time::Instant;

/// The CLI binary next to this example's directory (target/release).
fn binary() -> PathBuf {
    let exe = std::env::current_exe().expect("own path");
    let dir = exe.parent().and_then(Path::parent).expect("target dir");
    dir.join("iga-contact")
}

/// A block on a rigid floor (as `minimal.toml`) or a half disk (as
/// `hertz.toml`) at the given refinement.
fn scene(
    shape: &str,
    degree: usize,
    elements: [usize; 2],
    vtu: Option<usize>,
    extra: &str,
) -> String {
    let (geometry, support, load, contact) = match shape {
        "block" => (
            "{ rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }",
            "xi_min",
            "pressure = { body = \"b\", side = \"eta_max\", pressure = 1.0e4 }",
            "master = { rigid_segment = { from = [-0.5, 0.0], to = [1.5, 0.0] } }",
        ),
        _ => (
            "{ half_disk = { center = [0.0, 0.2], radius = 0.2 } }",
            "xi_min",
            "body_force = { body = \"b\", force = [0.0, -1.3e6] }",
            "master = { rigid_segment = { from = [-0.2, 0.0], to = [0.4, 0.0] } }",
        ),
    };
    let output = match vtu {
        Some(s) => format!("[output]\nvtu = true\nvtu_subdivisions = {s}\nsummary = true\n"),
        None => "[output]\nsummary = true\n".into(),
    };
    format!(
        r#"[[body]]
name = "b"
geometry = {geometry}
refine = {{ degree = {degree}, elements = [{}, {}] }}
material = {{ young = 2.0e7, poisson = 0.3, plane = "strain" }}

[[support]]
body = "b"
side = "{support}"
component = "x"

[[load]]
{load}

[[contact]]
slave = "b"
slave_side = "eta_min"
{contact}
{extra}
{output}"#,
        elements[0], elements[1]
    )
}

/// Runs the CLI and returns (exit code, peak RSS in bytes, seconds).
fn measure(scene_path: &Path, out: &Path) -> (i32, f64, f64) {
    let t = Instant::now();
    let child = Command::new(binary())
        .args(["run", scene_path.to_str().unwrap(), "--out"])
        .arg(out)
        .args(["--max-memory", "1T"])
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .spawn()
        .expect("the CLI runs");
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value for wait4 to fill in.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: waits for our own child; status and usage are valid out-pointers.
    unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    let code = if libc::WIFEXITED(status) {
        libc::WEXITSTATUS(status)
    } else {
        -libc::WTERMSIG(status)
    };
    (
        code,
        usage.ru_maxrss as f64 * 1024.0,
        t.elapsed().as_secs_f64(),
    )
}

fn main() {
    let work = std::env::temp_dir().join(format!("memory-calibration-{}", std::process::id()));
    std::fs::create_dir_all(&work).unwrap();
    type Case = (&'static str, usize, [usize; 2], Option<usize>, &'static str);
    let plain: Vec<(&str, usize, [usize; 2], Option<usize>)> = vec![
        ("block", 1, [256, 256], None),
        ("block", 1, [512, 512], None),
        ("block", 2, [128, 128], None),
        ("block", 2, [256, 256], None),
        ("block", 3, [128, 128], None),
        ("block", 4, [64, 64], None),
        ("block", 4, [1024, 1], None),
        ("block", 6, [32, 32], None),
        ("block", 6, [48, 48], None),
        ("block", 8, [24, 24], None),
        ("block", 10, [16, 16], None),
        ("block", 10, [24, 24], None),
        ("block", 2, [64, 64], Some(16)),
        ("half_disk", 2, [128, 128], None),
        ("half_disk", 3, [64, 64], Some(8)),
        ("half_disk", 5, [32, 32], None),
    ];
    let mut cases: Vec<Case> = plain
        .into_iter()
        .map(|(s, p, e, v)| (s, p, e, v, ""))
        .collect();
    // Kernels by LU: θ = 1, and the factorisation forced.
    cases.push(("block", 2, [128, 128], None, "theta = 1"));
    cases.push(("half_disk", 4, [48, 48], None, "theta = 1"));
    cases.push((
        "block",
        1,
        [256, 256],
        None,
        "[solver]\nfactorisation = \"lu\"",
    ));
    cases.push(("block", 3, [96, 96], None, "theta = -1"));

    println!("| scene | degree | elements | DOFs | non-zeros | estimate | measured | measured / estimate | seconds | exit |");
    println!("|---|---|---|---|---|---|---|---|---|---|");
    let mut worst: f64 = 0.0;
    for (k, (shape, degree, elements, vtu, extra)) in cases.iter().enumerate() {
        let text = scene(shape, *degree, *elements, *vtu, extra);
        let est = Scene::from_toml_str(&text)
            .and_then(|s| s.estimate())
            .expect("a valid scene");
        let path = work.join(format!("case{k}.toml"));
        std::fs::write(&path, &text).unwrap();
        let (code, peak, secs) = measure(&path, &work.join(format!("out{k}")));
        let ratio = peak / est.peak_bytes();
        worst = worst.max(ratio);
        let mut shape = shape.to_string();
        if let Some(s) = vtu {
            shape.push_str(&format!(", VTU ×{s}"));
        }
        if !extra.is_empty() {
            shape.push_str(&format!(", {}", extra.replace('\n', " ")));
        }
        println!(
            "| {shape} | {degree} | {elements:?} | {:.0} | {:.3e} | {} | {} | {ratio:.2} | {secs:.1} | {code} |",
            est.dofs,
            est.nonzeros,
            human_bytes(est.peak_bytes()),
            human_bytes(peak),
        );
    }
    println!("\nlargest measured / estimate: {worst:.2}");
    let _ = std::fs::remove_dir_all(&work);
}
