//! Closest-point projection of a slave point onto a master curve: the x̄²
//! of Eq. (4)–(5).

use crate::error::{GeometryError, Result};
use crate::nurbs::NurbsCurve;

/// Where a point projects on a curve.
#[derive(Clone, Copy, Debug)]
pub struct Projection {
    /// Curve parameter of the foot point.
    pub t: f64,
    pub point: [f64; 2],
    /// Unit tangent at the foot point (direction of increasing t).
    pub tangent: [f64; 2],
    pub distance: f64,
    /// False when the foot point is a curve end that is not an orthogonal
    /// projection: the slave point lies beyond the end of the master.
    pub orthogonal: bool,
}

fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// Projects `x` onto `curve`.
///
/// Newton on f(t) = (C(t) − x)·C'(t) is fast but only locally convergent
/// and can jump across knot spans on curved masters, so it is safeguarded:
/// it starts from the best of a few samples per knot span, stays inside the
/// parameter range, and a step that increases the distance is halved.
pub fn closest_point(curve: &NurbsCurve, x: [f64; 2]) -> Result<Projection> {
    if !(x[0].is_finite() && x[1].is_finite()) {
        return Err(GeometryError::NonFinitePoint { point: x }.into());
    }
    let (lo, hi) = (curve.knots.first(), curve.knots.last());
    let dist2 = |t: f64| {
        let d = sub(curve.point(t), x);
        dot(d, d)
    };
    let mut best = (lo, dist2(lo));
    for (_, a, b) in curve.knots.spans() {
        for k in 0..=8 {
            let t = a + (b - a) * k as f64 / 8.0;
            let d = dist2(t);
            if d < best.1 {
                best = (t, d);
            }
        }
    }
    let (mut t, mut d2) = best;
    let tol = 1e-15 * (hi - lo);
    for _ in 0..60 {
        let (c, dc) = curve.point_and_tangent(t);
        let ddc = curve.second_derivative(t);
        let r = sub(c, x);
        let f = dot(r, dc);
        let fp = dot(dc, dc) + dot(r, ddc);
        let fp = if fp > 0.0 { fp } else { dot(dc, dc) };
        let mut step = -f / fp;
        let mut accepted = false;
        for _ in 0..40 {
            let tn = (t + step).clamp(lo, hi);
            let dn = dist2(tn);
            if dn <= d2 * (1.0 + 1e-14) + 1e-300 {
                step = tn - t;
                t = tn;
                d2 = dn;
                accepted = true;
                break;
            }
            step *= 0.5;
        }
        if !accepted || step.abs() <= tol {
            break;
        }
    }
    let (c, dc) = curve.point_and_tangent(t);
    let len = dc[0].hypot(dc[1]);
    if len.is_nan() || len <= 0.0 || !c[0].is_finite() || !c[1].is_finite() {
        return Err(GeometryError::ZeroTangent { point: x, t }.into());
    }
    let tangent = [dc[0] / len, dc[1] / len];
    let r = sub(c, x);
    let distance = dot(r, r).sqrt();
    let scale = (hi - lo) * len;
    let orthogonal =
        dot(r, tangent).abs() <= 1e-8 * distance.max(1e-12 * scale) || (t > lo && t < hi);
    Ok(Projection {
        t,
        point: c,
        tangent,
        distance,
        orthogonal,
    })
}

/// Where the line through `x` along the unit vector `n` meets `curve`,
/// starting from the closest point (the nearest crossing on a curve that
/// the line meets once near `x`).
///
/// The unbiased form pairs each point of its mirrored half this way: a
/// point of the master side and the slave point whose closest point it is
/// lie on one normal line, so both halves measure one gap function (the
/// closest point from the master side would measure another along a
/// tilted normal, and the two penalties would pull against each other).
/// Newton on f(t) = (C(t) − x) × n, kept inside the parameter range;
/// `orthogonal` is false where the line misses the curve.
pub fn along_normal(curve: &NurbsCurve, x: [f64; 2], n: [f64; 2]) -> Result<Projection> {
    let start = closest_point(curve, x)?;
    let (lo, hi) = (curve.knots.first(), curve.knots.last());
    let cross = |a: [f64; 2]| a[0] * n[1] - a[1] * n[0];
    let mut t = start.t;
    let mut hit = false;
    for _ in 0..60 {
        let (c, dc) = curve.point_and_tangent(t);
        let f = cross(sub(c, x));
        let scale = dc[0].hypot(dc[1]) * (hi - lo);
        if f.abs() <= 1e-13 * scale.max(f64::MIN_POSITIVE) {
            hit = true;
            break;
        }
        let fp = cross(dc);
        if fp == 0.0 || !fp.is_finite() {
            break;
        }
        let tn = t - f / fp;
        if !(lo..=hi).contains(&tn) {
            break;
        }
        t = tn;
    }
    let (c, dc) = curve.point_and_tangent(t);
    let len = dc[0].hypot(dc[1]);
    if len.is_nan() || len <= 0.0 {
        return Err(GeometryError::NormalLineDegenerate { point: x, t }.into());
    }
    let r = sub(c, x);
    Ok(Projection {
        t,
        point: c,
        tangent: [dc[0] / len, dc[1] / len],
        distance: dot(r, r).sqrt(),
        orthogonal: hit && start.orthogonal,
    })
}
