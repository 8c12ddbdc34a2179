//! Rational curves: boundaries of patches and rigid obstacles.

use super::knots::KnotVector;
use crate::error::{Error, Result};

/// A planar NURBS curve C(u) = Σ R_i(u) P_i.
#[derive(Clone, Debug)]
pub struct NurbsCurve {
    pub knots: KnotVector,
    pub points: Vec<[f64; 2]>,
    pub weights: Vec<f64>,
}

/// Rational basis of a curve at one parameter: the non-zero functions, their
/// first derivatives, and the indices of the control points they belong to.
#[derive(Clone, Debug)]
pub struct CurveBasis {
    pub first: usize,
    pub r: Vec<f64>,
    pub dr: Vec<f64>,
}

impl NurbsCurve {
    pub fn new(knots: KnotVector, points: Vec<[f64; 2]>, weights: Vec<f64>) -> Result<Self> {
        check_net(knots.n_basis(), &points, &weights, "curve")?;
        Ok(Self {
            knots,
            points,
            weights,
        })
    }

    /// Rational basis at `u`, computed in the span that holds `u`.
    pub fn basis(&self, u: f64) -> CurveBasis {
        self.basis_in_span(self.knots.find_span(u), u)
    }

    /// Rational basis at `u` in a given span (needed at knots, where the
    /// one-sided derivative depends on the span).
    pub fn basis_in_span(&self, span: usize, u: f64) -> CurveBasis {
        let p = self.knots.degree();
        let n = self.knots.basis_ders(span, u, 1);
        let first = span - p;
        rationalise(&n[0], &n[1], &self.weights[first..=first + p], first)
    }

    pub fn point(&self, u: f64) -> [f64; 2] {
        let b = self.basis(u);
        combine(&b.r, &self.points[b.first..])
    }

    /// Point and first derivative.
    pub fn point_and_tangent(&self, u: f64) -> ([f64; 2], [f64; 2]) {
        let b = self.basis(u);
        (
            combine(&b.r, &self.points[b.first..]),
            combine(&b.dr, &self.points[b.first..]),
        )
    }

    /// Second derivative by central differences of the exact first
    /// derivative; only used to accelerate closest-point Newton steps.
    pub fn second_derivative(&self, u: f64) -> [f64; 2] {
        let h = 1e-6 * (self.knots.last() - self.knots.first());
        let a = (u - h).max(self.knots.first());
        let b = (u + h).min(self.knots.last());
        let (_, ta) = self.point_and_tangent(a);
        let (_, tb) = self.point_and_tangent(b);
        [(tb[0] - ta[0]) / (b - a), (tb[1] - ta[1]) / (b - a)]
    }
}

/// Turns B-spline values/derivatives into NURBS ones:
/// R_i = N_i w_i / W and R_i' = (N_i' w_i W - N_i w_i W') / W².
pub(crate) fn rationalise(n: &[f64], dn: &[f64], w: &[f64], first: usize) -> CurveBasis {
    let big_w: f64 = n.iter().zip(w).map(|(a, b)| a * b).sum();
    let big_dw: f64 = dn.iter().zip(w).map(|(a, b)| a * b).sum();
    let r: Vec<f64> = n.iter().zip(w).map(|(a, b)| a * b / big_w).collect();
    let dr = dn
        .iter()
        .zip(n)
        .zip(w)
        .map(|((d, v), wi)| wi * (d * big_w - v * big_dw) / (big_w * big_w))
        .collect();
    CurveBasis { first, r, dr }
}

pub(crate) fn combine(coef: &[f64], pts: &[[f64; 2]]) -> [f64; 2] {
    let mut x = [0.0; 2];
    for (c, p) in coef.iter().zip(pts) {
        x[0] += c * p[0];
        x[1] += c * p[1];
    }
    x
}

/// Validates a control net: sizes agree, coordinates finite, weights positive.
pub(crate) fn check_net(n: usize, points: &[[f64; 2]], weights: &[f64], what: &str) -> Result<()> {
    if points.len() != n {
        return Err(Error::invalid(
            format!("{what}.control_points"),
            points.len(),
            format!("the knot vectors need {n} control points"),
        ));
    }
    if weights.len() != n {
        return Err(Error::invalid(
            format!("{what}.weights"),
            weights.len(),
            format!("the knot vectors need {n} weights"),
        ));
    }
    for (i, p) in points.iter().enumerate() {
        if !(p[0].is_finite() && p[1].is_finite()) {
            return Err(Error::invalid(
                format!("{what}.control_points[{i}]"),
                format!("{p:?}"),
                "must be finite",
            ));
        }
    }
    for (i, w) in weights.iter().enumerate() {
        if !(w.is_finite() && *w > 0.0) {
            return Err(Error::invalid(
                format!("{what}.weights[{i}]"),
                w,
                "weights must be positive and finite",
            ));
        }
    }
    Ok(())
}
