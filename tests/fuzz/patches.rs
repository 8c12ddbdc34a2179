//! Knot vectors (sometimes valid open ones, often not) and what a patch
//! built from them must survive.

use crate::nasty_f64;
use iga_contact::nurbs::NurbsPatch;
use proptest::prelude::*;

/// Knot vectors: sometimes valid open ones, often not.
pub fn knots() -> impl Strategy<Value = (Vec<f64>, usize)> {
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

pub fn exercise_patch(patch: &NurbsPatch) {
    let _ = patch.n();
    let _ = patch.degree();
    for (xi, eta) in [(0.0, 0.0), (1.0, 1.0), (0.5, 0.25), (0.999, 0.001)] {
        let (a, b) = (patch.knots[0].first(), patch.knots[0].last());
        let (c, d) = (patch.knots[1].first(), patch.knots[1].last());
        let _ = patch.point(a + xi * (b - a), c + eta * (d - c));
    }
}
