//! Exact refinement: knot insertion (h), degree elevation (p) and their
//! composition (k), by the standard local algorithms.
//!
//! In homogeneous coordinates (wP, w) a NURBS is a plain B-spline, so both
//! operations act on B-spline coefficients:
//!
//! - **knot insertion** (Boehm's algorithm in the many-knots form of Piegl &
//!   Tiller, *The NURBS Book*, A5.4): each new coefficient is a convex
//!   combination of two old ones;
//! - **degree elevation** by Bézier extraction (Piegl & Tiller A5.9): every
//!   knot span is cut out as a Bézier segment by local knot insertion, the
//!   segment is elevated by the closed-form Bernstein formula, and the
//!   inserted knots are removed again, all in one sweep.
//!
//! Both touch each coefficient a bounded number of times (at most (p+1)²
//! operations per knot span), so refining n control points costs O(n p²)
//! time and O(n) memory. A patch is refined one direction at a time, the
//! rows of the other direction riding along as extra coordinates of each
//! coefficient. The geometry is unchanged up to round-off, which the tests
//! check to 1e-12 against an independent dense collocation solve.

use super::curve::NurbsCurve;
use super::knots::KnotVector;
use super::patch::NurbsPatch;
use crate::error::{Error, GeometryError, Result};

/// Spline coefficients with `dim` components each, coefficient i at
/// `data[i * dim..(i + 1) * dim]`.
struct Coefs {
    dim: usize,
    data: Vec<f64>,
}

impl Coefs {
    fn zeros(n: usize, dim: usize) -> Self {
        Self {
            dim,
            data: vec![0.0; n * dim],
        }
    }

    fn row(&self, i: usize) -> &[f64] {
        &self.data[i * self.dim..(i + 1) * self.dim]
    }

    fn row_mut(&mut self, i: usize) -> &mut [f64] {
        &mut self.data[i * self.dim..(i + 1) * self.dim]
    }

    fn copy_from(&mut self, i: usize, src: &[f64]) {
        self.row_mut(i).copy_from_slice(src);
    }

    /// Row i ← a·(row i) + (1 − a)·(row j), for i ≠ j.
    fn blend(&mut self, i: usize, a: f64, j: usize) {
        let d = self.dim;
        let (dst, src) = if i < j {
            let (lo, hi) = self.data.split_at_mut(j * d);
            (&mut lo[i * d..(i + 1) * d], &hi[..d])
        } else {
            let (lo, hi) = self.data.split_at_mut(i * d);
            (&mut hi[..d], &lo[j * d..(j + 1) * d])
        };
        for (x, y) in dst.iter_mut().zip(src) {
            *x = a * *x + (1.0 - a) * y;
        }
    }
}

/// Knot insertion, Piegl & Tiller A5.4: the coefficients of the same spline
/// on `knots` with the sorted interior values `x` added.
fn insert(knots: &[f64], p: usize, pw: &Coefs, x: &[f64]) -> (Vec<f64>, Coefs) {
    if x.is_empty() {
        return (
            knots.to_vec(),
            Coefs {
                dim: pw.dim,
                data: pw.data.clone(),
            },
        );
    }
    let u = knots;
    let n = u.len() - p - 2; // index of the last coefficient
    let m = n + p + 1; // index of the last knot
    let r = x.len() - 1;
    let span = |t: f64| {
        if t >= u[n + 1] {
            return n;
        }
        // knots[s] <= t < knots[s + 1], s in p..=n
        p + u[p + 1..=n + 1].partition_point(|&k| k <= t)
    };
    let a = span(x[0]);
    let b = span(x[r]) + 1;
    let mut qw = Coefs::zeros(n + r + 2, pw.dim);
    let mut ub = vec![0.0; m + r + 2];
    for j in 0..=a - p {
        qw.copy_from(j, pw.row(j));
    }
    for j in b - 1..=n {
        qw.copy_from(j + r + 1, pw.row(j));
    }
    ub[..=a].copy_from_slice(&u[..=a]);
    for j in b + p..=m {
        ub[j + r + 1] = u[j];
    }
    let mut i = b + p - 1;
    let mut k = b + p + r;
    for j in (0..=r).rev() {
        while x[j] <= u[i] && i > a {
            qw.copy_from(k - p - 1, pw.row(i - p - 1));
            ub[k] = u[i];
            k -= 1;
            i -= 1;
        }
        let (dst, src) = (k - p - 1, k - p);
        let row = qw.row(src).to_vec();
        qw.copy_from(dst, &row);
        for l in 1..=p {
            let ind = k - p + l;
            let alpha = ub[k + l] - x[j];
            if alpha == 0.0 {
                let row = qw.row(ind).to_vec();
                qw.copy_from(ind - 1, &row);
            } else {
                let alpha = alpha / (ub[k + l] - u[i - p + l]);
                qw.blend(ind - 1, alpha, ind);
            }
        }
        ub[k] = x[j];
        k -= 1;
    }
    (ub, qw)
}

fn binomial(n: usize, k: usize) -> f64 {
    (0..k).fold(1.0, |acc, i| acc * (n - i) as f64 / (i + 1) as f64)
}

/// a·x + b·y into `out`.
fn axpby(out: &mut [f64], a: f64, x: &[f64], b: f64, y: &[f64]) {
    for ((o, xv), yv) in out.iter_mut().zip(x).zip(y) {
        *o = a * xv + b * yv;
    }
}

/// Degree elevation by `t`, Piegl & Tiller A5.9: the coefficients and knots
/// of the same spline at degree p + t, every multiplicity raised by t.
fn elevate(knots: &[f64], p: usize, pw: &Coefs, t: usize) -> (Vec<f64>, Coefs) {
    if t == 0 {
        return (
            knots.to_vec(),
            Coefs {
                dim: pw.dim,
                data: pw.data.clone(),
            },
        );
    }
    let dim = pw.dim;
    let u = knots;
    let m = u.len() - 1;
    let ph = p + t;
    let ph2 = ph / 2;
    // Bézier elevation coefficients: bezalfs[i][j] = C(p,j) C(t,i-j) / C(ph,i)
    let mut bezalfs = vec![vec![0.0; p + 1]; ph + 1];
    bezalfs[0][0] = 1.0;
    bezalfs[ph][p] = 1.0;
    for i in 1..=ph2 {
        let inv = 1.0 / binomial(ph, i);
        for j in i.saturating_sub(t)..=p.min(i) {
            bezalfs[i][j] = inv * binomial(p, j) * binomial(t, i - j);
        }
    }
    for i in ph2 + 1..ph {
        for j in i.saturating_sub(t)..=p.min(i) {
            bezalfs[i][j] = bezalfs[ph - i][p - j];
        }
    }
    let breaks = {
        let mut c = 1;
        for w in u.windows(2) {
            if w[1] != w[0] {
                c += 1;
            }
        }
        c
    };
    let n_out = (u.len() - p - 1) + t * (breaks - 1);
    let mut qw = Coefs::zeros(n_out, dim);
    let mut uh = vec![0.0; n_out + ph + 1];
    let mut bpts = Coefs::zeros(p + 1, dim);
    let mut ebpts = Coefs::zeros(ph + 1, dim);
    let mut next_bpts = Coefs::zeros(p.saturating_sub(1).max(1), dim);
    let mut alphas = vec![0.0; p.max(1)];
    let mut scratch = vec![0.0; dim];

    let mut mh = ph;
    let mut kind = ph + 1;
    let mut r: isize = -1;
    let mut a = p;
    let mut b = p + 1;
    let mut cind = 1;
    let mut ua = u[0];
    qw.copy_from(0, pw.row(0));
    uh[..=ph].fill(ua);
    for i in 0..=p {
        bpts.copy_from(i, pw.row(i));
    }
    while b < m {
        let i0 = b;
        while b < m && u[b] == u[b + 1] {
            b += 1;
        }
        let mul = b - i0 + 1;
        mh += mul + t;
        let ub = u[b];
        let oldr = r;
        r = p as isize - mul as isize;
        let lbz = if oldr > 0 { (oldr as usize + 2) / 2 } else { 1 };
        let rbz = if r > 0 {
            ph - (r as usize).div_ceil(2)
        } else {
            ph
        };
        if r > 0 {
            // insert ub r times to cut out the Bézier segment [ua, ub]
            let numer = ub - ua;
            for k in (mul + 1..=p).rev() {
                alphas[k - mul - 1] = numer / (u[a + k] - ua);
            }
            let r = r as usize;
            for j in 1..=r {
                let save = r - j;
                let s = mul + j;
                for k in (s..=p).rev() {
                    bpts.blend(k, alphas[k - s], k - 1);
                }
                next_bpts.copy_from(save, bpts.row(p));
            }
        }
        // elevate the Bézier segment
        for i in lbz..=ph {
            let row = ebpts.row_mut(i);
            row.fill(0.0);
            for j in i.saturating_sub(t)..=p.min(i) {
                let c = bezalfs[i][j];
                for (e, v) in row.iter_mut().zip(bpts.row(j)) {
                    *e += c * v;
                }
            }
        }
        if oldr > 1 {
            // remove the knot ua oldr − 1 times
            let oldr = oldr as usize;
            let den = ub - ua;
            let bet = (ub - uh[kind - 1]) / den;
            for tr in 1..oldr {
                let mut i = kind - 1 - tr;
                let mut j = kind + tr - 1;
                let mut kj = j - kind + 1;
                while j - i > tr {
                    if i < cind {
                        let alf = (ub - uh[i]) / (ua - uh[i]);
                        qw.blend(i, alf, i - 1);
                    }
                    if j >= lbz {
                        let g = if j - tr <= kind - ph + oldr {
                            (ub - uh[j - tr]) / den
                        } else {
                            bet
                        };
                        axpby(&mut scratch, g, ebpts.row(kj), 1.0 - g, ebpts.row(kj + 1));
                        ebpts.copy_from(kj, &scratch);
                    }
                    i += 1;
                    j -= 1;
                    kj -= 1;
                }
            }
        }
        if a != p {
            let times = ph - oldr.max(0) as usize;
            uh[kind..kind + times].fill(ua);
            kind += times;
        }
        for j in lbz..=rbz {
            qw.copy_from(cind, ebpts.row(j));
            cind += 1;
        }
        if b < m {
            let r = r.max(0) as usize;
            for j in 0..r {
                bpts.copy_from(j, next_bpts.row(j));
            }
            for j in r..=p {
                bpts.copy_from(j, pw.row(b - p + j));
            }
            a = b;
            b += 1;
            ua = ub;
        } else {
            uh[kind..=kind + ph].fill(ub);
        }
    }
    debug_assert_eq!(mh - ph, n_out);
    debug_assert_eq!(cind, n_out);
    (uh, qw)
}

/// The sorted knots of `new` that are not in `old` (multiset difference),
/// or the first knot of `old` that `new` lacks.
fn missing_knots(old: &[f64], new: &[f64]) -> std::result::Result<Vec<f64>, f64> {
    let mut extra = Vec::new();
    let mut i = 0;
    for &k in new {
        if i < old.len() && old[i] == k {
            i += 1;
        } else if i < old.len() && old[i] < k {
            return Err(old[i]);
        } else {
            extra.push(k);
        }
    }
    match old.get(i) {
        Some(&k) => Err(k),
        None => Ok(extra),
    }
}

/// Coefficients in `new` of the splines whose coefficients in `old` are
/// `coef` (`dim` components per basis function, one basis function after
/// the other). `new` must contain the old space: the same parameter range,
/// a degree at least as high, and every old knot with its multiplicity
/// raised by the degree difference.
pub fn respace(old: &KnotVector, new: &KnotVector, coef: &[f64], dim: usize) -> Result<Vec<f64>> {
    if new.degree() < old.degree() || new.first() != old.first() || new.last() != old.last() {
        return Err(GeometryError::RefinementNotNested {
            old_degree: old.degree(),
            new_degree: new.degree(),
            old_range: [old.first(), old.last()],
            new_range: [new.first(), new.last()],
        }
        .into());
    }
    if coef.len() != old.n_basis() * dim {
        return Err(GeometryError::CoefficientCount {
            coefficients: coef.len(),
            dim,
            basis: old.n_basis(),
        }
        .into());
    }
    let t = new.degree() - old.degree();
    let mut raised = old.clone();
    for _ in 0..t {
        raised = raised.elevated();
    }
    let extra = missing_knots(raised.knots(), new.knots())
        .map_err(|knot| GeometryError::KnotMultiplicity { knot })?;
    let pw = Coefs {
        dim,
        data: coef.to_vec(),
    };
    let (knots, elevated) = elevate(old.knots(), old.degree(), &pw, t);
    debug_assert_eq!(knots, raised.knots());
    let (knots, out) = insert(&knots, new.degree(), &elevated, &extra);
    debug_assert_eq!(knots, new.knots());
    Ok(out.data)
}

impl NurbsCurve {
    /// The same curve in the space of `new`.
    pub fn respaced(&self, new: KnotVector) -> Result<Self> {
        let c: Vec<f64> = self
            .points
            .iter()
            .zip(&self.weights)
            .flat_map(|(p, &w)| [w * p[0], w * p[1], w])
            .collect();
        let d = respace(&self.knots, &new, &c, 3)?;
        let (points, weights) = d
            .chunks_exact(3)
            .map(|h| dehomogenise(h[0], h[1], h[2]))
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
        // Control point (a along dir, b across) of a patch whose ξ count is n_first.
        let idx = |a: usize, b: usize, n_first: usize| {
            if dir == 0 {
                a + b * n_first
            } else {
                b + a * n_first
            }
        };
        let dim = 3 * n_other;
        let mut c = vec![0.0; n_dir * dim];
        for a in 0..n_dir {
            for b in 0..n_other {
                let k = idx(a, b, n0);
                let w = self.weights[k];
                let h = &mut c[a * dim + 3 * b..a * dim + 3 * b + 3];
                h.copy_from_slice(&[w * self.points[k][0], w * self.points[k][1], w]);
            }
        }
        let d = respace(&self.knots[dir], &new, &c, dim)?;
        let n_new = new.n_basis();
        let new_n0 = if dir == 0 { n_new } else { n0 };
        let total = n_new * n_other;
        let mut points = vec![[0.0; 2]; total];
        let mut weights = vec![0.0; total];
        for a in 0..n_new {
            for b in 0..n_other {
                let k = idx(a, b, new_n0);
                let h = &d[a * dim + 3 * b..a * dim + 3 * b + 3];
                let (p, w) = dehomogenise(h[0], h[1], h[2]);
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

    /// The knot vectors of [`NurbsPatch::k_refined`], without the control
    /// net: what a resource estimate needs before any large allocation.
    pub fn k_refined_knots(
        knots: &[KnotVector; 2],
        degree: usize,
        divisions: [usize; 2],
    ) -> Result<[KnotVector; 2]> {
        let mut out = knots.clone();
        for dir in 0..2 {
            if divisions[dir] == 0 {
                return Err(Error::invalid(
                    format!("divisions[{dir}]"),
                    0,
                    "must be at least 1",
                ));
            }
            while out[dir].degree() < degree {
                out[dir] = out[dir].elevated();
            }
            let extra = out[dir].subdivision_knots(divisions[dir]);
            if !extra.is_empty() {
                out[dir] = out[dir].with_inserted(&extra)?;
            }
        }
        Ok(out)
    }

    /// k-refinement: elevate both directions to `degree` (if lower), then
    /// split every knot span into `divisions[d]` equal parts. Elevating
    /// first gives the maximal C^{p-1} continuity at the new knots.
    pub fn k_refined(&self, degree: usize, divisions: [usize; 2]) -> Result<Self> {
        let target = Self::k_refined_knots(&self.knots, degree, divisions)?;
        let mut out = self.clone();
        for (dir, new) in target.into_iter().enumerate() {
            out = out.respaced(dir, new)?;
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
