//! The pressure terms of the two mixed formulations: the local pressure
//! basis Q_{p−1} with its mass and divergence matrices, and the volumetric
//! terms of the spline pressure space that couple neighbouring elements.

use crate::dofs::Body;
use crate::error::{Error, GeometryError, Result};
use crate::material::Plane;
use crate::pressure::SplinePressure;
use crate::space::{Element, ElementValues};
use nalgebra::DMatrix;
use rayon::prelude::*;

/// The volumetric part of the mixed formulation's stiffness: one term
/// κ ĝ_i ĝ_iᵀ / m̂_i per pressure function i, as (DOFs 2·cp + component, values).
pub fn volumetric_terms(body: &Body, sp: &SplinePressure) -> Vec<(Vec<usize>, DMatrix<f64>)> {
    let kappa = body.material.bulk_modulus();
    (0..sp.len())
        .into_par_iter()
        .map(|i| {
            let g = sp.div(i);
            let m = sp.mass(i);
            let dofs = g.iter().map(|e| e.0).collect();
            let k = DMatrix::from_fn(g.len(), g.len(), |a, b| kappa * g[a].1 * g[b].1 / m);
            (dofs, k)
        })
        .collect()
}

/// The pressure basis of the local mixed formulation on element `el` at
/// (ξ, η): tensor products of Legendre polynomials of degree 0..p − 1 in
/// each parametric direction, on the element's own parameter range.
/// Legendre rather than monomials keep the element mass matrix M well
/// conditioned (diagonal on affine elements).
pub fn pressure_basis(body: &Body, el: &Element, xi: f64, eta: f64) -> Vec<f64> {
    let deg = body.space.patch.degree();
    let along = |d: usize, t: f64| -> Vec<f64> {
        let [a, b] = el.range[d];
        let s = 2.0 * (t - a) / (b - a) - 1.0;
        let n = deg[d].max(1);
        let mut out = Vec::with_capacity(n);
        // Bonnet's recursion
        let (mut p0, mut p1) = (1.0, s);
        for k in 0..n {
            match k {
                0 => out.push(1.0),
                1 => out.push(s),
                _ => {
                    let kf = k as f64;
                    let p2 = ((2.0 * kf - 1.0) * s * p1 - (kf - 1.0) * p0) / kf;
                    out.push(p2);
                    (p0, p1) = (p1, p2);
                }
            }
        }
        out
    };
    let (bx, by) = (along(0, xi), along(1, eta));
    by.iter()
        .flat_map(|&y| bx.iter().map(move |&x| x * y))
        .collect()
}

/// The mixed formulation needs plane strain: in plane stress σ_zz = 0 lets
/// the thickness change, so nothing locks and there is nothing to relax.
pub(super) fn check_mixed(body: &Body) -> Result<()> {
    if body.material.plane != Plane::Strain {
        return Err(Error::invalid(
            format!("body `{}`.formulation", body.name),
            "mixed",
            "the mixed formulation is for plane strain; plane stress does not lock (σ_zz = 0 frees the thickness), use formulation = \"displacement\"",
        ));
    }
    Ok(())
}

/// M = ∫ N_p N_pᵀ dΩ and G = ∫ N_p (∂/∂x, ∂/∂y) dΩ over element `e`.
pub(super) fn pressure_mass_and_divergence(
    values: &mut ElementValues,
    body: &Body,
    e: usize,
) -> Result<(DMatrix<f64>, DMatrix<f64>)> {
    let el = &body.space.elements[e];
    let n = el.cps.len();
    let mut m = DMatrix::zeros(0, 0);
    let mut g = DMatrix::zeros(0, 0);
    values.reinit(&body.space, el)?;
    for q in 0..values.n_points() {
        add_pressure_terms(body, el, values, q, n, &mut m, &mut g);
    }
    Ok((m, g))
}

/// Adds Gauss point `q` of `values` (element `el`) to M and G.
pub(super) fn add_pressure_terms(
    body: &Body,
    el: &Element,
    values: &ElementValues,
    q: usize,
    n: usize,
    m: &mut DMatrix<f64>,
    g: &mut DMatrix<f64>,
) {
    let [xi, eta] = values.param(q);
    let np = pressure_basis(body, el, xi, eta);
    if m.nrows() != np.len() {
        *m = DMatrix::zeros(np.len(), np.len());
        *g = DMatrix::zeros(np.len(), 2 * n);
    }
    for (i, &pi) in np.iter().enumerate() {
        let wp = values.weight(q) * pi;
        for (j, &pj) in np.iter().enumerate() {
            m[(i, j)] += wp * pj;
        }
        for (a, ga) in values.grads(q).iter().enumerate() {
            g[(i, 2 * a)] += wp * ga[0];
            g[(i, 2 * a + 1)] += wp * ga[1];
        }
    }
}

/// P = M⁻¹ G by a dense Cholesky of the small pressure mass matrix.
pub(super) fn projection_of(
    m: &DMatrix<f64>,
    g: &DMatrix<f64>,
    body: &Body,
    e: usize,
) -> Result<DMatrix<f64>> {
    let chol = m
        .clone()
        .cholesky()
        .ok_or_else(|| GeometryError::PressureMass {
            body: body.name.clone(),
            element: e,
        })?;
    Ok(chol.solve(g))
}
