//! Open knot vectors and the B-spline basis (Cox–de Boor).

use crate::error::{Error, Result};

/// A validated open knot vector of degree `p`.
///
/// Invariants, checked by [`KnotVector::new`]: finite, non-decreasing,
/// the first and last knots repeated exactly `p + 1` times (open), interior
/// multiplicities at most `p` (so the basis stays continuous), and a
/// non-empty parameter range.
#[derive(Clone, Debug, PartialEq)]
pub struct KnotVector {
    knots: Vec<f64>,
    degree: usize,
}

impl KnotVector {
    /// Validates `knots` for degree `degree`; `field` names the input in errors.
    pub fn new(knots: Vec<f64>, degree: usize) -> Result<Self> {
        Self::validated(knots, degree, "knots")
    }

    /// As [`KnotVector::new`], naming the input `field` in errors.
    pub fn validated(knots: Vec<f64>, degree: usize, field: &str) -> Result<Self> {
        if degree < 1 {
            return Err(Error::invalid(
                format!("{field}.degree"),
                degree,
                "must be at least 1",
            ));
        }
        let p = degree;
        if knots.len() < 2 * (p + 1) {
            return Err(Error::invalid(
                field,
                format!("{knots:?}"),
                format!("needs at least {} knots for degree {p}", 2 * (p + 1)),
            ));
        }
        for (i, &k) in knots.iter().enumerate() {
            if !k.is_finite() {
                return Err(Error::invalid(format!("{field}[{i}]"), k, "must be finite"));
            }
            if i > 0 && k < knots[i - 1] {
                return Err(Error::invalid(
                    format!("{field}[{i}]"),
                    k,
                    "knots must be non-decreasing",
                ));
            }
        }
        let (first, last) = (knots[0], knots[knots.len() - 1]);
        if last <= first {
            return Err(Error::invalid(
                field,
                format!("{knots:?}"),
                "parameter range is empty",
            ));
        }
        let mut i = 0;
        while i < knots.len() {
            let mut m = 1;
            while i + m < knots.len() && knots[i + m] == knots[i] {
                m += 1;
            }
            let at_end = i == 0 || i + m == knots.len();
            if at_end && m != p + 1 {
                return Err(Error::invalid(
                    format!("{field}[{i}]"),
                    knots[i],
                    format!("an open knot vector repeats its end knots exactly p+1 = {} times (found {m})", p + 1),
                ));
            }
            if !at_end && m > p {
                return Err(Error::invalid(
                    format!("{field}[{i}]"),
                    knots[i],
                    format!("interior multiplicity {m} exceeds the degree {p}: the basis would be discontinuous"),
                ));
            }
            i += m;
        }
        Ok(Self { knots, degree })
    }

    /// Open knot vector on [0, 1] with `spans` equal spans, each interior
    /// knot repeated `p - continuity` times (continuity = p - 1 is maximal).
    pub fn uniform(degree: usize, spans: usize, continuity: usize) -> Result<Self> {
        if spans == 0 {
            return Err(Error::invalid("elements", spans, "must be at least 1"));
        }
        if degree >= 1 && continuity >= degree {
            return Err(Error::invalid(
                "continuity",
                continuity,
                "must be below the degree",
            ));
        }
        let mult = degree.saturating_sub(continuity);
        let mut k = vec![0.0; degree + 1];
        for s in 1..spans {
            k.extend(std::iter::repeat_n(s as f64 / spans as f64, mult));
        }
        k.extend(std::iter::repeat_n(1.0, degree + 1));
        Self::new(k, degree)
    }

    pub fn degree(&self) -> usize {
        self.degree
    }

    pub fn knots(&self) -> &[f64] {
        &self.knots
    }

    /// Number of basis functions.
    pub fn n_basis(&self) -> usize {
        self.knots.len() - self.degree - 1
    }

    pub fn first(&self) -> f64 {
        self.knots[0]
    }

    pub fn last(&self) -> f64 {
        self.knots[self.knots.len() - 1]
    }

    /// Distinct knot values, in order.
    pub fn breaks(&self) -> Vec<f64> {
        let mut b: Vec<f64> = Vec::new();
        for &k in &self.knots {
            if b.last() != Some(&k) {
                b.push(k);
            }
        }
        b
    }

    /// Multiplicity of each distinct knot value, aligned with [`Self::breaks`].
    pub fn multiplicities(&self) -> Vec<usize> {
        let b = self.breaks();
        b.iter()
            .map(|v| self.knots.iter().filter(|k| *k == v).count())
            .collect()
    }

    /// Non-empty spans as `(span index, start, end)`, where the span index
    /// `i` satisfies `knots[i] <= u < knots[i+1]` inside the span.
    pub fn spans(&self) -> Vec<(usize, f64, f64)> {
        (self.degree..self.n_basis())
            .filter(|&i| self.knots[i + 1] > self.knots[i])
            .map(|i| (i, self.knots[i], self.knots[i + 1]))
            .collect()
    }

    /// The span index holding `u` (clamped into the parameter range; the
    /// right end belongs to the last non-empty span).
    pub fn find_span(&self, u: f64) -> usize {
        let n = self.n_basis();
        let p = self.degree;
        if u >= self.knots[n] {
            return n - 1;
        }
        if u <= self.knots[p] {
            return p;
        }
        // binary search for knots[i] <= u < knots[i+1]
        let (mut lo, mut hi) = (p, n);
        while hi - lo > 1 {
            let mid = (lo + hi) / 2;
            if u < self.knots[mid] {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        lo
    }

    /// The `p + 1` non-zero basis functions on span `span` at `u` and their
    /// derivatives up to order `nd`: `out[k][j]` is the k-th derivative of
    /// N_{span-p+j}. Cox–de Boor with the triangular table of Piegl & Tiller.
    pub fn basis_ders(&self, span: usize, u: f64, nd: usize) -> Vec<Vec<f64>> {
        let p = self.degree;
        let k = &self.knots;
        let mut ndu = vec![vec![0.0; p + 1]; p + 1];
        let mut left = vec![0.0; p + 1];
        let mut right = vec![0.0; p + 1];
        ndu[0][0] = 1.0;
        for j in 1..=p {
            left[j] = u - k[span + 1 - j];
            right[j] = k[span + j] - u;
            let mut saved = 0.0;
            for r in 0..j {
                ndu[j][r] = right[r + 1] + left[j - r];
                let temp = ndu[r][j - 1] / ndu[j][r];
                ndu[r][j] = saved + right[r + 1] * temp;
                saved = left[j - r] * temp;
            }
            ndu[j][j] = saved;
        }
        let nd_eff = nd.min(p);
        let mut ders = vec![vec![0.0; p + 1]; nd + 1];
        for j in 0..=p {
            ders[0][j] = ndu[j][p];
        }
        let mut a = [vec![0.0; p + 1], vec![0.0; p + 1]];
        for r in 0..=p {
            let (mut s1, mut s2) = (0usize, 1usize);
            a[0][0] = 1.0;
            for kk in 1..=nd_eff {
                let mut d = 0.0;
                let rk = r as isize - kk as isize;
                let pk = p - kk;
                if r >= kk {
                    a[s2][0] = a[s1][0] / ndu[pk + 1][rk as usize];
                    d = a[s2][0] * ndu[rk as usize][pk];
                }
                let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
                let j2 = if (r as isize - 1) <= pk as isize {
                    kk - 1
                } else {
                    p - r
                };
                for j in j1..=j2 {
                    let idx = (rk + j as isize) as usize;
                    a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                    d += a[s2][j] * ndu[idx][pk];
                }
                if r <= pk {
                    a[s2][kk] = -a[s1][kk - 1] / ndu[pk + 1][r];
                    d += a[s2][kk] * ndu[r][pk];
                }
                ders[kk][r] = d;
                std::mem::swap(&mut s1, &mut s2);
            }
        }
        let mut fac = p as f64;
        for kk in 1..=nd_eff {
            for v in ders[kk].iter_mut() {
                *v *= fac;
            }
            fac *= (p - kk) as f64;
        }
        ders
    }

    /// Greville abscissae: the averages of `p` consecutive interior knots.
    pub fn greville(&self) -> Vec<f64> {
        let p = self.degree;
        (0..self.n_basis())
            .map(|i| self.knots[i + 1..=i + p].iter().sum::<f64>() / p as f64)
            .collect()
    }

    /// The knot vector with every distinct knot repeated once more: the
    /// space of degree p+1 that contains this one (degree elevation).
    pub fn elevated(&self) -> KnotVector {
        let mut k = Vec::with_capacity(self.knots.len() + self.breaks().len());
        for (b, m) in self.breaks().into_iter().zip(self.multiplicities()) {
            k.extend(std::iter::repeat_n(b, m + 1));
        }
        KnotVector {
            knots: k,
            degree: self.degree + 1,
        }
    }

    /// This knot vector with `extra` knots merged in (knot insertion).
    pub fn with_inserted(&self, extra: &[f64]) -> Result<KnotVector> {
        let mut k = self.knots.clone();
        k.extend_from_slice(extra);
        k.sort_by(f64::total_cmp);
        KnotVector::validated(k, self.degree, "inserted knots")
    }

    /// Knots that split every non-empty span into `n` equal parts.
    pub fn subdivision_knots(&self, n: usize) -> Vec<f64> {
        let mut out = Vec::new();
        for (_, a, b) in self.spans() {
            for s in 1..n {
                out.push(a + (b - a) * s as f64 / n as f64);
            }
        }
        out
    }
}
