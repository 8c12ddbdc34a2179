//! The book against the code: every include of every chapter resolves, and
//! every chapter program, run afresh, writes exactly the files the book
//! embeds (except those that hold wall-clock times). So a number the prose
//! quotes can change neither in the prose (it is included, not typed) nor
//! in the data (the data must equal a fresh run) without a test failing.

mod common;

use common::example;
use iga_contact::report::atomic;
use iga_contact::report::chapter::{generated_root, Cost, Manifest, PROGRAMS};
use iga_contact::report::facts::{self, Facts};
use std::path::{Path, PathBuf};

fn book_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("book/src")
}

/// Every `{{#include path[:anchor]}}` in the chapters (escaped ones aside).
fn includes() -> Vec<(String, String, Option<String>)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(book_src()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        let chapter = path.file_name().unwrap().to_string_lossy().into_owned();
        let mut rest = text.as_str();
        while let Some(k) = rest.find("{{#include ") {
            let escaped = k > 0 && rest.as_bytes()[k - 1] == b'\\';
            let after = &rest[k + "{{#include ".len()..];
            let end = after.find("}}").expect("an include ends with }}");
            let target = after[..end].trim();
            if !escaped {
                let (file, anchor) = match target.split_once(':') {
                    Some((f, a)) => (f.to_string(), Some(a.to_string())),
                    None => (target.to_string(), None),
                };
                out.push((chapter.clone(), file, anchor));
            }
            rest = &after[end..];
        }
    }
    out
}

#[test]
fn every_include_names_an_existing_file_and_anchor() {
    let all = includes();
    assert!(all.len() > 100, "only {} includes found", all.len());
    for (chapter, file, anchor) in all {
        let path = book_src().join(&file);
        let text =
            std::fs::read_to_string(&path).unwrap_or_else(|e| panic!("{chapter}: {file}: {e}"));
        let Some(anchor) = anchor else { continue };
        if anchor.chars().next().is_some_and(|c| c.is_ascii_digit()) {
            continue; // a line range
        }
        if file.ends_with(facts::FILE) {
            let f = Facts::parse(&text).unwrap();
            assert!(
                f.get(&anchor).is_some(),
                "{chapter}: no fact `{anchor}` in {file}"
            );
        } else {
            let begin = format!("ANCHOR: {anchor}");
            let end = format!("ANCHOR_END: {anchor}");
            assert!(
                text.lines().any(|l| l.trim_end().ends_with(&begin))
                    && text.lines().any(|l| l.trim_end().ends_with(&end)),
                "{chapter}: no anchor `{anchor}` in {file}"
            );
        }
    }
}

/// The files of a generated folder, sorted.
fn listing(dir: &Path) -> Vec<String> {
    let mut v: Vec<String> = std::fs::read_dir(dir)
        .unwrap_or_else(|e| panic!("{}: {e}", dir.display()))
        .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
        .collect();
    v.sort();
    v
}

/// Runs chapter program `example` into a fresh folder and compares what it
/// writes with the committed `book/src/generated/<chapter>/`.
fn regenerates_identically(example_name: &str, chapter: &str) {
    let fresh = Path::new(env!("CARGO_TARGET_TMPDIR"))
        .join("book-check")
        .join(chapter);
    let _ = std::fs::remove_dir_all(&fresh);
    let status = std::process::Command::new(example(example_name))
        .arg("--out")
        .arg(&fresh)
        .stdout(std::process::Stdio::null())
        .stderr(std::process::Stdio::null())
        .status()
        .unwrap_or_else(|e| panic!("{example_name}: {e}"));
    assert!(status.success(), "{example_name} failed");
    let committed = generated_root().join(chapter);
    assert_eq!(
        listing(&fresh),
        listing(&committed),
        "{chapter}: the set of files"
    );
    let manifest = Manifest::load(&committed).unwrap();
    assert_eq!(
        manifest,
        Manifest::load(&fresh).unwrap(),
        "{chapter}: manifest"
    );
    for name in listing(&committed) {
        // The output manifest records file sizes, which timed files change.
        if manifest.timed_files.contains(&name) || name == atomic::MANIFEST {
            continue;
        }
        let (a, b) = (
            std::fs::read(committed.join(&name)).unwrap(),
            std::fs::read(fresh.join(&name)).unwrap(),
        );
        if name == facts::FILE {
            let parse = |bytes: &[u8]| Facts::parse(std::str::from_utf8(bytes).unwrap()).unwrap();
            let (a, b) = (parse(&a), parse(&b));
            let keys: Vec<&str> = a.keys().collect();
            assert_eq!(keys, b.keys().collect::<Vec<_>>(), "{chapter}: fact keys");
            for k in keys
                .iter()
                .filter(|k| !manifest.timed_facts.iter().any(|t| t == *k))
            {
                assert_eq!(
                    a.get(k),
                    b.get(k),
                    "{chapter}: fact `{k}` differs from a fresh run"
                );
            }
        } else {
            assert!(
                a == b,
                "{chapter}/{name} differs from a fresh run: regenerate the chapter"
            );
        }
    }
}

/// The book's data is what the code computes now: each chapter program, run
/// again, writes the committed bytes.
#[test]
fn the_generated_data_is_what_the_programs_compute() {
    for p in PROGRAMS.iter().filter(|p| p.cost == Cost::Quick) {
        regenerates_identically(p.example, p.chapter);
    }
}

/// Every test a chapter names, as `tests/FILE.rs::name`, is a function of
/// that file: a renamed or removed test cannot leave the book pointing at
/// nothing.
#[test]
fn every_test_a_chapter_names_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut named = 0;
    for entry in std::fs::read_dir(book_src()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_none_or(|e| e != "md") {
            continue;
        }
        let text = std::fs::read_to_string(&path).unwrap();
        for (at, _) in text.match_indices("tests/") {
            let rest = &text[at..];
            let Some((file, after)) = rest.split_once(".rs::") else {
                continue;
            };
            if file.contains(|c: char| !(c.is_ascii_alphanumeric() || c == '_' || c == '/')) {
                continue; // not one reference: the `.rs::` belongs to a later one
            }
            let name: String = after
                .chars()
                .take_while(|c| c.is_ascii_alphanumeric() || *c == '_')
                .collect();
            let source = std::fs::read_to_string(root.join(format!("{file}.rs")))
                .unwrap_or_else(|e| panic!("{}: {file}.rs: {e}", path.display()));
            assert!(
                source.contains(&format!("fn {name}(")),
                "{}: no test `{name}` in {file}.rs",
                path.display()
            );
            named += 1;
        }
    }
    assert!(named > 10, "only {named} tests named");
}
