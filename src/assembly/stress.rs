//! The stress of an element as linear functionals of its DOFs, for every
//! formulation, and the strain, stress and displacement at a point.

use super::mixed::{check_mixed, pressure_basis, pressure_mass_and_divergence, projection_of};
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::material::{Formulation, Plane};
use crate::pressure::SplinePressure;
use crate::space::{ElementValues, Shape};
use nalgebra::DMatrix;
use std::sync::Arc;

/// How an element's stress depends on the displacements.
#[derive(Clone, Debug)]
enum Dilatation {
    /// σ = D ε(u).
    Pointwise,
    /// The local projection P = M⁻¹ G onto Q_{p−1} on the element.
    Local(DMatrix<f64>),
    /// The spline projection of the body ([`SplinePressure`]).
    Spline(Arc<SplinePressure>),
}

/// The stress of one element as linear functionals of the DOFs of the
/// control points it reaches ([`ElementStress::cps`]: the element's own,
/// then for the mixed formulation those of the neighbouring elements under
/// its pressure functions), for every formulation. Build it once per
/// element and evaluate it at many points.
#[derive(Clone, Debug)]
pub struct ElementStress<'a> {
    body: &'a Body,
    element: usize,
    dilatation: Dilatation,
    cps: Vec<usize>,
}

impl<'a> ElementStress<'a> {
    /// For the mixed formulation this integrates the body's whole pressure
    /// space; to evaluate many elements, build it once and use
    /// [`ElementStress::with_pressure`].
    pub fn new(body: &'a Body, element: usize) -> Result<Self> {
        let sp = match body.formulation {
            Formulation::Mixed => Some(Arc::new(SplinePressure::new(body)?)),
            _ => None,
        };
        Self::with_pressure(body, element, sp.as_ref())
    }

    /// As [`ElementStress::new`] with the body's pressure space `sp`
    /// (required for, and only used by, the mixed formulation).
    pub fn with_pressure(
        body: &'a Body,
        element: usize,
        sp: Option<&Arc<SplinePressure>>,
    ) -> Result<Self> {
        let own = body.space.elements[element].cps.clone();
        let (dilatation, cps) = match body.formulation {
            Formulation::Displacement => (Dilatation::Pointwise, own),
            Formulation::LocalMixed => {
                check_mixed(body)?;
                let mut values = ElementValues::new(&body.space);
                let (m, g) = pressure_mass_and_divergence(&mut values, body, element)?;
                (
                    Dilatation::Local(projection_of(&m, &g, body, element)?),
                    own,
                )
            }
            Formulation::Mixed => {
                check_mixed(body)?;
                let sp = sp.ok_or_else(|| {
                    Error::invalid(
                        format!("body `{}`.formulation", body.name),
                        "mixed",
                        "the stress of the mixed formulation needs the body's pressure space",
                    )
                })?;
                let mut cps = own.clone();
                for &(i, _) in sp.on_element(element) {
                    for &(d, _) in sp.div(i) {
                        let cp = d / 2;
                        if !cps.contains(&cp) {
                            cps.push(cp);
                        }
                    }
                }
                cps[own.len()..].sort_unstable();
                (Dilatation::Spline(Arc::clone(sp)), cps)
            }
        };
        Ok(Self {
            body,
            element,
            dilatation,
            cps,
        })
    }

    /// The control points whose DOFs the stress reaches: the element's own
    /// first (in its local order), then the others, sorted.
    pub fn cps(&self) -> &[usize] {
        &self.cps
    }

    /// θ̄ at (ξ, η) as a functional over [`ElementStress::cps`] (2 per
    /// point), `None` for the displacement formulation.
    fn theta(&self, xi: f64, eta: f64) -> Option<Vec<f64>> {
        match &self.dilatation {
            Dilatation::Pointwise => None,
            Dilatation::Local(proj) => {
                let el = &self.body.space.elements[self.element];
                let np = pressure_basis(self.body, el, xi, eta);
                let t = DMatrix::from_row_slice(1, np.len(), &np) * proj;
                Some(t.iter().copied().collect())
            }
            Dilatation::Spline(sp) => {
                let mut out = vec![0.0; 2 * self.cps.len()];
                let spans = self.body.space.elements[self.element].spans;
                for (d, v) in sp.theta_row_on_element(spans, xi, eta) {
                    let k = self
                        .cps
                        .iter()
                        .position(|&c| c == d / 2)
                        .expect("θ̄ reaches only the element's pressure neighbourhood");
                    out[2 * k + d % 2] += v;
                }
                Some(out)
            }
        }
    }

    /// The rows of σ_xx, σ_yy, σ_xy and σ_zz over the DOFs of
    /// [`ElementStress::cps`] at (ξ, η), with `shape` the element's shape
    /// functions there.
    pub fn rows(&self, shape: &Shape, xi: f64, eta: f64) -> [Vec<f64>; 4] {
        let m = &self.body.material;
        let mut rows: [Vec<f64>; 4] = std::array::from_fn(|_| vec![0.0; 2 * self.cps.len()]);
        match self.theta(xi, eta) {
            None => {
                let d = m.d_matrix();
                for (a, g) in shape.grad.iter().enumerate() {
                    rows[0][2 * a] = d[0][0] * g[0];
                    rows[0][2 * a + 1] = d[0][1] * g[1];
                    rows[1][2 * a] = d[1][0] * g[0];
                    rows[1][2 * a + 1] = d[1][1] * g[1];
                    rows[2][2 * a] = d[2][2] * g[1];
                    rows[2][2 * a + 1] = d[2][2] * g[0];
                    if m.plane == Plane::Strain {
                        for c in 0..2 {
                            rows[3][2 * a + c] =
                                m.poisson * (rows[0][2 * a + c] + rows[1][2 * a + c]);
                        }
                    }
                }
            }
            Some(theta) => {
                let (mu, kappa) = (m.shear_modulus(), m.bulk_modulus());
                // p = κ θ̄ − (2μ/3) tr ε: the mean stress with ε_zz = 0
                for (k, t) in theta.iter().enumerate() {
                    for row in [0, 1, 3] {
                        rows[row][k] = kappa * t;
                    }
                }
                for (a, g) in shape.grad.iter().enumerate() {
                    for c in 0..2 {
                        for row in [0, 1, 3] {
                            rows[row][2 * a + c] -= 2.0 * mu / 3.0 * g[c];
                        }
                    }
                    rows[0][2 * a] += 2.0 * mu * g[0];
                    rows[1][2 * a + 1] += 2.0 * mu * g[1];
                    rows[2][2 * a] = mu * g[1];
                    rows[2][2 * a + 1] = mu * g[0];
                }
            }
        }
        rows
    }

    /// The DOFs of [`ElementStress::cps`] in a full vector of body `bi`.
    fn values(&self, map: &DofMap, u: &[f64], bi: usize) -> Vec<f64> {
        self.cps
            .iter()
            .flat_map(|&cp| map.cp_displacement(u, bi, cp))
            .collect()
    }

    /// (σ_xx, σ_yy, σ_xy) and σ_zz at (ξ, η) for the full displacement `u`
    /// of body `bi`.
    pub fn stress(
        &self,
        map: &DofMap,
        u: &[f64],
        bi: usize,
        shape: &Shape,
        xi: f64,
        eta: f64,
    ) -> ([f64; 3], f64) {
        let el = &self.body.space.elements[self.element];
        let m = &self.body.material;
        let eps = strain_at(map, u, bi, &el.cps, shape);
        match self.theta(xi, eta) {
            // the paper's path, operation for operation
            None => {
                let sig = m.stress(eps);
                (sig, m.stress_zz(sig))
            }
            Some(theta) => {
                let ue = self.values(map, u, bi);
                let t: f64 = theta.iter().zip(&ue).map(|(a, b)| a * b).sum();
                m.mixed_stress(eps, t)
            }
        }
    }

    /// The projected dilatation θ̄ at (ξ, η) (the trace of the strain for
    /// the displacement formulation).
    pub fn dilatation(
        &self,
        map: &DofMap,
        u: &[f64],
        bi: usize,
        shape: &Shape,
        xi: f64,
        eta: f64,
    ) -> f64 {
        match self.theta(xi, eta) {
            None => {
                let el = &self.body.space.elements[self.element];
                let eps = strain_at(map, u, bi, &el.cps, shape);
                eps[0] + eps[1]
            }
            Some(theta) => {
                let ue = self.values(map, u, bi);
                theta.iter().zip(&ue).map(|(a, b)| a * b).sum()
            }
        }
    }
}

/// Strain (Voigt, engineering shear) and stress of body `body` at (ξ, η)
/// for the full displacement vector `u`; the stress is that of the body's
/// formulation ([`ElementStress`]).
pub fn strain_stress(
    bodies: &[Body],
    map: &DofMap,
    u: &[f64],
    body: usize,
    xi: f64,
    eta: f64,
) -> Result<([f64; 3], [f64; 3])> {
    let b = &bodies[body];
    let ei = b.space.locate(xi, eta);
    let e = &b.space.elements[ei];
    let shape = b.space.shape(e, xi, eta)?;
    let (sig, _) = ElementStress::new(b, ei)?.stress(map, u, body, &shape, xi, eta);
    Ok((strain_at(map, u, body, &e.cps, &shape), sig))
}

/// ε = Σ_A B_A u_A at a point with known shape functions.
pub fn strain_at(map: &DofMap, u: &[f64], body: usize, cps: &[usize], shape: &Shape) -> [f64; 3] {
    let mut eps = [0.0; 3];
    for (a, &cp) in cps.iter().enumerate() {
        let d = map.cp_displacement(u, body, cp);
        let g = shape.grad[a];
        eps[0] += g[0] * d[0];
        eps[1] += g[1] * d[1];
        eps[2] += g[1] * d[0] + g[0] * d[1];
    }
    eps
}

/// Displacement at a point with known shape functions.
pub fn displacement_at(
    map: &DofMap,
    u: &[f64],
    body: usize,
    cps: &[usize],
    shape: &Shape,
) -> [f64; 2] {
    let mut out = [0.0; 2];
    for (a, &cp) in cps.iter().enumerate() {
        let d = map.cp_displacement(u, body, cp);
        out[0] += shape.r[a] * d[0];
        out[1] += shape.r[a] * d[1];
    }
    out
}
