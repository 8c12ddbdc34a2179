//! Verification of the NURBS layer (Eq. 1–2): knot vectors, the Cox–de Boor
//! basis, the rational basis of a patch, exact refinement (h, p, k), the
//! circle-exact geometry builders and the outward normals of their sides.
//!
//! Every tolerance here is absolute for geometry of radius about 1 unless
//! said otherwise. Random points come from a small deterministic LCG, so a
//! failure is reproducible.
//!
//! One module per concern: [`knots`] (knot vectors), [`bspline`] (the
//! Cox–de Boor basis), [`rational`] (the rational basis and side curves),
//! [`refinement`] (h, p, k and the collocation oracle), [`normals`]
//! (Jacobians and outward normals), [`builders`] (the half disk and the
//! builders' validation); the helpers they share are here.

mod bspline;
mod builders;
mod knots;
mod normals;
mod rational;
mod refinement;

use iga_contact::geometry;
use iga_contact::nurbs::{KnotVector, NurbsPatch, Side};
use iga_contact::Error;

// ---------------------------------------------------------------------------
// helpers
// ---------------------------------------------------------------------------

/// Knuth's MMIX linear congruential generator; `next` is uniform in [0, 1).
struct Lcg(u64);

impl Lcg {
    fn new(seed: u64) -> Self {
        Lcg(seed ^ 0x9E37_79B9_7F4A_7C15)
    }
    fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6_364_136_223_846_793_005)
            .wrapping_add(1_442_695_040_888_963_407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
    /// Uniform in [a, b].
    fn range(&mut self, a: f64, b: f64) -> f64 {
        a + (b - a) * self.next()
    }
}

fn dist(a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - b[0]).hypot(a[1] - b[1])
}

fn det(j: [[f64; 2]; 2]) -> f64 {
    j[0][0] * j[1][1] - j[0][1] * j[1][0]
}

/// A non-uniform open knot vector of degree `p` on [0, 1] with interior
/// knots repeated up to the degree (C^0 where the multiplicity is p).
fn nonuniform(p: usize) -> KnotVector {
    let breaks = [0.13, 0.3, 0.55, 0.62, 0.9];
    let mult = [1, 2.min(p), p, 1, (p - 1).max(1)];
    let mut k = vec![0.0; p + 1];
    for (b, m) in breaks.iter().zip(mult) {
        k.extend(std::iter::repeat_n(*b, m));
    }
    k.extend(std::iter::repeat_n(1.0, p + 1));
    KnotVector::new(k, p).expect("valid non-uniform knots")
}

/// The four test geometries of radius about one, with a name, and a list
/// of (side, centre, radius) for the sides that are circular arcs.
type Circles = Vec<(Side, [f64; 2], f64)>;

const DISK_C: [f64; 2] = [0.25, -0.5];

fn test_geometries() -> Vec<(&'static str, NurbsPatch, Circles)> {
    let all_sides = Side::ALL.iter().map(|&s| (s, DISK_C, 1.0)).collect();
    vec![
        (
            "full disk",
            geometry::full_disk(DISK_C, 1.0).unwrap(),
            all_sides,
        ),
        (
            "half disk",
            geometry::half_disk(DISK_C, 1.0).unwrap(),
            vec![
                (Side::EtaMin, DISK_C, 1.0),
                (Side::XiMax, DISK_C, 1.0),
                (Side::EtaMax, DISK_C, 1.0),
            ],
        ),
        (
            "quarter annulus",
            geometry::quarter_annulus(0.5, 1.0).unwrap(),
            vec![
                (Side::EtaMin, [0.0, 0.0], 0.5),
                (Side::EtaMax, [0.0, 0.0], 1.0),
            ],
        ),
        (
            "distorted quadrilateral",
            geometry::quadrilateral([[0.0, 0.0], [1.1, 0.2], [0.9, 1.0], [-0.1, 0.8]]).unwrap(),
            vec![],
        ),
    ]
}

/// Interior knots to insert in direction `dir` of `patch`, with one knot
/// repeated when the degree allows it.
fn knots_to_insert(patch: &NurbsPatch, dir: usize) -> Vec<f64> {
    let mut k = vec![0.3, 0.5, 0.77];
    if patch.degree()[dir] >= 2 {
        k.push(0.5);
    }
    k
}

/// Every refinement the tests apply, with a label.
fn refinements(patch: &NurbsPatch) -> Vec<(String, NurbsPatch)> {
    let mut out = Vec::new();
    let h0 = patch.insert_knots(0, &knots_to_insert(patch, 0)).unwrap();
    let h = h0.insert_knots(1, &knots_to_insert(patch, 1)).unwrap();
    out.push(("h (insert_knots)".to_string(), h.clone()));
    let p1 = patch.elevate(0).unwrap().elevate(1).unwrap();
    out.push(("p (elevate once)".to_string(), p1.clone()));
    out.push((
        "p (elevate twice)".to_string(),
        p1.elevate(0).unwrap().elevate(1).unwrap(),
    ));
    out.push((
        "h then p".to_string(),
        h.elevate(0).unwrap().elevate(1).unwrap(),
    ));
    for (deg, div) in [(4, [5, 3]), (3, [2, 7]), (2, [4, 4]), (5, [3, 2])] {
        out.push((
            format!("k (k_refined({deg}, {div:?}))"),
            patch.k_refined(deg, div).unwrap(),
        ));
    }
    out
}

/// `patch` itself (labelled "original") and every refinement of it.
fn with_refinements(patch: &NurbsPatch) -> Vec<(String, NurbsPatch)> {
    let mut cases = vec![("original".to_string(), patch.clone())];
    cases.extend(refinements(patch));
    cases
}

fn invalid_field(e: &Error) -> (&str, &str) {
    match e {
        Error::InvalidInput { field, value, .. } => (field.as_str(), value.as_str()),
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

/// Side points strictly inside a side (singular corners excluded).
fn interior_side_params(n: usize) -> impl Iterator<Item = f64> {
    (1..n).map(move |i| i as f64 / n as f64)
}
