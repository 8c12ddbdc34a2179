//! Geometry builders. Circles are quadratic rational arcs, so every circular
//! boundary is exact, before and after refinement.

use crate::error::{Error, Result};
use crate::nurbs::interpolate::Collocation;
use crate::nurbs::{KnotVector, NurbsCurve, NurbsPatch};

const S: f64 = std::f64::consts::FRAC_1_SQRT_2;

fn check_positive(field: &str, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(field, v, "must be positive and finite"))
    }
}

fn bilinear() -> [KnotVector; 2] {
    let k = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).expect("static knots");
    [k.clone(), k]
}

fn quadratic_single_span() -> KnotVector {
    KnotVector::new(vec![0.0, 0.0, 0.0, 1.0, 1.0, 1.0], 2).expect("static knots")
}

/// The rectangle [x0, x1] × [y0, y1] as a bilinear patch (ξ along x, η along y).
pub fn rectangle(x0: f64, y0: f64, x1: f64, y1: f64) -> Result<NurbsPatch> {
    for (f, v) in [("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1)] {
        crate::error::finite(f, v)?;
    }
    check_positive("width", x1 - x0)?;
    check_positive("height", y1 - y0)?;
    NurbsPatch::new(
        bilinear(),
        vec![[x0, y0], [x1, y0], [x0, y1], [x1, y1]],
        vec![1.0; 4],
    )
}

/// A general bilinear quadrilateral with corners in counter-clockwise order
/// (used for distorted patch tests).
pub fn quadrilateral(c: [[f64; 2]; 4]) -> Result<NurbsPatch> {
    NurbsPatch::new(bilinear(), vec![c[0], c[1], c[3], c[2]], vec![1.0; 4])
}

/// The full disk of radius `r` about `center`: the classical nine-point
/// quadratic patch whose four sides are 90° arcs, with corners at 225°,
/// 315°, 45° and 135°.
///
/// The Jacobian vanishes at the four corners (the boundary is smooth there),
/// which Gauss quadrature never samples.
pub fn full_disk(center: [f64; 2], r: f64) -> Result<NurbsPatch> {
    check_positive("radius", r)?;
    let q = std::f64::consts::SQRT_2;
    let unit = [
        ([-S, -S], 1.0),
        ([0.0, -q], S),
        ([S, -S], 1.0),
        ([-q, 0.0], S),
        ([0.0, 0.0], 1.0),
        ([q, 0.0], S),
        ([-S, S], 1.0),
        ([0.0, q], S),
        ([S, S], 1.0),
    ];
    let points = unit
        .iter()
        .map(|(p, _)| [center[0] + r * p[0], center[1] + r * p[1]])
        .collect();
    let weights = unit.iter().map(|(_, w)| *w).collect();
    NurbsPatch::new(
        [quadratic_single_span(), quadratic_single_span()],
        points,
        weights,
    )
}

/// The half disk {x ≥ cx} of the disk of radius `r` about `center`: the
/// right half of [`full_disk`], cut exactly along ξ = 1/2 by knot insertion.
///
/// Sides: `xi_min` is the straight diameter (symmetry line), `eta_min` the
/// 45° arc from the lowest point (cx, cy − r) to the 315° point, `xi_max` the
/// 90° arc on the right and `eta_max` the 45° arc ending at the top.
pub fn half_disk(center: [f64; 2], r: f64) -> Result<NurbsPatch> {
    full_disk(center, r)?.upper_part_xi(0.5)
}

/// The quarter annulus r_in ≤ |x| ≤ r_out in the first quadrant. ξ runs
/// along the arcs (quadratic, from the x axis to the y axis), η radially
/// (linear). Sides: `eta_min` inner arc, `eta_max` outer arc, `xi_min` on
/// the x axis, `xi_max` on the y axis.
pub fn quarter_annulus(r_in: f64, r_out: f64) -> Result<NurbsPatch> {
    check_positive("inner_radius", r_in)?;
    check_positive("outer_radius - inner_radius", r_out - r_in)?;
    let mut points = Vec::new();
    let mut weights = Vec::new();
    for r in [r_in, r_out] {
        points.extend([[r, 0.0], [r, r], [0.0, r]]);
        weights.extend([1.0, S, 1.0]);
    }
    let lin = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1).expect("static knots");
    NurbsPatch::new([quadratic_single_span(), lin], points, weights)
}

/// A straight segment as a linear NURBS curve (a rigid flat obstacle).
pub fn segment(a: [f64; 2], b: [f64; 2]) -> Result<NurbsCurve> {
    let k = KnotVector::new(vec![0.0, 0.0, 1.0, 1.0], 1)?;
    NurbsCurve::new(k, vec![a, b], vec![1.0, 1.0])
}

/// The isoparametric Lagrange (FEM) counterpart of `exact`: a C⁰ spline of
/// degree `degree` on `elements` equal parameter spans per direction that
/// interpolates `exact` at the equispaced Lagrange nodes of every element.
///
/// Per element, the C⁰ spline space *is* Q_p, and interpolation at the
/// nodes is exactly the Lagrange interpolant, so this reproduces an
/// isoparametric Q1/Q2 mesh whose nodes lie on the exact geometry (on the
/// circle, for a disk) while the edges between nodes are polynomial chords.
/// Being a spline patch, it runs through the same assembly, contact and
/// solvers as the NURBS model — only the basis differs.
pub fn lagrange_interpolant(
    exact: &NurbsPatch,
    degree: usize,
    elements: [usize; 2],
) -> Result<NurbsPatch> {
    if !(1..=4).contains(&degree) {
        return Err(Error::invalid(
            "lagrange_degree",
            degree,
            "must lie in 1..=4",
        ));
    }
    let mut knots = Vec::new();
    let mut nodes = Vec::new();
    for (dir, &n) in elements.iter().enumerate() {
        let (a, b) = (exact.knots[dir].first(), exact.knots[dir].last());
        let kv = KnotVector::uniform(degree, n, 0)?;
        let tau: Vec<f64> = (0..=n * degree)
            .map(|k| a + (b - a) * k as f64 / (n * degree) as f64)
            .collect();
        let scaled: Vec<f64> = kv.knots().iter().map(|t| a + (b - a) * t).collect();
        knots.push(KnotVector::new(scaled, degree)?);
        nodes.push(tau);
    }
    let c0 = Collocation::new(&knots[0], &nodes[0])?;
    let c1 = Collocation::new(&knots[1], &nodes[1])?;
    let (n0, n1) = (nodes[0].len(), nodes[1].len());
    // Tensor-product interpolation: the values at the nodes, solved along
    // ξ for every η row, then along η for every ξ column.
    let mut values = Vec::with_capacity(n0 * n1);
    for &eta in &nodes[1] {
        for &xi in &nodes[0] {
            values.push(exact.point(xi, eta));
        }
    }
    let mut line = Vec::with_capacity(n0.max(n1));
    for c in 0..2 {
        for j in 0..n1 {
            line.clear();
            line.extend((0..n0).map(|i| values[i + j * n0][c]));
            c0.solve_in_place(&mut line);
            for (i, v) in line.iter().enumerate() {
                values[i + j * n0][c] = *v;
            }
        }
        for i in 0..n0 {
            line.clear();
            line.extend((0..n1).map(|j| values[i + j * n0][c]));
            c1.solve_in_place(&mut line);
            for (j, v) in line.iter().enumerate() {
                values[i + j * n0][c] = *v;
            }
        }
    }
    let points = values;
    let [k0, k1]: [KnotVector; 2] = knots.try_into().expect("two directions");
    NurbsPatch::new([k0, k1], points, vec![1.0; n0 * n1])
}
