//! Outputs as one transaction: after any failure — an i/o error part-way
//! through writing, a kill at any moment, a signal, two runs at once — the
//! output directory holds exactly the earlier set of files, byte for byte,
//! or exactly the new one; staging left by a kill is removed by the next
//! run; and problems with the output location are reported before any work.

use iga_contact::report::atomic::{self, read_manifest, OutputSet, MANIFEST};
use iga_contact::Error;
use std::collections::BTreeMap;
use std::path::{Path, PathBuf};
use std::process::{Child, Command, Output, Stdio};
use std::time::{Duration, Instant};

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

// ---------------------------------------------------------------------------
// The library type
// ---------------------------------------------------------------------------

#[test]
fn a_commit_replaces_the_whole_set_and_lists_it_in_the_manifest() {
    let target = workdir("replace").join("out");
    commit(
        &target,
        &[("a.csv", b"1"), ("b.svg", b"2"), ("c.vtu", b"3")],
    );
    let files = commit(&target, &[("a.csv", b"new"), ("sub/d.md", b"4")]);
    assert_eq!(files, vec![target.join("a.csv"), target.join("sub/d.md")]);
    let snap = snapshot(&target);
    let names: Vec<&str> = snap.keys().map(String::as_str).collect();
    // b.svg and c.vtu belonged to the earlier set: gone, not mixed in.
    assert_eq!(names, vec![MANIFEST, "a.csv", "sub/d.md"]);
    assert_eq!(snap["a.csv"], b"new");
    assert_eq!(read_manifest(&target).unwrap(), vec!["a.csv", "sub/d.md"]);
    assert!(staging_left(&target).is_empty());
}

#[test]
fn an_io_failure_part_way_through_leaves_the_earlier_set_byte_for_byte() {
    let target = workdir("io-failure").join("out");
    commit(&target, &[("one.csv", b"old 1"), ("two.csv", b"old 2")]);
    let before = snapshot(&target);
    // A producer whose k-th file fails half-way (disk full), for every k.
    for k in 0..4 {
        let mut set = OutputSet::begin(&target).unwrap();
        let mut failure = None;
        for i in 0..4 {
            let name = format!("file{i}.csv");
            let r = set.stage_with(&name, |w| {
                w.write_all(b"the first half, ")?;
                if i == k {
                    return Err(std::io::Error::from_raw_os_error(28)); // ENOSPC
                }
                w.write_all(b"the second half")
            });
            if let Err(e) = r {
                failure = Some(e);
                break;
            }
        }
        let e = failure.expect("the k-th file fails");
        assert!(matches!(e, Error::Io { .. }), "{e}");
        assert!(e.to_string().contains(&format!("file{k}.csv")), "{e}");
        drop(set);
        assert_eq!(
            snapshot(&target),
            before,
            "k = {k}: the earlier set changed"
        );
        assert!(staging_left(&target).is_empty(), "k = {k}: staging left");
    }
}

#[test]
fn output_location_problems_are_named_before_any_work() {
    let dir = workdir("location");
    // A file where the directory should be.
    let file = dir.join("taken");
    std::fs::write(&file, "x").unwrap();
    let e = OutputSet::begin(&file).err().expect("refused").to_string();
    assert!(
        e.contains("taken") && e.contains("is an existing file, not a directory"),
        "{e}"
    );
    // A file where a parent directory should be.
    let e = OutputSet::begin(file.join("out"))
        .err()
        .expect("refused")
        .to_string();
    assert!(
        e.contains("`") && e.contains("taken") && e.contains("not a directory"),
        "{e}"
    );
    // A directory that holds something else than an earlier output set.
    let other = dir.join("home");
    std::fs::create_dir_all(other.join("photos")).unwrap();
    std::fs::write(other.join("notes.txt"), "mine").unwrap();
    let e = OutputSet::begin(&other).err().expect("refused").to_string();
    assert!(e.contains("did not write"), "{e}");
    assert_eq!(std::fs::read(other.join("notes.txt")).unwrap(), b"mine");
    // An earlier run without a manifest is taken over when it holds only
    // files of the declared names.
    let legacy = dir.join("legacy");
    std::fs::create_dir_all(&legacy).unwrap();
    std::fs::write(legacy.join("summary.toml"), "old").unwrap();
    std::fs::write(legacy.join(".solution.vtu.1234.tmp"), "debris").unwrap();
    let mut set = OutputSet::begin_expecting(&legacy, &["summary.toml"]).unwrap();
    set.stage("summary.toml", b"new").unwrap();
    set.commit().unwrap();
    let names: Vec<String> = snapshot(&legacy).into_keys().collect();
    assert_eq!(
        names,
        vec![MANIFEST.to_string(), "summary.toml".to_string()]
    );
    // Nothing was created for a refused target.
    assert!(!file.join("out").exists());
}

#[test]
fn staging_of_a_dead_owner_is_removed_by_the_next_set() {
    let target = workdir("stale").join("out");
    commit(&target, &[("a.csv", b"1")]);
    let before = snapshot(&target);
    // What a SIGKILL leaves: a staging directory with a half-written file,
    // and its lock file, which no living process holds.
    let parent = target.parent().unwrap();
    let stale = parent.join(".out.staging-999999-1");
    std::fs::create_dir_all(&stale).unwrap();
    std::fs::write(stale.join("a.csv"), "half").unwrap();
    std::fs::write(parent.join(".out.staging-999999-1.lock"), "").unwrap();
    // ... and one whose lock file was never made.
    std::fs::create_dir_all(parent.join(".out.staging-999999-2")).unwrap();
    assert_eq!(snapshot(&target), before);
    // A living set's staging is not touched by another set's clean-up.
    let alive = OutputSet::begin(&target).unwrap();
    assert_eq!(
        staging_left(&target).len(),
        2,
        "{:?}",
        staging_left(&target)
    );
    let other = OutputSet::begin(&target).unwrap();
    assert!(alive.dir().is_dir());
    drop(other);
    drop(alive);
    assert!(staging_left(&target).is_empty());
    assert_eq!(snapshot(&target), before);
}

#[test]
fn names_outside_the_set_are_refused() {
    let target = workdir("names").join("out");
    let mut set = OutputSet::begin(&target).unwrap();
    for bad in ["../escape.csv", "/abs.csv", "", MANIFEST, "a/../../b"] {
        assert!(set.stage(bad, b"x").is_err(), "{bad:?} accepted");
    }
}

// ---------------------------------------------------------------------------
// The command line: kills, signals, a full disk, concurrent runs
// ---------------------------------------------------------------------------

/// A block with outputs of every kind; `subdivisions` sets the VTU size.
fn scene_text(title: &str, elements: usize, subdivisions: usize) -> String {
    format!(
        r#"title = "{title}"
[[body]]
name = "block"
geometry = {{ rectangle = {{ x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 }} }}
refine = {{ degree = 2, elements = [{elements}, {elements}] }}
material = {{ young = 1.0e6, poisson = 0.3, plane = "strain" }}

[[support]]
body = "block"
side = "xi_min"
component = "x"

[[load]]
pressure = {{ body = "block", side = "eta_max", pressure = 1.0e4 }}

[[contact]]
slave = "block"
slave_side = "eta_min"
master = {{ rigid_segment = {{ from = [-0.5, 0.0], to = [1.5, 0.0] }} }}

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

/// `iga-contact ARGS` in `dir`.
fn cli(dir: &Path, args: &[&str]) -> Output {
    Command::new(BIN)
        .args(args)
        .current_dir(dir)
        .output()
        .unwrap()
}

#[test]
fn an_output_path_that_is_a_file_is_refused_before_the_solve() {
    let dir = workdir("fail-fast");
    // A solve that would fail (one iteration allowed): if the output were
    // checked after the solve, the solver's error would be reported.
    // (lifted off the floor and started from the tied kernel, which glues
    // the block at its gap: one iteration cannot land it)
    let text = scene_text("doomed", 8, 2).replace(
        "y0 = 0.0, x1 = 1.0, y1 = 0.5",
        "y0 = 0.1, x1 = 1.0, y1 = 0.6",
    ) + "\n[solver]\nstart = \"tied\"\nmax_iter = 1\n";
    std::fs::write(dir.join("doomed.toml"), text).unwrap();
    let o = cli(&dir, &["run", "doomed.toml", "--out", "results"]);
    let err = String::from_utf8_lossy(&o.stderr);
    assert_eq!(o.status.code(), Some(1), "the solve fails: {err}");
    assert!(
        !dir.join("results").exists(),
        "a failed run created its directory"
    );
    std::fs::write(dir.join("taken"), "a file").unwrap();
    for (out, says) in [
        ("taken", "`taken` is an existing file, not a directory"),
        ("taken/run", "`taken` is an existing file, not a directory"),
    ] {
        let o = cli(&dir, &["run", "doomed.toml", "--out", out]);
        assert_eq!(o.status.code(), Some(2), "--out {out}");
        let line = single_error_line(&o);
        assert!(line.contains(says), "{line}");
    }
    assert_eq!(std::fs::read(dir.join("taken")).unwrap(), b"a file");
}

// ---------------------------------------------------------------------------
// Locations a rename cannot replace: mount points, protected inodes
// ---------------------------------------------------------------------------

/// Runs `tool ARGS`; `Err` with the reason when it is missing or refuses
/// (not root, no such file-system feature), so a test can say why it skips.
fn try_tool(tool: &str, args: &[&OsStr]) -> Result<(), String> {
    match Command::new(tool).args(args).output() {
        Ok(o) if o.status.success() => Ok(()),
        Ok(o) => Err(format!(
            "`{tool}` failed: {}",
            String::from_utf8_lossy(&o.stderr).trim()
        )),
        Err(e) => Err(format!("`{tool}` cannot run: {e}")),
    }
}

use std::ffi::OsStr;

/// `chattr +FLAG path`, undone on drop.
struct Attr(PathBuf, &'static str);

impl Attr {
    fn set(path: &Path, flag: &'static str) -> Result<Self, String> {
        try_tool(
            "chattr",
            &[OsStr::new(&format!("+{flag}")), path.as_os_str()],
        )?;
        Ok(Self(path.to_path_buf(), flag))
    }
}

impl Drop for Attr {
    fn drop(&mut self) {
        let _ = try_tool(
            "chattr",
            &[OsStr::new(&format!("-{}", self.1)), self.0.as_os_str()],
        );
    }
}

/// A tmpfs mounted at a directory, unmounted on drop.
struct Mount(PathBuf);

impl Mount {
    fn at(dir: &Path) -> Result<Self, String> {
        std::fs::create_dir_all(dir).unwrap();
        let args = ["-t", "tmpfs", "-o", "size=8m", "iga-contact-test"].map(OsStr::new);
        let mut all: Vec<&OsStr> = args.to_vec();
        all.push(dir.as_os_str());
        try_tool("mount", &all)?;
        Ok(Self(dir.to_path_buf()))
    }
}

impl Drop for Mount {
    fn drop(&mut self) {
        let _ = try_tool("umount", &[self.0.as_os_str()]);
    }
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

/// Refused before the solve with exit 2 and one line saying `says`, by
/// the library and by the binary, leaving no staging behind.
#[track_caller]
fn refused_early(dir: &Path, out: &str, says: &str) {
    let target = dir.join(out);
    match OutputSet::begin(&target) {
        Err(Error::Output { reason, .. }) => assert!(reason.contains(says), "{reason}"),
        Err(e) => panic!("{out}: not an output error: {e}"),
        Ok(_) => panic!("{out}: accepted"),
    }
    let o = cli(dir, &["run", "doomed.toml", "--out", out]);
    assert_eq!(o.status.code(), Some(2), "--out {out}: {o:?}");
    let line = single_error_line(&o);
    assert!(line.contains(says) && line.contains(out), "{line}");
    assert!(
        staging_left(&target).is_empty(),
        "{:?}",
        staging_left(&target)
    );
}

#[test]
fn a_mount_point_is_refused_before_the_solve_and_a_folder_inside_it_works() {
    let dir = workdir("mount-point");
    doomed(&dir);
    let mount = match Mount::at(&dir.join("mnt")) {
        Ok(m) => m,
        Err(why) => {
            eprintln!("SKIPPED: cannot mount a tmpfs here ({why})");
            return;
        }
    };
    // Empty, and again holding an earlier set: a rename cannot move either.
    refused_early(&dir, "mnt", "is a mount point");
    commit(&dir.join("mnt/run"), &[("a.csv", b"1")]);
    std::fs::rename(dir.join("mnt/run/a.csv"), dir.join("mnt/a.csv")).unwrap();
    std::fs::rename(
        dir.join("mnt/run/.outputs.toml"),
        dir.join("mnt/.outputs.toml"),
    )
    .unwrap();
    std::fs::remove_dir(dir.join("mnt/run")).unwrap();
    refused_early(&dir, "mnt", "is a mount point");
    assert_eq!(std::fs::read(dir.join("mnt/a.csv")).unwrap(), b"1");
    // The folder the message proposes takes the outputs.
    let files = commit(&dir.join("mnt/run"), &[("b.csv", b"2")]);
    assert_eq!(files, vec![dir.join("mnt/run/b.csv")]);
    assert!(staging_left(&dir.join("mnt/run")).is_empty());
    drop(mount);
}

#[test]
fn an_immutable_folder_or_file_is_refused_before_the_solve_and_leaves_no_staging() {
    let dir = workdir("immutable");
    doomed(&dir);
    let empty = dir.join("empty");
    std::fs::create_dir(&empty).unwrap();
    let attr = match Attr::set(&empty, "i") {
        Ok(a) => a,
        Err(why) => {
            eprintln!("SKIPPED: cannot set inode attributes here ({why})");
            return;
        }
    };
    refused_early(&dir, "empty", "immutable (chattr +i)");
    drop(attr);
    // An earlier result with one immutable file, then one append-only
    // subfolder: the swap would work, deleting the earlier set would not.
    let target = dir.join("earlier");
    commit(&target, &[("a.csv", b"old"), ("sub/b.svg", b"old")]);
    let before = snapshot(&target);
    for (path, flag, says) in [
        (
            target.join("a.csv"),
            "i",
            "holds `a.csv` with the immutable",
        ),
        (target.join("sub"), "a", "holds `sub` with the append-only"),
    ] {
        let attr = Attr::set(&path, flag).unwrap();
        refused_early(&dir, "earlier", says);
        assert_eq!(snapshot(&target), before);
        drop(attr);
    }
    // Without the attribute the same target is replaced, and nothing stays.
    commit(&target, &[("c.csv", b"new")]);
    assert_eq!(read_manifest(&target).unwrap(), vec!["c.csv"]);
    assert!(
        staging_left(&target).is_empty(),
        "{:?}",
        staging_left(&target)
    );
}
