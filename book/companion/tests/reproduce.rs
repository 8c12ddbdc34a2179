//! The `reproduce` tool's refusals, which come before any build or run:
//! an unknown chapter program is named, with the list of programs, and
//! leaves every generated folder as it was.

use std::process::Command;

const BIN: &str = env!("CARGO_BIN_EXE_reproduce");

#[test]
fn an_unknown_program_is_refused_naming_it_and_the_programs() {
    let o = Command::new(BIN)
        .args(["--only", "no-such-study"])
        .output()
        .expect("the binary runs");
    assert_eq!(o.status.code(), Some(2));
    let err = String::from_utf8_lossy(&o.stderr);
    let lines: Vec<&str> = err.lines().collect();
    assert_eq!(lines.len(), 1, "{err}");
    assert!(lines[0].starts_with("error: "), "{err}");
    assert!(lines[0].contains("no-such-study"), "{err}");
    for p in companion::PROGRAMS {
        assert!(lines[0].contains(p.example), "{err}");
    }
    assert!(o.stdout.is_empty());
}

#[test]
fn a_bad_flag_is_a_usage_error() {
    let o = Command::new(BIN)
        .arg("--all=3")
        .output()
        .expect("the binary runs");
    assert_eq!(o.status.code(), Some(2));
    assert!(String::from_utf8_lossy(&o.stderr).contains("--all"));
}
