//! The element stiffness of Eq. (3), ∫ Bᵀ D B dΩ, and the element load of a
//! body force, from one pass over the element's quadrature points.

use super::load::add_shape_times;
use super::mixed::{add_pressure_terms, check_mixed, projection_of};
use crate::dofs::Body;
use crate::error::Result;
use crate::material::Formulation;
use crate::space::ElementValues;
use nalgebra::{DMatrix, DVector};

/// The strain-displacement product B_aᵀ D B_b for two shape-function
/// gradients, written out for an isotropic D (D₀₂ = D₁₂ = 0).
#[inline]
pub fn btdb(ga: [f64; 2], gb: [f64; 2], d: &[[f64; 3]; 3]) -> [[f64; 2]; 2] {
    [
        [
            ga[0] * d[0][0] * gb[0] + ga[1] * d[2][2] * gb[1],
            ga[0] * d[0][1] * gb[1] + ga[1] * d[2][2] * gb[0],
        ],
        [
            ga[1] * d[1][0] * gb[0] + ga[0] * d[2][2] * gb[1],
            ga[1] * d[1][1] * gb[1] + ga[0] * d[2][2] * gb[0],
        ],
    ]
}

/// Element stiffness in local order (control point major): ∫ Bᵀ D B dΩ
/// for the displacement formulation; for the local mixed one ∫ Bᵀ D_dev B
/// dΩ + κ Gᵀ M⁻¹ G ([`ElementStress`](super::ElementStress)); for the mixed one only the
/// deviatoric part ∫ Bᵀ D_dev B dΩ — its volumetric part couples the
/// elements under each pressure function ([`volumetric_terms`](super::volumetric_terms)).
pub fn element_stiffness(body: &Body, e: usize) -> Result<DMatrix<f64>> {
    element_stiffness_with(&mut ElementValues::new(&body.space), body, e)
}

/// [`element_stiffness`] with caller-owned quadrature buffers, reused
/// across the elements of one thread.
pub fn element_stiffness_with(
    values: &mut ElementValues,
    body: &Body,
    e: usize,
) -> Result<DMatrix<f64>> {
    Ok(element_integrals(values, body, e, None)?.0)
}

/// The element stiffness and, for a body force b, the element load
/// ∫ R b dΩ, from one pass over the quadrature points.
pub(super) fn element_integrals(
    values: &mut ElementValues,
    body: &Body,
    e: usize,
    force: Option<[f64; 2]>,
) -> Result<(DMatrix<f64>, DVector<f64>)> {
    let el = &body.space.elements[e];
    let n = el.cps.len();
    let deviatoric = body.formulation != Formulation::Displacement;
    let mixed = body.formulation == Formulation::LocalMixed;
    if deviatoric {
        check_mixed(body)?;
    }
    // the mixed formulations keep only the deviatoric part pointwise; the
    // local one adds its volumetric part κ Gᵀ M⁻¹ G after the loop, the
    // spline one in `volumetric_terms`
    let d = if deviatoric {
        body.material.d_deviatoric()
    } else {
        body.material.d_matrix()
    };
    let mut ke = DMatrix::zeros(2 * n, 2 * n);
    let mut fe = DVector::zeros(if force.is_some() { 2 * n } else { 0 });
    let (mut pm, mut pg) = (DMatrix::zeros(0, 0), DMatrix::zeros(0, 0));
    values.reinit(&body.space, el)?;
    for q in 0..values.n_points() {
        let (weight, grad) = (values.weight(q), values.grads(q));
        if let Some(b) = force {
            add_shape_times(&mut fe, values.values(q), b, weight);
        }
        if mixed {
            add_pressure_terms(body, el, values, q, n, &mut pm, &mut pg);
        }
        // Blocks with b ≥ a only; the lower triangle is mirrored below.
        for a in 0..n {
            let ga = grad[a];
            for b in a..n {
                let k = btdb(ga, grad[b], &d);
                for i in 0..2 {
                    for j in 0..2 {
                        ke[(2 * a + i, 2 * b + j)] += weight * k[i][j];
                    }
                }
            }
        }
    }
    for a in 0..n {
        for b in a + 1..n {
            for i in 0..2 {
                for j in 0..2 {
                    ke[(2 * b + j, 2 * a + i)] = ke[(2 * a + i, 2 * b + j)];
                }
            }
        }
    }
    if mixed {
        let proj = projection_of(&pm, &pg, body, e)?;
        // κ Gᵀ M⁻¹ G, symmetrised against round-off
        let vol = body.material.bulk_modulus() * pg.transpose() * proj;
        ke += 0.5 * (&vol + vol.transpose());
    }
    Ok((ke, fe))
}
