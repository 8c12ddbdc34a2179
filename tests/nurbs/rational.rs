//! The rational basis of a patch and its side curves: partition of unity,
//! derivatives against central differences, the Jacobian, curve validation.

use crate::{dist, invalid_field, nonuniform, Lcg, DISK_C};
use iga_contact::geometry;
use iga_contact::nurbs::{KnotVector, NurbsCurve, NurbsPatch, Side};

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
