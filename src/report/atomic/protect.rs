//! Why an entry cannot be replaced: immutable or append-only attributes,
//! mount points, and temporaries left by older versions.

use std::fs::File;
use std::path::{Path, PathBuf};

/// The attribute names the refusals print.
pub(super) const IMMUTABLE: &str = "immutable (chattr +i)";
pub(super) const APPEND_ONLY: &str = "append-only (chattr +a)";

/// The inode attribute of `path` (a regular file or a directory, not
/// followed if a link) that forbids renaming or deleting it, if any.
#[cfg(target_os = "linux")]
pub(super) fn protected(path: &Path) -> Option<&'static str> {
    use std::os::fd::AsRawFd;
    const FS_IMMUTABLE_FL: libc::c_long = 0x10;
    const FS_APPEND_FL: libc::c_long = 0x20;
    let meta = std::fs::symlink_metadata(path).ok()?;
    if !(meta.is_file() || meta.is_dir()) {
        return None;
    }
    let f = File::open(path).ok()?;
    let mut flags: libc::c_long = 0;
    // SAFETY: FS_IOC_GETFLAGS writes at most a long into `flags`, through a
    // descriptor owned by `f`, which outlives the call.
    let rc = unsafe { libc::ioctl(f.as_raw_fd(), libc::FS_IOC_GETFLAGS, &mut flags) };
    if rc != 0 {
        // A file system without inode attributes has none to refuse with.
        return None;
    }
    if flags & FS_IMMUTABLE_FL != 0 {
        Some(IMMUTABLE)
    } else if flags & FS_APPEND_FL != 0 {
        Some(APPEND_ONLY)
    } else {
        None
    }
}

#[cfg(not(target_os = "linux"))]
pub(super) fn protected(_path: &Path) -> Option<&'static str> {
    None
}

/// The first entry below `dir` (an earlier set) that cannot be deleted:
/// one with a protecting attribute, or one inside a directory that has
/// one.
pub(super) fn protected_entry(dir: &Path) -> Option<(PathBuf, &'static str)> {
    for entry in std::fs::read_dir(dir).ok()?.flatten() {
        let path = entry.path();
        if let Some(flag) = protected(&path) {
            return Some((path, flag));
        }
        if entry.file_type().is_ok_and(|t| t.is_dir()) {
            if let Some(found) = protected_entry(&path) {
                return Some(found);
            }
        }
    }
    None
}

/// Whether `dir` is a mount point: on another device than its parent, or
/// listed in `/proc/self/mountinfo` (a bind mount of the same device).
pub(super) fn is_mount_point(dir: &Path) -> bool {
    use std::os::unix::fs::MetadataExt;
    let Ok(path) = std::fs::canonicalize(dir) else {
        return false;
    };
    let Some(parent) = path.parent() else {
        return true; // the root
    };
    match (std::fs::metadata(&path), std::fs::metadata(parent)) {
        (Ok(a), Ok(b)) if a.dev() != b.dev() => return true,
        _ => {}
    }
    let Ok(text) = std::fs::read_to_string("/proc/self/mountinfo") else {
        return false;
    };
    // Field 5 is the mount point, with space, tab, newline and backslash
    // escaped in octal.
    text.lines()
        .filter_map(|l| l.split(' ').nth(4))
        .any(|m| Path::new(&unescape_mount(m)) == path)
}

fn unescape_mount(m: &str) -> String {
    let b = m.as_bytes();
    let mut out = Vec::with_capacity(b.len());
    let mut i = 0;
    while i < b.len() {
        if b[i] == b'\\'
            && i + 3 < b.len()
            && b[i + 1..i + 4].iter().all(|c| (b'0'..=b'7').contains(c))
        {
            out.push((b[i + 1] - b'0') * 64 + (b[i + 2] - b'0') * 8 + (b[i + 3] - b'0'));
            i += 4;
        } else {
            out.push(b[i]);
            i += 1;
        }
    }
    String::from_utf8_lossy(&out).into_owned()
}

/// `.NAME.PID.tmp`: left by killed runs of versions that wrote file by file.
pub(super) fn is_legacy_temporary(name: &str) -> bool {
    name.starts_with('.')
        && name.ends_with(".tmp")
        && name
            .trim_end_matches(".tmp")
            .rsplit('.')
            .next()
            .is_some_and(|pid| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()))
}
