//! Property-based fuzzing: nothing a user can write — in a scene file or
//! through the public geometry API — may panic. Errors are fine; panics
//! (index out of bounds, unwrap on None, overflow) are bugs.
//!
//! The default case counts add up to a little over 100 000 inputs and run in
//! well under a minute in release mode. For a longer offline run, scale
//! every count with the environment variable `FUZZ_SCALE`, e.g.
//! `FUZZ_SCALE=20 cargo test --release --test fuzz`.
//!
//! Scene inputs that pass validation are also built (`Scene::build`), but
//! only when they stay small (≤ 8 elements per direction, degree ≤ 4), so
//! that the cost per case stays in the millisecond range.

use iga_contact::geometry;
use iga_contact::nurbs::{KnotVector, NurbsPatch};
use iga_contact::scene::{GeometrySpec, Scene};
use proptest::prelude::*;
use proptest::test_runner::Config;

/// `base` cases scaled by `FUZZ_SCALE` (default 1).
fn cases(base: u32) -> u32 {
    let scale = std::env::var("FUZZ_SCALE")
        .ok()
        .and_then(|s| s.parse::<f64>().ok())
        .filter(|s| s.is_finite() && *s > 0.0)
        .unwrap_or(1.0);
    ((base as f64 * scale).round() as u32).max(1)
}

fn config(base: u32) -> Config {
    Config {
        cases: cases(base),
        // No regression files in the source tree; a failure prints its input.
        failure_persistence: None,
        ..Config::default()
    }
}

const SCENES: [&str; 4] = [
    include_str!("../data/scenes/taylor.toml"),
    include_str!("../data/scenes/hertz.toml"),
    include_str!("../data/scenes/hertz_fem_q2.toml"),
    include_str!("../data/scenes/minimal.toml"),
];

/// Numbers that break naive code: non-finite, signed zeros, extremes,
/// subnormals, and ordinary values of both signs.
fn nasty_f64() -> impl Strategy<Value = f64> {
    prop_oneof![
        Just(f64::NAN),
        Just(f64::INFINITY),
        Just(f64::NEG_INFINITY),
        Just(0.0),
        Just(-0.0),
        Just(1e308),
        Just(-1e308),
        Just(f64::MIN_POSITIVE),
        Just(5e-324),
        Just(1.0),
        any::<f64>(),
        -2.0..2.0f64,
        -1e9..1e9f64,
    ]
}

/// Scenes small enough to build in a millisecond or so.
fn small(scene: &Scene) -> bool {
    let ok_quad = |q: Option<usize>| q.is_none_or(|q| q <= 8);
    scene.bodies.iter().all(|b| {
        let geometry_ok = match &b.geometry {
            GeometrySpec::Nurbs(n) => {
                n.degree.iter().all(|&p| p <= 4)
                    && n.knots_xi.len() <= 24
                    && n.knots_eta.len() <= 24
            }
            _ => true,
        };
        let refine_ok = b
            .refine
            .as_ref()
            .is_none_or(|r| r.elements().iter().all(|&n| n <= 8) && r.degree() <= 4);
        geometry_ok && refine_ok && ok_quad(b.quadrature)
    }) && scene
        .contacts
        .iter()
        .all(|c| ok_quad(c.nitsche.gauss_points))
        && scene.bodies.len() <= 4
}

/// Top-level keys of a scene, and the names of non-key locations.
const ROOTS: [&str; 10] = [
    "title",
    "allow_underintegration",
    "body",
    "support",
    "load",
    "contact",
    "solver",
    "output",
    "scene",
    "line",
];

/// An error names a place in the scene: a key path below a top-level key
/// (`body[0].geometry.full_disk.radius`), a line of the text, or the scene.
fn assert_names_a_scene_key(e: &iga_contact::Error) {
    let msg = e.to_string();
    assert!(!msg.contains('\n'), "multi-line error: {msg}");
    if let iga_contact::Error::InvalidInput { field, reason, .. } = e {
        // An unknown key is named where the text has it.
        let root = field.split(['.', '[', ' ']).next().unwrap_or("");
        assert!(
            ROOTS.contains(&root) || reason.starts_with("unknown field"),
            "`{field}` is not a scene key path: {msg}"
        );
    }
}

/// Parses, and builds what validates and is small. Must not panic, and
/// every error must name a scene key.
fn parse_and_build(text: &str) {
    match Scene::from_toml_str(text) {
        Ok(scene) => {
            if small(&scene) {
                if let Err(e) = scene.build() {
                    assert_names_a_scene_key(&e);
                }
            }
        }
        Err(e) => assert_names_a_scene_key(&e),
    }
}

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
enum Mutation {
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

fn mutation() -> impl Strategy<Value = Mutation> {
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

fn apply(root: &mut toml::Value, m: &Mutation) {
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
enum Edit {
    DeleteRange(usize, usize),
    Insert(usize, String),
    DuplicateLine(usize),
    DeleteLine(usize),
    SwapLines(usize, usize),
}

fn edit() -> impl Strategy<Value = Edit> {
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

fn apply_edit(text: &mut String, e: &Edit) {
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

// ---------------------------------------------------------------------------
// (a) scene text
// ---------------------------------------------------------------------------

proptest! {
    #![proptest_config(config(30_000))]

    /// Arbitrary Unicode text.
    #[test]
    fn arbitrary_strings_never_panic(text in any::<String>()) {
        parse_and_build(&text);
    }
}

proptest! {
    #![proptest_config(config(20_000))]

    /// Text over TOML's punctuation and the scene's vocabulary, so that the
    /// parser gets past the first character more often.
    #[test]
    fn toml_like_strings_never_panic(
        text in "((\\[\\[?(body|support|load|contact)\\]\\]?|\\[(solver|output)\\]|[a-z_]{1,12} = ([-+]?[0-9.e]{1,6}|nan|inf|\"[a-z_]{0,8}\"|\\{[^\n]{0,30}\\}|\\[[^\n]{0,20}\\]|true))\n){0,12}"
    ) {
        parse_and_build(&text);
    }
}

proptest! {
    #![proptest_config(config(8_000))]

    /// Random edits of the shipped scenes' text.
    #[test]
    fn text_mutations_of_valid_scenes_never_panic(
        which in 0..SCENES.len(),
        edits in prop::collection::vec(edit(), 1..4),
    ) {
        let mut text = SCENES[which].to_string();
        for e in &edits {
            apply_edit(&mut text, e);
        }
        parse_and_build(&text);
    }
}

proptest! {
    #![proptest_config(config(6_000))]

    /// Numbers of the shipped scenes scaled by mostly plausible factors:
    /// most cases stay valid and reach `build` with unusual geometry,
    /// materials, loads and contact parameters.
    #[test]
    fn numeric_perturbations_of_valid_scenes_never_panic(
        which in 0..SCENES.len(),
        scalings in prop::collection::vec(
            (any::<usize>(), prop_oneof![4 => 0.05..4.0f64, 1 => -2.0..0.0f64, 1 => Just(1e-12), 1 => Just(1e12)]),
            1..5,
        ),
    ) {
        let mut root = toml::Value::Table(toml::from_str(SCENES[which]).unwrap());
        for &(n, f) in &scalings {
            apply(&mut root, &Mutation::Scale(n, f));
        }
        if let Ok(text) = toml::to_string(&root) {
            parse_and_build(&text);
        }
    }
}

proptest! {
    #![proptest_config(config(8_000))]

    /// Key deletions, number replacements (NaN, ±inf, huge, negative),
    /// type changes and transplants in the shipped scenes' structure.
    #[test]
    fn structural_mutations_of_valid_scenes_never_panic(
        which in 0..SCENES.len(),
        mutations in prop::collection::vec(mutation(), 1..4),
    ) {
        let mut root = toml::Value::Table(toml::from_str(SCENES[which]).unwrap());
        for m in &mutations {
            apply(&mut root, m);
        }
        // The TOML writer cannot express every value tree (e.g. a table
        // that is no longer a table at the root); such cases are skipped.
        if let Ok(text) = toml::to_string(&root) {
            parse_and_build(&text);
        }
    }
}

// ---------------------------------------------------------------------------
// (b) geometry API
// ---------------------------------------------------------------------------

/// Knot vectors: sometimes valid open ones, often not.
fn knots() -> impl Strategy<Value = (Vec<f64>, usize)> {
    prop_oneof![
        // Anything.
        (prop::collection::vec(nasty_f64(), 0..16), 0usize..8),
        // Sorted values from a small set (repeats likely) — near-valid.
        (
            prop::collection::vec(
                prop_oneof![Just(0.0), Just(0.25), Just(0.5), Just(1.0), -1.0..2.0f64],
                0..14
            ),
            0usize..6
        )
            .prop_map(|(mut k, p)| {
                k.sort_by(f64::total_cmp);
                (k, p)
            }),
        // Valid open vectors with random interior knots.
        (1usize..5, prop::collection::vec(0.0..1.0f64, 0..6)).prop_map(|(p, mut inner)| {
            inner.sort_by(f64::total_cmp);
            let mut k = vec![0.0; p + 1];
            k.extend(inner);
            k.extend(vec![1.0; p + 1]);
            (k, p)
        }),
    ]
}

fn exercise_patch(patch: &NurbsPatch) {
    let _ = patch.n();
    let _ = patch.degree();
    for (xi, eta) in [(0.0, 0.0), (1.0, 1.0), (0.5, 0.25), (0.999, 0.001)] {
        let (a, b) = (patch.knots[0].first(), patch.knots[0].last());
        let (c, d) = (patch.knots[1].first(), patch.knots[1].last());
        let _ = patch.point(a + xi * (b - a), c + eta * (d - c));
    }
}

proptest! {
    #![proptest_config(config(15_000))]

    #[test]
    fn knot_vectors_never_panic((k, p) in knots(), t in 0.0..=1.0f64) {
        if let Ok(kv) = KnotVector::new(k, p) {
            let _ = kv.n_basis();
            let _ = kv.breaks();
            let _ = kv.spans();
            let u = kv.first() + t * (kv.last() - kv.first());
            let span = kv.find_span(u);
            let _ = kv.basis_ders(span, u, 1);
        }
    }
}

proptest! {
    #![proptest_config(config(10_000))]

    #[test]
    fn nurbs_patches_never_panic(
        (kx, p) in knots(),
        (ky, q) in knots(),
        points in prop::collection::vec((nasty_f64(), nasty_f64()), 0..40),
        weights in prop::collection::vec(nasty_f64(), 0..40),
        n_points in 0usize..40,
    ) {
        let (Ok(kx), Ok(ky)) = (KnotVector::new(kx, p), KnotVector::new(ky, q)) else {
            return Ok(());
        };
        // Often exactly the right count, so the net checks are reached.
        let need = kx.n_basis() * ky.n_basis();
        let count = if n_points % 2 == 0 { need } else { n_points };
        let mut pts: Vec<[f64; 2]> = points.iter().map(|&(x, y)| [x, y]).collect();
        pts.resize(count, [0.5, 0.5]);
        let mut w = weights.clone();
        w.resize(if n_points % 3 == 0 { count + 1 } else { count }, 1.0);
        if let Ok(patch) = NurbsPatch::new([kx, ky], pts, w) {
            exercise_patch(&patch);
        }
    }
}

proptest! {
    #![proptest_config(config(12_000))]

    #[test]
    fn geometry_builders_never_panic(
        a in nasty_f64(), b in nasty_f64(), c in nasty_f64(), d in nasty_f64(),
        corners in prop::array::uniform4((nasty_f64(), nasty_f64())),
        sane in prop::array::uniform4(-2.0..2.0f64),
    ) {
        let results = [
            geometry::rectangle(a, b, c, d),
            geometry::rectangle(sane[0], sane[1], sane[2], sane[3]),
            geometry::quadrilateral(corners.map(|(x, y)| [x, y])),
            geometry::quadrilateral([[sane[0], sane[1]], [1.0, 0.0], [sane[2], sane[3]], [0.0, 1.0]]),
            geometry::full_disk([a, b], c),
            geometry::half_disk([a, b], c),
            geometry::half_disk([sane[0], sane[1]], sane[2]),
            geometry::quarter_annulus(c, d),
            geometry::quarter_annulus(sane[2], sane[3]),
        ];
        for patch in results.iter().flatten() {
            exercise_patch(patch);
        }
        let _ = geometry::segment([a, b], [c, d]);
    }
}

proptest! {
    #![proptest_config(config(3_000))]

    /// k-refinement and the Lagrange interpolant with small random degrees
    /// and element counts (including the invalid 0).
    #[test]
    fn refinement_never_panics(
        kind in 0usize..5,
        r in prop_oneof![Just(1.0), 1e-3..10.0f64, nasty_f64()],
        degree in 0usize..6,
        elements in (0usize..7, 0usize..7),
        lagrange in 0usize..6,
    ) {
        let exact = match kind {
            0 => geometry::rectangle(0.0, 0.0, r, 1.0),
            1 => geometry::full_disk([0.0, 0.0], r),
            2 => geometry::half_disk([0.0, r], r),
            3 => geometry::quarter_annulus(r, 2.0 * r),
            _ => geometry::quadrilateral([[0.0, 0.0], [r, 0.0], [1.0, 1.0], [0.0, r]]),
        };
        let Ok(exact) = exact else { return Ok(()); };
        let el = [elements.0, elements.1];
        if let Ok(p) = exact.k_refined(degree, el) {
            exercise_patch(&p);
        }
        if let Ok(p) = geometry::lagrange_interpolant(&exact, lagrange, el) {
            exercise_patch(&p);
        }
    }
}
