//! The book against the code: every include of every chapter resolves, and
//! every chapter program, run afresh, writes exactly the files the book
//! embeds (except those that hold wall-clock times). So a number the prose
//! quotes can change neither in the prose (it is included, not typed) nor
//! in the data (the data must equal a fresh run) without a test failing.

mod common;

use common::example;
use companion::chapter::{generated_root, Cost, Manifest, PROGRAMS};
use companion::facts::{self, Facts};
use iga_contact::report::atomic;
use std::path::{Path, PathBuf};

fn book_src() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("book/src")
}

/// Every chapter source: its file name (`hertz.md`) and its text.
fn chapters() -> Vec<(String, String)> {
    let mut out = Vec::new();
    for entry in std::fs::read_dir(book_src()).unwrap() {
        let path = entry.unwrap().path();
        if path.extension().is_some_and(|e| e == "md") {
            let name = path.file_name().unwrap().to_string_lossy().into_owned();
            out.push((name, std::fs::read_to_string(&path).unwrap()));
        }
    }
    out
}

/// Every `{{#include path[:anchor]}}` in the chapters (escaped ones aside).
fn includes() -> Vec<(String, String, Option<String>)> {
    let mut out = Vec::new();
    for (chapter, text) in chapters() {
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

/// The source of the test target a chapter names as `tests/NAME.rs`: that
/// file, or, for a target split into a directory (`tests/NAME/main.rs`
/// declaring one module per concern), every file of the directory.
fn target_source(root: &Path, file: &str) -> std::io::Result<String> {
    let dir = root.join(file);
    if !root.join(format!("{file}.rs")).exists() && dir.join("main.rs").is_file() {
        let mut files: Vec<PathBuf> = std::fs::read_dir(&dir)?
            .map(|e| e.map(|e| e.path()))
            .collect::<std::io::Result<_>>()?;
        files.retain(|p| p.extension().is_some_and(|e| e == "rs"));
        files.sort();
        let mut text = String::new();
        for f in files {
            text.push_str(&std::fs::read_to_string(f)?);
        }
        return Ok(text);
    }
    std::fs::read_to_string(root.join(format!("{file}.rs")))
}

/// Every test a chapter names, as `tests/FILE.rs::name`, is a function of
/// that file (or of the directory target `tests/FILE/`): a renamed or
/// removed test cannot leave the book pointing at nothing.
#[test]
fn every_test_a_chapter_names_exists() {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut named = 0;
    for (chapter, text) in chapters() {
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
            let source =
                target_source(root, file).unwrap_or_else(|e| panic!("{chapter}: {file}.rs: {e}"));
            assert!(
                source.contains(&format!("fn {name}(")),
                "{chapter}: no test `{name}` in {file}.rs"
            );
            named += 1;
        }
    }
    assert!(named > 10, "only {named} tests named");
}

/// The prose of a chapter with code, maths, includes and link targets
/// removed: what a reader sees as typed text.
fn prose(text: &str) -> String {
    let mut out = String::new();
    let mut in_fence = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
            continue;
        }
        if !in_fence {
            out.push_str(line);
            out.push('\n');
        }
    }
    // Cut spans between delimiters, longest delimiters first.
    for (open, close) in [
        ("{{#include", "}}"),
        ("<!--", "-->"),
        ("$$", "$$"),
        ("$", "$"),
        ("`", "`"),
        ("](", ")"),
    ] {
        let mut kept = String::new();
        let mut rest = out.as_str();
        while let Some(k) = rest.find(open) {
            kept.push_str(&rest[..k]);
            let after = &rest[k + open.len()..];
            match after.find(close) {
                Some(e) => {
                    kept.push(' ');
                    rest = &after[e + close.len()..];
                }
                None => {
                    rest = after;
                }
            }
        }
        kept.push_str(rest);
        out = kept;
    }
    out
}

/// Numbers in `prose` that look like measured results: a decimal number, or
/// a number followed by a unit or a percent sign.
fn typed_results(prose: &str) -> Vec<String> {
    const UNITS: [&str; 17] = [
        "%",
        "mm",
        "MPa",
        "GPa",
        "Pa",
        "ms",
        "s",
        "GB",
        "MB",
        "N/m",
        "N",
        "iterations",
        "iteration",
        "factorisations",
        "corrections",
        "times faster",
        "times slower",
    ];
    let chars: Vec<char> = prose.chars().collect();
    let mut found = Vec::new();
    let mut i = 0;
    while i < chars.len() {
        let starts = chars[i].is_ascii_digit()
            && (i == 0 || !(chars[i - 1].is_alphanumeric() || chars[i - 1] == '.'));
        if !starts {
            i += 1;
            continue;
        }
        let mut j = i;
        while j < chars.len() && (chars[j].is_ascii_digit() || chars[j] == '.') {
            j += 1;
        }
        let number: String = chars[i..j].iter().collect::<String>();
        let number = number.trim_end_matches('.').to_string();
        let mut k = j;
        while k < chars.len() && chars[k] == ' ' {
            k += 1;
        }
        let tail: String = chars[k..chars.len().min(k + 16)].iter().collect();
        let unit = UNITS.iter().find(|u| {
            tail.starts_with(*u)
                && !tail[u.len()..]
                    .chars()
                    .next()
                    .is_some_and(|c| c.is_alphanumeric())
        });
        if number.contains('.') || unit.is_some() {
            found.push(format!(
                "{number}{}",
                unit.map_or(String::new(), |u| format!(" {u}"))
            ));
        }
        i = j;
    }
    found
}

/// Numbers the prose may type: parameters of a set-up, targets and test
/// bounds, and values quoted from the paper. Everything else a chapter says
/// about a result is included from its generated data.
const TYPED_ON_PURPOSE: &[(&str, &str, &str)] = &[
    ("claims.md", "8 iterations", "the paper's rule, quoted"),
    ("correction.md", "8 iterations", "the paper's rule, quoted"),
    (
        "elasticity.md",
        "0.1",
        "the convergence test's bound on the measured rates",
    ),
    ("error_vs_time.md", "5 %", "an accuracy target"),
    (
        "incompressibility.md",
        "2 %",
        "issue 20's tolerance on Hertz, a requirement",
    ),
    ("error_vs_time.md", "1 %", "an accuracy target"),
    ("error_vs_time.md", "0.1 %", "an accuracy target"),
    ("gap.md", "15 %", "how far the sketch lifts the arc"),
    ("iga_vs_fem.md", "8 iterations", "the paper's rule, quoted"),
    ("hertz.md", "3 %", "the doc-test's tolerance against Hertz"),
    ("hertz.md", "4 %", "the doc-test's tolerance against Hertz"),
    ("nurbs.md", "0.2", "the radius of the half disk"),
    ("nurbs.md", "0.5", "a weight of the example basis"),
    ("penalty.md", "0.1", "a penalty factor"),
    ("penalty_study.md", "0.2", "the block's size in its scene"),
    ("penalty_study.md", "0.4", "the block's size in its scene"),
    (
        "penalty_study.md",
        "2 %",
        "the accuracy required of the contrast study",
    ),
    (
        "penalty_study.md",
        "8 iterations",
        "the paper's rule, quoted",
    ),
    ("solvers.md", "8 iterations", "the paper's rule, quoted"),
    ("stability.md", "0.3", "a Poisson ratio of the atlas"),
    (
        "stability.md",
        "50 %",
        "the doc-test's bound on a wrong answer",
    ),
    ("stability.md", "0.45", "a Poisson ratio of the atlas"),
    ("stability.md", "0.49", "a Poisson ratio of the atlas"),
    ("stability.md", "0.499", "a Poisson ratio of the atlas"),
    ("stability.md", "0.4999", "a Poisson ratio of the atlas"),
    ("taylor.md", "0.1", "the paper's printed displacement"),
    ("taylor.md", "100 Pa", "the paper's printed stress"),
];

#[test]
fn the_prose_types_no_measured_number() {
    let mut offenders = Vec::new();
    for (chapter, text) in chapters() {
        for token in typed_results(&prose(&text)) {
            let allowed = TYPED_ON_PURPOSE
                .iter()
                .any(|(c, t, _)| *c == chapter && *t == token);
            if !allowed {
                offenders.push(format!("{chapter}: {token}"));
            }
        }
    }
    offenders.sort();
    offenders.dedup();
    assert!(
        offenders.is_empty(),
        "numbers typed in the prose (include them from generated data, or list them in \
         TYPED_ON_PURPOSE with the reason):\n{}",
        offenders.join("\n")
    );
}

/// The code of every table and figure caption (`**Table IN1.**` has `IN`).
fn caption_codes(text: &str) -> Vec<String> {
    let mut out = Vec::new();
    for marker in ["**Table ", "**Fig. "] {
        for (at, _) in text.match_indices(marker) {
            let rest = &text[at + marker.len()..];
            let code: String = rest
                .chars()
                .take_while(|c| c.is_ascii_uppercase())
                .collect();
            let numbered = rest[code.len()..].starts_with(|c: char| c.is_ascii_digit());
            if !code.is_empty() && numbered {
                out.push(code);
            }
        }
    }
    out
}

#[test]
fn every_caption_code_is_listed_in_the_introduction() {
    let intro = std::fs::read_to_string(book_src().join("introduction.md")).unwrap();
    let mut missing = Vec::new();
    for (chapter, text) in chapters() {
        for code in caption_codes(&text) {
            if !intro.contains(&format!(" {code} (")) {
                missing.push(format!("{chapter}: {code}"));
            }
        }
    }
    missing.sort();
    missing.dedup();
    assert!(
        missing.is_empty(),
        "caption codes missing from the numbering list of introduction.md:\n{}",
        missing.join("\n")
    );
}
