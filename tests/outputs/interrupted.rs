//! The command line interrupted: a kill at any moment, SIGINT and SIGTERM,
//! a full disk part-way through, and concurrent runs into one directory
//! each leave exactly one complete set.

use crate::{scene_text, single_error_line, snapshot, staging_left, workdir, BIN};
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

fn spawn(dir: &Path, scene: &str, out: &Path) -> Child {
    Command::new(BIN)
        .args(["run", scene, "--out"])
        .arg(out)
        .current_dir(dir)
        .stdout(Stdio::null())
        .stderr(Stdio::piped())
        .spawn()
        .expect("the binary runs")
}

fn run(dir: &Path, scene: &str, out: &Path) -> Output {
    spawn(dir, scene, out).wait_with_output().unwrap()
}

/// An earlier set from scene `old.toml`, and the complete new set that
/// `new.toml` writes (produced once into a reference directory).
struct Sets {
    dir: PathBuf,
    out: PathBuf,
    old: BTreeMap<String, Vec<u8>>,
    new: BTreeMap<String, Vec<u8>>,
    /// Seconds of one clean run of `new.toml`.
    seconds: f64,
}

fn two_sets(name: &str, elements: usize, subdivisions: usize) -> Sets {
    let dir = workdir(name);
    std::fs::write(
        dir.join("old.toml"),
        scene_text("old", elements, subdivisions),
    )
    .unwrap();
    std::fs::write(
        dir.join("new.toml"),
        scene_text("new", elements, subdivisions),
    )
    .unwrap();
    let reference = dir.join("reference");
    let t = Instant::now();
    let o = run(&dir, "new.toml", &reference);
    let seconds = t.elapsed().as_secs_f64();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let out = dir.join("out");
    let o = run(&dir, "old.toml", &out);
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let (old, new) = (snapshot(&out), snapshot(&reference));
    assert_ne!(old, new);
    Sets {
        dir,
        out,
        old,
        new,
        seconds,
    }
}

impl Sets {
    /// The output holds exactly one complete set; returns which.
    #[track_caller]
    fn assert_one_set(&self, when: &str) -> &'static str {
        let now = snapshot(&self.out);
        if now == self.old {
            "old"
        } else if now == self.new {
            "new"
        } else {
            let names: Vec<&String> = now.keys().collect();
            panic!("{when}: the output is a mix: {names:?}")
        }
    }
}

#[test]
fn a_kill_at_any_moment_leaves_one_complete_set_and_the_next_run_cleans_up() {
    let s = two_sets("kill", 24, 12);
    // Kills spread over a whole run: parse, build, solve, staging, commit.
    let mut outcomes = Vec::new();
    for k in 0..8 {
        let delay = s.seconds * k as f64 / 7.0;
        let mut child = spawn(&s.dir, "new.toml", &s.out);
        std::thread::sleep(Duration::from_secs_f64(delay));
        let _ = child.kill(); // SIGKILL
        let _ = child.wait();
        outcomes.push(s.assert_one_set(&format!("SIGKILL after {delay:.2} s")));
        // Restore the old set for the next kill.
        let o = run(&s.dir, "old.toml", &s.out);
        assert!(o.status.success());
        assert!(
            staging_left(&s.out).is_empty(),
            "the next run left {:?}",
            staging_left(&s.out)
        );
    }
    // And a kill while the VTU is being staged.
    let mut child = spawn(&s.dir, "new.toml", &s.out);
    let parent = s.out.parent().unwrap().to_path_buf();
    let start = Instant::now();
    let mut caught = false;
    while start.elapsed().as_secs_f64() < 20.0 * s.seconds.max(0.5) {
        let writing = std::fs::read_dir(&parent).unwrap().flatten().any(|e| {
            e.path().is_dir()
                && e.file_name().to_string_lossy().starts_with(".out.staging-")
                && e.path().join("solution.vtu").exists()
        });
        if writing {
            let _ = child.kill();
            caught = true;
            break;
        }
        if child.try_wait().unwrap().is_some() {
            break;
        }
        std::thread::sleep(Duration::from_micros(200));
    }
    let _ = child.wait();
    s.assert_one_set("SIGKILL while the VTU is staged");
    if caught {
        assert!(
            !staging_left(&s.out).is_empty(),
            "a kill leaves its staging"
        );
    }
    let o = run(&s.dir, "new.toml", &s.out);
    assert!(o.status.success());
    assert_eq!(s.assert_one_set("after the next run"), "new");
    assert!(
        staging_left(&s.out).is_empty(),
        "stale staging was not removed"
    );
    eprintln!("kill outcomes: {outcomes:?}, caught mid-VTU: {caught}");
}

#[test]
fn sigint_and_sigterm_end_the_run_without_partial_files() {
    let s = two_sets("signals", 24, 12);
    for (sig, code) in [(libc::SIGINT, 130), (libc::SIGTERM, 143)] {
        for k in 1..4 {
            let delay = s.seconds * k as f64 / 4.0;
            let child = spawn(&s.dir, "new.toml", &s.out);
            std::thread::sleep(Duration::from_secs_f64(delay));
            // SAFETY: sends a signal to our own child process.
            unsafe { libc::kill(child.id() as i32, sig) };
            let o = child.wait_with_output().unwrap();
            // The old set, or the new one if the signal came during the
            // commit, which is finished first.
            s.assert_one_set(&format!("signal {sig} after {delay:.2} s"));
            assert!(
                staging_left(&s.out).is_empty(),
                "signal {sig}: staging left"
            );
            match o.status.code() {
                Some(c) if c == code => {
                    let line = single_error_line(&o);
                    assert!(line.contains("interrupted"), "{line}");
                }
                // The run finished before the signal arrived.
                Some(0) => {}
                other => panic!(
                    "signal {sig}: exit {other:?}: {}",
                    String::from_utf8_lossy(&o.stderr)
                ),
            }
            let o = run(&s.dir, "old.toml", &s.out);
            assert!(o.status.success());
        }
    }
}

#[test]
fn a_full_disk_part_way_through_leaves_the_earlier_set() {
    let s = two_sets("full-disk", 16, 8);
    // A file-size limit stands in for a full disk: the first output file
    // larger than the limit fails (EFBIG) while the smaller ones succeeded.
    let mut sizes: Vec<u64> = s.new.values().map(|v| v.len() as u64).collect();
    sizes.sort();
    for limit in sizes.iter().filter(|&&b| b > 0).map(|b| b - 1) {
        let o = Command::new("prlimit")
            .arg(format!("--fsize={limit}"))
            .arg(BIN)
            .args(["run", "new.toml", "--out"])
            .arg(&s.out)
            .current_dir(&s.dir)
            .output();
        let Ok(o) = o else {
            eprintln!("prlimit is not available: skipped");
            return;
        };
        assert_eq!(
            o.status.code(),
            Some(1),
            "limit {limit}: {}",
            String::from_utf8_lossy(&o.stderr)
        );
        let line = single_error_line(&o);
        assert!(line.contains("i/o on"), "{line}");
        assert_eq!(s.assert_one_set(&format!("file-size limit {limit}")), "old");
        assert!(staging_left(&s.out).is_empty());
    }
}

#[test]
fn concurrent_runs_into_one_directory_never_mix() {
    let s = two_sets("concurrent", 8, 2);
    let mut seen = Vec::new();
    for round in 0..10 {
        let a = spawn(&s.dir, "old.toml", &s.out);
        let b = spawn(&s.dir, "new.toml", &s.out);
        for child in [a, b] {
            let o = child.wait_with_output().unwrap();
            assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
        }
        seen.push(s.assert_one_set(&format!("round {round}")));
        assert!(staging_left(&s.out).is_empty());
    }
    eprintln!("final sets: {seen:?}");
}
