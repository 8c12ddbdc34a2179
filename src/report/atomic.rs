//! Output as one transaction: a run's files appear together or not at all.
//!
//! [`OutputSet`] stages every file of a run in a fresh directory beside the
//! target (`.NAME.staging-ID` next to `NAME`), then [`OutputSet::commit`]
//! swaps the staged directory and the target in one atomic step
//! (`renameat2(RENAME_EXCHANGE)` on Linux) and deletes the earlier set. At
//! every instant the target holds either the complete earlier set of files
//! or the complete new one:
//!
//! - a failure while staging (full disk, a producer's error) drops the
//!   staging directory; the target is untouched;
//! - SIGINT and SIGTERM, once [`install_signal_cleanup`] is called, remove
//!   the staging directories of the process and exit (130 / 143) — a commit
//!   in progress is finished first;
//! - a SIGKILL leaves a staging directory whose owner is dead; the next
//!   [`OutputSet::begin`] on the same target removes it (each staging
//!   directory is owned through a `flock` on a lock file beside it, which
//!   the kernel releases when its process dies);
//! - concurrent runs into one target each stage privately and commit by an
//!   exchange, so the target ends up holding one of the complete sets.
//!
//! A committed directory holds a manifest, [`MANIFEST`], listing its files.
//! Since a commit replaces the whole directory, an output set only takes
//! over a directory that is absent, empty, holds a manifest (an earlier
//! output set), or holds nothing but regular files whose names the set
//! declares (an earlier run of a version without manifests). Anything else
//! is refused before any work is done, naming the path and the reason.
//!
//! ```
//! use iga_contact::report::atomic::OutputSet;
//! let dir = std::env::temp_dir().join(format!("atomic-doc-{}", std::process::id()));
//! let mut set = OutputSet::begin(&dir)?;
//! set.stage("a.csv", b"x,y\n1,2\n")?;
//! set.stage("figures/b.svg", b"<svg/>")?;
//! let files = set.commit()?;
//! assert_eq!(files.len(), 2);
//! assert_eq!(std::fs::read(dir.join("a.csv")).unwrap(), b"x,y\n1,2\n");
//! # std::fs::remove_dir_all(&dir).unwrap();
//! # Ok::<(), iga_contact::Error>(())
//! ```
//!
//! [`write_atomic`] remains for single files (rename of a temporary sibling).

use crate::error::{Error, Result};
use std::fs::File;
use std::io::Write;
use std::path::{Component, Path, PathBuf};
use std::sync::Mutex;

/// The manifest file inside a committed output directory.
pub const MANIFEST: &str = ".outputs.toml";

/// Staging directories of this process that are not committed yet, for the
/// signal handler. Staging writes and commits hold the lock, so a signal
/// waits for them and never sees a half-swapped target.
static ACTIVE: Mutex<Vec<(PathBuf, PathBuf)>> = Mutex::new(Vec::new());

fn active() -> std::sync::MutexGuard<'static, Vec<(PathBuf, PathBuf)>> {
    ACTIVE.lock().unwrap_or_else(|e| e.into_inner())
}

fn io_error(path: &Path, source: std::io::Error) -> Error {
    Error::Io {
        path: path.display().to_string(),
        source,
    }
}

fn output_error(path: &Path, reason: impl Into<String>) -> Error {
    Error::Output {
        path: path.display().to_string(),
        reason: reason.into(),
    }
}

/// An output set being staged for one target directory. Dropping it
/// without [`OutputSet::commit`] discards everything staged.
pub struct OutputSet {
    target: PathBuf,
    parent: PathBuf,
    staging: PathBuf,
    lock_path: PathBuf,
    /// Held (flock) while the set lives: marks the staging directory as owned.
    _lock: File,
    /// File names an earlier manifest-less directory may hold.
    known: Vec<String>,
    /// The topmost ancestor directory `begin` created, removed again (when
    /// empty) if the set is discarded.
    created: Option<PathBuf>,
    committed: bool,
}

/// What the target holds before a commit.
enum TargetState {
    Absent,
    /// An existing directory this set may replace.
    Replaceable,
}

impl OutputSet {
    /// Starts an output set for the directory `target`: checks at once that
    /// it can be created and replaced (so problems show before any
    /// computation), removes staging left by killed runs, and creates the
    /// staging directory.
    pub fn begin(target: impl AsRef<Path>) -> Result<Self> {
        Self::begin_expecting(target, &[])
    }

    /// As [`OutputSet::begin`], declaring the file names the set will hold:
    /// an existing directory without a manifest is then taken over if it
    /// holds only these files.
    pub fn begin_expecting(target: impl AsRef<Path>, names: &[&str]) -> Result<Self> {
        let given = target.as_ref();
        let target = resolve(given)?;
        let name = target
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .ok_or_else(|| output_error(given, "names no directory (use a path like `out/run`)"))?;
        let parent = match target.parent() {
            Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let created = create_parent(&parent, &target)?;
        let known: Vec<String> = names.iter().map(|s| s.to_string()).collect();
        // Fail fast: a file in the way, or foreign content (judged by the
        // declared names now, by the staged ones again at the commit).
        let declared = (!known.is_empty()).then_some(known.as_slice());
        target_state(&target, declared)?;
        let _guard = DirLock::acquire(&parent)?;
        remove_stale(&parent, &name, &target);
        static SERIAL: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
        let id = format!(
            "{}-{}-{}",
            std::process::id(),
            std::time::SystemTime::now()
                .duration_since(std::time::UNIX_EPOCH)
                .map_or(0, |d| d.as_nanos()),
            SERIAL.fetch_add(1, std::sync::atomic::Ordering::Relaxed)
        );
        let staging = parent.join(format!(".{name}.staging-{id}"));
        let lock_path = parent.join(format!(".{name}.staging-{id}.lock"));
        let mut registry = active();
        let unwritable = |e: std::io::Error| {
            output_error(
                &target,
                format!(
                    "cannot be prepared: its parent `{}` is not writable ({e}), and outputs are \
                     staged beside the target",
                    parent.display()
                ),
            )
        };
        let lock = File::create(&lock_path).map_err(unwritable)?;
        lock_exclusive(&lock, false).map_err(|e| io_error(&lock_path, e))?;
        if let Err(e) = std::fs::create_dir(&staging) {
            let _ = std::fs::remove_file(&lock_path);
            return Err(unwritable(e));
        }
        registry.push((staging.clone(), lock_path.clone()));
        drop(registry);
        Ok(Self {
            target,
            parent,
            staging,
            lock_path,
            _lock: lock,
            known,
            created,
            committed: false,
        })
    }

    /// The directory the outputs go to once committed.
    pub fn target(&self) -> &Path {
        &self.target
    }

    /// The staging directory, for producers that write files themselves
    /// (figures rendered to a path, a chapter's study). Everything in it
    /// at [`OutputSet::commit`] becomes part of the set.
    pub fn dir(&self) -> &Path {
        &self.staging
    }

    /// Stages the file `name` (relative, `/`-separated subdirectories
    /// allowed) with the given bytes.
    pub fn stage(&mut self, name: &str, bytes: &[u8]) -> Result<PathBuf> {
        self.stage_with(name, |w| w.write_all(bytes))
    }

    /// Stages the file `name`, written by `write` through a buffered
    /// writer, so a large output never has to exist in memory as a whole.
    /// An error from `write` (or from the disk) fails the stage, and the
    /// whole set is then discarded on drop.
    pub fn stage_with(
        &mut self,
        name: &str,
        write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
    ) -> Result<PathBuf> {
        let rel = checked_name(name)?;
        let path = self.staging.join(&rel);
        let _registry = active();
        let result = (|| {
            if let Some(dir) = path.parent() {
                std::fs::create_dir_all(dir)?;
            }
            let mut w = std::io::BufWriter::with_capacity(1 << 16, File::create(&path)?);
            write(&mut w)?;
            w.into_inner().map_err(|e| e.into_error())?.sync_all()
        })();
        result.map_err(|e| io_error(&self.target.join(&rel), e))?;
        Ok(self.target.join(rel))
    }

    /// Commits the staged files as a whole: writes the manifest, flushes
    /// everything to disk, swaps the staging directory in for the target
    /// and deletes the earlier set. Returns the committed files (manifest
    /// excluded), sorted. On error the target is as it was.
    pub fn commit(mut self) -> Result<Vec<PathBuf>> {
        let files = list_files(&self.staging).map_err(|e| io_error(&self.staging, e))?;
        let mut manifest = String::from(
            "# Written by iga-contact: the files of this directory, committed together.\n",
        );
        for (rel, bytes) in &files {
            manifest.push_str(&format!(
                "\n[[file]]\nname = {}\nbytes = {bytes}\n",
                toml::Value::String(rel.clone())
            ));
        }
        let mpath = self.staging.join(MANIFEST);
        let synced = (|| {
            let mut f = File::create(&mpath)?;
            f.write_all(manifest.as_bytes())?;
            f.sync_all()?;
            sync_tree(&self.staging)
        })();
        synced.map_err(|e| io_error(&self.staging, e))?;
        let mut known = self.known.clone();
        known.extend(files.iter().map(|(n, _)| n.clone()));
        // Lock order, everywhere: the directory lock, then the registry
        // (which keeps the signal handler out until the swap is done).
        let guard = DirLock::acquire(&self.parent)?;
        let mut registry = active();
        match target_state(&self.target, Some(&known))? {
            TargetState::Absent => std::fs::rename(&self.staging, &self.target),
            TargetState::Replaceable => exchange(&self.staging, &self.target),
        }
        .map_err(|e| io_error(&self.target, e))?;
        self.committed = true;
        // The swap is durable once the parent directory is.
        if let Ok(d) = File::open(&self.parent) {
            let _ = d.sync_all();
        }
        drop(guard);
        // The staging path now holds the earlier set (or nothing).
        discard(&self.staging, &self.lock_path);
        registry.retain(|(s, _)| s != &self.staging);
        Ok(files
            .into_iter()
            .map(|(rel, _)| self.target.join(rel))
            .collect())
    }

    /// Discards everything staged (the same as dropping the set).
    pub fn abort(self) {}
}

impl Drop for OutputSet {
    fn drop(&mut self) {
        if !self.committed {
            let mut registry = active();
            discard(&self.staging, &self.lock_path);
            registry.retain(|(s, _)| s != &self.staging);
            if let Some(top) = &self.created {
                // Directories created for nothing go again, innermost first;
                // `remove_dir` stops at one that is not empty.
                let mut dir = self.parent.clone();
                while dir.starts_with(top) && std::fs::remove_dir(&dir).is_ok() {
                    if !dir.pop() {
                        break;
                    }
                }
            }
        }
    }
}

/// Removes a staging directory and then its lock file.
fn discard(staging: &Path, lock_path: &Path) {
    for _ in 0..3 {
        match std::fs::remove_dir_all(staging) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => continue,
            _ => break,
        }
    }
    let _ = std::fs::remove_file(lock_path);
}

/// The target with a symbolic link at its end followed, so that the link's
/// destination, not the link, is replaced.
fn resolve(target: &Path) -> Result<PathBuf> {
    match std::fs::symlink_metadata(target) {
        Ok(m) if m.file_type().is_symlink() => std::fs::canonicalize(target).map_err(|e| {
            output_error(
                target,
                format!("is a symbolic link that cannot be followed ({e})"),
            )
        }),
        _ => Ok(target.to_path_buf()),
    }
}

/// Creates the parent directory, explaining a file in the way. Returns the
/// topmost directory it created, if any.
fn create_parent(parent: &Path, target: &Path) -> Result<Option<PathBuf>> {
    let mut top = None;
    let mut p = parent.to_path_buf();
    while !p.as_os_str().is_empty() && std::fs::symlink_metadata(&p).is_err() {
        top = Some(p.clone());
        if !p.pop() {
            break;
        }
    }
    if let Err(e) = std::fs::create_dir_all(parent) {
        // Find the first component that exists and is not a directory.
        let mut p = PathBuf::new();
        for c in parent.components() {
            p.push(c);
            if let Ok(m) = std::fs::metadata(&p) {
                if !m.is_dir() {
                    return Err(output_error(
                        target,
                        format!(
                            "cannot be created: `{}` is an existing file, not a directory",
                            p.display()
                        ),
                    ));
                }
            }
        }
        return Err(output_error(target, format!("cannot be created ({e})")));
    }
    Ok(top)
}

/// Checks what the target is, and that this set may replace it. `known`:
/// the names a directory without a manifest may hold (`None`: any regular
/// files, to be judged again when the names are known).
fn target_state(target: &Path, known: Option<&[String]>) -> Result<TargetState> {
    let meta = match std::fs::symlink_metadata(target) {
        Ok(m) => m,
        Err(e) if e.kind() == std::io::ErrorKind::NotFound => return Ok(TargetState::Absent),
        Err(e) => return Err(output_error(target, format!("cannot be inspected ({e})"))),
    };
    if !meta.is_dir() {
        return Err(output_error(
            target,
            "is an existing file, not a directory: choose another output directory or remove the file",
        ));
    }
    let manifest = read_manifest(target);
    let entries = std::fs::read_dir(target)
        .map_err(|e| output_error(target, format!("cannot be read ({e})")))?;
    for entry in entries {
        let entry = entry.map_err(|e| output_error(target, format!("cannot be read ({e})")))?;
        let name = entry.file_name().to_string_lossy().into_owned();
        if name == MANIFEST {
            continue;
        }
        let ours = match &manifest {
            // Files of the earlier set may sit in subdirectories: a
            // directory is ours if the manifest lists a file below it.
            Some(files) => files
                .iter()
                .any(|f| f == &name || f.starts_with(&format!("{name}/"))),
            None => {
                let is_file = entry.file_type().is_ok_and(|t| t.is_file());
                is_file && known.is_none_or(|k| k.contains(&name) || is_legacy_temporary(&name))
            }
        };
        if !ours {
            let what = if entry.file_type().is_ok_and(|t| t.is_dir()) {
                "directory"
            } else {
                "file"
            };
            return Err(output_error(
                target,
                format!(
                    "holds the {what} `{name}`, which iga-contact did not write; a run replaces \
                     the whole directory, so choose a new or empty directory or move it away"
                ),
            ));
        }
    }
    replaceable(target)?;
    Ok(TargetState::Replaceable)
}

/// Checks that the commit can do what it will do to an existing target:
/// swap it with the staging directory by a rename (which a mount point or
/// an immutable directory refuses), then delete the earlier set (which an
/// immutable or append-only entry in it refuses). Asked at the start, so
/// that a run never computes outputs it cannot commit.
fn replaceable(target: &Path) -> Result<()> {
    if is_mount_point(target) {
        return Err(output_error(
            target,
            format!(
                "is a mount point: a run replaces its output directory as a whole by a rename,                  which cannot move a mount point; give a directory inside it, such as `{}`",
                target.join("run").display()
            ),
        ));
    }
    if let Some(flag) = protected(target) {
        return Err(output_error(
            target,
            format!(
                "has the {flag} attribute, so it cannot be replaced by a rename; remove the                  attribute (`chattr -{} {}`) or choose another output directory",
                flag_letter(flag),
                target.display()
            ),
        ));
    }
    if let Some((path, flag)) = protected_entry(target) {
        return Err(output_error(
            target,
            format!(
                "holds `{}` with the {flag} attribute, which replacing the earlier outputs would                  have to delete; remove the attribute (`chattr -{} {}`) or choose another output                  directory",
                path.strip_prefix(target).unwrap_or(&path).display(),
                flag_letter(flag),
                path.display()
            ),
        ));
    }
    Ok(())
}

fn flag_letter(flag: &str) -> char {
    if flag == IMMUTABLE {
        'i'
    } else {
        'a'
    }
}

const IMMUTABLE: &str = "immutable (chattr +i)";
const APPEND_ONLY: &str = "append-only (chattr +a)";

/// The inode attribute of `path` (a regular file or a directory, not
/// followed if a link) that forbids renaming or deleting it, if any.
#[cfg(target_os = "linux")]
fn protected(path: &Path) -> Option<&'static str> {
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
fn protected(_path: &Path) -> Option<&'static str> {
    None
}

/// The first entry below `dir` (an earlier set) that cannot be deleted:
/// one with a protecting attribute, or one inside a directory that has
/// one.
fn protected_entry(dir: &Path) -> Option<(PathBuf, &'static str)> {
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
fn is_mount_point(dir: &Path) -> bool {
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
fn is_legacy_temporary(name: &str) -> bool {
    name.starts_with('.')
        && name.ends_with(".tmp")
        && name
            .trim_end_matches(".tmp")
            .rsplit('.')
            .next()
            .is_some_and(|pid| !pid.is_empty() && pid.bytes().all(|b| b.is_ascii_digit()))
}

/// The file names listed in the manifest of `dir`, if it has one.
pub fn read_manifest(dir: &Path) -> Option<Vec<String>> {
    #[derive(serde::Deserialize)]
    struct Entry {
        name: String,
    }
    #[derive(serde::Deserialize)]
    struct Manifest {
        #[serde(default)]
        file: Vec<Entry>,
    }
    let text = std::fs::read_to_string(dir.join(MANIFEST)).ok()?;
    let m: Manifest = toml::from_str(&text).ok()?;
    Some(m.file.into_iter().map(|e| e.name).collect())
}

/// Every file below `dir` (relative, `/`-separated, the manifest included)
/// with its bytes: what a reader of the directory sees, for comparing two
/// states of an output directory byte for byte.
pub fn snapshot(dir: &Path) -> std::io::Result<std::collections::BTreeMap<String, Vec<u8>>> {
    let mut out = std::collections::BTreeMap::new();
    if !dir.exists() {
        return Ok(out);
    }
    for (rel, _) in list_files(dir)? {
        let bytes = std::fs::read(dir.join(&rel))?;
        out.insert(rel, bytes);
    }
    if let Ok(m) = std::fs::read(dir.join(MANIFEST)) {
        out.insert(MANIFEST.to_string(), m);
    }
    Ok(out)
}

/// Staging directories and lock files beside `target` (of living or dead
/// output sets): empty once every set has ended and a later one cleaned up.
pub fn staging_entries(target: &Path) -> Vec<PathBuf> {
    let Some(name) = target.file_name().map(|n| n.to_string_lossy().into_owned()) else {
        return Vec::new();
    };
    let parent = match target.parent() {
        Some(p) if !p.as_os_str().is_empty() => p.to_path_buf(),
        _ => PathBuf::from("."),
    };
    let prefix = format!(".{name}.staging-");
    let mut out: Vec<PathBuf> = std::fs::read_dir(&parent)
        .map(|rd| {
            rd.flatten()
                .filter(|e| e.file_name().to_string_lossy().starts_with(&prefix))
                .map(|e| e.path())
                .collect()
        })
        .unwrap_or_default();
    out.sort();
    out
}

/// A relative path with plain components only.
fn checked_name(name: &str) -> Result<PathBuf> {
    let p = Path::new(name);
    let plain = !name.is_empty() && p.components().all(|c| matches!(c, Component::Normal(_)));
    if !plain || name == MANIFEST {
        return Err(Error::invalid(
            "output file name",
            format!("{name:?}"),
            "must be a relative path of plain names (no `..`, no root), other than the manifest",
        ));
    }
    Ok(p.to_path_buf())
}

/// Regular files below `dir` (relative, `/`-separated) with their sizes, sorted.
fn list_files(dir: &Path) -> std::io::Result<Vec<(String, u64)>> {
    fn walk(base: &Path, dir: &Path, out: &mut Vec<(String, u64)>) -> std::io::Result<()> {
        for entry in std::fs::read_dir(dir)? {
            let entry = entry?;
            let t = entry.file_type()?;
            let path = entry.path();
            if t.is_dir() {
                walk(base, &path, out)?;
            } else {
                let rel = path.strip_prefix(base).expect("below base");
                let rel: Vec<String> = rel
                    .components()
                    .map(|c| c.as_os_str().to_string_lossy().into_owned())
                    .collect();
                let rel = rel.join("/");
                if rel != MANIFEST {
                    out.push((rel, entry.metadata()?.len()));
                }
            }
        }
        Ok(())
    }
    let mut out = Vec::new();
    walk(dir, dir, &mut out)?;
    out.sort();
    Ok(out)
}

/// fsync every file and directory below `dir`, and `dir` itself.
fn sync_tree(dir: &Path) -> std::io::Result<()> {
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
fn remove_stale(parent: &Path, name: &str, target: &Path) {
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
struct DirLock(#[allow(dead_code)] File);

impl DirLock {
    fn acquire(dir: &Path) -> Result<Self> {
        let f =
            File::open(dir).map_err(|e| output_error(dir, format!("cannot be opened ({e})")))?;
        lock_exclusive(&f, false).map_err(|e| io_error(dir, e))?;
        Ok(DirLock(f))
    }
}

/// `flock(LOCK_EX)`, blocking or not; `Err(WouldBlock)` if `try_only` and
/// the lock is held elsewhere.
#[cfg(unix)]
fn lock_exclusive(f: &File, try_only: bool) -> std::io::Result<()> {
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
fn lock_exclusive(_f: &File, _try_only: bool) -> std::io::Result<()> {
    Ok(())
}

/// Swaps two directories atomically (Linux `renameat2(RENAME_EXCHANGE)`).
/// Where the file system cannot, falls back to two renames; a crash between
/// them leaves the earlier set beside the target, not lost.
fn exchange(a: &Path, b: &Path) -> std::io::Result<()> {
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

/// Installs handlers so that SIGINT and SIGTERM remove this process's
/// staging directories (after any commit in progress) and exit with
/// 128 + the signal number, printing one `error:` line. Call it once, at
/// the start of a program that writes output sets.
///
/// The work a clean exit needs (deleting directories) is not allowed in a
/// signal handler, so the `signal-hook` crate forwards the signals to a
/// thread that does it.
#[cfg(unix)]
pub fn install_signal_cleanup() -> Result<()> {
    use signal_hook::consts::{SIGINT, SIGTERM};
    let mut signals =
        signal_hook::iterator::Signals::new([SIGINT, SIGTERM]).map_err(|e| Error::Io {
            path: "signal handlers".into(),
            source: e,
        })?;
    std::thread::Builder::new()
        .name("output-cleanup".into())
        .spawn(move || {
            if let Some(sig) = signals.forever().next() {
                let registry = active();
                for (staging, lock) in registry.iter() {
                    discard(staging, lock);
                }
                let name = if sig == SIGINT { "SIGINT" } else { "SIGTERM" };
                eprintln!("error: interrupted by {name}; no output was written");
                std::process::exit(128 + sig);
            }
        })
        .map_err(|e| Error::Io {
            path: "signal handler thread".into(),
            source: e,
        })?;
    Ok(())
}

#[cfg(not(unix))]
pub fn install_signal_cleanup() -> Result<()> {
    Ok(())
}

/// Writes `bytes` to `path` atomically, creating parent directories: a
/// temporary sibling is written and renamed over `path`, so a reader (or a
/// crash) never sees half a file. For a set of files that belong together
/// use [`OutputSet`].
pub fn write_atomic(path: impl AsRef<Path>, bytes: &[u8]) -> Result<()> {
    let path = path.as_ref();
    let io = |source| Error::Io {
        path: path.display().to_string(),
        source,
    };
    if let Some(dir) = path.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(io)?;
    }
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    let tmp = path.with_file_name(format!(".{name}.{}.tmp", std::process::id()));
    let result = (|| {
        let mut f = std::fs::File::create(&tmp)?;
        f.write_all(bytes)?;
        f.sync_all()?;
        std::fs::rename(&tmp, path)
    })();
    if result.is_err() {
        let _ = std::fs::remove_file(&tmp);
    }
    result.map_err(io)
}

/// Text convenience wrapper around [`write_atomic`].
pub fn write_text(path: impl AsRef<Path>, text: &str) -> Result<()> {
    write_atomic(path, text.as_bytes())
}
