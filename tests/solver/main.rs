//! The default solver: large initial gaps, zero load, the round-off
//! stopping rule, iteration counts, and why the tied start (17) is not the
//! default.
//!
//! One module per concern: [`gaps`] (large initial gaps and zero load),
//! [`iterations`] (the stopping rule and iteration counts), [`kernels`]
//! (why the tied start is not the default; the layer space's kernels),
//! [`hard_cases`] (the stability atlas's hard cases). The block above the
//! floor they share is here.

#[path = "../common/mod.rs"]
mod common;

mod gaps;
mod hard_cases;
mod iterations;
mod kernels;

use iga_contact::assembly::Load;
use iga_contact::contact::{ContactPair, Master};
use iga_contact::dofs::{Body, DofMap};
use iga_contact::geometry;
use iga_contact::material::{Material, Plane};
use iga_contact::nurbs::Side;
use iga_contact::problem::Problem;

const WIDTH: f64 = 1.0;
const HEIGHT: f64 = 0.5;
const PRESSURE: f64 = 1e7;

/// A block [0, 1] × [gap, gap + 0.5] held only by rollers on its left
/// edge (u_x = 0), pushed down by a pressure on its top, above the rigid
/// floor y = 0: only a rigid motion closes the gap.
fn block(gap: f64, elements: [usize; 2], pressure: f64) -> Problem {
    let patch = geometry::rectangle(0.0, gap, WIDTH, gap + HEIGHT)
        .unwrap()
        .k_refined(2, elements)
        .unwrap();
    let bodies = vec![Body {
        name: "block".into(),
        space: iga_contact::space::Space::new(patch, None).unwrap(),
        material: Material::new(1e9, 0.3, Plane::Strain).unwrap(),
        formulation: iga_contact::material::Formulation::Displacement,
    }];
    let mut b = DofMap::builder(&bodies);
    b.fix_side(0, Side::XiMin, 0, 0.0).unwrap();
    let map = b.build();
    let loads = [Load::Pressure {
        body: 0,
        side: Side::EtaMax,
        pressure,
    }];
    let floor = geometry::segment([-1.0, 0.0], [2.0, 0.0]).unwrap();
    let pair = ContactPair::new(0, Side::EtaMin, Master::Rigid(floor));
    Problem::new(bodies, map, &loads, vec![pair]).unwrap()
}
