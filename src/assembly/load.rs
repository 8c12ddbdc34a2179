//! External loads of Eq. (3) and the load vector L(v).

use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::nurbs::Side;
use crate::quadrature;
use crate::space::ElementValues;
use nalgebra::DVector;
use rayon::prelude::*;

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

pub(super) fn add_shape_times(fe: &mut DVector<f64>, r: &[f64], v: [f64; 2], weight: f64) {
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

/// The body forces of `loads` summed per body (for [`stiffness_matrix`](super::stiffness_matrix)),
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
