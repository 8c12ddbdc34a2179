//! Problems with the output location, named before any work: a file where
//! a folder should be, a folder of someone else's files, and locations a
//! rename cannot replace (mount points, immutable or append-only inodes).

use crate::{cli, commit, doomed, single_error_line, snapshot, staging_left, workdir};
use iga_contact::report::atomic::{read_manifest, OutputSet, MANIFEST};
use iga_contact::Error;
use std::ffi::OsStr;
use std::path::{Path, PathBuf};
use std::process::Command;

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
fn an_output_path_that_is_a_file_is_refused_before_the_solve() {
    let dir = workdir("fail-fast");
    // A solve that would fail (one iteration allowed): if the output were
    // checked after the solve, the solver's error would be reported.
    // (lifted off the floor and started from the tied kernel, which glues
    // the block at its gap: one iteration cannot land it)
    doomed(&dir);
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
