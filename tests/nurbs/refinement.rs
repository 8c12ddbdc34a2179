//! Exact refinement (h, p, k): the geometry and its circles are kept, the
//! structure is the expected one, and the local algorithms match a dense
//! collocation oracle.

use crate::{
    dist, invalid_field, nonuniform, refinements, test_geometries, with_refinements, Lcg, DISK_C,
};
use iga_contact::geometry;
use iga_contact::nurbs::{KnotVector, NurbsCurve, Side};

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
        let cases = with_refinements(&patch);
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
