//! Exact refinement: knot insertion (h), degree elevation (p) and their
//! composition (k).
//!
//! All three are one operation: re-expressing a spline in a richer space
//! that contains it. In homogeneous coordinates (wP, w) a NURBS is a plain
//! B-spline, so if the new knot vector spans a superset of the old space the
//! new coefficients are uniquely fixed by interpolation at the Greville
//! points of the new space (Schoenberg–Whitney guarantees the collocation
//! matrix is invertible). The geometry is therefore unchanged up to
//! round-off, which the tests check to 1e-12.

use super::curve::NurbsCurve;
use super::knots::KnotVector;
use super::patch::NurbsPatch;
use crate::error::{Error, Result};
use nalgebra::DMatrix;

/// Dense collocation matrix B[k][i] = N_i(τ_k) of `knots` at the points `tau`.
fn collocation(knots: &KnotVector, tau: &[f64]) -> DMatrix<f64> {
    let p = knots.degree();
    let mut m = DMatrix::zeros(tau.len(), knots.n_basis());
    for (k, &t) in tau.iter().enumerate() {
        let span = knots.find_span(t);
        let n = knots.basis_ders(span, t, 0);
        for a in 0..=p {
            m[(k, span - p + a)] = n[0][a];
        }
    }
    m
}

/// Coefficients in `new` of the splines whose coefficients in `old` are the
/// columns of `coef` (one row per old basis function). `new` must contain
/// the old space; this is checked by comparing the splines at the new
/// Greville points after the solve.
pub fn respace(old: &KnotVector, new: &KnotVector, coef: &DMatrix<f64>) -> Result<DMatrix<f64>> {
    if new.degree() < old.degree() || new.first() != old.first() || new.last() != old.last() {
        return Err(Error::Geometry(
            "refinement must keep the parameter range and not lower the degree".into(),
        ));
    }
    for (b, m) in old.breaks().iter().zip(old.multiplicities()) {
        let m_new = new.knots().iter().filter(|k| *k == b).count();
        let needed = m + new.degree() - old.degree();
        if m_new < needed {
            return Err(Error::Geometry(format!(
                "knot {b} needs multiplicity {needed} in the refined space to keep the continuity, got {m_new}"
            )));
        }
    }
    let tau = new.greville();
    let values = collocation(old, &tau) * coef;
    let lu = collocation(new, &tau).lu();
    lu.solve(&values).ok_or_else(|| {
        Error::Geometry("collocation matrix of the refined space is singular".into())
    })
}

impl NurbsCurve {
    /// The same curve in the space of `new`.
    pub fn respaced(&self, new: KnotVector) -> Result<Self> {
        let n = self.knots.n_basis();
        let mut c = DMatrix::zeros(n, 3);
        for i in 0..n {
            let w = self.weights[i];
            c[(i, 0)] = w * self.points[i][0];
            c[(i, 1)] = w * self.points[i][1];
            c[(i, 2)] = w;
        }
        let d = respace(&self.knots, &new, &c)?;
        let (points, weights) = (0..new.n_basis())
            .map(|i| dehomogenise(d[(i, 0)], d[(i, 1)], d[(i, 2)]))
            .unzip();
        NurbsCurve::new(new, points, weights)
    }
}

fn dehomogenise(wx: f64, wy: f64, w: f64) -> ([f64; 2], f64) {
    ([wx / w, wy / w], w)
}

impl NurbsPatch {
    /// The same patch with direction `dir` (0 = ξ, 1 = η) in the space of `new`.
    pub fn respaced(&self, dir: usize, new: KnotVector) -> Result<Self> {
        let [n0, n1] = self.n();
        let (n_dir, n_other) = if dir == 0 { (n0, n1) } else { (n1, n0) };
        let idx = |a: usize, b: usize, n_first: usize| {
            if dir == 0 {
                a + b * n_first
            } else {
                b + a * n_first
            }
        };
        let mut c = DMatrix::zeros(n_dir, 3 * n_other);
        for a in 0..n_dir {
            for b in 0..n_other {
                let k = idx(a, b, n0);
                let w = self.weights[k];
                c[(a, 3 * b)] = w * self.points[k][0];
                c[(a, 3 * b + 1)] = w * self.points[k][1];
                c[(a, 3 * b + 2)] = w;
            }
        }
        let d = respace(&self.knots[dir], &new, &c)?;
        let n_new = new.n_basis();
        let new_n0 = if dir == 0 { n_new } else { n0 };
        let total = n_new * n_other;
        let mut points = vec![[0.0; 2]; total];
        let mut weights = vec![0.0; total];
        for a in 0..n_new {
            for b in 0..n_other {
                let k = idx(a, b, new_n0);
                let (p, w) = dehomogenise(d[(a, 3 * b)], d[(a, 3 * b + 1)], d[(a, 3 * b + 2)]);
                points[k] = p;
                weights[k] = w;
            }
        }
        let mut knots = self.knots.clone();
        knots[dir] = new;
        NurbsPatch::new(knots, points, weights)
    }

    /// h-refinement: insert `knots` in direction `dir`.
    pub fn insert_knots(&self, dir: usize, knots: &[f64]) -> Result<Self> {
        let new = self.knots[dir].with_inserted(knots)?;
        self.respaced(dir, new)
    }

    /// p-refinement: raise the degree of direction `dir` by one, keeping the
    /// continuity at every knot.
    pub fn elevate(&self, dir: usize) -> Result<Self> {
        let new = self.knots[dir].elevated();
        self.respaced(dir, new)
    }

    /// k-refinement: elevate both directions to `degree` (if lower), then
    /// split every knot span into `divisions[d]` equal parts. Elevating
    /// first gives the maximal C^{p-1} continuity at the new knots.
    pub fn k_refined(&self, degree: usize, divisions: [usize; 2]) -> Result<Self> {
        let mut out = self.clone();
        for dir in 0..2 {
            if divisions[dir] == 0 {
                return Err(Error::invalid(
                    format!("divisions[{dir}]"),
                    0,
                    "must be at least 1",
                ));
            }
            while out.knots[dir].degree() < degree {
                out = out.elevate(dir)?;
            }
            let extra = out.knots[dir].subdivision_knots(divisions[dir]);
            if !extra.is_empty() {
                out = out.insert_knots(dir, &extra)?;
            }
        }
        Ok(out)
    }

    /// Splits the patch at ξ = `at` and keeps the part ξ ≥ `at`,
    /// re-parameterised on [0, 1]. Used to cut the half disk out of the full one.
    pub fn upper_part_xi(&self, at: f64) -> Result<Self> {
        let p = self.knots[0].degree();
        let have = self.knots[0].knots().iter().filter(|&&k| k == at).count();
        let cut = self.insert_knots(0, &vec![at; p.saturating_sub(have)])?;
        let k = cut.knots[0].knots();
        let first = k.iter().position(|&v| v == at).expect("inserted knot") - 1;
        let (lo, hi) = (at, cut.knots[0].last());
        let mut new_k = vec![0.0];
        new_k.extend(k[first + 1..].iter().map(|v| (v - lo) / (hi - lo)));
        let kv = KnotVector::new(new_k, p)?;
        let [n0, n1] = cut.n();
        let mut points = Vec::new();
        let mut weights = Vec::new();
        for j in 0..n1 {
            for i in first..n0 {
                points.push(cut.points[cut.index(i, j)]);
                weights.push(cut.weights[cut.index(i, j)]);
            }
        }
        NurbsPatch::new([kv, cut.knots[1].clone()], points, weights)
    }
}
