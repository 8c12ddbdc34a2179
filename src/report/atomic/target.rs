//! What the target of an output set is, and whether a commit may replace
//! it: followed links, a parent to create, an earlier set, foreign content.

use super::errors::output_error;
use super::listing::read_manifest;
use super::listing::MANIFEST;
use super::protect::IMMUTABLE;
use super::protect::{is_legacy_temporary, is_mount_point, protected, protected_entry};
use crate::error::Result;
use std::path::{Path, PathBuf};

/// The target with a symbolic link at its end followed, so that the link's
/// destination, not the link, is replaced.
pub(super) fn resolve(target: &Path) -> Result<PathBuf> {
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
pub(super) fn create_parent(parent: &Path, target: &Path) -> Result<Option<PathBuf>> {
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
pub(super) fn target_state(target: &Path, known: Option<&[String]>) -> Result<TargetState> {
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

/// What the target holds before a commit.
pub(super) enum TargetState {
    Absent,
    /// An existing directory this set may replace.
    Replaceable,
}
