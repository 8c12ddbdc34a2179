//! The geometry builders: the half disk's sides, corners and relation to
//! the full disk, and the validation of every builder's input.

use crate::{det, dist, interior_side_params, invalid_field, Lcg};
use iga_contact::geometry;
use iga_contact::nurbs::Side;

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
