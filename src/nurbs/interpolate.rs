//! Spline interpolation: the coefficients of the spline of a knot vector
//! that takes given values at given points.
//!
//! When the points satisfy the Schoenberg–Whitney condition (N_k(τ_k) ≠ 0),
//! the collocation matrix `B[k][i] = N_i(τ_k)` is banded — row k holds at most
//! p + 1 consecutive non-zeros, and the diagonal lies among them — and
//! totally positive, so Gaussian elimination without pivoting is stable
//! (de Boor, 1976). Elimination inside the band costs O(n p²) time and
//! O(n p) memory, where a dense solve would cost O(n³) and O(n²).

use super::knots::KnotVector;
use crate::error::{GeometryError, Result};

/// The LU factors of a collocation matrix, in band storage: entry (k, j)
/// at `band[k * width + (j + p - k)]` for |j − k| ≤ p.
pub struct Collocation {
    n: usize,
    p: usize,
    band: Vec<f64>,
}

impl Collocation {
    /// Factorises the collocation matrix of `knots` at the increasing points `tau`.
    pub fn new(knots: &KnotVector, tau: &[f64]) -> Result<Self> {
        let n = knots.n_basis();
        let p = knots.degree();
        if tau.len() != n {
            return Err(GeometryError::InterpolationPointCount {
                basis: n,
                points: tau.len(),
            }
            .into());
        }
        let width = 2 * p + 1;
        let mut band = vec![0.0; n * width];
        for (k, &t) in tau.iter().enumerate() {
            let span = knots.find_span(t);
            let values = &knots.basis_ders(span, t, 0)[0];
            for (a, &v) in values.iter().enumerate() {
                let j = span - p + a;
                if j.abs_diff(k) > p {
                    if v != 0.0 {
                        return Err(GeometryError::FarFromSupport {
                            point: t,
                            function: k,
                        }
                        .into());
                    }
                    continue;
                }
                band[k * width + j + p - k] = v;
            }
        }
        let at = |k: usize, j: usize| k * width + j + p - k;
        for k in 0..n {
            let pivot = band[at(k, k)];
            if !(pivot.is_finite() && pivot.abs() > 0.0) {
                return Err(GeometryError::OutsideSupport {
                    point: tau[k],
                    function: k,
                }
                .into());
            }
            for i in k + 1..(k + p + 1).min(n) {
                let l = band[at(i, k)] / pivot;
                if l == 0.0 {
                    continue;
                }
                band[at(i, k)] = l;
                for j in k + 1..(k + p + 1).min(n) {
                    band[at(i, j)] -= l * band[at(k, j)];
                }
            }
        }
        Ok(Self { n, p, band })
    }

    /// Number of unknowns.
    pub fn n(&self) -> usize {
        self.n
    }

    /// Overwrites the values `b` (one per point) with the coefficients.
    pub fn solve_in_place(&self, b: &mut [f64]) {
        let (n, p) = (self.n, self.p);
        let width = 2 * p + 1;
        let at = |k: usize, j: usize| k * width + j + p - k;
        for i in 0..n {
            let mut s = b[i];
            for k in i.saturating_sub(p)..i {
                s -= self.band[at(i, k)] * b[k];
            }
            b[i] = s;
        }
        for i in (0..n).rev() {
            let mut s = b[i];
            for j in i + 1..(i + p + 1).min(n) {
                s -= self.band[at(i, j)] * b[j];
            }
            b[i] = s / self.band[at(i, i)];
        }
    }
}
