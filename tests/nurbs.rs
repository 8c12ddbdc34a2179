//! Verification of the NURBS layer (Eq. 1–2): knot vectors, the Cox–de Boor
//! basis, the rational basis of a patch, exact refinement (h, p, k), the
//! circle-exact geometry builders and the outward normals of their sides.
//!
//! Every tolerance here is absolute for geometry of radius about 1 unless
//! said otherwise. Random points come from a small deterministic LCG, so a
//! failure is reproducible.

use iga_contact::geometry;
use iga_contact::nurbs::{KnotVector, NurbsCurve, NurbsPatch, Side};
use iga_contact::quadrature;
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

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// The Bernstein polynomial B_{i,p}(u) and its first two derivatives.
fn bernstein(p: usize, i: usize, u: f64) -> [f64; 3] {
    let b = |q: usize, k: isize| -> f64 {
        if k < 0 || k as usize > q {
            0.0
        } else {
            let k = k as usize;
            binomial(q, k) * u.powi(k as i32) * (1.0 - u).powi((q - k) as i32)
        }
    };
    let i = i as isize;
    let pf = p as f64;
    let d1 = if p >= 1 {
        pf * (b(p - 1, i - 1) - b(p - 1, i))
    } else {
        0.0
    };
    let d2 = if p >= 2 {
        pf * (pf - 1.0) * (b(p - 2, i - 2) - 2.0 * b(p - 2, i - 1) + b(p - 2, i))
    } else {
        0.0
    };
    [b(p, i), d1, d2]
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

/// Gauss points (ξ, η) of every element of a patch, p+1 per direction.
fn gauss_points(patch: &NurbsPatch) -> Vec<(f64, f64, f64)> {
    let [p, q] = patch.degree();
    let mut pts = Vec::new();
    for (_, a0, b0) in patch.knots[0].spans() {
        for (_, a1, b1) in patch.knots[1].spans() {
            for (xi, w0) in quadrature::on_interval(p + 1, a0, b0) {
                for (eta, w1) in quadrature::on_interval(q + 1, a1, b1) {
                    pts.push((xi, eta, w0 * w1));
                }
            }
        }
    }
    pts
}

fn invalid_field(e: &Error) -> (&str, &str) {
    match e {
        Error::InvalidInput { field, value, .. } => (field.as_str(), value.as_str()),
        other => panic!("expected InvalidInput, got {other:?}"),
    }
}

// ---------------------------------------------------------------------------
// knot vectors
// ---------------------------------------------------------------------------

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

// ---------------------------------------------------------------------------
// the B-spline basis
// ---------------------------------------------------------------------------

#[test]
fn bspline_partition_of_unity_and_non_negativity() {
    let mut rng = Lcg::new(2);
    for p in 1..=5 {
        let k = nonuniform(p);
        let mut max_err: f64 = 0.0;
        for i in 0..2000 {
            // random points plus every knot value
            let u = if i < k.knots().len() {
                k.knots()[i]
            } else {
                rng.next()
            };
            let span = k.find_span(u);
            let d = k.basis_ders(span, u, p);
            assert_eq!(d.len(), p + 1);
            assert_eq!(d[0].len(), p + 1);
            let sum: f64 = d[0].iter().sum();
            max_err = max_err.max((sum - 1.0).abs());
            assert!(d[0].iter().all(|&v| v >= 0.0), "p={p} u={u}: {:?}", d[0]);
            // derivatives of a constant sum vanish
            for (order, row) in d.iter().enumerate().skip(1) {
                let scale: f64 = row.iter().map(|v| v.abs()).fold(1.0, f64::max);
                let s: f64 = row.iter().sum();
                assert!(
                    s.abs() <= 1e-12 * scale,
                    "p={p} u={u}: sum of derivatives of order {order} = {s}"
                );
            }
        }
        assert!(
            max_err <= 1e-14,
            "p={p}: partition of unity off by {max_err}"
        );
        // the ends interpolate
        let d = k.basis_ders(k.find_span(0.0), 0.0, 0);
        assert_eq!(d[0][0], 1.0);
        let d = k.basis_ders(k.find_span(1.0), 1.0, 0);
        assert_eq!(d[0][p], 1.0);
    }
}

#[test]
fn bspline_derivatives_match_central_differences() {
    let mut rng = Lcg::new(3);
    let h = 1e-6;
    for p in 1..=5 {
        let k = nonuniform(p);
        let mut worst: f64 = 0.0;
        for (span, a, b) in k.spans() {
            for i in 0..60 {
                // include both span ends: with the span fixed, basis_ders is
                // the span's polynomial piece, so differences across the
                // knot stay one-sided-free
                let u = match i {
                    0 => a,
                    1 => b,
                    _ => rng.range(a, b),
                };
                let d = k.basis_ders(span, u, 2);
                let dp = k.basis_ders(span, u + h, 1);
                let dm = k.basis_ders(span, u - h, 1);
                for order in 1..=2usize.min(p) {
                    let norm = d[order].iter().map(|v| v.abs()).fold(0.0, f64::max);
                    for j in 0..=p {
                        let fd = (dp[order - 1][j] - dm[order - 1][j]) / (2.0 * h);
                        let rel = (fd - d[order][j]).abs() / norm;
                        worst = worst.max(rel);
                        assert!(
                            rel <= 1e-6,
                            "p={p} span={span} u={u} order={order} j={j}: {} vs fd {fd}",
                            d[order][j]
                        );
                    }
                }
                if p == 1 {
                    assert!(d[2].iter().all(|&v| v == 0.0), "p=1 has no curvature");
                }
            }
        }
        // the same through find_span, at points at least 1e-4 from a knot
        for _ in 0..500 {
            let u = rng.range(1e-3, 1.0 - 1e-3);
            if k.knots().iter().any(|t| (t - u).abs() < 1e-4) {
                continue;
            }
            let s = k.find_span(u);
            assert_eq!(k.find_span(u + h), s);
            assert_eq!(k.find_span(u - h), s);
        }
        eprintln!("p={p}: worst relative FD mismatch {worst:.2e}");
    }
}

#[test]
fn bspline_on_one_span_is_bernstein() {
    let mut rng = Lcg::new(4);
    for p in 1..=5 {
        let mut knots = vec![0.0; p + 1];
        knots.extend(vec![1.0; p + 1]);
        let k = KnotVector::new(knots, p).unwrap();
        assert_eq!(k.n_basis(), p + 1);
        for i in 0..500 {
            let u = match i {
                0 => 0.0,
                1 => 1.0,
                _ => rng.next(),
            };
            let span = k.find_span(u);
            assert_eq!(span, p);
            let d = k.basis_ders(span, u, 2);
            for (order, row) in d.iter().enumerate() {
                for (j, &v) in row.iter().enumerate() {
                    let b = bernstein(p, j, u)[order];
                    let tol = 1e-14 * b.abs().max(1.0);
                    assert!(
                        (v - b).abs() <= tol,
                        "p={p} u={u} j={j} order={order}: {v} vs Bernstein {b}"
                    );
                }
            }
        }
        // orders above p are zero
        let d = k.basis_ders(p, 0.3, p + 2);
        assert_eq!(d.len(), p + 3);
        assert!(d[p + 1].iter().chain(&d[p + 2]).all(|&v| v == 0.0));
    }
}

#[test]
fn bspline_continuity_at_repeated_knots() {
    // A knot of multiplicity m leaves the basis C^{p-m}: values agree from
    // both sides everywhere (m <= p), first derivatives wherever m < p.
    for p in 1..=5 {
        let k = nonuniform(p);
        for (b, m) in k.breaks().iter().zip(k.multiplicities()) {
            if *b == 0.0 || *b == 1.0 {
                continue;
            }
            let right = k.find_span(*b);
            let left = k.spans().iter().rev().find(|s| s.2 == *b).unwrap().0;
            let dl = k.basis_ders(left, *b, 1);
            let dr = k.basis_ders(right, *b, 1);
            // global index of the local functions
            let mut gl = vec![[0.0; 2]; k.n_basis()];
            let mut gr = vec![[0.0; 2]; k.n_basis()];
            for j in 0..=p {
                gl[left - p + j] = [dl[0][j], dl[1][j]];
                gr[right - p + j] = [dr[0][j], dr[1][j]];
            }
            for i in 0..k.n_basis() {
                assert!((gl[i][0] - gr[i][0]).abs() < 1e-14, "p={p} knot {b} N_{i}");
                if m < p {
                    let s = gl[i][1].abs().max(1.0);
                    assert!(
                        (gl[i][1] - gr[i][1]).abs() < 1e-12 * s,
                        "p={p} knot {b} (m={m}) N_{i}': {} vs {}",
                        gl[i][1],
                        gr[i][1]
                    );
                }
            }
        }
    }
}

// ---------------------------------------------------------------------------
// the rational basis
// ---------------------------------------------------------------------------

/// A patch with uneven weights and non-uniform knots in both directions.
fn skewed_patch() -> NurbsPatch {
    let kx = nonuniform(3);
    let ky = nonuniform(2);
    let [n0, n1] = [kx.n_basis(), ky.n_basis()];
    let mut rng = Lcg::new(5);
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for j in 0..n1 {
        for i in 0..n0 {
            points.push([
                i as f64 / (n0 - 1) as f64 + 0.02 * rng.next(),
                j as f64 / (n1 - 1) as f64 + 0.02 * rng.next(),
            ]);
            weights.push(rng.range(0.3, 2.0));
        }
    }
    NurbsPatch::new([kx, ky], points, weights).unwrap()
}

#[test]
fn rational_basis_partition_of_unity_and_derivatives() {
    let h = 1e-6;
    let patches = [
        ("skewed", skewed_patch()),
        (
            "refined full disk",
            geometry::full_disk(DISK_C, 1.0)
                .unwrap()
                .k_refined(3, [3, 2])
                .unwrap(),
        ),
        ("half disk", geometry::half_disk(DISK_C, 1.0).unwrap()),
    ];
    let mut rng = Lcg::new(6);
    for (name, patch) in &patches {
        let mut worst: f64 = 0.0;
        for _ in 0..1000 {
            let (xi, eta) = (rng.next(), rng.next());
            let b = patch.basis(xi, eta);
            let [p, q] = patch.degree();
            assert_eq!(b.r.len(), (p + 1) * (q + 1));
            let sum: f64 = b.r.iter().sum();
            assert!((sum - 1.0).abs() <= 1e-14, "{name}: sum R = {sum}");
            assert!(b.r.iter().all(|&r| r >= 0.0), "{name}: negative R");
            let scale =
                b.dr.iter()
                    .flat_map(|d| d.iter())
                    .map(|v| v.abs())
                    .fold(0.0, f64::max);
            let dsum =
                b.dr.iter()
                    .fold([0.0, 0.0], |s, d| [s[0] + d[0], s[1] + d[1]]);
            assert!(dsum[0].abs().max(dsum[1].abs()) <= 1e-13 * scale, "{name}");

            // central differences in the same spans
            let spans = [patch.knots[0].find_span(xi), patch.knots[1].find_span(eta)];
            let bx = [
                patch.basis_in_spans(spans, xi + h, eta),
                patch.basis_in_spans(spans, xi - h, eta),
            ];
            let by = [
                patch.basis_in_spans(spans, xi, eta + h),
                patch.basis_in_spans(spans, xi, eta - h),
            ];
            for k in 0..b.r.len() {
                assert_eq!(bx[0].indices[k], b.indices[k]);
                let fd = [
                    (bx[0].r[k] - bx[1].r[k]) / (2.0 * h),
                    (by[0].r[k] - by[1].r[k]) / (2.0 * h),
                ];
                for (c, (&f, &an)) in fd.iter().zip(&b.dr[k]).enumerate() {
                    let rel = (f - an).abs() / scale;
                    worst = worst.max(rel);
                    assert!(
                        rel <= 1e-6,
                        "{name} ({xi}, {eta}) R_{k} d/dξ{c}: {an} vs fd {f}"
                    );
                }
            }

            // the Jacobian is the derivative of the map
            let j = patch.jacobian_of(&b);
            let xp = patch.map(&bx[0]);
            let xm = patch.map(&bx[1]);
            let yp = patch.map(&by[0]);
            let ym = patch.map(&by[1]);
            for r in 0..2 {
                let fd = [(xp[r] - xm[r]) / (2.0 * h), (yp[r] - ym[r]) / (2.0 * h)];
                for c in 0..2 {
                    assert!((fd[c] - j[r][c]).abs() <= 1e-6 * j[r][c].abs().max(1.0));
                }
            }
        }
        eprintln!("{name}: worst relative FD mismatch of dR {worst:.2e}");
    }
}

#[test]
fn rational_curve_basis_and_side_curves() {
    let mut rng = Lcg::new(7);
    let disk = geometry::full_disk(DISK_C, 1.0).unwrap();
    for side in Side::ALL {
        let c = disk.side_curve(side);
        for _ in 0..200 {
            let t = rng.next();
            let b = c.basis(t);
            assert!((b.r.iter().sum::<f64>() - 1.0).abs() <= 1e-14);
            assert!(b.dr.iter().sum::<f64>().abs() <= 1e-13);
            // the side curve is the patch restricted to the side
            let [xi, eta] = disk.side_point(side, t);
            let d = dist(c.point(t), disk.point(xi, eta));
            assert!(d <= 1e-14, "{side:?} t={t}: {d}");
            // and lies on the circle
            assert!((dist(c.point(t), DISK_C) - 1.0).abs() <= 1e-14);
            // tangent vs central differences
            let h = 1e-6;
            let (_, tan) = c.point_and_tangent(t);
            let (pp, pm) = (c.point(t + h), c.point(t - h));
            for r in 0..2 {
                let fd = (pp[r] - pm[r]) / (2.0 * h);
                assert!((fd - tan[r]).abs() <= 1e-6 * tan[r].abs().max(1.0));
            }
            // second derivative is normal-ish: for a circle, x'' has a
            // component −|x'|²/R along the outward radius
            let acc = c.second_derivative(t);
            let x = c.point(t);
            let radial = [x[0] - DISK_C[0], x[1] - DISK_C[1]];
            let along = acc[0] * radial[0] + acc[1] * radial[1];
            let speed2 = tan[0] * tan[0] + tan[1] * tan[1];
            assert!(
                (along + speed2).abs() <= 1e-4 * speed2,
                "{along} vs {speed2}"
            );
        }
    }

    // a curve: validation of the control net
    let k = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).unwrap();
    let e = NurbsCurve::new(k.clone(), vec![[0.0, 0.0]], vec![1.0, 1.0]).unwrap_err();
    assert_eq!(invalid_field(&e).0, "curve.control_points");
    let e = NurbsCurve::new(k, vec![[0.0, 0.0], [1.0, 0.0]], vec![1.0, -1.0]).unwrap_err();
    assert_eq!(invalid_field(&e), ("curve.weights[1]", "-1"));

    // segment
    let s = geometry::segment([-1.0, 0.0], [3.0, 2.0]).unwrap();
    assert!(dist(s.point(0.25), [0.0, 0.5]) < 1e-15);
}

// ---------------------------------------------------------------------------
// refinement
// ---------------------------------------------------------------------------

#[test]
fn refinement_keeps_the_geometry() {
    let mut worst_all: f64 = 0.0;
    for (name, patch, _) in test_geometries() {
        for (label, refined) in refinements(&patch) {
            let mut rng = Lcg::new(8);
            let mut worst: f64 = 0.0;
            for _ in 0..1000 {
                let (xi, eta) = (rng.next(), rng.next());
                let d = dist(refined.point(xi, eta), patch.point(xi, eta));
                worst = worst.max(d);
            }
            // the parameter corners too
            for xi in [0.0, 1.0] {
                for eta in [0.0, 1.0] {
                    let d = dist(refined.point(xi, eta), patch.point(xi, eta));
                    worst = worst.max(d);
                }
            }
            assert!(
                worst <= 1e-12,
                "{name}, {label}: geometry moved by {worst:.3e}"
            );
            assert!(refined.weights.iter().all(|&w| w > 0.0));
            eprintln!("{name:>24}, {label:<28}: max |Δx| = {worst:.2e}");
            worst_all = worst_all.max(worst);
        }
    }
    eprintln!("max refinement error over all cases: {worst_all:.2e}");
}

#[test]
fn refinement_keeps_circles_exact() {
    let mut worst_all: f64 = 0.0;
    for (name, patch, circles) in test_geometries() {
        let mut cases = vec![("original".to_string(), patch.clone())];
        cases.extend(refinements(&patch));
        for (label, refined) in cases {
            for &(side, c, r) in &circles {
                let mut rng = Lcg::new(9);
                let mut worst: f64 = 0.0;
                for i in 0..1000 {
                    let t = match i {
                        0 => 0.0,
                        1 => 1.0,
                        _ => rng.next(),
                    };
                    let [xi, eta] = refined.side_point(side, t);
                    let x = refined.point(xi, eta);
                    worst = worst.max((dist(x, c) - r).abs());
                    // the side curve agrees with the patch on its side
                    let y = refined.side_curve(side).point(t);
                    assert!(dist(x, y) <= 1e-13, "{name} {label} {side:?}");
                }
                assert!(
                    worst <= 1e-12,
                    "{name}, {label}, {side:?}: |x - c| - R up to {worst:.3e}"
                );
                worst_all = worst_all.max(worst);
            }
        }
    }
    eprintln!("max | |x - c| - R | over all circular sides: {worst_all:.2e}");
}

#[test]
fn refinement_structure_and_errors() {
    let disk = geometry::full_disk(DISK_C, 1.0).unwrap();
    let k = disk.k_refined(4, [5, 3]).unwrap();
    assert_eq!(k.degree(), [4, 4]);
    // maximal continuity: every interior knot simple
    for dir in 0..2 {
        let m = k.knots[dir].multiplicities();
        assert!(m[1..m.len() - 1].iter().all(|&m| m == 1), "{m:?}");
    }
    assert_eq!(k.knots[0].spans().len(), 5);
    assert_eq!(k.knots[1].spans().len(), 3);
    assert_eq!(k.n(), [4 + 5, 4 + 3]);

    // elevation then insertion (k) is smoother than insertion then
    // elevation (the inserted knot keeps multiplicity 2 in the latter)
    let hp = disk.insert_knots(0, &[0.5]).unwrap().elevate(0).unwrap();
    assert_eq!(hp.knots[0].multiplicities(), vec![4, 2, 4]);
    let ph = disk.elevate(0).unwrap().insert_knots(0, &[0.5]).unwrap();
    assert_eq!(ph.knots[0].multiplicities(), vec![4, 1, 4]);

    // k_refined never lowers a degree
    let q = disk.k_refined(1, [2, 2]).unwrap();
    assert_eq!(q.degree(), [2, 2]);

    // zero divisions is an input error naming the field
    let e = disk.k_refined(3, [0, 2]).unwrap_err();
    assert_eq!(invalid_field(&e), ("divisions[0]", "0"));

    // a space that does not contain the old one is rejected
    let coarse = KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2).unwrap();
    let fine = disk.insert_knots(1, &[0.4]).unwrap();
    assert!(fine.respaced(1, coarse.clone()).is_err(), "dropping a knot");
    let cubic = KnotVector::new(vec![0.0, 0.0, 0.0, 0.0, 0.4, 1.0, 1.0, 1.0, 1.0], 3).unwrap();
    assert!(
        fine.respaced(1, cubic).is_err(),
        "elevating without raising the knot's multiplicity"
    );
    let linear = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).unwrap();
    assert!(disk.respaced(0, linear).is_err(), "lowering the degree");
    let shifted = KnotVector::new(vec![0.0, 0.0, 0.0, 2.0, 2.0, 2.0], 2).unwrap();
    assert!(disk.respaced(0, shifted).is_err(), "changing the range");

    // curves refine the same way
    let arc = disk.side_curve(Side::EtaMin);
    let kv = arc.knots.elevated().with_inserted(&[0.2, 0.7]).unwrap();
    let fine_arc = arc.respaced(kv).unwrap();
    let mut rng = Lcg::new(10);
    for _ in 0..1000 {
        let t = rng.next();
        assert!(dist(fine_arc.point(t), arc.point(t)) <= 1e-13);
    }
}

/// The dense collocation matrix B[r][i] = N_i(τ_r).
fn collocation(k: &KnotVector, tau: &[f64]) -> nalgebra::DMatrix<f64> {
    let p = k.degree();
    let mut m = nalgebra::DMatrix::zeros(tau.len(), k.n_basis());
    for (r, &t) in tau.iter().enumerate() {
        let span = k.find_span(t);
        let n = k.basis_ders(span, t, 0);
        for a in 0..=p {
            m[(r, span - p + a)] = n[0][a];
        }
    }
    m
}

/// Test oracle: refinement as a dense collocation solve, the cubic method
/// the local algorithms replaced. If `new` contains the old space, the
/// coefficients in `new` are fixed by interpolation at its Greville points
/// (Schoenberg–Whitney), so this is an independent route to the same numbers.
fn respace_by_collocation(old: &KnotVector, new: &KnotVector, coef: &[[f64; 3]]) -> Vec<[f64; 3]> {
    let tau = new.greville();
    let c = nalgebra::DMatrix::from_fn(coef.len(), 3, |i, j| coef[i][j]);
    let values = collocation(old, &tau) * c;
    let d = collocation(new, &tau)
        .lu()
        .solve(&values)
        .expect("invertible");
    (0..new.n_basis())
        .map(|i| [d[(i, 0)], d[(i, 1)], d[(i, 2)]])
        .collect()
}

#[test]
fn local_refinement_matches_the_collocation_oracle() {
    let mut rng = Lcg::new(21);
    let mut worst: f64 = 0.0;
    let mut cases = 0;
    for p in 1..=5 {
        let old = nonuniform(p);
        for round in 0..12 {
            let n = old.n_basis();
            let points: Vec<[f64; 2]> = (0..n)
                .map(|_| [rng.range(-1.0, 1.0), rng.range(-1.0, 1.0)])
                .collect();
            let weights: Vec<f64> = (0..n).map(|_| rng.range(0.3, 2.0)).collect();
            let curve = NurbsCurve::new(old.clone(), points, weights).unwrap();
            // elevate by 0..=3, then insert 0..6 random knots (some repeated)
            let t = round % 4;
            let mut new = old.clone();
            for _ in 0..t {
                new = new.elevated();
            }
            let mut extra: Vec<f64> = (0..round / 2).map(|_| rng.range(0.01, 0.99)).collect();
            if round % 3 == 0 && p >= 2 {
                extra.push(0.41);
                extra.push(0.41);
            }
            if !extra.is_empty() {
                new = new.with_inserted(&extra).unwrap();
            }
            let local = curve.respaced(new.clone()).unwrap();
            let homogeneous: Vec<[f64; 3]> = curve
                .points
                .iter()
                .zip(&curve.weights)
                .map(|(q, &w)| [w * q[0], w * q[1], w])
                .collect();
            let oracle = respace_by_collocation(&old, &new, &homogeneous);
            assert_eq!(local.points.len(), oracle.len());
            for (i, o) in oracle.iter().enumerate() {
                let w = local.weights[i];
                let h = [w * local.points[i][0], w * local.points[i][1], w];
                for c in 0..3 {
                    worst = worst.max((h[c] - o[c]).abs());
                }
            }
            cases += 1;
        }
    }
    eprintln!("{cases} cases: max |local − collocation| = {worst:.2e}");
    assert!(
        worst <= 1e-12,
        "local refinement differs from the oracle by {worst:.3e}"
    );
}

#[test]
fn banded_interpolation_matches_a_dense_solve() {
    use iga_contact::nurbs::interpolate::Collocation;
    let mut rng = Lcg::new(22);
    for p in 1..=6 {
        let k = nonuniform(p);
        let tau = k.greville();
        let values: Vec<f64> = tau.iter().map(|_| rng.range(-1.0, 1.0)).collect();
        let mut banded = values.clone();
        Collocation::new(&k, &tau)
            .unwrap()
            .solve_in_place(&mut banded);
        let dense = collocation(&k, &tau)
            .lu()
            .solve(&nalgebra::DVector::from_vec(values.clone()))
            .unwrap();
        for (b, d) in banded.iter().zip(dense.iter()) {
            assert!((b - d).abs() <= 1e-12, "p = {p}: {b} vs {d}");
        }
        // and the spline takes the values
        for (t, v) in tau.iter().zip(&values) {
            let span = k.find_span(*t);
            let n = k.basis_ders(span, *t, 0);
            let s: f64 = (0..=p).map(|a| n[0][a] * banded[span - p + a]).sum();
            assert!((s - v).abs() <= 1e-12, "p = {p}: {s} vs {v}");
        }
    }
    // points outside the supports are refused, not solved
    let k = nonuniform(2);
    let mut tau = k.greville();
    let last = tau.len() - 1;
    tau[last] = tau[0];
    assert!(Collocation::new(&k, &tau).is_err());
}

// ---------------------------------------------------------------------------
// Jacobians and normals
// ---------------------------------------------------------------------------

#[test]
fn jacobian_positive_at_gauss_points_of_disks() {
    let disks = [
        ("full disk", geometry::full_disk(DISK_C, 1.0).unwrap()),
        ("half disk", geometry::half_disk(DISK_C, 1.0).unwrap()),
    ];
    for (name, disk) in &disks {
        let mut cases = vec![("original".to_string(), disk.clone())];
        cases.extend(refinements(disk));
        for (label, patch) in cases {
            let mut min_det = f64::INFINITY;
            let mut area = 0.0;
            for (xi, eta, w) in gauss_points(&patch) {
                let d = det(patch.jacobian(xi, eta));
                min_det = min_det.min(d);
                area += w * d;
            }
            assert!(min_det > 0.0, "{name} {label}: det J = {min_det:e}");
            // a low-order Gauss rule does not integrate the rational det J
            // exactly, but it is close
            let exact = if *name == "full disk" {
                std::f64::consts::PI
            } else {
                std::f64::consts::FRAC_PI_2
            };
            assert!(
                (area - exact).abs() < 2e-2 * exact,
                "{name} {label}: area {area} vs {exact}"
            );
        }
        // with a rich rule the area converges to π R² (or half)
        let fine = disk.k_refined(2, [8, 8]).unwrap();
        let mut area = 0.0;
        for (_, a0, b0) in fine.knots[0].spans() {
            for (_, a1, b1) in fine.knots[1].spans() {
                for (xi, w0) in quadrature::on_interval(10, a0, b0) {
                    for (eta, w1) in quadrature::on_interval(10, a1, b1) {
                        area += w0 * w1 * det(fine.jacobian(xi, eta));
                    }
                }
            }
        }
        let exact = if *name == "full disk" {
            std::f64::consts::PI
        } else {
            std::f64::consts::FRAC_PI_2
        };
        assert!(
            (area - exact).abs() < 1e-12,
            "{name}: area {area} vs {exact} ({:.2e})",
            area - exact
        );
    }
}

#[test]
fn full_disk_jacobian_vanishes_only_at_the_corners() {
    let disk = geometry::full_disk(DISK_C, 1.0).unwrap();
    for xi in [0.0, 1.0] {
        for eta in [0.0, 1.0] {
            assert!(det(disk.jacobian(xi, eta)).abs() < 1e-12);
        }
    }
    // mid-side points are regular
    for (xi, eta) in [(0.5, 0.0), (0.0, 0.5), (1.0, 0.5), (0.5, 1.0), (0.5, 0.5)] {
        assert!(det(disk.jacobian(xi, eta)) > 0.1);
    }
}

/// Side points strictly inside a side (singular corners excluded).
fn interior_side_params(n: usize) -> impl Iterator<Item = f64> {
    (1..n).map(move |i| i as f64 / n as f64)
}

#[test]
fn quarter_annulus_outward_normals() {
    let ann = geometry::quarter_annulus(0.5, 1.0).unwrap();
    let mut cases = vec![("original".to_string(), ann.clone())];
    cases.extend(refinements(&ann));
    for (label, patch) in cases {
        for t in (0..=100).map(|i| i as f64 / 100.0) {
            for side in Side::ALL {
                let [xi, eta] = patch.side_point(side, t);
                let b = patch.basis_in_spans(
                    [patch.knots[0].find_span(xi), patch.knots[1].find_span(eta)],
                    xi,
                    eta,
                );
                let x = patch.map(&b);
                let (n, len) = patch.side_frame(side, &b);
                let r = x[0].hypot(x[1]);
                let expected = match side {
                    Side::EtaMin => [-x[0] / r, -x[1] / r],
                    Side::EtaMax => [x[0] / r, x[1] / r],
                    Side::XiMin => [0.0, -1.0],
                    Side::XiMax => [-1.0, 0.0],
                };
                assert!(
                    dist(n, expected) < 1e-12,
                    "{label} {side:?} t={t}: n = {n:?}, expected {expected:?}"
                );
                assert!(len > 0.0);
                // |∂x/∂t| by central differences along the side
                let h = 1e-6;
                let (ta, tb) = ((t - h).max(0.0), (t + h).min(1.0));
                let [xa, ya] = patch.side_point(side, ta);
                let [xb, yb] = patch.side_point(side, tb);
                let fd = dist(patch.point(xb, yb), patch.point(xa, ya)) / (tb - ta);
                assert!((fd - len).abs() < 1e-5 * len, "{label} {side:?}");
            }
        }
    }
}

#[test]
fn disk_normals_point_away_from_the_centre() {
    let half = geometry::half_disk(DISK_C, 1.0).unwrap();
    let full = geometry::full_disk(DISK_C, 1.0).unwrap();
    // mirrored (left-handed) parametrisation: normals must still be outward
    let mirrored = full.transformed(|p| [2.0 * DISK_C[0] - p[0], p[1]]);
    assert!(det(mirrored.jacobian(0.5, 0.5)) < 0.0);
    let shapes = [
        (
            "half disk",
            half.clone(),
            vec![Side::EtaMin, Side::XiMax, Side::EtaMax],
        ),
        ("full disk", full.clone(), Side::ALL.to_vec()),
        ("mirrored full disk", mirrored, Side::ALL.to_vec()),
    ];
    for (name, patch, arcs) in shapes {
        let mut cases = vec![("original".to_string(), patch.clone())];
        cases.extend(refinements(&patch));
        for (label, p) in cases {
            for &side in &arcs {
                for t in interior_side_params(64) {
                    let [xi, eta] = p.side_point(side, t);
                    let b = p.basis(xi, eta);
                    let x = p.map(&b);
                    let (n, _) = p.side_frame(side, &b);
                    let radial = [x[0] - DISK_C[0], x[1] - DISK_C[1]];
                    assert!(
                        dist(n, radial) < 1e-11,
                        "{name} {label} {side:?} t={t}: n = {n:?}, radial {radial:?}"
                    );
                }
            }
        }
    }
    // the diameter of the half disk faces −x
    for t in interior_side_params(16) {
        let b = half.basis(0.0, t);
        let (n, _) = half.side_frame(Side::XiMin, &b);
        assert!(dist(n, [-1.0, 0.0]) < 1e-14, "{n:?}");
    }
}

// ---------------------------------------------------------------------------
// the half disk
// ---------------------------------------------------------------------------

#[test]
fn half_disk_sides() {
    let c = [0.3, 1.7];
    let r = 2.0;
    let half = geometry::half_disk(c, r).unwrap();
    assert_eq!(half.degree(), [2, 2]);
    assert_eq!(half.knots[0].knots(), &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0][..]);

    // xi_min is the straight diameter on x = cx, from bottom to top
    for &a in &half.side_indices(Side::XiMin) {
        assert!((half.points[a][0] - c[0]).abs() < 1e-15);
    }
    let mut rng = Lcg::new(11);
    let mut ts: Vec<f64> = (0..1000).map(|_| rng.next()).collect();
    ts.sort_by(f64::total_cmp);
    let mut last_y = f64::NEG_INFINITY;
    for &t in &ts {
        let x = half.point(0.0, t);
        assert!((x[0] - c[0]).abs() < 1e-14, "t={t}: x = {x:?}");
        assert!(x[1] >= last_y, "diameter not monotone");
        assert!(x[1] >= c[1] - r - 1e-14 && x[1] <= c[1] + r + 1e-14);
        last_y = x[1];
    }
    assert!(dist(half.point(0.0, 0.0), [c[0], c[1] - r]) < 1e-14);
    assert!(dist(half.point(0.0, 1.0), [c[0], c[1] + r]) < 1e-14);
    // straight: the tangent of the diameter is vertical everywhere
    for t in interior_side_params(32) {
        let j = half.jacobian(0.0, t);
        assert!(j[0][1].abs() < 1e-13 * j[1][1].abs() && j[1][1] > 0.0);
    }

    // eta_min starts at the lowest point and runs to the 315° point
    let s = std::f64::consts::FRAC_1_SQRT_2;
    assert!(dist(half.point(0.0, 0.0), [c[0], c[1] - r]) < 1e-14);
    assert!(dist(half.point(1.0, 0.0), [c[0] + r * s, c[1] - r * s]) < 1e-14);
    // xi_max: from 315° to 45°; eta_max: from the top to 45°
    assert!(dist(half.point(1.0, 1.0), [c[0] + r * s, c[1] + r * s]) < 1e-14);
    assert!(dist(half.point(0.0, 1.0), [c[0], c[1] + r]) < 1e-14);
    // the lowest point really is the lowest point of the body
    let mut rng = Lcg::new(12);
    for _ in 0..1000 {
        let x = half.point(rng.next(), rng.next());
        assert!(x[1] >= c[1] - r - 1e-14);
        assert!(x[0] >= c[0] - 1e-14, "the half disk is x >= cx");
        assert!(dist(x, c) <= r + 1e-14);
    }

    // the half disk is the right half of the full disk, point for point:
    // half(ξ, η) = full((1 + ξ)/2, η)
    let full = geometry::full_disk(c, r).unwrap();
    let mut rng = Lcg::new(13);
    for _ in 0..1000 {
        let (xi, eta) = (rng.next(), rng.next());
        let d = dist(half.point(xi, eta), full.point(0.5 * (1.0 + xi), eta));
        assert!(d < 1e-13 * r, "{d:e}");
    }

    // the two flat corners on the arc (ξ = 1) are singular, the others not
    assert!(det(half.jacobian(1.0, 0.0)).abs() < 1e-12);
    assert!(det(half.jacobian(1.0, 1.0)).abs() < 1e-12);
    assert!(det(half.jacobian(0.0, 0.0)) > 0.1);
    assert!(det(half.jacobian(0.0, 1.0)) > 0.1);
}

#[test]
fn geometry_builders_validate_input() {
    let e = geometry::full_disk([0.0, 0.0], -1.0).unwrap_err();
    assert_eq!(invalid_field(&e), ("radius", "-1"));
    let e = geometry::half_disk([0.0, 0.0], f64::NAN).unwrap_err();
    assert_eq!(invalid_field(&e).0, "radius");
    let e = geometry::quarter_annulus(1.0, 0.5).unwrap_err();
    assert_eq!(invalid_field(&e).0, "outer_radius - inner_radius");
    let e = geometry::quarter_annulus(0.0, 0.5).unwrap_err();
    assert_eq!(invalid_field(&e).0, "inner_radius");
    let e = geometry::rectangle(0.0, 0.0, -1.0, 1.0).unwrap_err();
    assert_eq!(invalid_field(&e).0, "width");
    let e = geometry::rectangle(0.0, f64::INFINITY, 1.0, 1.0).unwrap_err();
    assert_eq!(invalid_field(&e).0, "y0");

    // the rectangle is the identity-like bilinear map
    let r = geometry::rectangle(1.0, 2.0, 4.0, 3.0).unwrap();
    assert!(dist(r.point(0.5, 0.25), [2.5, 2.25]) < 1e-15);
    let j = r.jacobian(0.3, 0.9);
    let expected = [[3.0, 0.0], [0.0, 1.0]];
    for (row, erow) in j.iter().zip(expected) {
        for (v, e) in row.iter().zip(erow) {
            assert!((v - e).abs() < 1e-14, "{j:?}");
        }
    }
}
