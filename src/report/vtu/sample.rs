//! Where a VTU sample is drawn and which shape functions its strain comes
//! from, when the geometric map is not regular at the requested point.
//!
//! Two kinds of points need care. At the corners of the nine-point disk the
//! exact map is singular (det J = 0, up to rounding), but only the
//! parameterisation is: an exact field is smooth there, yet the gradients
//! of the discrete solution grow like 1 / det J towards the corner (as the
//! normal stress of the corner element does in the penalty chapter); a
//! sample 1e-6 element sizes inside gave von Mises stresses 10³ times the
//! peak contact pressure on the shipped Hertz run. The isoparametric
//! Lagrange interpolant of that disk instead folds in a sliver at those
//! corners (det J < 0 within about 1.4 % of an element of the corner for
//! Q2 on 8 × 8), with the same growth towards the fold line. In both cases
//! the strain is taken well inside the regular part, while the point drawn
//! and its displacement stay at the requested point (neither needs J⁻¹), so
//! the grid stays closed.
//!
//! Every sample falls back, at worst, on the element's [`Anchor`], a point
//! where the map is regular. On a mesh the solver accepted the element
//! centre or one of its quadrature points is one, so sampling it cannot
//! fail; [`check_sampling`] finds the anchors before a solve.

use crate::dofs::Body;
use crate::error::{GeometryError, Result};
use crate::quadrature;
use crate::space::{Element, Shape, Space};

/// A det J this much smaller than at the element centre counts as singular
/// even though it is positive: at the corners of the nine-point disk
/// rounding leaves det J ≈ 1e-15 of the centre value instead of 0, so
/// [`Space::shape`] succeeds but its gradients are noise.
const SINGULAR_RATIO: f64 = 1e-8;

/// Where the map is singular or folds, the strain is taken at the first of
/// these steps towards the anchor (fractions δ of the element: scaling
/// about the centre by 1 − 2δ moves a corner by δ·h in each direction)
/// where det J is at least [`REGULAR_RATIO`] of the anchor's; the anchor
/// itself is the last resort.
const FOLD_STEPS: [f64; 6] = [0.01, 0.02, 0.05, 0.1, 0.2, 0.35];

/// How regular the map must be where a folded point's strain is taken.
/// Measured at the folded corner (1, 0) of the Q2 Hertz solution on
/// 8 × 8: σ_xx is −204 kPa where det J is 1/100 of the centre's (δ = 0.01),
/// −18.5 kPa at 1/11 (δ = 0.05) and −7.3 kPa at 1/5 (δ = 0.1), against
/// −4.5 to −12 kPa at the element's other samples: at 1/10 the fold no
/// longer dominates the value.
const REGULAR_RATIO: f64 = 0.1;

/// A point of an element where the map is regular: the element centre if
/// it is, else its quadrature point of largest det J. Every sample of the
/// element falls back on it.
#[derive(Clone, Debug)]
pub(super) struct Anchor {
    param: [f64; 2],
    shape: Shape,
}

/// One sample: where it is drawn and what its fields are evaluated from.
#[derive(Clone, Debug)]
pub(super) struct SamplePoint {
    /// The physical (undeformed) point drawn.
    pub x: [f64; 2],
    /// The basis at the drawn point, in the element's local order: the
    /// displacement there is Σ r_a d_a.
    pub r: Vec<f64>,
    /// The shape functions whose gradients give the strain.
    pub strain: Shape,
}

impl SamplePoint {
    fn at(shape: Shape) -> Self {
        SamplePoint {
            x: shape.x,
            r: shape.r.clone(),
            strain: shape,
        }
    }
}

/// The [`Anchor`] of element `e`, or why it has none: the error at the
/// centre.
pub(super) fn anchor(space: &Space, e: &Element) -> Result<Anchor> {
    let [[xa, xb], [ya, yb]] = e.range;
    let centre = [0.5 * (xa + xb), 0.5 * (ya + yb)];
    let at_centre = match space.shape(e, centre[0], centre[1]) {
        Ok(shape) => {
            return Ok(Anchor {
                param: centre,
                shape,
            })
        }
        Err(err) => err,
    };
    // a centre off a Gauss point (an even rule) may lie in a fold the
    // solver never sees; its quadrature points are then regular
    let n = space.quad_order;
    let mut best: Option<Anchor> = None;
    for (xi, _) in quadrature::on_interval(n, xa, xb) {
        for (eta, _) in quadrature::on_interval(n, ya, yb) {
            if let Ok(shape) = space.shape(e, xi, eta) {
                if best.as_ref().is_none_or(|b| shape.det_j > b.shape.det_j) {
                    best = Some(Anchor {
                        param: [xi, eta],
                        shape,
                    });
                }
            }
        }
    }
    best.ok_or(at_centre)
}

/// The sample of element `e` at (ξ, η): there if the map is regular; where
/// it is singular (the disk corners) or folds,
/// drawn at (ξ, η) with the strain of the first regular point towards the
/// anchor. Cannot fail: the anchor is regular.
pub(super) fn sample_point(
    space: &Space,
    e: &Element,
    anchor: &Anchor,
    xi: f64,
    eta: f64,
) -> SamplePoint {
    let det_ref = anchor.shape.det_j;
    let regular = |s: &Shape, ratio: f64| s.det_j >= ratio * det_ref;
    if let Ok(s) = space.shape(e, xi, eta) {
        if regular(&s, SINGULAR_RATIO) {
            return SamplePoint::at(s);
        }
    }
    let c = anchor.param;
    let towards = |d: f64| {
        [
            c[0] + (1.0 - 2.0 * d) * (xi - c[0]),
            c[1] + (1.0 - 2.0 * d) * (eta - c[1]),
        ]
    };
    let strain = FOLD_STEPS
        .iter()
        .find_map(|&d| {
            let [x, y] = towards(d);
            space
                .shape(e, x, y)
                .ok()
                .filter(|s| regular(s, REGULAR_RATIO))
        })
        .unwrap_or_else(|| anchor.shape.clone());
    let b = space.patch.basis_in_spans(e.spans, xi, eta);
    SamplePoint {
        x: space.patch.map(&b),
        r: b.r,
        strain,
    }
}

/// `cause` located at element `e` of `body`.
pub(super) fn in_element(body: &Body, e: &Element, cause: GeometryError) -> GeometryError {
    GeometryError::Element {
        body: body.name.clone(),
        spans: e.spans,
        cause: Box::new(cause),
    }
}

/// Everything about the VTU sampling of `bodies` that the solution does not
/// decide: that every element has a regular point to fall back on. Cheap
/// (one shape evaluation per element, as a rule), so a run checks it
/// before it solves.
pub fn check_sampling(bodies: &[Body]) -> Result<()> {
    for body in bodies {
        for e in &body.space.elements {
            anchor(&body.space, e).map_err(|err| err.map_geometry(|c| in_element(body, e, c)))?;
        }
    }
    Ok(())
}
