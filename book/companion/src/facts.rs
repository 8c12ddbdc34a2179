//! Facts: the numbers a chapter's prose quotes, written by the chapter's
//! program next to its tables, so that the prose never types a result.
//!
//! A facts file holds one anchored block per fact, in the form mdBook's
//! `{{#include file:anchor}}` understands:
//!
//! ```text
//! ANCHOR: p0_8x8
//! 2.3536
//! ANCHOR_END: p0_8x8
//! ```
//!
//! so a chapter writes `{{#include generated/hertz/facts.txt:p0_8x8}}`
//! where the number goes. The book's tests check that every such include
//! names an existing fact, and the chapters' doc-tests read the same file
//! ([`Facts::load`]) to assert the claims the prose makes about the numbers.

use iga_contact::report::table::Format;
use iga_contact::{Error, Result};
use std::collections::BTreeMap;
use std::path::Path;

/// The name of the facts file in a chapter's generated folder.
pub const FILE: &str = "facts.txt";

/// The facts of one chapter, by key.
#[derive(Clone, Debug, Default)]
pub struct Facts {
    entries: BTreeMap<String, String>,
    /// Keys whose values are wall-clock times or ratios of them, which
    /// change from run to run.
    timed: std::collections::BTreeSet<String>,
}

fn valid_key(key: &str) -> bool {
    !key.is_empty()
        && key
            .chars()
            .all(|c| c.is_ascii_alphanumeric() || c == '_' || c == '-')
}

/// Facts are equal when their keys and texts are (which of them are timed
/// is not part of the file).
impl PartialEq for Facts {
    fn eq(&self, other: &Self) -> bool {
        self.entries == other.entries
    }
}

impl Facts {
    pub fn new() -> Self {
        Self::default()
    }

    /// Records `text` under `key` (letters, digits, `_` and `-`).
    pub fn text(&mut self, key: &str, text: impl Into<String>) -> Result<()> {
        let text = text.into();
        if !valid_key(key) {
            return Err(Error::invalid(
                "fact key",
                key,
                "use letters, digits, _ or -",
            ));
        }
        if text.contains('\n') || text.contains("ANCHOR") {
            return Err(Error::invalid(
                format!("fact {key}"),
                &text,
                "a fact is one line without the word ANCHOR",
            ));
        }
        self.entries.insert(key.to_string(), text);
        Ok(())
    }

    /// Records the number `value` written in `format`.
    pub fn number(&mut self, key: &str, value: f64, format: Format) -> Result<()> {
        if !value.is_finite() {
            return Err(Error::invalid(
                format!("fact {key}"),
                value,
                "must be finite",
            ));
        }
        self.text(key, format.render(value))
    }

    /// Records the relative errors of a peak pressure and a half-width,
    /// `measured = [p₀, a]` against `truth = [p₀, a]`, as the facts
    /// `{prefix}_p0_vs_{against}` and `{prefix}_a_vs_{against}`: the one
    /// naming of these errors across the chapters.
    pub fn contact_errors(
        &mut self,
        prefix: &str,
        measured: [f64; 2],
        against: &str,
        truth: [f64; 2],
        format: Format,
    ) -> Result<()> {
        for (name, (m, t)) in ["p0", "a"].iter().zip(measured.into_iter().zip(truth)) {
            let key = format!("{prefix}_{name}_vs_{against}");
            self.number(&key, iga_contact::post::relative(m, t), format)?;
        }
        Ok(())
    }

    /// Records a number derived from wall-clock times (a time, or a ratio of
    /// times measured in one run): it changes from run to run, so checks of
    /// the book against a fresh run leave it out.
    pub fn timed_number(&mut self, key: &str, value: f64, format: Format) -> Result<()> {
        self.number(key, value, format)?;
        self.timed.insert(key.to_string());
        Ok(())
    }

    /// Records a text that changes from run to run (a date, the machine's
    /// load), left out of checks against a fresh run like a timed number.
    pub fn timed_text(&mut self, key: &str, text: impl Into<String>) -> Result<()> {
        self.text(key, text)?;
        self.timed.insert(key.to_string());
        Ok(())
    }

    /// The keys recorded by [`Facts::timed_number`] and [`Facts::timed_text`].
    pub fn timed_keys(&self) -> impl Iterator<Item = &str> {
        self.timed.iter().map(String::as_str)
    }

    /// Records an integer.
    pub fn count(&mut self, key: &str, n: usize) -> Result<()> {
        self.text(key, n.to_string())
    }

    /// The text of `key`.
    pub fn get(&self, key: &str) -> Option<&str> {
        self.entries.get(key).map(String::as_str)
    }

    /// The number written under `key`, read back from its text: typographic
    /// minus, a trailing `%` (divided by 100), `×`, `²` and powers of ten
    /// (`3.0×10⁻³`) are understood.
    pub fn value(&self, key: &str) -> Option<f64> {
        let mut t = self.get(key)?.replace('−', "-");
        if let Some((m, e)) = t.split_once("×10") {
            let e: String = e
                .chars()
                .map(|c| match "⁰¹²³⁴⁵⁶⁷⁸⁹".chars().position(|s| s == c) {
                    Some(d) => char::from(b'0' + d as u8),
                    None if c == '⁻' => '-',
                    None => c,
                })
                .collect();
            t = format!("{m}e{e}");
        }
        let t = t.trim();
        if let Some(p) = t.strip_suffix('%') {
            return p.trim().parse::<f64>().ok().map(|v| v / 100.0);
        }
        t.trim_end_matches(['×', '²']).trim().parse().ok()
    }

    /// Every key.
    pub fn keys(&self) -> impl Iterator<Item = &str> {
        self.entries.keys().map(String::as_str)
    }

    /// The anchored file text.
    pub fn to_text(&self) -> String {
        let mut s = String::new();
        for (k, v) in &self.entries {
            s.push_str(&format!("ANCHOR: {k}\n{v}\nANCHOR_END: {k}\n"));
        }
        s
    }

    /// Reads the anchored text back.
    pub fn parse(text: &str) -> Result<Self> {
        let mut facts = Self::new();
        let mut lines = text.lines();
        while let Some(line) = lines.next() {
            let bad = |why: &str| Error::invalid("facts file", line, why.to_string());
            let key = line
                .strip_prefix("ANCHOR: ")
                .ok_or_else(|| bad("expected `ANCHOR: key`"))?;
            let value = lines
                .next()
                .ok_or_else(|| bad("no value after the anchor"))?;
            if lines.next() != Some(&format!("ANCHOR_END: {key}")) {
                return Err(bad("no matching ANCHOR_END"));
            }
            facts.text(key, value)?;
        }
        Ok(facts)
    }

    /// Reads `<dir>/facts.txt`.
    pub fn load(dir: impl AsRef<Path>) -> Result<Self> {
        let path = dir.as_ref().join(FILE);
        let text = std::fs::read_to_string(&path).map_err(|source| Error::Io {
            path: path.display().to_string(),
            source,
        })?;
        Self::parse(&text)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn facts_round_trip_and_read_back_numbers() {
        let mut f = Facts::new();
        f.number("p0_error", -0.0137, Format::SignedPercent(2))
            .unwrap();
        f.number("ratio", 3.125, Format::Times(1)).unwrap();
        f.count("iterations", 11).unwrap();
        f.text("mesh", "8×8").unwrap();
        f.number("small", -2.95e-3, Format::Pow10(2)).unwrap();
        let back = Facts::parse(&f.to_text()).unwrap();
        assert_eq!(back, f);
        assert_eq!(back.get("p0_error"), Some("−1.37 %"));
        assert_eq!(back.value("p0_error"), Some(-0.0137));
        assert_eq!(back.value("ratio"), Some(3.1));
        assert_eq!(back.value("iterations"), Some(11.0));
        assert_eq!(back.value("small"), Some(-2.95e-3));
        assert!(f.text("bad key", "x").is_err());
        assert!(f.text("k", "two\nlines").is_err());
        assert!(f.number("k", f64::NAN, Format::Plain).is_err());
        assert!(Facts::parse("ANCHOR: a\n1\nANCHOR_END: b\n").is_err());
    }
}
