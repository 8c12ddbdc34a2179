//! The library's modules depend on one another in the order the data flows
//! (geometry → space → assembly → contact → solver → post-processing →
//! report), as `scripts/module_graph.py` checks: no cycle between modules or
//! files, no edge from a lower layer to a higher one.

use std::path::Path;
use std::process::Command;

fn module_graph(src: Option<&Path>) -> (bool, String) {
    let root = Path::new(env!("CARGO_MANIFEST_DIR"));
    let mut cmd = Command::new("python3");
    cmd.arg(root.join("scripts/module_graph.py")).arg("--quiet");
    if let Some(src) = src {
        cmd.arg("--src").arg(src);
    }
    let out = cmd.output().expect("python3 runs scripts/module_graph.py");
    (
        out.status.success(),
        String::from_utf8_lossy(&out.stdout).into_owned(),
    )
}

#[test]
fn the_library_has_no_cycle_and_no_edge_against_the_data_flow() {
    let (ok, report) = module_graph(None);
    assert!(ok, "scripts/module_graph.py:\n{report}");
    assert!(
        report.contains("0 module cycles, 0 file cycles, 0 edges against the order"),
        "{report}"
    );
}

/// The check is only worth its pass if it fails on a tree that breaks the
/// order: the fixture's root error names the solver, which names the error.
#[test]
fn the_check_reports_a_cycle_and_an_edge_against_the_order() {
    let fixture = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/fixtures/module_graph/src");
    let (ok, report) = module_graph(Some(&fixture));
    assert!(!ok, "{report}");
    for expected in [
        "edge against the order: error [0] -> solver [7]",
        "module cycle: error <-> solver",
        "file cycle: src/error.rs <-> src/solver/mod.rs",
    ] {
        assert!(
            report.contains(expected),
            "missing `{expected}` in:\n{report}"
        );
    }
}
