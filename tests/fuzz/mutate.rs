//! Mutations of a scene: structural ones of its TOML tree (deletions,
//! number replacements, type changes, transplants, scalings) and edits of
//! its text.

use crate::nasty_f64;
use proptest::prelude::*;

// ---------------------------------------------------------------------------
// Structural mutations of the shipped scenes
// ---------------------------------------------------------------------------

#[derive(Clone, Debug)]
enum Key {
    Name(String),
    Index(usize),
}

/// Paths of every node below the root.
fn paths(v: &toml::Value, prefix: &mut Vec<Key>, out: &mut Vec<Vec<Key>>) {
    match v {
        toml::Value::Table(t) => {
            for (k, child) in t {
                prefix.push(Key::Name(k.clone()));
                out.push(prefix.clone());
                paths(child, prefix, out);
                prefix.pop();
            }
        }
        toml::Value::Array(a) => {
            for (i, child) in a.iter().enumerate() {
                prefix.push(Key::Index(i));
                out.push(prefix.clone());
                paths(child, prefix, out);
                prefix.pop();
            }
        }
        _ => {}
    }
}

fn node<'a>(root: &'a toml::Value, path: &[Key]) -> Option<&'a toml::Value> {
    let mut v = root;
    for k in path {
        v = match k {
            Key::Name(n) => v.as_table()?.get(n)?,
            Key::Index(i) => v.as_array()?.get(*i)?,
        };
    }
    Some(v)
}

fn node_mut<'a>(root: &'a mut toml::Value, path: &[Key]) -> Option<&'a mut toml::Value> {
    let mut v = root;
    for k in path {
        v = match k {
            Key::Name(n) => v.as_table_mut()?.get_mut(n)?,
            Key::Index(i) => v.as_array_mut()?.get_mut(*i)?,
        };
    }
    Some(v)
}

#[derive(Clone, Debug)]
pub enum Mutation {
    Delete(usize),
    Float(usize, f64),
    Integer(usize, i64),
    Retype(usize, u8),
    /// Copies one node over another (e.g. a table where a number belongs).
    Transplant(usize, usize),
    /// Multiplies a number of the scene (only numbers are picked): keeps
    /// the type right, so more cases pass validation and reach `build`.
    Scale(usize, f64),
}

pub fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        any::<usize>().prop_map(Mutation::Delete),
        (any::<usize>(), nasty_f64()).prop_map(|(n, x)| Mutation::Float(n, x)),
        (
            any::<usize>(),
            prop_oneof![
                Just(i64::MIN),
                Just(i64::MAX),
                Just(-1i64),
                Just(0i64),
                -3i64..20,
                any::<i64>()
            ]
        )
            .prop_map(|(n, x)| Mutation::Integer(n, x)),
        (any::<usize>(), any::<u8>()).prop_map(|(n, t)| Mutation::Retype(n, t)),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Mutation::Transplant(a, b)),
        (
            any::<usize>(),
            prop_oneof![
                Just(-1.0),
                Just(0.0),
                Just(1e-9),
                Just(1e9),
                Just(f64::NAN),
                0.0..3.0f64,
                -3.0..0.0f64
            ]
        )
            .prop_map(|(n, f)| Mutation::Scale(n, f)),
    ]
}

fn retyped(t: u8) -> toml::Value {
    use toml::Value as V;
    match t % 8 {
        0 => V::String(String::new()),
        1 => V::String("eta_min".into()),
        2 => V::Boolean(t % 2 == 0),
        3 => V::Array(Vec::new()),
        4 => V::Array(vec![V::Float(0.5), V::Float(-0.5)]),
        5 => V::Table(toml::Table::new()),
        6 => V::String("disk".into()),
        _ => V::Array(vec![V::Integer(1), V::Integer(2), V::Integer(3)]),
    }
}

pub fn apply(root: &mut toml::Value, m: &Mutation) {
    let mut all = Vec::new();
    paths(root, &mut Vec::new(), &mut all);
    if all.is_empty() {
        return;
    }
    let pick = |n: usize| all[n % all.len()].clone();
    match m {
        Mutation::Delete(n) => {
            let path = pick(*n);
            let (last, parent) = path.split_last().expect("non-empty path");
            match (node_mut(root, parent), last) {
                (Some(toml::Value::Table(t)), Key::Name(k)) => {
                    t.remove(k);
                }
                (Some(toml::Value::Array(a)), Key::Index(i)) if *i < a.len() => {
                    a.remove(*i);
                }
                _ => {}
            }
        }
        Mutation::Float(n, x) => {
            if let Some(v) = node_mut(root, &pick(*n)) {
                *v = toml::Value::Float(*x);
            }
        }
        Mutation::Integer(n, x) => {
            if let Some(v) = node_mut(root, &pick(*n)) {
                *v = toml::Value::Integer(*x);
            }
        }
        Mutation::Retype(n, t) => {
            if let Some(v) = node_mut(root, &pick(*n)) {
                *v = retyped(*t);
            }
        }
        Mutation::Scale(n, f) => {
            let numbers: Vec<&Vec<Key>> = all
                .iter()
                .filter(|p| {
                    matches!(
                        node(root, p),
                        Some(toml::Value::Float(_) | toml::Value::Integer(_))
                    )
                })
                .collect();
            if numbers.is_empty() {
                return;
            }
            let path = numbers[n % numbers.len()].clone();
            match node_mut(root, &path) {
                Some(toml::Value::Float(x)) => *x *= f,
                Some(toml::Value::Integer(i)) => {
                    let scaled = (*i as f64 * f).round();
                    if scaled.is_finite() && scaled.abs() < 9e18 {
                        *i = scaled as i64;
                    }
                }
                _ => {}
            }
        }
        Mutation::Transplant(a, b) => {
            let from = node_mut(root, &pick(*a)).map(|v| v.clone());
            if let (Some(from), Some(to)) = (from, node_mut(root, &pick(*b))) {
                *to = from;
            }
        }
    }
}

// ---------------------------------------------------------------------------
// Text-level mutations
// ---------------------------------------------------------------------------

#[derive(Clone, Debug)]
pub enum Edit {
    DeleteRange(usize, usize),
    Insert(usize, String),
    DuplicateLine(usize),
    DeleteLine(usize),
    SwapLines(usize, usize),
}

pub fn edit() -> impl Strategy<Value = Edit> {
    prop_oneof![
        (any::<usize>(), 0usize..12).prop_map(|(a, n)| Edit::DeleteRange(a, n)),
        (
            any::<usize>(),
            prop_oneof![
                "[\\[\\]{}=\",.#\\n0-9a-z_ -]{0,12}",
                Just("nan".to_string()),
                Just("-inf".to_string()),
                Just("1e400".to_string()),
                Just("\n[[body]]\n".to_string()),
                Just("\n[output]\nvtu = true\n".to_string()),
                any::<String>(),
            ]
        )
            .prop_map(|(a, s)| Edit::Insert(a, s)),
        any::<usize>().prop_map(Edit::DuplicateLine),
        any::<usize>().prop_map(Edit::DeleteLine),
        (any::<usize>(), any::<usize>()).prop_map(|(a, b)| Edit::SwapLines(a, b)),
    ]
}

fn floor_char_boundary(s: &str, mut i: usize) -> usize {
    i = i.min(s.len());
    while !s.is_char_boundary(i) {
        i -= 1;
    }
    i
}

pub fn apply_edit(text: &mut String, e: &Edit) {
    match e {
        Edit::DeleteRange(a, n) => {
            let start = floor_char_boundary(text, a % (text.len() + 1));
            let end = floor_char_boundary(text, start + n);
            text.replace_range(start..end, "");
        }
        Edit::Insert(a, s) => {
            let at = floor_char_boundary(text, a % (text.len() + 1));
            text.insert_str(at, s);
        }
        Edit::DuplicateLine(a) | Edit::DeleteLine(a) => {
            let mut lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return;
            }
            let i = a % lines.len();
            if matches!(e, Edit::DuplicateLine(_)) {
                lines.insert(i, lines[i]);
            } else {
                lines.remove(i);
            }
            *text = lines.join("\n");
        }
        Edit::SwapLines(a, b) => {
            let mut lines: Vec<&str> = text.lines().collect();
            if lines.is_empty() {
                return;
            }
            let n = lines.len();
            lines.swap(a % n, b % n);
            *text = lines.join("\n");
        }
    }
}
