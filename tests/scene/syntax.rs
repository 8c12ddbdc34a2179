//! Syntax errors and errors beside the table of refused scenes: the line
//! and column of bad TOML, unknown kinds, missing keys, unreadable files.

use crate::text::base_with;
use iga_contact::scene::Scene;
use iga_contact::Error;

#[test]
fn syntax_error_names_line_and_column() {
    let text = base_with("rtol = 1e-10", "rtol = 1e-10 2");
    let line = 1 + text.lines().position(|l| l.contains("1e-10 2")).unwrap();
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(msg.contains(&format!("`line {line}, column ")), "{msg}");
    assert!(msg.contains("= rtol = 1e-10 2:"), "{msg}");
    assert!(msg.contains("not valid TOML"), "{msg}");
}

/// An inline table left open: TOML finds the error at the start of the
/// next line, but the brace was left open on this one, which the message
/// names (inline tables do not go on to the next line; a multi-line array
/// keeps the line TOML gives).
#[test]
fn an_unclosed_inline_table_is_named_on_its_own_line() {
    let text = base_with("y1 = 0.5 } }", "y1 = 0.5 }");
    let line = 1 + text.lines().position(|l| l.contains("y1 = 0.5 }")).unwrap();
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(msg.contains(&format!("`line {line}, column ")), "{msg}");
    assert!(msg.contains("not closed on it"), "{msg}");
    let array = "title = \"t\"\nv = [\n  1,\n  2\n  3,\n]\n";
    let msg = Scene::from_toml_str(array).unwrap_err().to_string();
    assert!(!msg.contains("not closed on it"), "{msg}");
}

#[test]
fn unknown_geometry_kind_is_rejected() {
    let text = base_with("{ rectangle = {", "{ square = {");
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(msg.contains("`body[0].geometry`"), "{msg}");
    assert!(msg.contains("unknown variant `square`"), "{msg}");
}

#[test]
fn missing_required_key_names_its_table() {
    let text = base_with("name = \"lower\"\n", "");
    let msg = Scene::from_toml_str(&text).unwrap_err().to_string();
    assert!(
        msg.contains("`body[0]`") && msg.contains("missing field `name`"),
        "{msg}"
    );
}

#[test]
fn unreadable_file_is_invalid_input() {
    let err = Scene::load("/nonexistent/scene.toml").unwrap_err();
    assert!(matches!(err, Error::InvalidInput { .. }), "{err}");
    assert!(err.to_string().contains("/nonexistent/scene.toml"));
}
