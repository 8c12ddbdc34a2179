//! Interfaces between patches: the joined DOF map reproduces affine fields
//! across them, the folded stiffness equals a direct assembly into the
//! shared unknowns, non-matching interfaces are tied and partial ones
//! refused.

use crate::{bodies, bodies_q, C, R};
use iga_contact::assembly;
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry::{disk_5, half_disk_4};
use iga_contact::linsolve::{mul, Factoriser, Method, Pattern};
use iga_contact::material::Formulation;
use iga_contact::nurbs::Side;
use iga_contact::problem::Problem;
use iga_contact::space::Space;

/// The joined map of all patches of `b`, every control point of the
/// boundary `outer` set to `field`.
fn joined(b: &[Body], outer: &[(usize, Side)], field: impl Fn([f64; 2]) -> [f64; 2]) -> DofMap {
    let all: Vec<usize> = (0..b.len()).collect();
    let mut builder = DofMap::builder(b);
    builder.join("disk", &all).unwrap();
    for &(p, side) in outer {
        builder.fix_side_field(p, side, &field).unwrap();
    }
    builder.build()
}

#[test]
fn affine_field_is_reproduced_across_the_interfaces() {
    let a = [[1.0e-3, -2.5e-3], [0.7e-3, 1.8e-3]];
    let field = move |x: [f64; 2]| {
        [
            a[0][0] * x[0] + a[0][1] * x[1] + 0.4e-3,
            a[1][0] * x[0] + a[1][1] * x[1] - 0.9e-3,
        ]
    };
    for (mp, outer) in [
        (disk_5(C, R).unwrap(), "arc"),
        (half_disk_4(C, R).unwrap(), "arc"),
    ] {
        let mut outer = mp.boundary(outer).unwrap().to_vec();
        if let Some(s) = mp.boundary("straight") {
            outer.extend_from_slice(s);
        }
        // the rational map makes p + 1 points inexact for ∫ ∇v det J, which
        // would blur an exact reproduction by ~1e-9; 12 points remove that
        let b = bodies_q(&mp, 3, [5, 3], Some(12));
        let map = joined(&b, &outer, field);
        // shared control points are one unknown: fewer free DOFs than the
        // patches' interior ones added up
        let split = map.unlinked().0;
        assert!(map.n_free() < split.n_free());
        let problem = Problem::new(b, map, &[], Vec::new()).unwrap();
        let f = Factoriser::default()
            .factor(&problem.k, Method::Cholesky)
            .unwrap();
        let u = f.solve(&problem.rhs).unwrap();
        let full = problem.map.expand(&u);
        let mut worst = 0.0_f64;
        for (bi, body) in problem.bodies.iter().enumerate() {
            for (cp, x) in body.space.patch.points.iter().enumerate() {
                let d = problem.map.cp_displacement(&full, bi, cp);
                let e = field(*x);
                worst = worst.max((d[0] - e[0]).hypot(d[1] - e[1]));
            }
            // and at the Gauss points, through the shape functions
            for el in &body.space.elements {
                for q in body.space.quadrature(el).unwrap() {
                    let d = assembly::displacement_at(&problem.map, &full, bi, &el.cps, &q.shape);
                    let e = field(q.shape.x);
                    worst = worst.max((d[0] - e[0]).hypot(d[1] - e[1]));
                }
            }
        }
        // relative to the field's size, 3e-3 · R
        assert!(worst < 1e-12 * 6e-4, "affine field off by {worst:e}");
    }
}

#[test]
fn folded_stiffness_equals_the_joined_triplet_assembly() {
    // Two independent assemblies of the joined stiffness: per patch on the
    // split map then folded (the solver's), and element triplets scattered
    // straight into the shared unknowns.
    let mp = disk_5(C, R).unwrap();
    let b = bodies(&mp, 2, [4, 3]);
    let outer = mp.boundary("arc_bottom").unwrap().to_vec();
    let map = joined(&b, &outer, |_| [0.0, 0.0]);
    let (trip, _) = assembly::stiffness(&b, &map).unwrap();
    let k2 = Pattern::new(map.n_free(), &[&trip])
        .unwrap()
        .matrix(&[&trip.vals])
        .unwrap();
    let problem = Problem::new(b, map, &[], Vec::new()).unwrap();
    let n = problem.n();
    let x: Vec<f64> = (0..n).map(|i| ((i * 37 % 101) as f64).sin()).collect();
    let (y1, y2) = (mul(&problem.k, &x), mul(&k2, &x));
    let scale = y2.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
    let diff = y1
        .iter()
        .zip(&y2)
        .fold(0.0_f64, |m, (a, b)| m.max((a - b).abs()));
    assert!(diff < 1e-12 * scale, "{diff:e} of {scale:e}");
}

#[test]
fn non_matching_interfaces_are_tied_and_partial_ones_refused_naming_body_and_patches() {
    let mp = disk_5(C, R).unwrap();
    let mut b = bodies(&mp, 2, [4, 3]);
    // the core refined differently: its sides no longer match the arcs',
    // and are tied instead
    b[0] = bodies(&mp, 2, [5, 3]).swap_remove(0);
    assert_eq!(b[0].space.n_elements(), [5, 5]);
    let all: Vec<usize> = (0..b.len()).collect();
    let mut builder = DofMap::builder(&b);
    builder.join("disk", &all).expect("tied");
    assert_eq!(builder.build().ties().len(), 4);
    // a block beside the lower half of another's right side: the sides
    // meet over only part of their length
    let material = b[0].material;
    let block = |x0: f64, y1: f64| Body {
        name: "blocks".into(),
        space: Space::new(
            iga_contact::geometry::rectangle(x0, 0.0, x0 + 1.0, y1).unwrap(),
            None,
        )
        .unwrap(),
        material,
        formulation: Formulation::Displacement,
    };
    let two = [block(0.0, 1.0), block(1.0, 0.5)];
    let e = DofMap::builder(&two)
        .join("blocks", &[0, 1])
        .err()
        .expect("refused");
    let msg = e.to_string();
    assert!(
        msg.contains("blocks") && msg.contains("patches 0") && msg.contains("part of their length"),
        "{msg}"
    );
    assert!(!msg.contains('\n'), "{msg}");
}
