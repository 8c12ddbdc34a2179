//! What the chapters draw of a discretised problem: element boundaries,
//! control nets, and scalar fields sampled on (optionally deformed) bodies,
//! as the polylines and cells of [`super::plot`].

use super::plot::{FieldCell, LineKind, Polyline};
use crate::assembly::displacement_at;
use crate::error::Result;
use crate::nurbs::NurbsPatch;
use crate::problem::Problem;

/// The element boundaries (knot lines) of a patch, `samples` segments each.
pub fn element_lines(patch: &NurbsPatch, style: LineKind, color: usize) -> Vec<Polyline> {
    let mut lines = Vec::new();
    for dir in 0..2 {
        for b in patch.knots[dir].breaks() {
            lines.push(Polyline::new(patch.iso_curve(dir, b, 32), style, color));
        }
    }
    lines
}

/// The control net of a patch: its rows and columns of control points.
pub fn control_net(patch: &NurbsPatch, color: usize) -> Vec<Polyline> {
    let [n0, n1] = patch.n();
    let row = |j: usize| (0..n0).map(|i| patch.points[patch.index(i, j)]).collect();
    let col = |i: usize| (0..n1).map(|j| patch.points[patch.index(i, j)]).collect();
    (0..n1)
        .map(row)
        .chain((0..n0).map(col))
        .map(|pts| Polyline::new(pts, LineKind::ControlNet, color))
        .collect()
}

/// Gives every polyline the legend `label` (polylines sharing a label share
/// one legend entry).
pub fn labelled(lines: Vec<Polyline>, label: &str) -> Vec<Polyline> {
    lines.into_iter().map(|l| l.labelled(label)).collect()
}

/// Where a sampled field is drawn.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Placement {
    /// On the undeformed bodies.
    Reference,
    /// On the bodies moved by the displacement, at true scale.
    Deformed,
}

/// The state at the centre of a sampled cell.
#[derive(Clone, Copy, Debug)]
pub struct FieldPoint {
    pub body: usize,
    /// Reference position.
    pub x: [f64; 2],
    pub displacement: [f64; 2],
    /// Voigt stress (σ_xx, σ_yy, σ_xy).
    pub stress: [f64; 3],
}

/// `value` sampled on `sub` × `sub` cells per element of every body of
/// `problem` for the displacement `full`, each cell filled with the value
/// at its centre.
///
/// Cell corners need no Jacobian, so corners of a patch where the
/// parametrisation degenerates (the classical disk's) are drawn too; the
/// stress is only evaluated at cell centres, where the map is regular.
pub fn field_cells(
    problem: &Problem,
    full: &[f64],
    sub: usize,
    placement: Placement,
    value: impl Fn(&FieldPoint) -> f64,
) -> Result<Vec<FieldCell>> {
    let map = &problem.map;
    let n = sub.max(1);
    let mut cells = Vec::new();
    for (bi, body) in problem.bodies.iter().enumerate() {
        let space = &body.space;
        let pressure = match body.formulation {
            crate::material::Formulation::Mixed => Some(std::sync::Arc::new(
                crate::pressure::SplinePressure::new(body)?,
            )),
            _ => None,
        };
        for (ei, e) in space.elements.iter().enumerate() {
            let stress_of =
                crate::assembly::ElementStress::with_pressure(body, ei, pressure.as_ref())?;
            let [[xa, xb], [ya, yb]] = e.range;
            let param = |s: f64, t: f64| (xa + (xb - xa) * s, ya + (yb - ya) * t);
            let corner = |s: f64, t: f64| -> [f64; 2] {
                let (xi, eta) = param(s, t);
                let b = space.patch.basis_in_spans(e.spans, xi, eta);
                let x = space.patch.map(&b);
                match placement {
                    Placement::Reference => x,
                    Placement::Deformed => {
                        let mut u = [0.0; 2];
                        for (r, &cp) in b.r.iter().zip(&b.indices) {
                            let d = map.cp_displacement(full, bi, cp);
                            u[0] += r * d[0];
                            u[1] += r * d[1];
                        }
                        [x[0] + u[0], x[1] + u[1]]
                    }
                }
            };
            for j in 0..n {
                for i in 0..n {
                    let (s0, s1) = (i as f64 / n as f64, (i + 1) as f64 / n as f64);
                    let (t0, t1) = (j as f64 / n as f64, (j + 1) as f64 / n as f64);
                    let (xi, eta) = param(0.5 * (s0 + s1), 0.5 * (t0 + t1));
                    let shape = space.shape(e, xi, eta)?;
                    let point = FieldPoint {
                        body: bi,
                        x: shape.x,
                        displacement: displacement_at(map, full, bi, &e.cps, &shape),
                        stress: stress_of.stress(map, full, bi, &shape, xi, eta).0,
                    };
                    cells.push(FieldCell {
                        corners: [
                            corner(s0, t0),
                            corner(s1, t0),
                            corner(s1, t1),
                            corner(s0, t1),
                        ],
                        value: value(&point),
                    });
                }
            }
        }
    }
    Ok(cells)
}
