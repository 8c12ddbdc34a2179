//! The output set: staged beside its target, committed by one exchange,
//! dropped on failure; and the registry of this process's staging
//! directories that the signal handler clears.

use super::errors::{io_error, output_error};
use super::fsops::{exchange, lock_exclusive, remove_stale, sync_tree, DirLock};
use super::listing::MANIFEST;
use super::listing::{checked_name, list_files};
use super::target::{create_parent, resolve, target_state, TargetState};
use crate::error::Result;
use std::fs::File;
use std::io::Write;
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Staging directories of this process that are not committed yet, for the
/// signal handler. Staging writes and commits hold the lock, so a signal
/// waits for them and never sees a half-swapped target.
static ACTIVE: Mutex<Vec<(PathBuf, PathBuf)>> = Mutex::new(Vec::new());

pub(super) fn active() -> std::sync::MutexGuard<'static, Vec<(PathBuf, PathBuf)>> {
    ACTIVE.lock().unwrap_or_else(|e| e.into_inner())
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
                    "cannot be prepared: no file can be created in its parent `{}` ({e}), and \
                     outputs are staged beside the target",
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
        // A write into the staging holds the registry, as `stage_with`
        // does: a signal arriving now waits, and then removes the whole
        // staging instead of racing a file being created in it.
        let registry = active();
        let synced = (|| {
            let mut f = File::create(&mpath)?;
            f.write_all(manifest.as_bytes())?;
            f.sync_all()?;
            sync_tree(&self.staging)
        })();
        drop(registry);
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
pub(super) fn discard(staging: &Path, lock_path: &Path) {
    for _ in 0..3 {
        match std::fs::remove_dir_all(staging) {
            Err(e) if e.kind() != std::io::ErrorKind::NotFound => continue,
            _ => break,
        }
    }
    let _ = std::fs::remove_file(lock_path);
}
