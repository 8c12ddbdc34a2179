//! The B-spline basis (Cox–de Boor): partition of unity, derivatives
//! against central differences and Bernstein polynomials, continuity at
//! repeated knots.

use crate::{nonuniform, Lcg};
use iga_contact::nurbs::KnotVector;

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
