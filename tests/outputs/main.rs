//! Outputs as one transaction: after any failure — an i/o error part-way
//! through writing, a kill at any moment, a signal, two runs at once — the
//! output directory holds exactly the earlier set of files, byte for byte,
//! or exactly the new one; staging left by a kill is removed by the next
//! run; and problems with the output location are reported before any work.
//!
//! One module per concern: [`library`] (the `OutputSet` type: a commit
//! replaces the whole set, an i/o failure leaves the earlier one, stale
//! staging is removed), [`interrupted`] (the command line killed,
//! signalled, out of disk, or run twice at once), [`location`] (problems
//! with the output location named before any work). The helpers they share
//! are here.

#[path = "../common/mod.rs"]
mod common;

mod interrupted;
mod library;
mod location;

use common::block::{block_on_floor, HELD};
use iga_contact::report::atomic::{self, OutputSet};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Command, Output};

const BIN: &str = env!("CARGO_BIN_EXE_iga-contact");

/// A fresh, empty parent directory for one test.
fn workdir(name: &str) -> PathBuf {
    let dir = Path::new(env!("CARGO_TARGET_TMPDIR")).join(format!("outputs-{name}"));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// The files of `dir` by name, with what differs between two runs of one
/// scene taken out: the `[timing]` table of `summary.toml` (wall-clock
/// times) and, in the manifest, the byte counts that follow from it.
fn snapshot(dir: &Path) -> BTreeMap<String, Vec<u8>> {
    companion::timing::untimed_snapshot(dir).unwrap()
}

/// Staging entries beside `target`, by name.
fn staging_left(target: &Path) -> Vec<String> {
    atomic::staging_entries(target)
        .iter()
        .map(|p| p.file_name().unwrap().to_string_lossy().into_owned())
        .collect()
}

/// Stages `files` and commits them.
fn commit(target: &Path, files: &[(&str, &[u8])]) -> Vec<PathBuf> {
    let mut set = OutputSet::begin(target).unwrap();
    for (name, bytes) in files {
        set.stage(name, bytes).unwrap();
    }
    set.commit().unwrap()
}

/// A block with outputs of every kind; `subdivisions` sets the VTU size.
fn scene_text(title: &str, elements: usize, subdivisions: usize) -> String {
    let block = block_on_floor([elements, elements], HELD);
    format!(
        r#"title = "{title}"
{block}
[output]
iterations = true
pressure_profile = true
summary = true
figures = true
vtu = true
vtu_subdivisions = {subdivisions}
"#
    )
}

/// Exactly one non-empty stderr line, starting with `error:`.
#[track_caller]
fn single_error_line(o: &Output) -> String {
    let err = String::from_utf8_lossy(&o.stderr).into_owned();
    let lines: Vec<&str> = err.lines().filter(|l| !l.trim().is_empty()).collect();
    // A run that has solved may have printed its warnings (one line per
    // cause) before it failed; the failure itself is one `error:` line.
    let (last, before) = lines.split_last().expect("an error line on stderr");
    assert!(last.starts_with("error: "), "stderr: {err}");
    assert!(
        before.iter().all(|l| l.starts_with("warning: ")),
        "stderr: {err}"
    );
    last.to_string()
}

/// `iga-contact ARGS` in `dir`.
fn cli(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

/// The scene `doomed.toml` of `dir`: a solve that fails (exit 1) if it
/// ever starts, so exit 2 shows the output was refused before the solve.
fn doomed(dir: &Path) {
    let text = scene_text("doomed", 8, 2).replace(
        "y0 = 0.0, x1 = 1.0, y1 = 0.5",
        "y0 = 0.1, x1 = 1.0, y1 = 0.6",
    ) + "\n[solver]\nstart = \"tied\"\nmax_iter = 1\n";
    std::fs::write(dir.join("doomed.toml"), text).unwrap();
}
