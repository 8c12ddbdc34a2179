//! Element-by-element assembly of Eq. (3), a(u, v) = L(v), into sparse
//! triplets over the free DOFs.

use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::nurbs::Side;
use crate::quadrature;
use crate::space::Shape;
use nalgebra::{DMatrix, DVector};
use rayon::prelude::*;

/// Coordinate-format entries over the free DOFs. Duplicates are summed when
/// the matrix is built, so element matrices are appended as they come.
#[derive(Clone, Debug, Default)]
pub struct Triplets {
    pub rows: Vec<usize>,
    pub cols: Vec<usize>,
    pub vals: Vec<f64>,
}

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

    pub fn len(&self) -> usize {
        self.vals.len()
    }

    pub fn is_empty(&self) -> bool {
        self.vals.is_empty()
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

/// Element stiffness ∫ Bᵀ D B dΩ in local order (control point major).
pub fn element_stiffness(body: &Body, e: usize) -> Result<DMatrix<f64>> {
    let el = &body.space.elements[e];
    let n = el.cps.len();
    let d = body.material.d_matrix();
    let mut ke = DMatrix::zeros(2 * n, 2 * n);
    for qp in body.space.quadrature(el)? {
        // Blocks with b ≥ a only; the lower triangle is mirrored below.
        for a in 0..n {
            let ga = qp.shape.grad[a];
            for b in a..n {
                let k = btdb(ga, qp.shape.grad[b], &d);
                for i in 0..2 {
                    for j in 0..2 {
                        ke[(2 * a + i, 2 * b + j)] += qp.weight * k[i][j];
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
    Ok(ke)
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
            .map(|e| element_stiffness(body, e))
            .collect();
        for (e, ke) in kes.into_iter().enumerate() {
            let dofs = map.element_dofs(bi, &body.space.elements[e].cps);
            trip.add(map, &dofs, &ke?, &mut lift);
        }
    }
    Ok((trip, lift))
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

fn add_shape_times(fe: &mut DVector<f64>, shape: &Shape, v: [f64; 2], weight: f64) {
    for (a, r) in shape.r.iter().enumerate() {
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

/// The load vector L(v) over the free DOFs.
pub fn load_vector(bodies: &[Body], map: &DofMap, loads: &[Load]) -> Result<Vec<f64>> {
    let mut f = vec![0.0; map.n_free()];
    for load in loads {
        let bi = *load.body();
        let body = bodies.get(bi).ok_or_else(|| {
            Error::invalid(
                "load.body",
                bi,
                format!("there are {} bodies", bodies.len()),
            )
        })?;
        let space = &body.space;
        match *load {
            Load::BodyForce { force, .. } => {
                for (i, c) in force.iter().enumerate() {
                    crate::error::finite(&format!("load.body_force[{i}]"), *c)?;
                }
                // elements in parallel, scattered in order: deterministic
                let fes: Vec<Result<DVector<f64>>> = space
                    .elements
                    .par_iter()
                    .map(|el| {
                        let mut fe = DVector::zeros(2 * el.cps.len());
                        for qp in space.quadrature(el)? {
                            add_shape_times(&mut fe, &qp.shape, force, qp.weight);
                        }
                        Ok(fe)
                    })
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
                        add_shape_times(&mut fe, &shape, tr, w * len);
                    }
                    scatter_vector(map, &map.element_dofs(bi, &el.cps), &fe, &mut f);
                }
            }
        }
    }
    Ok(f)
}

/// Strain (Voigt, engineering shear) and stress of body `body` at (ξ, η)
/// for the full displacement vector `u`.
pub fn strain_stress(
    bodies: &[Body],
    map: &DofMap,
    u: &[f64],
    body: usize,
    xi: f64,
    eta: f64,
) -> Result<([f64; 3], [f64; 3])> {
    let b = &bodies[body];
    let e = &b.space.elements[b.space.locate(xi, eta)];
    let shape = b.space.shape(e, xi, eta)?;
    let eps = strain_at(map, u, body, &e.cps, &shape);
    Ok((eps, b.material.stress(eps)))
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
