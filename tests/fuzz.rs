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
//!
//! This file is the table of fuzz families: each `proptest!` block below is
//! one family with its case count (`config(N)`), and the reliability
//! chapter's program counts the inputs and families by reading this file,
//! which is why they stay here. What the families feed and check lives in
//! `tests/fuzz/`: [`scenes`] (the shipped scenes, and what every input must
//! do), [`mutate`] (structural and text mutations of a scene), [`patches`]
//! (knot vectors and patches to exercise).

#[path = "fuzz/mutate.rs"]
mod mutate;
#[path = "fuzz/patches.rs"]
mod patches;
#[path = "fuzz/scenes.rs"]
mod scenes;

use iga_contact::geometry;
use iga_contact::nurbs::{KnotVector, NurbsPatch};
use mutate::{apply, apply_edit, edit, mutation, Mutation};
use patches::{exercise_patch, knots};
use proptest::prelude::*;
use proptest::test_runner::Config;
use scenes::{parse_and_build, SCENES};

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
