//! The fields sampled for a VTU: displacement, stress, von Mises stress and
//! the body index at the corners of linear quads inside every element.

use super::mesh::{PointField, VtuMesh, VTK_QUAD};
use super::sample::{anchor, in_element, sample_point};
use crate::assembly::ElementStress;
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::material::Formulation;
use crate::pressure::SplinePressure;
use std::sync::Arc;

/// von Mises stress including σ_zz, which plane strain makes non-zero:
/// leaving it out would understate the equivalent stress.
fn von_mises(s: [f64; 3], szz: f64) -> f64 {
    let [sxx, syy, sxy] = s;
    (0.5 * ((sxx - syy).powi(2) + (syy - szz).powi(2) + (szz - sxx).powi(2)) + 3.0 * sxy * sxy)
        .sqrt()
}

/// Samples every element of every body on a (`subdivisions` + 1)² grid of
/// parametric points and returns linear quads carrying the exact NURBS
/// fields at their corners: "displacement" (x, y, 0), "stress" (σxx, σyy,
/// σxy), "von_mises" and "body" (the body index).
///
/// Points are the undeformed positions (warp by "displacement" to see the
/// deformed shape). They are not shared between elements: stress is
/// discontinuous across C⁰ element edges, and duplicating points keeps each
/// element's own values instead of an arbitrary one.
pub fn sample_bodies(
    bodies: &[Body],
    map: &DofMap,
    u_full: &[f64],
    subdivisions: usize,
) -> Result<VtuMesh> {
    if subdivisions == 0 {
        return Err(Error::invalid("vtu.subdivisions", 0, "must be at least 1"));
    }
    if u_full.len() != map.n_total() {
        return Err(Error::invalid(
            "vtu.displacement",
            format!("{} values", u_full.len()),
            format!("the DOF map has {} DOFs", map.n_total()),
        ));
    }
    let n_dofs: usize = bodies.iter().map(|b| 2 * b.space.n_cp()).sum();
    if n_dofs != map.n_total() {
        return Err(Error::invalid(
            "vtu.bodies",
            format!("{} bodies with {n_dofs} DOFs", bodies.len()),
            format!("the DOF map has {} DOFs", map.n_total()),
        ));
    }
    if let Some(g) = u_full.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            format!("vtu.displacement[{g}]"),
            u_full[g],
            "must be a finite number",
        ));
    }

    let s = subdivisions;
    let per_el = (s + 1) * (s + 1);
    let n_el: usize = bodies.iter().map(|b| b.space.elements.len()).sum();
    let np = n_el * per_el;
    let mut mesh = VtuMesh {
        points: Vec::with_capacity(np),
        cells: Vec::with_capacity(n_el * s * s),
        cell_types: Vec::with_capacity(n_el * s * s),
        point_data: Vec::new(),
    };
    let mut disp = Vec::with_capacity(3 * np);
    let mut stress = Vec::with_capacity(3 * np);
    let mut vm = Vec::with_capacity(np);
    let mut body_id = Vec::with_capacity(np);

    for (bi, body) in bodies.iter().enumerate() {
        let space = &body.space;
        // the stress of the body's formulation (mixed: one pressure space
        // per body, shared by its elements)
        let pressure = match body.formulation {
            Formulation::Mixed => Some(Arc::new(SplinePressure::new(body)?)),
            _ => None,
        };
        for (ei, e) in space.elements.iter().enumerate() {
            let anchor =
                anchor(space, e).map_err(|err| err.map_geometry(|c| in_element(body, e, c)))?;
            let stress_of = ElementStress::with_pressure(body, ei, pressure.as_ref())?;
            let [[xa, xb], [ya, yb]] = e.range;
            let base = mesh.points.len() as i64;
            for j in 0..=s {
                // Exact end values, so neighbouring elements meet exactly.
                let eta = if j == s {
                    yb
                } else {
                    ya + (yb - ya) * j as f64 / s as f64
                };
                for i in 0..=s {
                    let xi = if i == s {
                        xb
                    } else {
                        xa + (xb - xa) * i as f64 / s as f64
                    };
                    let at = sample_point(space, e, &anchor, xi, eta);
                    // in the operation order of `assembly::displacement_at`
                    let mut u = [0.0; 2];
                    for (r, &cp) in at.r.iter().zip(&e.cps) {
                        let d = map.cp_displacement(u_full, bi, cp);
                        u[0] += r * d[0];
                        u[1] += r * d[1];
                    }
                    // θ̄ (mixed) needs no J⁻¹: it is taken at (ξ, η) itself
                    let (sig, szz) = stress_of.stress(map, u_full, bi, &at.strain, xi, eta);
                    mesh.points.push([at.x[0], at.x[1], 0.0]);
                    disp.extend([u[0], u[1], 0.0]);
                    stress.extend(sig);
                    vm.push(von_mises(sig, szz));
                    body_id.push(bi as f64);
                }
            }
            let w = (s + 1) as i64;
            for j in 0..s as i64 {
                for i in 0..s as i64 {
                    let p = base + i + j * w;
                    mesh.cells.push(vec![p, p + 1, p + 1 + w, p + w]);
                    mesh.cell_types.push(VTK_QUAD);
                }
            }
        }
    }
    mesh.point_data = vec![
        PointField {
            name: "displacement".into(),
            components: 3,
            values: disp,
        },
        PointField {
            name: "stress".into(),
            components: 3,
            values: stress,
        },
        PointField {
            name: "von_mises".into(),
            components: 1,
            values: vm,
        },
        PointField {
            name: "body".into(),
            components: 1,
            values: body_id,
        },
    ];
    // Finite inputs can still give non-finite outputs (an overflowing
    // displacement): catch it here, naming the field, not at write time.
    mesh.validate()?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn von_mises_of_pure_shear_and_hydrostatic_state() {
        assert!((von_mises([0.0, 0.0, 1.0], 0.0) - 3f64.sqrt()).abs() < 1e-15);
        assert_eq!(von_mises([2.0, 2.0, 0.0], 2.0), 0.0);
    }
}
