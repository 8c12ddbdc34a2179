//! The multi-patch builders' geometry: the five-patch disks and the
//! four-patch half disk are exact (area and arc lengths to round-off) and
//! regular (det J > 0 at every Gauss point).

use crate::{bodies_q, rel, C, R};
use iga_contact::dofs::Body;
use iga_contact::geometry::{disk_5, half_disk_4};
use iga_contact::nurbs::Side;
use iga_contact::quadrature;
use std::f64::consts::PI;

/// Area by Gauss quadrature of every element (which fails where det J ≤ 0);
/// det J is rational, so only a rule well above p + 1 makes it exact to
/// round-off.
fn area(bodies: &[Body]) -> f64 {
    bodies
        .iter()
        .flat_map(|b| {
            b.space
                .elements
                .iter()
                .map(|e| b.space.quadrature(e).unwrap())
        })
        .flatten()
        .map(|q| {
            assert!(q.shape.det_j > 0.0);
            q.weight
        })
        .sum()
}

/// Length of the pieces of a boundary, by Gauss quadrature of |∂x/∂t|.
fn length(bodies: &[Body], pieces: &[(usize, Side)]) -> f64 {
    pieces
        .iter()
        .map(|&(b, side)| {
            let s = &bodies[b].space;
            s.boundary(side)
                .iter()
                .map(|be| {
                    quadrature::on_interval(24, be.range[0], be.range[1])
                        .iter()
                        .map(|&(t, w)| w * s.side_shape(be, t).unwrap().2)
                        .sum::<f64>()
                })
                .sum::<f64>()
        })
        .sum()
}

#[test]
fn five_patch_disk_is_exact_and_regular() {
    let mp = disk_5(C, R).unwrap();
    assert_eq!(mp.patches.len(), 5);
    for elements in [[1, 1], [4, 2], [8, 8]] {
        let b = bodies_q(&mp, 2, elements, Some(14));
        assert!(rel(area(&b), PI * R * R) < 1e-12, "{}", area(&b));
        let arc = length(&b, mp.boundary("arc").unwrap());
        assert!(rel(arc, 2.0 * PI * R) < 1e-12, "{arc}");
        let bottom = length(&b, mp.boundary("arc_bottom").unwrap());
        assert!(rel(bottom, PI * R / 2.0) < 1e-12, "{bottom}");
    }
}

#[test]
fn four_patch_half_disk_is_exact_and_regular() {
    let mp = half_disk_4(C, R).unwrap();
    for elements in [[1, 1], [3, 2], [8, 8]] {
        let b = bodies_q(&mp, 2, elements, Some(14));
        assert!(rel(area(&b), PI * R * R / 2.0) < 1e-12, "{}", area(&b));
        let arc = length(&b, mp.boundary("arc").unwrap());
        assert!(rel(arc, PI * R) < 1e-12, "{arc}");
        let straight = length(&b, mp.boundary("straight").unwrap());
        assert!(rel(straight, 2.0 * R) < 1e-12, "{straight}");
        let lower = length(&b, mp.boundary("arc_lower").unwrap());
        assert!(rel(lower, 0.75 * PI * R) < 1e-12, "{lower}");
        // every control point of the straight side lies on x = cx
        for &(p, side) in mp.boundary("straight").unwrap() {
            for a in b[p].space.patch.side_indices(side) {
                assert!((b[p].space.patch.points[a][0] - C[0]).abs() < 1e-15);
            }
        }
    }
}

#[test]
fn diagonal_five_patch_disk_is_exact_with_corners_on_the_centre_line() {
    let mp = iga_contact::geometry::disk_5_diagonal(C, R).unwrap();
    for elements in [[1, 1], [4, 2], [8, 8]] {
        let b = bodies_q(&mp, 2, elements, Some(14));
        assert!(rel(area(&b), PI * R * R) < 1e-12, "{}", area(&b));
        let arc = length(&b, mp.boundary("arc").unwrap());
        assert!(rel(arc, 2.0 * PI * R) < 1e-12, "{arc}");
        for half in ["arc_lower", "arc_upper", "arc_left", "arc_right"] {
            let l = length(&b, mp.boundary(half).unwrap());
            assert!(rel(l, PI * R) < 1e-12, "{half}: {l}");
        }
    }
    // the lower half runs from 180° to 360°: from (cx − R, cy) through the
    // lowest point, a patch corner, to (cx + R, cy)
    let lower = mp.boundary("arc_lower").unwrap();
    let (first, last) = (lower[0], lower[lower.len() - 1]);
    let start = mp.patches[first.0].side_curve(first.1);
    let end = mp.patches[last.0].side_curve(last.1);
    let at = |c: &iga_contact::nurbs::NurbsCurve, t: f64| c.point(t);
    let a = at(&start, start.knots.first());
    let z = at(&end, end.knots.last());
    let lowest = at(&start, start.knots.last());
    for (got, want) in [
        (a, [C[0] - R, C[1]]),
        (z, [C[0] + R, C[1]]),
        (lowest, [C[0], C[1] - R]),
    ] {
        assert!(
            (got[0] - want[0]).hypot(got[1] - want[1]) < 1e-15,
            "{got:?}"
        );
    }
    // the core's top and bottom corners lie on the vertical centre line
    let core = &mp.patches[0];
    let on_line = core
        .points
        .iter()
        .filter(|p| (p[0] - C[0]).abs() < 1e-15 && (p[1] - C[1]).abs() > 0.5 * R)
        .count();
    assert_eq!(on_line, 2);
}
