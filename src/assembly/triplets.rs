//! Assembly into coordinate triplets: element matrices added through the DOF
//! map (the prescribed columns moved to the right-hand side), and the whole
//! stiffness as triplets, the simple path that the compressed one is checked
//! against.

use super::element::element_stiffness_with;
use super::mixed::volumetric_terms;
use crate::dofs::{Body, DofMap};
use crate::error::Result;
use crate::material::Formulation;
use crate::pressure::SplinePressure;
use crate::space::ElementValues;
use crate::sparse::Triplets;
use nalgebra::DMatrix;
use rayon::prelude::*;

// Assembly's own way of filling triplets: element matrices through the DOF
// map (the type itself lives below, in `sparse`, for the linear algebra).
impl Triplets {
    /// Appends an element matrix `ke` acting on the global DOFs `dofs`.
    /// Columns of prescribed DOFs move to the right-hand side: `lift[i] +=
    /// ke[i][j] · ū_j` (subtract `lift` from the load).
    pub fn add(&mut self, map: &DofMap, dofs: &[usize], ke: &DMatrix<f64>, lift: &mut [f64]) {
        self.add_block(map, dofs, dofs, ke, lift);
    }

    /// As [`Triplets::add`] for a rectangular block: rows `rdofs`, columns `cdofs`.
    pub fn add_block(
        &mut self,
        map: &DofMap,
        rdofs: &[usize],
        cdofs: &[usize],
        ke: &DMatrix<f64>,
        lift: &mut [f64],
    ) {
        for (a, &ga) in rdofs.iter().enumerate() {
            let Some(i) = map.free(ga) else { continue };
            for (b, &gb) in cdofs.iter().enumerate() {
                let v = ke[(a, b)];
                match map.free(gb) {
                    Some(j) => {
                        self.rows.push(i);
                        self.cols.push(j);
                        self.vals.push(v);
                    }
                    None => lift[i] += v * map.prescribed(gb),
                }
            }
        }
    }
}

/// The stiffness of all bodies as triplets over the free DOFs, and the lift
/// K_fc ū of the prescribed values. Elements are integrated in parallel and
/// appended in a fixed order, so the result is deterministic.
pub fn stiffness(bodies: &[Body], map: &DofMap) -> Result<(Triplets, Vec<f64>)> {
    let mut trip = Triplets::default();
    let mut lift = vec![0.0; map.n_free()];
    let cap: usize = bodies
        .iter()
        .flat_map(|b| {
            b.space
                .elements
                .iter()
                .map(|e| 4 * e.cps.len() * e.cps.len())
        })
        .sum();
    trip.rows.reserve(cap);
    trip.cols.reserve(cap);
    trip.vals.reserve(cap);
    for (bi, body) in bodies.iter().enumerate() {
        let kes: Vec<Result<DMatrix<f64>>> = (0..body.space.elements.len())
            .into_par_iter()
            .map_init(
                || ElementValues::new(&body.space),
                |values, e| element_stiffness_with(values, body, e),
            )
            .collect();
        for (e, ke) in kes.into_iter().enumerate() {
            let dofs = map.element_dofs(bi, &body.space.elements[e].cps);
            trip.add(map, &dofs, &ke?, &mut lift);
        }
        if body.formulation == Formulation::Mixed {
            let sp = SplinePressure::new(body)?;
            for (local, k) in volumetric_terms(body, &sp) {
                let dofs: Vec<usize> = local
                    .iter()
                    .map(|&d| map.global(bi, d / 2, d % 2))
                    .collect();
                trip.add(map, &dofs, &k, &mut lift);
            }
        }
    }
    Ok((trip, lift))
}
