//! Relation sentences carry their check.
//!
//! A sentence of the book that states a relation between results or a
//! property of the method ("faster", "fewer", "every solver", "monotone",
//! "converges", "never", "exact", "the same …") must be followed by an HTML
//! comment `<!-- check: KEY -->` (several keys: `<!-- check: a, b -->`), and
//! the same chapter must hold a Rust code block (a doc-test) with the comment
//! `// check: KEY` right above the assertion that fails when the relation
//! stops holding. The prose lint of `tests/book.rs` keeps typed numbers out of
//! the text; this test keeps unchecked claims out.
//!
//! `cargo test --release --test relations -- --nocapture` prints, chapter by
//! chapter, every relation sentence and the check behind it.

use std::collections::BTreeSet;
use std::path::PathBuf;

/// The words (lower case, whole words) that make a sentence a relation.
const RELATION_WORDS: &[&str] = &[
    "faster",
    "slower",
    "ahead of",
    "fewer",
    "more accurate",
    "less accurate",
    "every",
    "converge",
    "converges",
    "monotone",
    "monotonic",
    "monotonically",
    "never",
    "always",
    "exact",
    "exactly",
    "identical",
    "the same",
];

/// Phrases holding a relation word that name a thing rather than state a
/// result; they are removed before the words are looked for.
const NAMES: &[(&str, &str)] = &[
    (
        "exact solution",
        "the analytic solution of a benchmark is its name",
    ),
    (
        "exact solutions",
        "the analytic solutions of the benchmarks",
    ),
    (
        "exact arc",
        "the circular arc itself, as opposed to a polygon",
    ),
    ("exact circle", "the circle itself, as opposed to a polygon"),
    ("exact geometry", "the CAD geometry itself"),
    ("exact curve", "the boundary curve itself"),
    ("exact boundary", "the boundary curve itself"),
    ("exact disk", "the disk itself"),
    ("exact hertz", "Hertz's closed form, a name"),
    ("exact value", "the closed-form value a test compares with"),
    (
        "exact values",
        "the closed-form values a test compares with",
    ),
    (
        "exact contact state",
        "the state of a benchmark's exact solution",
    ),
    ("exact stress", "the analytic stress of a benchmark, a name"),
    ("exact field", "the analytic field of a benchmark, a name"),
    (
        "exact x",
        "the analytic field written in maths (x stands for the formula), a name",
    ),
    ("exact state", "the analytic state of a benchmark, a name"),
    (
        "exact nurbs",
        "the NURBS disk that is the circle itself, a name",
    ),
];

/// Sentences that use a relation word but state no result: (chapter,
/// fragment of the sentence, why it is no relation).
const NO_RELATION: &[(&str, &str, &str)] = &[
    (
        "introduction.md",
        "compiles and runs every Rust code block",
        "what cargo test does, not a result",
    ),
    (
        "introduction.md",
        "Every problem is planar",
        "a convention of the book",
    ),
    (
        "introduction.md",
        "a sentence that states a relation between results",
        "the convention this test enforces, quoting its words",
    ),
    (
        "reliability.md",
        "requires the same iterations",
        "what tests/scale.rs asserts, which fails when it stops holding",
    ),
    (
        "reliability.md",
        "in the kernel of every matrix of the method",
        "linear algebra: σ(r) = 0 and jnᵀr = 0 for such an r",
    ),
    (
        "taylor.md",
        "a sound method should reproduce it exactly",
        "what the patch test asks of a method, its definition",
    ),
    (
        "taylor.md",
        "carries an error into every other problem",
        "why the patch test matters, an argument, not a measured result",
    ),
    (
        "taylor.md",
        "The integration tests in code check more than this",
        "lists what tests/taylor.rs asserts; those tests are the check",
    ),
    (
        "hertz.md",
        "A Lagrange mesh with the same number of elements would only interpolate",
        "a property of Lagrange interpolation, which no chapter program computes",
    ),
    (
        "bfgs.md",
        "while every kernel it meets is regular, it either converges or revisits an active set",
        "a property of a map between finitely many active sets, each a linear piece: an argument, not a measured result",
    ),
    (
        "bfgs.md",
        "for every step only when",
        "the algebra of the update (16), shown in the sentence itself",
    ),
    (
        "hertz.md",
        "Every chapter of this book measures our own solutions with one estimator",
        "a convention of the book's programs (they all call iga_contact::post), not a measured result",
    ),
    (
        "hertz.md",
        "It rebuilds the contact points of the problem with code and the same pairs",
        "describes the code of PressureProfile::dense",
    ),
    (
        "hertz.md",
        "A whole disk, with its zone x, gives the same x.",
        "the estimator's definition on a symmetric zone, not a measurement",
    ),
    (
        "hertz.md",
        "the statement that both converge to the analytic curve",
        "reports what the paper states, whose values were lost",
    ),
    (
        "hertz.md",
        "against N for FEM on the same mesh",
        "reports the paper's setting",
    ),
    (
        "hertz.md",
        "so only rows of the same options compare",
        "a reading instruction for Table H5",
    ),
    (
        "hertz.md",
        "the half-width must converge as the profile is sampled more densely",
        "lists what tests/hertz.rs asserts; those tests are the check",
    ),
    (
        "iga_vs_fem.md",
        "If BFGS does not converge, the failure is recorded",
        "the program's fallback, not a result (the committed run needed none: check same_setup)",
    ),
    (
        "iga_vs_fem.md",
        "and with the default solver on every thread of the machine",
        "names the thread setting of a run, not a result",
    ),
    (
        "iga_vs_fem.md",
        "All methods are timed in the same run of the program",
        "how the timing is run, not a result",
    ),
    (
        "iga_vs_fem.md",
        "(above 1: IGA is slower)",
        "a table caption defining its ratio column",
    ),
    (
        "penalty_study.md",
        "the BFGS iterations, x against the paper's setting ((11), θ = 0) on the same mesh",
        "a table caption: each row is compared with the paper's setting on its own mesh",
    ),
    (
        "penalty_study.md",
        "x of BFGS against the rigid plane on the same mesh for the three variants",
        "a table caption: each row is compared with the rigid plane on its own mesh",
    ),
    (
        "penalty_study.md",
        "from the same body as the consistency term",
        "the reason for the default, from the trace inequality, not a measurement",
    ),
    (
        "penalty_study.md",
        "which names the pair, how many active points lie below",
        "describes the warning line; tests/penalty.rs checks it",
    ),
    (
        "penalty_study.md",
        "the same line in the code list of code",
        "describes summary.toml; tests/penalty.rs checks it",
    ),
    (
        "penalty_study.md",
        "gives the same warning before any solve",
        "describes iga-contact check; tests/penalty.rs (check_warns_where_the_bodies_first_touch) checks it",
    ),
    (
        "error_vs_time.md",
        "is only half the question",
        "quotes the paper's claim that the chapter reframes",
    ),
    (
        "error_vs_time.md",
        "interpolated linearly at the same x",
        "describes the estimator post::Reference::errors",
    ),
    (
        "error_vs_time.md",
        "If it does not converge, the failure is kept",
        "the program's fallback, not a result",
    ),
    (
        "error_vs_time.md",
        "Assembly includes the sharp stability bound of every slave element",
        "describes what building a problem computes, not a measured result",
    ),
    (
        "scenes.md",
        "Every transcript in this chapter is the output of that binary",
        "how the transcripts are made; tests/book.rs reruns the program and compares them byte for byte",
    ),
    (
        "scenes.md",
        "BFGS with the secant correction, BFGS never corrected, or semismooth Newton",
        "names the variants of SolverKind",
    ),
    (
        "scenes.md",
        "iterate on the contact layer or over every free DOF, as the paper does",
        "names the variants of IterationSpace",
    ),
    (
        "scenes.md",
        "displacement, stress and von Mises stress on every element",
        "describes the VTU file, which tests/vtu.rs reads back",
    ),
    (
        "scenes.md",
        "Nothing that was not asked for is computed",
        "describes the run's code paths; tests/scene/outputs.rs (a_scene_without_outputs_writes_nothing, a_scene_asking_only_for_iterations_writes_only_that) checks the files",
    ),
    (
        "scenes.md",
        "does everything code does before it solves",
        "describes Scene::check; tests/cli.rs (check_builds_without_solving) runs it",
    ),
    (
        "scenes.md",
        "Each rule is a row of one table of refused scenes in code",
        "names the tests that enforce the rules",
    ),
    (
        "scenes.md",
        "multiplies every case count by 20",
        "describes an environment variable of tests/fuzz.rs",
    ),
    (
        "scenes.md",
        "Every file is staged in a fresh folder",
        "describes OutputSet; tests/outputs/ checks it",
    ),
    (
        "scenes.md",
        "so files of an earlier run never linger",
        "tests/outputs/library.rs (a_commit_replaces_the_whole_set_and_lists_it_in_the_manifest)",
    ),
    (
        "scenes.md",
        "the earlier results stay exactly as they were",
        "tests/outputs/library.rs (an_io_failure_part_way_through_leaves_the_earlier_set_byte_for_byte), tests/outputs/interrupted.rs (a_full_disk_part_way_through_leaves_the_earlier_set)",
    ),
    (
        "scenes.md",
        "is removed by the next run into the same folder",
        "tests/outputs/interrupted.rs (sigint_and_sigterm_end_the_run_without_partial_files), tests/outputs/library.rs (staging_of_a_dead_owner_is_removed_by_the_next_set)",
    ),
    (
        "scenes.md",
        "Every chapter program writes its folder code the same way",
        "the chapter programs write through companion::chapter, which commits an OutputSet",
    ),
    (
        "claims.md",
        "The code blocks on this page then recompute each verdict from the same facts",
        "how the page is checked, not a result",
    ),
    (
        "claims.md",
        "The like-for-like test is the paper's iteration with and without that correction",
        "the set-up of the Hertz ladder's two paper rows: companion::Solver::options_from (book/companion/src/solvers.rs) changes only the solver kind of the scene's [solver] table",
    ),
];

/// The chapters whose relation sentences are not annotated yet. Each is
/// read by the other checks but not by the one that asks every relation
/// sentence for its key. Empty it as the chapters are annotated; an empty
/// list is the goal.
const NOT_YET_ANNOTATED: &[&str] = &[];

const ABBREVIATIONS: &[&str] = &[
    "eq", "eqs", "fig", "figs", "e.g", "i.e", "al", "cf", "vs", "no", "approx", "ref", "sec",
];

fn book_src() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("book/src")
}

/// The chapters of SUMMARY.md, in its order (file name, text).
fn chapters() -> Vec<(String, String)> {
    let summary = std::fs::read_to_string(book_src().join("SUMMARY.md")).unwrap();
    let mut out = Vec::new();
    let mut rest = summary.as_str();
    while let Some(k) = rest.find("](") {
        let after = &rest[k + 2..];
        let end = after.find(')').expect("a SUMMARY link ends with )");
        let file = &after[..end];
        if file.ends_with(".md") {
            let text = std::fs::read_to_string(book_src().join(file))
                .unwrap_or_else(|e| panic!("SUMMARY.md lists {file}: {e}"));
            out.push((file.to_string(), text));
        }
        rest = &after[end..];
    }
    out
}

/// One sentence of a chapter's prose and the check keys written after it.
#[derive(Debug, Clone, PartialEq)]
struct Sentence {
    text: String,
    keys: Vec<String>,
}

const MARK_OPEN: char = '⟦';
const MARK_CLOSE: char = '⟧';

/// Removes the spans `open … close` from `text`, replacing each by `with`.
fn cut(text: &str, open: &str, close: &str, with: &str) -> String {
    let mut kept = String::new();
    let mut rest = text;
    while let Some(k) = rest.find(open) {
        kept.push_str(&rest[..k]);
        let after = &rest[k + open.len()..];
        match after.find(close) {
            Some(e) => {
                kept.push_str(with);
                rest = &after[e + close.len()..];
            }
            None => {
                rest = after;
            }
        }
    }
    kept.push_str(rest);
    kept
}

/// `<!-- check: a, b -->` becomes the marker ⟦a,b⟧; other comments go.
fn mark_checks(text: &str) -> String {
    let mut out = String::new();
    let mut rest = text;
    while let Some(k) = rest.find("<!--") {
        out.push_str(&rest[..k]);
        let after = &rest[k + 4..];
        let Some(e) = after.find("-->") else {
            rest = after;
            break;
        };
        let body = after[..e].trim();
        if let Some(keys) = body.strip_prefix("check:") {
            let keys: Vec<&str> = keys.split(',').map(str::trim).collect();
            out.push(' ');
            out.push(MARK_OPEN);
            out.push_str(&keys.join(","));
            out.push(MARK_CLOSE);
        }
        rest = &after[e + 3..];
    }
    out.push_str(rest);
    out
}

/// The paragraphs of a chapter's prose: fenced code, display maths, headings,
/// table rows and images left out; list items and quoted lines start a new
/// paragraph.
fn paragraphs(text: &str) -> Vec<String> {
    let text = mark_checks(text);
    let mut lines = Vec::new();
    let mut in_fence = false;
    for line in text.lines() {
        if line.trim_start().starts_with("```") {
            in_fence = !in_fence;
            lines.push(String::new());
            continue;
        }
        if !in_fence {
            lines.push(line.to_string());
        }
    }
    let text = cut(&lines.join("\n"), "$$", "$$", "\n\n");
    let mut out = Vec::new();
    let mut current = String::new();
    let flush = |current: &mut String, out: &mut Vec<String>| {
        if !current.trim().is_empty() {
            out.push(std::mem::take(current));
        }
        current.clear();
    };
    for line in text.lines() {
        let mut t = line.trim();
        while let Some(rest) = t.strip_prefix('>') {
            t = rest.trim_start();
        }
        let list_item = t.starts_with("- ")
            || t.starts_with("* ")
            || t.split_once(". ")
                .is_some_and(|(n, _)| !n.is_empty() && n.chars().all(|c| c.is_ascii_digit()));
        if t.is_empty() || t.starts_with('#') || t.starts_with('|') || t.starts_with("![") {
            flush(&mut current, &mut out);
            continue;
        }
        if list_item {
            flush(&mut current, &mut out);
        }
        current.push_str(t);
        current.push(' ');
    }
    flush(&mut current, &mut out);
    out
}

/// Inline maths, code, includes and link targets reduced to placeholders.
fn plain(paragraph: &str) -> String {
    let p = cut(paragraph, "{{#include", "}}", "N");
    let p = cut(&p, "$", "$", "x");
    let p = cut(&p, "`", "`", "code");
    cut(&p, "](", ")", "]")
        .replace(['[', ']', '*'], "")
        .split_whitespace()
        .collect::<Vec<_>>()
        .join(" ")
}

/// Splits a paragraph into sentences; a check marker right after a sentence's
/// full stop belongs to that sentence.
fn sentences(paragraph: &str) -> Vec<Sentence> {
    let text = plain(paragraph);
    let chars: Vec<char> = text.chars().collect();
    let mut pieces: Vec<String> = Vec::new();
    let mut start = 0;
    for i in 0..chars.len() {
        let c = chars[i];
        if !matches!(c, '.' | '!' | '?') {
            continue;
        }
        let next_is_space = chars.get(i + 1).is_none_or(|n| n.is_whitespace());
        if !next_is_space {
            continue;
        }
        let word: String = chars[start..i]
            .iter()
            .rev()
            .take_while(|c| !c.is_whitespace() && **c != '(')
            .collect::<Vec<_>>()
            .into_iter()
            .rev()
            .collect();
        if ABBREVIATIONS.contains(&word.to_lowercase().as_str()) {
            continue;
        }
        pieces.push(chars[start..=i].iter().collect());
        start = i + 1;
    }
    pieces.push(chars[start..].iter().collect());

    let mut out: Vec<Sentence> = Vec::new();
    for piece in pieces {
        let mut piece = piece.trim().to_string();
        // Markers at the start of a piece follow the previous sentence.
        while piece.starts_with(MARK_OPEN) {
            let end = piece.find(MARK_CLOSE).expect("a marker closes");
            let keys = &piece[MARK_OPEN.len_utf8()..end];
            if let Some(last) = out.last_mut() {
                last.keys.extend(keys.split(',').map(str::to_string));
            }
            piece = piece[end + MARK_CLOSE.len_utf8()..].trim().to_string();
        }
        let mut keys = Vec::new();
        let mut text = String::new();
        let mut rest = piece.as_str();
        while let Some(k) = rest.find(MARK_OPEN) {
            text.push_str(&rest[..k]);
            let end = rest.find(MARK_CLOSE).expect("a marker closes");
            keys.extend(
                rest[k + MARK_OPEN.len_utf8()..end]
                    .split(',')
                    .map(str::to_string),
            );
            rest = &rest[end + MARK_CLOSE.len_utf8()..];
        }
        text.push_str(rest);
        let text = text.split_whitespace().collect::<Vec<_>>().join(" ");
        if !text.is_empty() {
            out.push(Sentence { text, keys });
        }
    }
    out
}

/// The relation words of a sentence (names removed first).
fn relation_words(sentence: &str) -> Vec<&'static str> {
    let mut s = format!(" {} ", sentence.to_lowercase());
    for (name, _) in NAMES {
        s = replace_word(&s, name, " ");
    }
    RELATION_WORDS
        .iter()
        .copied()
        .filter(|w| find_word(&s, w).is_some())
        .collect()
}

fn is_word_char(c: char) -> bool {
    c.is_alphanumeric() || c == '_' || c == '-'
}

fn find_word(s: &str, word: &str) -> Option<usize> {
    let mut from = 0;
    while let Some(k) = s[from..].find(word) {
        let at = from + k;
        let before = s[..at].chars().next_back().is_none_or(|c| !is_word_char(c));
        let after = s[at + word.len()..]
            .chars()
            .next()
            .is_none_or(|c| !is_word_char(c));
        if before && after {
            return Some(at);
        }
        from = at + word.len();
    }
    None
}

fn replace_word(s: &str, word: &str, with: &str) -> String {
    let mut s = s.to_string();
    while let Some(at) = find_word(&s, word) {
        s.replace_range(at..at + word.len(), with);
    }
    s
}

/// The keys a chapter's Rust code blocks check: a `// check: KEY` comment
/// followed (after further check comments and blank lines only) by a line
/// with an assertion.
fn checked_keys(text: &str) -> (BTreeSet<String>, Vec<String>) {
    let mut keys = BTreeSet::new();
    let mut dangling = Vec::new();
    let mut in_rust = false;
    let mut pending: Vec<String> = Vec::new();
    for line in text.lines() {
        let t = line.trim();
        if t.starts_with("```") {
            if in_rust {
                dangling.append(&mut pending);
            }
            in_rust = !in_rust && t.starts_with("```rust") && !t.contains("ignore");
            continue;
        }
        if !in_rust {
            continue;
        }
        let code = t.strip_prefix("# ").unwrap_or(t).trim();
        if let Some(key) = code.strip_prefix("// check:") {
            pending.extend(key.split(',').map(|k| k.trim().to_string()));
        } else if code.is_empty() || (code.starts_with("//") && !pending.is_empty()) {
            continue;
        } else if code.contains("assert") {
            keys.extend(pending.drain(..));
        } else {
            dangling.append(&mut pending);
        }
    }
    dangling.append(&mut pending);
    (keys, dangling)
}

fn allowed(chapter: &str, sentence: &str) -> bool {
    NO_RELATION
        .iter()
        .any(|(c, fragment, _)| *c == chapter && sentence.contains(fragment))
}

/// The problems of one chapter: relation sentences with no key, keys with no
/// assertion, malformed keys, check comments not right above an assertion.
fn problems(chapter: &str, text: &str, annotated: bool) -> (Vec<String>, Vec<String>) {
    let (checked, dangling) = checked_keys(text);
    let mut problems = Vec::new();
    let mut listing = Vec::new();
    for key in dangling {
        problems.push(format!(
            "{chapter}: `// check: {key}` is not right above an assertion"
        ));
    }
    for sentence in paragraphs(text).iter().flat_map(|p| sentences(p)) {
        for key in &sentence.keys {
            if key.is_empty()
                || !key
                    .chars()
                    .all(|c| c.is_ascii_lowercase() || c.is_ascii_digit() || c == '_')
            {
                problems.push(format!("{chapter}: malformed check key {key:?}"));
            } else if !checked.contains(key) {
                problems.push(format!(
                    "{chapter}: <!-- check: {key} --> has no `// check: {key}` above an \
                     assertion in the chapter's Rust code"
                ));
            }
        }
        let words = relation_words(&sentence.text);
        if words.is_empty() {
            continue;
        }
        if !sentence.keys.is_empty() {
            listing.push(format!(
                "  [{}] {}",
                sentence.keys.join(", "),
                sentence.text
            ));
        } else if annotated && !allowed(chapter, &sentence.text) {
            problems.push(format!(
                "{chapter}: relation ({}) with no check: {}",
                words.join(", "),
                sentence.text
            ));
        }
    }
    (problems, listing)
}

#[test]
fn every_relation_sentence_carries_a_check() {
    let mut all = Vec::new();
    for (chapter, text) in chapters() {
        let annotated = !NOT_YET_ANNOTATED.contains(&chapter.as_str());
        let (problems, listing) = problems(&chapter, &text, annotated);
        println!(
            "{chapter}{}",
            if annotated {
                ""
            } else {
                " (not yet annotated)"
            }
        );
        for line in listing {
            println!("{line}");
        }
        if annotated {
            all.extend(problems);
        } else {
            // listed, not enforced: these chapters' keys follow the looser
            // convention they were written to (a check key in the block,
            // not always right above its assertion)
            println!("  ({} problems not enforced)", problems.len());
        }
    }
    assert!(
        all.is_empty(),
        "relation sentences need `<!-- check: KEY -->` after them and `// check: KEY` above an \
         assertion in the same chapter (or an entry in NO_RELATION with the reason):\n{}",
        all.join("\n")
    );
}

#[test]
fn every_chapter_is_read() {
    let chapters = chapters();
    let names: Vec<&str> = chapters.iter().map(|(c, _)| c.as_str()).collect();
    for must in [
        "introduction.md",
        "nitsche.md",
        "notation.md",
        "limitations.md",
    ] {
        assert!(names.contains(&must), "{must} is not in SUMMARY.md");
    }
    // Every Markdown file of the book is a chapter of SUMMARY.md.
    for entry in std::fs::read_dir(book_src()).unwrap() {
        let name = entry.unwrap().file_name().to_string_lossy().into_owned();
        if name.ends_with(".md") && name != "SUMMARY.md" {
            assert!(
                names.contains(&name.as_str()),
                "{name} is not in SUMMARY.md"
            );
        }
    }
}

#[test]
fn the_allow_lists_are_not_stale() {
    let chapters = chapters();
    for (chapter, fragment, _) in NO_RELATION {
        let Some((_, text)) = chapters.iter().find(|(c, _)| c == chapter) else {
            panic!("NO_RELATION names {chapter}, which is not a chapter");
        };
        let hit = paragraphs(text)
            .iter()
            .flat_map(|p| sentences(p))
            .any(|s| s.text.contains(fragment) && !relation_words(&s.text).is_empty());
        assert!(
            hit,
            "NO_RELATION: no relation sentence of {chapter} holds {fragment:?}"
        );
    }
}

#[test]
fn the_scanner_finds_an_unchecked_relation() {
    let text = "# T\n\nThe solver is faster than BFGS. It runs, e.g. on Eq. 3, in order.\n\n\
                Newton converges in fewer steps. <!-- check: fewer -->\n\n\
                - Every point is open.\n\n```rust\n// check: fewer\nassert!(1 < 2);\n```\n";
    let (found, listing) = problems("t.md", text, true);
    assert_eq!(found.len(), 2, "{found:?}");
    assert!(found[0].contains("faster") && found[0].contains("is faster than BFGS."));
    assert!(found[1].contains("Every point is open."));
    assert_eq!(listing.len(), 1);
    assert!(listing[0].starts_with("  [fewer] Newton converges"));
    // the abbreviations did not split the second sentence
    let s = sentences("It runs, e.g. on Eq. 3, in order. Next.");
    assert_eq!(s.len(), 2, "{s:?}");
    // a key with no assertion below it, and a key no code checks
    let text = "A is exact. <!-- check: a -->\n\n```rust\n// check: a\nlet x = 1;\n```\n";
    let (found, _) = problems("t.md", text, true);
    assert_eq!(found.len(), 2, "{found:?}");
    // names are not relations
    assert!(relation_words("The exact solution is linear.").is_empty());
    assert_eq!(relation_words("It is exact."), ["exact"]);
    assert!(relation_words("The exactness of it.").is_empty());
}
