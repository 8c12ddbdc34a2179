//! The command line: `iga-contact run` of a case's scene as a child of the
//! case's process, its wall and processor time, its peak memory (`wait4`)
//! and the `[timing]` table of its summary.

use crate::process::{cpu_of, repeats};
use iga_contact::timing::PhaseTimes;
use std::path::Path;
use std::process::{Command, Stdio};
use std::time::Instant;

/// The scene file the command line runs: `hertz.toml` refined to p, N²,
/// with the default solver and only the summary as output.
fn cli_scene(p: usize, n: usize) -> Result<String, String> {
    let path = companion::shipped_path("hertz.toml");
    let text = std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
    let mut doc: toml::Table = toml::from_str(&text).map_err(|e| e.to_string())?;
    doc.insert(
        "title".into(),
        format!("Hertz contact, IGA p = {p}, {n} × {n}").into(),
    );
    let refine = doc
        .get_mut("body")
        .and_then(|b| b.as_array_mut())
        .and_then(|b| b.first_mut())
        .and_then(|b| b.get_mut("refine"))
        .and_then(|r| r.as_table_mut())
        .ok_or("hertz.toml: no body[0].refine")?;
    refine.insert("degree".into(), (p as i64).into());
    refine.insert(
        "elements".into(),
        toml::Value::Array(vec![(n as i64).into(), (n as i64).into()]),
    );
    doc.remove("solver");
    let mut output = toml::Table::new();
    output.insert("summary".into(), true.into());
    doc.insert("output".into(), output.into());
    toml::to_string(&doc).map_err(|e| e.to_string())
}

/// One command-line run: wall time from spawn to exit, peak resident
/// memory (bytes) and the `[timing]` of its summary.
pub struct CliRun {
    /// `None`: the default memory budget; else the `--max-memory` given
    /// because the default refused the run.
    pub max_memory: Option<&'static str>,
    pub wall: f64,
    /// Processor time, user and system, of all its threads.
    pub cpu: f64,
    pub peak: f64,
    pub timing: PhaseTimes,
    pub iterations: usize,
}

/// Runs `iga-contact run` on the scene of p, N² in `dir` (a fresh folder).
fn cli_run(
    bin: &Path,
    dir: &Path,
    p: usize,
    n: usize,
    max_memory: Option<&'static str>,
) -> Result<CliRun, String> {
    let scene = dir.join("scene.toml");
    std::fs::write(&scene, cli_scene(p, n)?).map_err(|e| e.to_string())?;
    let out = dir.join("out");
    let err = dir.join("stderr.txt");
    let stderr = std::fs::File::create(&err).map_err(|e| e.to_string())?;
    let t = Instant::now();
    let mut command = Command::new(bin);
    command.arg("run").arg(&scene).arg("--out").arg(&out);
    if let Some(m) = max_memory {
        command.args(["--max-memory", m]);
    }
    let child = command
        .stdout(Stdio::null())
        .stderr(stderr)
        .spawn()
        .map_err(|e| format!("{}: {e}", bin.display()))?;
    // wait4, not Child::wait: it reports the child's own peak memory
    let mut status = 0;
    // SAFETY: an all-zero rusage is a valid value of the plain C struct.
    let mut usage: libc::rusage = unsafe { std::mem::zeroed() };
    // SAFETY: the pid is our unwaited child; status and usage are valid
    // for writes for the duration of the call.
    let waited = unsafe { libc::wait4(child.id() as i32, &mut status, 0, &mut usage) };
    let wall = t.elapsed().as_secs_f64();
    if waited < 0 || !libc::WIFEXITED(status) || libc::WEXITSTATUS(status) != 0 {
        let msg = std::fs::read_to_string(&err).unwrap_or_default();
        let how = if waited >= 0 && libc::WIFSIGNALED(status) {
            // SIGKILL without a message: the kernel's out-of-memory killer
            format!(
                "killed by signal {} at {:.1} GB resident",
                libc::WTERMSIG(status),
                usage.ru_maxrss as f64 * 1024.0 / 1e9
            )
        } else {
            msg.trim().to_string()
        };
        return Err(format!("iga-contact run, p = {p}, {n}²: {how}"));
    }
    let summary = std::fs::read_to_string(out.join("summary.toml")).map_err(|e| e.to_string())?;
    let summary: toml::Table = toml::from_str(&summary).map_err(|e| e.to_string())?;
    let t = summary
        .get("timing")
        .and_then(|t| t.as_table())
        .ok_or("summary.toml has no [timing]")?;
    let timing = PhaseTimes::from_keys(|k| t.get(k)?.as_float())
        .map_err(|k| format!("summary.toml: no timing.{k}"))?;
    let iterations = summary
        .get("iterations")
        .and_then(|v| v.as_integer())
        .ok_or("summary.toml: no iterations")? as usize;
    Ok(CliRun {
        max_memory,
        wall,
        cpu: cpu_of(&usage),
        // ru_maxrss is in kilobytes on Linux
        peak: usage.ru_maxrss as f64 * 1024.0,
        timing,
        iterations,
    })
}

/// The budget given when the default memory budget refuses a run: the
/// estimate is an upper bound (22.9 GiB for p = 2 on 512², whose measured
/// peak is about 3 GB), so the fallback lifts the refusal, and the measured
/// peak in the table is the figure to read.
pub const FALLBACK_MAX_MEMORY: &str = "256G";

/// The median (by wall time) of `repeats(n)` command-line runs, with the
/// default memory budget, or [`FALLBACK_MAX_MEMORY`] where it refuses.
pub fn cli(p: usize, n: usize) -> Result<CliRun, String> {
    let bin = companion::chapter::cli_binary().map_err(|e| e.to_string())?;
    let dir = std::env::temp_dir().join(format!("solver_scaling_cli_{}", std::process::id()));
    let mut runs = Vec::new();
    let mut max_memory = None;
    while runs.len() < repeats(n) {
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).map_err(|e| e.to_string())?;
        let run = cli_run(&bin, &dir, p, n, max_memory);
        let _ = std::fs::remove_dir_all(&dir);
        match run {
            Err(e) if max_memory.is_none() && e.contains("over the memory budget") => {
                eprintln!(
                    "  the default memory budget refuses it: --max-memory {FALLBACK_MAX_MEMORY}"
                );
                max_memory = Some(FALLBACK_MAX_MEMORY);
            }
            run => runs.push(run?),
        }
    }
    runs.sort_by(|a, b| a.wall.total_cmp(&b.wall));
    let k = runs.len() / 2;
    Ok(runs.swap_remove(k))
}
