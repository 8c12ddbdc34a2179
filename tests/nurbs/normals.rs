//! Jacobians and normals: det J > 0 at the Gauss points of the disks (zero
//! only at the full disk's corners), and outward normals on every side.

use crate::{det, dist, interior_side_params, with_refinements, DISK_C};
use iga_contact::geometry;
use iga_contact::nurbs::{NurbsPatch, Side};
use iga_contact::quadrature;

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

#[test]
fn jacobian_positive_at_gauss_points_of_disks() {
    let disks = [
        ("full disk", geometry::full_disk(DISK_C, 1.0).unwrap()),
        ("half disk", geometry::half_disk(DISK_C, 1.0).unwrap()),
    ];
    for (name, disk) in &disks {
        let cases = with_refinements(disk);
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

#[test]
fn quarter_annulus_outward_normals() {
    let ann = geometry::quarter_annulus(0.5, 1.0).unwrap();
    let cases = with_refinements(&ann);
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
        let cases = with_refinements(&patch);
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
