//! Reading a scene: text to TOML (syntax errors with line and column),
//! TOML to [`Scene`] (shape errors with their key path), then
//! [`Scene::validate`].

use super::Scene;
use crate::error::{Error, Result};
use std::path::Path;

/// Shortens a value shown in an error message.
fn shorten(s: String) -> String {
    const MAX: usize = 80;
    let one_line = s.replace('\n', " ");
    if one_line.chars().count() <= MAX {
        one_line
    } else {
        let cut: String = one_line.chars().take(MAX).collect();
        format!("{cut}…")
    }
}

/// The value at `path` in the parsed document, for error messages.
fn lookup<'a>(root: &'a toml::Value, path: &serde_path_to_error::Path) -> Option<&'a toml::Value> {
    use serde_path_to_error::Segment;
    let mut v = root;
    for seg in path.iter() {
        v = match seg {
            Segment::Seq { index } => v.as_array()?.get(*index)?,
            Segment::Map { key } | Segment::Enum { variant: key } => v.as_table()?.get(key)?,
            Segment::Unknown => return None,
        };
    }
    Some(v)
}

/// 1-based line and column of byte `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

/// serde's words for a shape error, in the scene's terms: what was
/// expected and what was found, without Rust type names.
fn plain(message: &str) -> String {
    let message = message.trim().replace('\n', " ");
    match message.as_str() {
        "wanted exactly 1 element, found 0 elements" => {
            return "name exactly one kind (the table is empty)".into()
        }
        "wanted exactly 1 element, more than 1 element" => {
            return "name exactly one kind, not several".into()
        }
        "invalid type: unit variant, expected string only" => {
            return "expected a table with one key, the kind".into()
        }
        _ => {}
    }
    let shape = ["invalid type: ", "invalid value: "]
        .iter()
        .find_map(|p| message.strip_prefix(p))
        .and_then(|rest| rest.split_once(", expected "));
    let Some((found, expected)) = shape else {
        return message;
    };
    let expected = match expected {
        "usize" | "u64" | "u32" => "a non-negative integer",
        "f64" | "f32" => "a number",
        "a boolean" | "bool" => "true or false",
        e if e.starts_with("struct ") => "a table",
        e => e,
    };
    format!("expected {expected}, found {found}")
}

fn syntax_error(text: &str, e: toml::de::Error) -> Error {
    let mut reason = format!("not valid TOML: {}", e.message().trim().replace('\n', " "));
    let (field, value) = match e.span() {
        Some(span) => {
            let (mut line, mut col) = line_col(text, span.start);
            // an inline table cannot go on to the next line (an array
            // can), so an error found at the start of a line after one that
            // leaves a brace open belongs to that line
            let open = |l: &str| l.matches('{').count() > l.matches('}').count();
            if col == 1 && line > 1 {
                let lines: Vec<&str> = text.lines().take(line - 1).collect();
                if let Some((k, prev)) = lines
                    .iter()
                    .enumerate()
                    .rev()
                    .find(|(_, l)| !l.trim().is_empty())
                    .filter(|(_, l)| open(l))
                {
                    line = k + 1;
                    col = prev.chars().count() + 1;
                    reason.push_str(" (an inline table opened on this line is not closed on it)");
                }
            }
            let source = text.lines().nth(line - 1).unwrap_or("").trim();
            (format!("line {line}, column {col}"), shorten(source.into()))
        }
        None => ("scene".into(), "(the scene text)".into()),
    };
    Error::invalid(field, value, reason)
}

/// An error in the choice of keys of one table (`refine`, `master`),
/// raised while serde reads the table, so that the key path names it.
///
/// The path serde reports stops at the table, so the error carries the key
/// below it (empty: the table itself) and the value to show, which
/// [`Scene::from_toml_str`] puts back; the message through serde is this,
/// encoded between separators no TOML key or value in an error contains.
pub(super) struct TableError {
    key: &'static str,
    value: String,
    reason: String,
}

const SEP: char = '\u{1f}';

impl TableError {
    pub(super) fn new(
        key: &'static str,
        value: impl std::fmt::Display,
        reason: impl Into<String>,
    ) -> Self {
        Self {
            key,
            value: value.to_string(),
            reason: reason.into(),
        }
    }

    /// The key, value and reason encoded in `message`, if it is one.
    fn decode(message: &str) -> Option<(&str, &str, &str)> {
        let mut parts = message.strip_prefix(SEP)?.splitn(3, SEP);
        Some((parts.next()?, parts.next()?, parts.next()?))
    }
}

impl std::fmt::Display for TableError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(
            f,
            "{SEP}{}{SEP}{}{SEP}{}",
            self.key, self.value, self.reason
        )
    }
}

impl Scene {
    /// Parses and validates a scene. Every error names the key path and the
    /// offending value.
    pub fn from_toml_str(text: &str) -> Result<Scene> {
        let table: toml::Table = toml::from_str(text).map_err(|e| syntax_error(text, e))?;
        let root = toml::Value::Table(table);
        let scene: Scene = serde_path_to_error::deserialize(root.clone()).map_err(|e| {
            let path = e.path().clone();
            let shown = lookup(&root, &path)
                .map(|v| shorten(v.to_string()))
                .unwrap_or_else(|| "(absent)".into());
            let message = e.into_inner().message().to_string();
            let field = match path.to_string().as_str() {
                "." => "scene".to_string(),
                p => p.to_string(),
            };
            match TableError::decode(&message) {
                Some(("", value, reason)) => Error::invalid(field, value, reason),
                Some((key, value, reason)) => {
                    Error::invalid(format!("{field}.{key}"), value, reason)
                }
                None => Error::invalid(field, shown, plain(&message)),
            }
        })?;
        scene.validate()?;
        Ok(scene)
    }
    /// Reads, parses and validates a scene file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| {
            Error::invalid("scene file", path.display(), format!("cannot be read: {e}"))
        })?;
        Scene::from_toml_str(&text)
    }
}
