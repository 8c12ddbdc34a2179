//! File-system steps of a commit: fsync of a tree, removal of stale staging
//! directories, directory locks, and the atomic exchange of two directories.

use super::errors::{io_error, output_error};
use crate::error::Result;
use std::fs::File;
use std::path::{Path, PathBuf};

/// fsync every file and directory below `dir`, and `dir` itself.
pub(super) fn sync_tree(dir: &Path) -> std::io::Result<()> {
    for entry in std::fs::read_dir(dir)? {
        let entry = entry?;
        if entry.file_type()?.is_dir() {
            sync_tree(&entry.path())?;
        } else {
            File::open(entry.path())?.sync_all()?;
        }
    }
    File::open(dir)?.sync_all()
}

/// Removes staging directories of `name` whose owners are dead, after
/// putting back an earlier set that a crash left aside (see [`exchange`]).
pub(super) fn remove_stale(parent: &Path, name: &str, target: &Path) {
    let prefix = format!(".{name}.staging-");
    let Ok(entries) = std::fs::read_dir(parent) else {
        return;
    };
    let names: Vec<String> = entries
        .flatten()
        .map(|e| e.file_name().to_string_lossy().into_owned())
        .filter(|n| n.starts_with(&prefix))
        .collect();
    for n in &names {
        if n.ends_with(".previous") {
            if std::fs::symlink_metadata(target).is_err() {
                let _ = std::fs::rename(parent.join(n), target);
            } else {
                let _ = std::fs::remove_dir_all(parent.join(n));
            }
        } else if let Some(dir) = n.strip_suffix(".lock") {
            // A lock nobody holds: its owner died.
            let lock_path = parent.join(n);
            if let Ok(f) = File::open(&lock_path) {
                if lock_exclusive(&f, true).is_ok() {
                    let _ = std::fs::remove_dir_all(parent.join(dir));
                    let _ = std::fs::remove_file(&lock_path);
                }
            }
        } else if !names.contains(&format!("{n}.lock")) {
            // Owners create the lock before the directory and remove it
            // after: a directory without a lock is left over.
            let _ = std::fs::remove_dir_all(parent.join(n));
        }
    }
}

/// An exclusive `flock` on a directory, serialising the creation, clean-up
/// and commit of staging directories between processes.
pub(super) struct DirLock(#[allow(dead_code)] File);

impl DirLock {
    pub(super) fn acquire(dir: &Path) -> Result<Self> {
        let f =
            File::open(dir).map_err(|e| output_error(dir, format!("cannot be opened ({e})")))?;
        lock_exclusive(&f, false).map_err(|e| io_error(dir, e))?;
        Ok(DirLock(f))
    }
}

/// `flock(LOCK_EX)`, blocking or not; `Err(WouldBlock)` if `try_only` and
/// the lock is held elsewhere.
#[cfg(unix)]
pub(super) fn lock_exclusive(f: &File, try_only: bool) -> std::io::Result<()> {
    use std::os::fd::AsRawFd;
    let op = libc::LOCK_EX | if try_only { libc::LOCK_NB } else { 0 };
    loop {
        // SAFETY: flock on a file descriptor owned by `f`, which outlives the call.
        if unsafe { libc::flock(f.as_raw_fd(), op) } == 0 {
            return Ok(());
        }
        let e = std::io::Error::last_os_error();
        if e.kind() != std::io::ErrorKind::Interrupted {
            return Err(e);
        }
    }
}

#[cfg(not(unix))]
pub(super) fn lock_exclusive(_f: &File, _try_only: bool) -> std::io::Result<()> {
    Ok(())
}

/// Swaps two directories atomically (Linux `renameat2(RENAME_EXCHANGE)`).
/// Where the file system cannot, falls back to two renames; a crash between
/// them leaves the earlier set beside the target, not lost.
pub(super) fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
    #[cfg(target_os = "linux")]
    {
        use std::ffi::CString;
        use std::os::unix::ffi::OsStrExt;
        let ca = CString::new(a.as_os_str().as_bytes())?;
        let cb = CString::new(b.as_os_str().as_bytes())?;
        // SAFETY: two valid NUL-terminated paths, relative to the working directory.
        let rc = unsafe {
            libc::renameat2(
                libc::AT_FDCWD,
                ca.as_ptr(),
                libc::AT_FDCWD,
                cb.as_ptr(),
                libc::RENAME_EXCHANGE,
            )
        };
        if rc == 0 {
            return Ok(());
        }
        let e = std::io::Error::last_os_error();
        if !matches!(
            e.raw_os_error(),
            Some(libc::EINVAL) | Some(libc::ENOSYS) | Some(libc::EOPNOTSUPP)
        ) {
            return Err(e);
        }
    }
    let aside = {
        let mut s = a.as_os_str().to_owned();
        s.push(".previous");
        PathBuf::from(s)
    };
    std::fs::rename(b, &aside)?;
    if let Err(e) = std::fs::rename(a, b) {
        let _ = std::fs::rename(&aside, b);
        return Err(e);
    }
    std::fs::rename(&aside, a)
}
