//! The stiffness assembled straight into compressed columns (pattern from
//! control-point connectivity, values in place, in parallel) against the
//! element triplets summed by a general sparsity pattern.

use iga_contact::assembly::{load_vector, stiffness, stiffness_matrix, Load};
mod common;

use common::{HertzCase, TaylorCase};
use iga_contact::linsolve::Pattern;
use iga_contact::problem::Problem;

fn check(name: &str, p: &Problem) {
    let (trip, lift) = stiffness(&p.bodies, &p.map).unwrap();
    let want = Pattern::new(p.n(), &[&trip])
        .unwrap()
        .matrix(&[&trip.vals])
        .unwrap()
        .to_dense();
    let force = [0.3, -1.3e6];
    let forces = vec![force; p.bodies.len()];
    let bulk = stiffness_matrix(&p.bodies, &p.map, &[], &forces).unwrap();
    // the body force integrated with the stiffness equals the load vector's
    let loads: Vec<Load> = (0..p.bodies.len())
        .map(|body| Load::BodyForce { body, force })
        .collect();
    let want_load = load_vector(&p.bodies, &p.map, &loads).unwrap();
    let d = want_load
        .iter()
        .zip(&bulk.body_load)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    let size = want_load.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    assert!(d <= 1e-13 * size, "{name}: body load {d:.2e}");
    let (k, lift2) = (bulk.k, bulk.lift);
    let got = k.to_dense();
    let scale = want.norm_max();
    assert!(
        (&got - &want).norm_max() <= 1e-13 * scale,
        "{name}: {:.2e}",
        (&got - &want).norm_max() / scale
    );
    // no structural entry beyond the element couplings
    let s = k.symbolic();
    for j in 0..p.n() {
        for &i in &s.row_idx()[s.col_ptr()[j]..s.col_ptr()[j + 1]] {
            let coupled = trip
                .rows
                .iter()
                .zip(&trip.cols)
                .any(|(&r, &c)| r == i && c == j);
            assert!(coupled, "{name}: ({i}, {j}) is not an element coupling");
        }
    }
    let d = lift
        .iter()
        .zip(&lift2)
        .map(|(a, b)| (a - b).abs())
        .fold(0.0, f64::max);
    assert!(d <= 1e-13 * scale, "{name}: lift {d:.2e}");
    // the problem's matrix: the same values, contact couplings as zeros
    let pk = p.k.to_dense();
    assert!(
        (&pk - &want).norm_max() <= 1e-13 * scale,
        "{name}: Problem::k"
    );
}

#[test]
fn the_compressed_assembly_equals_the_triplet_assembly() {
    for (degree, elements) in [(2, 5), (3, 4), (4, 3)] {
        let p = HertzCase {
            degree,
            elements,
            ..HertzCase::default()
        }
        .build()
        .unwrap();
        check(&format!("hertz p = {degree}, {elements}²"), &p);
    }
    // C⁰ lines (repeated knots) and a Dirichlet lift
    let q2 = HertzCase {
        elements: 3,
        lagrange: Some(2),
        ..HertzCase::default()
    }
    .build()
    .unwrap();
    check("hertz Q2", &q2);
    let taylor = TaylorCase::default().build().unwrap();
    check("taylor", &taylor);
}
