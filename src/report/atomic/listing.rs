//! The files of a committed set: its manifest, a snapshot of its contents,
//! staging directories beside a target, and checked relative names.

use crate::error::{Error, Result};
use std::path::{Component, Path, PathBuf};

/// The manifest file inside a committed output directory.
pub const MANIFEST: &str = ".outputs.toml";

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
pub(super) fn checked_name(name: &str) -> Result<PathBuf> {
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
pub(super) fn list_files(dir: &Path) -> std::io::Result<Vec<(String, u64)>> {
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
