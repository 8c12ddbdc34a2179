//! Element-by-element assembly of Eq. (3), a(u, v) = L(v), into sparse
//! triplets over the free DOFs.

use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::material::{Formulation, Plane};
use crate::nurbs::Side;
use crate::pressure::SplinePressure;
use crate::quadrature;
use crate::space::{Element, ElementValues, Shape};
use faer::sparse::{SparseColMat, SymbolicSparseColMat};
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;
use std::sync::Arc;

pub use crate::sparse::Triplets;

// Assembly's own way of filling triplets: element matrices through the DOF
// map (the type itself lives below, in `sparse`, for the linear algebra).
impl Triplets {
    /// Appends an element matrix `ke` acting on the global DOFs `dofs`.
    /// Columns of prescribed DOFs move to the right-hand side: `lift[i] +=
    /// ke[i][j] · ū_j` (subtract `lift` from the load).
    pub fn add(&mut self, map: &DofMap, dofs: &[usize], ke: &DMatrix<f64>, lift: &mut [f64]) {
        for (a, &ga) in dofs.iter().enumerate() {
            let Some(i) = map.free(ga) else { continue };
            for (b, &gb) in dofs.iter().enumerate() {
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
/// dΩ + κ Gᵀ M⁻¹ G ([`ElementStress`]); for the mixed one only the
/// deviatoric part ∫ Bᵀ D_dev B dΩ — its volumetric part couples the
/// elements under each pressure function ([`volumetric_terms`]).
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
                for (d, v) in sp.theta_row(xi, eta) {
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

/// The mixed formulation needs plane strain: in plane stress σ_zz = 0 lets
/// the thickness change, so nothing locks and there is nothing to relax.
fn check_mixed(body: &Body) -> Result<()> {
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
fn pressure_mass_and_divergence(
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
fn add_pressure_terms(
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
fn projection_of(
    m: &DMatrix<f64>,
    g: &DMatrix<f64>,
    body: &Body,
    e: usize,
) -> Result<DMatrix<f64>> {
    let chol = m.clone().cholesky().ok_or_else(|| {
        Error::Geometry(format!(
            "body `{}`, element {e}: the pressure mass matrix is not positive definite",
            body.name
        ))
    })?;
    Ok(chol.solve(g))
}

/// The element stiffness and, for a body force b, the element load
/// ∫ R b dΩ, from one pass over the quadrature points.
fn element_integrals(
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

// ---------------------------------------------------------------- CSC

/// For every basis function of a knot vector, the first and last basis
/// function it shares a span with — or, with `reach` = r > 0, a span
/// within r spans of one of its own (the mixed formulation couples two
/// functions when both meet the support of one pressure function, whose
/// support is p spans wide: r = p − 1).
fn coupled_range(knots: &crate::nurbs::KnotVector, reach: usize) -> Vec<(usize, usize)> {
    let p = knots.degree();
    let spans: Vec<usize> = knots.spans().iter().map(|s| s.0).collect();
    let mut own = vec![(usize::MAX, 0usize); knots.n_basis()];
    for (k, &s) in spans.iter().enumerate() {
        for r in &mut own[s - p..=s] {
            r.0 = r.0.min(k);
            r.1 = r.1.max(k);
        }
    }
    own.iter()
        .map(|&(lo, hi)| {
            let (lo, hi) = (lo.saturating_sub(reach), (hi + reach).min(spans.len() - 1));
            (spans[lo] - p, spans[hi])
        })
        .collect()
}

/// The number of free DOFs with a global index below g, for every g.
fn free_before(map: &DofMap) -> Vec<usize> {
    let mut out = Vec::with_capacity(map.n_total() + 1);
    let mut k = 0;
    for g in 0..map.n_total() {
        out.push(k);
        if map.free(g).is_some() {
            k += 1;
        }
    }
    out.push(k);
    out
}

/// Splits `v` at the increasing positions `at` (first 0, last `v.len()`).
fn split_at_all<'a, T>(mut v: &'a mut [T], at: &[usize]) -> Vec<&'a mut [T]> {
    let mut out = Vec::with_capacity(at.len().saturating_sub(1));
    for w in at.windows(2) {
        let (head, tail) = v.split_at_mut(w[1] - w[0]);
        out.push(head);
        v = tail;
    }
    out
}

/// Column chunks per body for the parallel passes: rows of control points
/// (η index) [k0, k1), with the free columns they own.
struct Chunk {
    body: usize,
    rows: [usize; 2],
    cols: [usize; 2],
}

fn chunks(bodies: &[Body], map: &DofMap, before: &[usize]) -> Vec<Chunk> {
    let threads = rayon::current_num_threads().max(1);
    let mut out = Vec::new();
    for (b, body) in bodies.iter().enumerate() {
        let [n0, n1] = body.space.patch.n();
        let q = body.space.patch.degree()[1];
        // a few bands per thread balance the load; an element is integrated
        // by every band it touches, so bands much taller than the q + 1
        // rows of an element keep that repetition small
        let height = n1.div_ceil(4 * threads).max(4 * (q + 1));
        let mut k0 = 0;
        while k0 < n1 {
            let k1 = (k0 + height).min(n1);
            let col = |k: usize| {
                if k == n1 {
                    before[map.global(b, 0, 0) + 2 * n0 * n1]
                } else {
                    before[map.global(b, k * n0, 0)]
                }
            };
            out.push(Chunk {
                body: b,
                rows: [k0, k1],
                cols: [col(k0), col(k1)],
            });
            k0 = k1;
        }
    }
    out
}

/// The bulk operator of all bodies over the free DOFs: see
/// [`stiffness_matrix`].
pub struct Bulk {
    /// The stiffness, compressed by columns.
    pub k: SparseColMat<usize, f64>,
    /// K_fc ū, the columns of the prescribed DOFs times their values.
    pub lift: Vec<f64>,
    /// The load of the body forces.
    pub body_load: Vec<f64>,
}

/// The stiffness of all bodies, assembled straight into compressed
/// columns over the free DOFs, the lift K_fc ū, and the load of the
/// constant body forces `forces` (one per body; the integrals share the
/// stiffness's quadrature).
///
/// The pattern comes from control-point connectivity: in a tensor-product
/// patch, control points (i, k) and (i', k') share an element exactly when
/// i, i' share a span of ξ and k, k' one of η, so a column's rows are a
/// product of two index ranges, known before any element is integrated.
/// `couplings` adds (row, column) pairs of free DOFs that no element
/// joins (contact between bodies), with zero values. Elements are then
/// integrated in parallel and their values added in place: the columns are
/// split into bands of control-point rows, each owned by one task, which
/// integrates every element touching its band (elements on a band's edge
/// are integrated by both neighbours) and writes only its own columns.
pub fn stiffness_matrix(
    bodies: &[Body],
    map: &DofMap,
    couplings: &[(usize, usize)],
    forces: &[[f64; 2]],
) -> Result<Bulk> {
    let n = map.n_free();
    let before = free_before(map);
    // extra couplings by column, sorted, without duplicates
    let mut extra: Vec<(usize, usize)> = couplings.iter().map(|&(i, j)| (j, i)).collect();
    extra.sort_unstable();
    extra.dedup();
    let mut extra_ptr = vec![0usize; n + 1];
    for &(j, _) in &extra {
        extra_ptr[j + 1] += 1;
    }
    for j in 0..n {
        extra_ptr[j + 1] += extra_ptr[j];
    }
    // the global DOF of every free column
    let mut global_of = vec![0usize; n];
    for g in 0..map.n_total() {
        if let Some(i) = map.free(g) {
            global_of[i] = g;
        }
    }
    let ranges: Vec<[Vec<(usize, usize)>; 2]> = bodies
        .iter()
        .map(|b| {
            let reach = |d: usize| match b.formulation {
                Formulation::Mixed => b.space.patch.knots[d].degree().saturating_sub(1),
                _ => 0,
            };
            [
                coupled_range(&b.space.patch.knots[0], reach(0)),
                coupled_range(&b.space.patch.knots[1], reach(1)),
            ]
        })
        .collect();
    let chunks = chunks(bodies, map, &before);
    // rows of column j: the free DOFs of the coupled control points,
    // merged with the extra couplings (both sorted)
    let column = |b: usize, j: usize, emit: &mut dyn FnMut(usize)| {
        let g = global_of[j];
        let n0 = bodies[b].space.patch.n()[0];
        let cp = (g - map.global(b, 0, 0)) / 2;
        let (ri, rk) = (ranges[b][0][cp % n0], ranges[b][1][cp / n0]);
        let mut ex = extra[extra_ptr[j]..extra_ptr[j + 1]]
            .iter()
            .map(|e| e.1)
            .peekable();
        let mut push = |i: usize, emit: &mut dyn FnMut(usize)| {
            while let Some(&e) = ex.peek() {
                if e < i {
                    emit(e);
                    ex.next();
                } else {
                    if e == i {
                        ex.next();
                    }
                    break;
                }
            }
            emit(i);
        };
        for k in rk.0..=rk.1 {
            for i in ri.0..=ri.1 {
                for c in 0..2 {
                    if let Some(f) = map.free(map.global(b, i + k * n0, c)) {
                        push(f, &mut *emit);
                    }
                }
            }
        }
        for e in ex {
            emit(e);
        }
    };
    let mut counts = vec![0usize; n];
    chunks
        .par_iter()
        .zip(split_at_all(&mut counts, &chunk_bounds(&chunks, n)).into_par_iter())
        .for_each(|(ch, cnt)| {
            for (j, c) in (ch.cols[0]..ch.cols[1]).zip(cnt.iter_mut()) {
                column(ch.body, j, &mut |_| *c += 1);
            }
        });
    let mut col_ptr = vec![0usize; n + 1];
    for j in 0..n {
        col_ptr[j + 1] = col_ptr[j] + counts[j];
    }
    drop(counts);
    let nnz = col_ptr[n];
    let mut row_idx = vec![0usize; nnz];
    let bounds: Vec<usize> = chunk_bounds(&chunks, n)
        .iter()
        .map(|&j| col_ptr[j])
        .collect();
    chunks
        .par_iter()
        .zip(split_at_all(&mut row_idx, &bounds).into_par_iter())
        .for_each(|(ch, rows)| {
            let mut at = 0;
            for j in ch.cols[0]..ch.cols[1] {
                column(ch.body, j, &mut |i| {
                    rows[at] = i;
                    at += 1;
                });
            }
        });
    // values, in place
    let mut val = vec![0.0; nnz];
    let mut lift = vec![0.0; n];
    let mut body_load = vec![0.0; n];
    let lifts = split_at_all(&mut lift, &chunk_bounds(&chunks, n));
    let body_loads = split_at_all(&mut body_load, &chunk_bounds(&chunks, n));
    let vals = split_at_all(&mut val, &bounds);
    let (col_ptr_ref, row_idx_ref) = (&col_ptr, &row_idx);
    // the pressure space of each mixed body, built once; its volumetric
    // terms κ ĝ_i ĝ_iᵀ / m̂_i are rank one and formed where they are added
    let pressures: Vec<Option<SplinePressure>> = bodies
        .iter()
        .map(|b| match b.formulation {
            Formulation::Mixed => SplinePressure::new(b).map(Some),
            _ => Ok(None),
        })
        .collect::<Result<_>>()?;
    let pressures = &pressures;
    chunks
        .par_iter()
        .zip(
            vals.into_par_iter()
                .zip(lifts.into_par_iter().zip(body_loads)),
        )
        .map(|(ch, (vals, (lift, body_load)))| -> Result<()> {
            let body = &bodies[ch.body];
            let force = forces.get(ch.body).copied().filter(|f| *f != [0.0, 0.0]);
            let q = body.space.patch.degree()[1];
            let owned = OwnedColumns {
                cols: ch.cols,
                col_ptr: col_ptr_ref,
                row_idx: row_idx_ref,
            };
            let mut values = ElementValues::new(&body.space);
            for (e, el) in body.space.elements.iter().enumerate() {
                let sy = el.spans[1];
                if sy < ch.rows[0] || sy - q >= ch.rows[1] {
                    continue;
                }
                let (ke, fe) = element_integrals(&mut values, body, e, force)?;
                let dofs = map.element_dofs(ch.body, &el.cps);
                let free: Vec<Option<usize>> = dofs.iter().map(|&g| map.free(g)).collect();
                owned.add(map, &dofs, &free, |a, b| ke[(a, b)], vals, lift);
                if force.is_some() {
                    for (a, fa) in free.iter().enumerate() {
                        if let Some(i) = owned.column(fa) {
                            body_load[i - ch.cols[0]] += fe[a];
                        }
                    }
                }
            }
            // the mixed formulation's volumetric terms, one per pressure
            // function, into the columns this task owns
            if let Some(sp) = &pressures[ch.body] {
                let kappa = body.material.bulk_modulus();
                for i in 0..sp.len() {
                    let (g, m) = (sp.div(i), sp.mass(i));
                    let dofs: Vec<usize> = g
                        .iter()
                        .map(|e| map.global(ch.body, e.0 / 2, e.0 % 2))
                        .collect();
                    let free: Vec<Option<usize>> = dofs.iter().map(|&d| map.free(d)).collect();
                    if free.iter().any(|f| owned.column(f).is_some()) {
                        let k = |a: usize, b: usize| kappa * g[a].1 * g[b].1 / m;
                        owned.add(map, &dofs, &free, k, vals, lift);
                    }
                }
            }
            Ok(())
        })
        .collect::<Result<Vec<()>>>()?;
    let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
    Ok(Bulk {
        k: SparseColMat::new(symbolic, val),
        lift,
        body_load,
    })
}

/// The columns [cols₀, cols₁) of the compressed matrix that one task owns,
/// with the pattern of the whole matrix.
struct OwnedColumns<'a> {
    cols: [usize; 2],
    col_ptr: &'a [usize],
    row_idx: &'a [usize],
}

impl OwnedColumns<'_> {
    /// The free index `f` if this task owns it.
    fn column(&self, f: &Option<usize>) -> Option<usize> {
        f.filter(|&j| j >= self.cols[0] && j < self.cols[1])
    }

    /// Adds the local matrix `k(a, b)` over the global DOFs `dofs` (free indices
    /// `free`): its owned columns into `vals` (the values of the owned
    /// columns), and for its owned rows the prescribed columns times their
    /// values into `lift` (indexed from cols₀). The free rows of `dofs`
    /// must be increasing, like a column's rows, so one pass finds them.
    fn add(
        &self,
        map: &DofMap,
        dofs: &[usize],
        free: &[Option<usize>],
        k: impl Fn(usize, usize) -> f64,
        vals: &mut [f64],
        lift: &mut [f64],
    ) {
        let base = self.col_ptr[self.cols[0]];
        for (bl, fb) in free.iter().enumerate() {
            let Some(j) = self.column(fb) else { continue };
            let rows = &self.row_idx[self.col_ptr[j]..self.col_ptr[j + 1]];
            let mut at = 0;
            for (a, fa) in free.iter().enumerate() {
                let Some(i) = *fa else { continue };
                while rows[at] < i {
                    at += 1;
                }
                vals[self.col_ptr[j] - base + at] += k(a, bl);
            }
        }
        for (a, fa) in free.iter().enumerate() {
            let Some(i) = self.column(fa) else { continue };
            for (bl, fb) in free.iter().enumerate() {
                if fb.is_none() {
                    lift[i - self.cols[0]] += k(a, bl) * map.prescribed(dofs[bl]);
                }
            }
        }
    }
}

/// The free-column boundaries of the chunks: 0, …, n.
fn chunk_bounds(chunks: &[Chunk], n: usize) -> Vec<usize> {
    let mut b: Vec<usize> = chunks.iter().map(|c| c.cols[0]).collect();
    b.push(n);
    b
}

/// External loads of Eq. (3). `B` names the body: its index here, its
/// name in a scene file (`Load<String>`, resolved by [`Load::map_body`]).
#[derive(Clone, Debug, PartialEq, serde::Serialize, serde::Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum Load<B = usize> {
    /// A constant body force per unit volume.
    BodyForce { body: B, force: [f64; 2] },
    /// A constant traction vector (force per unit length) on a side.
    Traction {
        body: B,
        side: Side,
        traction: [f64; 2],
    },
    /// A uniform pressure on a side, acting against the outward normal.
    Pressure { body: B, side: Side, pressure: f64 },
}

/// Scatters a local load vector into the free DOFs.
fn scatter_vector(map: &DofMap, dofs: &[usize], fe: &DVector<f64>, f: &mut [f64]) {
    for (a, &g) in dofs.iter().enumerate() {
        if let Some(i) = map.free(g) {
            f[i] += fe[a];
        }
    }
}

fn add_shape_times(fe: &mut DVector<f64>, r: &[f64], v: [f64; 2], weight: f64) {
    for (a, r) in r.iter().enumerate() {
        fe[2 * a] += weight * r * v[0];
        fe[2 * a + 1] += weight * r * v[1];
    }
}

impl<B> Load<B> {
    /// The body the load acts on.
    pub fn body(&self) -> &B {
        match self {
            Load::BodyForce { body, .. }
            | Load::Traction { body, .. }
            | Load::Pressure { body, .. } => body,
        }
    }

    /// The same load with its body reference mapped (a name to an index).
    pub fn map_body<C>(&self, f: impl FnOnce(&B) -> C) -> Load<C> {
        match self {
            Load::BodyForce { body, force } => Load::BodyForce {
                body: f(body),
                force: *force,
            },
            Load::Traction {
                body,
                side,
                traction,
            } => Load::Traction {
                body: f(body),
                side: *side,
                traction: *traction,
            },
            Load::Pressure {
                body,
                side,
                pressure,
            } => Load::Pressure {
                body: f(body),
                side: *side,
                pressure: *pressure,
            },
        }
    }
}

/// The body a load acts on, checked.
fn load_body<'a>(bodies: &'a [Body], load: &Load) -> Result<&'a Body> {
    let bi = *load.body();
    bodies.get(bi).ok_or_else(|| {
        Error::invalid(
            "load.body",
            bi,
            format!("there are {} bodies", bodies.len()),
        )
    })
}

fn check_force(force: [f64; 2]) -> Result<()> {
    for (i, c) in force.iter().enumerate() {
        crate::error::finite(&format!("load.body_force[{i}]"), *c)?;
    }
    Ok(())
}

/// The body forces of `loads` summed per body (for [`stiffness_matrix`]),
/// and the other loads.
pub fn split_body_forces(bodies: &[Body], loads: &[Load]) -> Result<(Vec<[f64; 2]>, Vec<Load>)> {
    let mut forces = vec![[0.0; 2]; bodies.len()];
    let mut rest = Vec::new();
    for load in loads {
        load_body(bodies, load)?;
        match *load {
            Load::BodyForce { body, force } => {
                check_force(force)?;
                forces[body][0] += force[0];
                forces[body][1] += force[1];
            }
            _ => rest.push(load.clone()),
        }
    }
    Ok((forces, rest))
}

/// The load vector L(v) over the free DOFs.
pub fn load_vector(bodies: &[Body], map: &DofMap, loads: &[Load]) -> Result<Vec<f64>> {
    let mut f = vec![0.0; map.n_free()];
    for load in loads {
        let bi = *load.body();
        let body = load_body(bodies, load)?;
        let space = &body.space;
        match *load {
            Load::BodyForce { force, .. } => {
                check_force(force)?;
                // elements in parallel, scattered in order: deterministic
                let fes: Vec<Result<DVector<f64>>> = space
                    .elements
                    .par_iter()
                    .map_init(
                        || ElementValues::new(space),
                        |values, el| {
                            let mut fe = DVector::zeros(2 * el.cps.len());
                            values.reinit(space, el)?;
                            for q in 0..values.n_points() {
                                add_shape_times(&mut fe, values.values(q), force, values.weight(q));
                            }
                            Ok(fe)
                        },
                    )
                    .collect();
                for (el, fe) in space.elements.iter().zip(fes) {
                    scatter_vector(map, &map.element_dofs(bi, &el.cps), &fe?, &mut f);
                }
            }
            Load::Traction { side, .. } | Load::Pressure { side, .. } => {
                let traction = |n: [f64; 2]| match *load {
                    Load::Traction { traction, .. } => traction,
                    Load::Pressure { pressure, .. } => [-pressure * n[0], -pressure * n[1]],
                    Load::BodyForce { .. } => unreachable!(),
                };
                for be in space.boundary(side) {
                    let el = &space.elements[be.element];
                    let mut fe = DVector::zeros(2 * el.cps.len());
                    for (t, w) in
                        quadrature::on_interval(space.quad_order, be.range[0], be.range[1])
                    {
                        let (shape, n, len) = space.side_shape(&be, t)?;
                        let tr = traction(n);
                        crate::error::finite("load.traction", tr[0] + tr[1])?;
                        add_shape_times(&mut fe, &shape.r, tr, w * len);
                    }
                    scatter_vector(map, &map.element_dofs(bi, &el.cps), &fe, &mut f);
                }
            }
        }
    }
    Ok(f)
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
