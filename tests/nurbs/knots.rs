//! Knot vectors: validation naming the field and value, and the queries.

use crate::{invalid_field, nonuniform, Lcg};
use iga_contact::nurbs::KnotVector;

#[test]
fn knot_validation_rejects_bad_input_and_names_field_and_value() {
    // decreasing
    let e = KnotVector::new(vec![0.0, 0.0, 0.0, 0.6, 0.4, 1.0, 1.0, 1.0], 2).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots[4]", "0.4"), "{e}");
    assert!(e.to_string().contains("non-decreasing"), "{e}");
    assert!(
        e.to_string().contains("knots[4]") && e.to_string().contains("0.4"),
        "{e}"
    );

    // non-open start (end knot repeated p times only)
    let e = KnotVector::new(vec![0.0, 0.0, 0.5, 1.0, 1.0, 1.0], 2).unwrap_err();
    assert_eq!(invalid_field(&e).0, "knots[0]", "{e}");
    assert!(e.to_string().contains("open"), "{e}");
    // non-open end (repeated p + 2 times)
    let e = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0, 1.0], 2).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots[3]", "1"), "{e}");
    // non-open end (repeated once)
    let e = KnotVector::new(vec![0.0, 0.0, 0.0, 0.3, 0.6, 1.0], 2).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots[5]", "1"), "{e}");

    // interior multiplicity above the degree
    let e = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 0.5, 1.0, 1.0, 1.0], 2).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots[3]", "0.5"), "{e}");
    assert!(e.to_string().contains("multiplicity 3"), "{e}");
    // ... while multiplicity p is accepted (C^0)
    KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0], 2).unwrap();

    // NaN, interior and at the start; infinity
    let e = KnotVector::new(vec![0.0, 0.0, f64::NAN, 1.0, 1.0], 1).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots[2]", "NaN"), "{e}");
    let e = KnotVector::new(vec![f64::NAN, 0.0, 1.0, 1.0], 1).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots[0]", "NaN"), "{e}");
    let e = KnotVector::new(vec![0.0, 0.0, 1.0, f64::INFINITY], 1).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots[3]", "inf"), "{e}");

    // degree 0
    let e = KnotVector::new(vec![0.0, 1.0], 0).unwrap_err();
    assert_eq!(invalid_field(&e), ("knots.degree", "0"), "{e}");
    assert!(e.to_string().contains("knots.degree"), "{e}");

    // too short, empty range
    assert!(KnotVector::new(vec![0.0, 0.0, 1.0], 1).is_err());
    assert!(KnotVector::new(vec![1.0, 1.0, 1.0, 1.0], 1).is_err());

    // the field name is passed through by `validated`
    let e = KnotVector::validated(vec![0.0, 0.0, 1.0, 0.5], 1, "patch.knots_xi").unwrap_err();
    assert_eq!(invalid_field(&e).0, "patch.knots_xi[3]", "{e}");

    // knot insertion re-validates: inserting past multiplicity p fails
    let k = KnotVector::new(vec![0.0, 0.0, 0.0, 0.5, 1.0, 1.0, 1.0], 2).unwrap();
    assert!(k.with_inserted(&[0.5, 0.5]).is_err());
    assert!(k.with_inserted(&[0.5]).is_ok());
}

#[test]
fn knot_vector_queries() {
    let k = nonuniform(3);
    assert_eq!(k.degree(), 3);
    assert_eq!(k.n_basis(), k.knots().len() - 4);
    assert_eq!(k.breaks(), vec![0.0, 0.13, 0.3, 0.55, 0.62, 0.9, 1.0]);
    assert_eq!(k.multiplicities(), vec![4, 1, 2, 3, 1, 2, 4]);
    assert_eq!(k.spans().len(), 6);

    // find_span: knots[s] <= u < knots[s+1] inside, the last span at the end
    let mut rng = Lcg::new(1);
    for _ in 0..1000 {
        let u = rng.next();
        let s = k.find_span(u);
        assert!(
            k.knots()[s] <= u && u < k.knots()[s + 1],
            "u = {u}, span {s}"
        );
    }
    for (s, a, _) in k.spans() {
        assert_eq!(k.find_span(a), s, "span starting at a knot");
    }
    let last = k.find_span(1.0);
    assert!(k.knots()[last] < k.knots()[last + 1] && k.knots()[last + 1] == 1.0);
    assert_eq!(k.find_span(-0.5), 3, "clamped below");
    assert_eq!(k.find_span(1.5), last, "clamped above");

    // Greville points: strictly increasing, from first to last knot
    let g = k.greville();
    assert_eq!(g.len(), k.n_basis());
    assert_eq!(g[0], 0.0);
    assert!((g[g.len() - 1] - 1.0).abs() < 1e-15);
    assert!(g.windows(2).all(|w| w[0] < w[1]), "{g:?}");

    // elevation: degree + 1 and every multiplicity + 1
    let e = k.elevated();
    assert_eq!(e.degree(), 4);
    assert_eq!(e.breaks(), k.breaks());
    let m: Vec<usize> = k.multiplicities().iter().map(|m| m + 1).collect();
    assert_eq!(e.multiplicities(), m);

    // uniform and subdivision
    let u = KnotVector::uniform(2, 4, 1).unwrap();
    assert_eq!(
        u.knots(),
        &[0.0, 0.0, 0.0, 0.25, 0.5, 0.75, 1.0, 1.0, 1.0][..]
    );
    let c0 = KnotVector::uniform(2, 2, 0).unwrap();
    assert_eq!(c0.knots(), &[0.0, 0.0, 0.0, 0.5, 0.5, 1.0, 1.0, 1.0][..]);
    assert!(KnotVector::uniform(2, 2, 2).is_err());
    assert!(KnotVector::uniform(2, 0, 1).is_err());
    assert_eq!(c0.subdivision_knots(2), vec![0.25, 0.75]);
    assert!(c0.subdivision_knots(1).is_empty());
}
