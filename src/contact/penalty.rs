//! The empirical penalty of Eq. (11), and the sharp penalty it replaces.
//!
//! γ is a *stiffness* here, γ = 0.1 · E · (p+1)(p+d) · (1/h₁ + 1/h₂): it grows
//! with the modulus and shrinks with the element size, like the largest
//! eigenvalue of the boundary trace inequality it replaces. (Chouly, Hild &
//! Renard write the reciprocal, a compliance γ₀h with γ₀ in 1/Pa, so
//! "small γ₀" there means a large γ here; GetFEM's Nitsche contact brick
//! takes a stiffness γ₀ in Pa and forms γ₀/h, like this γ.)

use super::contacts::Contacts;
use super::point::ContactPoint;
pub use super::stability::stability_bound;
use crate::error::Result;

/// Inputs of Eq. (11) at one contact quadrature point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PenaltyInputs {
    /// E of the body chosen by the pair's [`super::Modulus`] (by default
    /// the slave's).
    pub young: f64,
    /// Spline degree p.
    pub degree: usize,
    /// Physical length of the slave boundary element holding the point.
    pub h_slave: f64,
    /// Same on the master side; `None` for a rigid obstacle (1/h₂ = 0).
    pub h_master: Option<f64>,
}

/// The spatial dimension d of Eq. (11).
pub const DIM: f64 = 2.0;

/// γ of Eq. (11), scaled by the user's `factor` (1 reproduces the paper).
pub fn empirical_penalty(inp: PenaltyInputs, factor: f64) -> f64 {
    let p = inp.degree as f64;
    let inv_h = 1.0 / inp.h_slave + inp.h_master.map_or(0.0, |h| 1.0 / h);
    factor * 0.1 * inp.young * (p + 1.0) * (p + DIM) * inv_h
}

/// The trace-inverse constant of one slave element: the largest λ with
///
///   Σ_q w_q σ_n(v)(x_q)² = λ a_e(v, v)
///
/// over the displacements v of the element, where a_e is the element's
/// stiffness `stiffness` (2n × 2n, local order) and each `(w_q, s_q)` is a
/// contact quadrature point of the element, with σ_n(v)(x_q) = s_q·v (the
/// first 2n entries of `ContactPoint::sn`). This is the constant C_T of the
/// local trace inequality ‖σ_n(v)‖²_Γe ≤ C_T a_e(v, v) that the sharp Nitsche
/// penalty needs, for the quadrature the solver actually uses.
///
/// The stiffness is singular on the element's rigid motions `rigid` (2n × 3:
/// the two translations and the rotation at the control points), where σ_n
/// vanishes too. With B = W Wᵀ, W = \[√w_q s_q\], λ is the largest
/// eigenvalue of the small k × k matrix Wᵀ (a_e + R Rᵀ)⁻¹ W (k points): the
/// rigid modes make the stiffness invertible without changing it on the
/// functionals. Cost: one dense Cholesky of 2n × 2n and a k × k
/// eigenproblem, with nalgebra. Where the Cholesky fails (round-off at high
/// degree, or an under-integrated element with zero-energy modes) the
/// eigenpairs of the regularised stiffness take over; if a mode of no
/// energy carries normal stress, no bound exists and the constant is ∞.
pub fn trace_constant<'a>(
    stiffness: &nalgebra::DMatrix<f64>,
    rigid: &nalgebra::DMatrix<f64>,
    points: impl IntoIterator<Item = (f64, &'a [f64])>,
) -> Result<f64> {
    let n = stiffness.nrows();
    // Jacobi scaling v = D v', D = diag(K)^(-1/2): the quotient is the same
    // in the new variables, but at high degree the element's B-splines that
    // barely reach into it have diagonal entries 10⁻¹⁰ of the largest and
    // more, and in the unscaled basis their tiny energies and tiny stresses
    // are lost to round-off (at p = 6 the regularised stiffness then looks
    // singular and the constant infinite)
    let d: Vec<f64> = stiffness
        .diagonal()
        .iter()
        .map(|&k| if k > 0.0 { 1.0 / k.sqrt() } else { 1.0 })
        .collect();
    let stiffness = nalgebra::DMatrix::from_fn(n, n, |i, j| d[i] * stiffness[(i, j)] * d[j]);
    let rigid = nalgebra::DMatrix::from_fn(n, rigid.ncols(), |i, j| rigid[(i, j)] / d[i]);
    let columns: Vec<nalgebra::DVector<f64>> = points
        .into_iter()
        .map(|(w, s)| w.sqrt() * nalgebra::DVector::from_fn(n, |i, _| d[i] * s[i]))
        .collect();
    if columns.is_empty() {
        return Ok(0.0);
    }
    let (stiffness, rigid) = (&stiffness, &rigid);
    let w = nalgebra::DMatrix::from_columns(&columns);
    // scale the rigid block to the stiffness so that neither swamps the other
    let scale = stiffness.diagonal().amax()
        / rigid
            .column_iter()
            .map(|c| c.norm_squared())
            .fold(0.0, f64::max)
            .max(f64::MIN_POSITIVE);
    let regular = stiffness + scale * rigid * rigid.transpose();
    let small = match regular.clone().cholesky() {
        Some(chol) => w.transpose() * chol.solve(&w),
        None => {
            // Round-off at high degree, or zero-energy modes beyond the rigid
            // ones (an under-integrated element): eigenpairs, and a mode of
            // no energy that carries normal stress makes the constant infinite.
            let eig = regular.symmetric_eigen();
            let top = eig.eigenvalues.amax();
            let mut small = nalgebra::DMatrix::<f64>::zeros(columns.len(), columns.len());
            let wnorm = w.norm();
            for (k, &lambda) in eig.eigenvalues.iter().enumerate() {
                let proj = w.transpose() * eig.eigenvectors.column(k);
                if lambda <= 1e-12 * top {
                    if proj.norm() > 1e-8 * wnorm {
                        return Ok(f64::INFINITY);
                    }
                    continue;
                }
                small += &proj * proj.transpose() / lambda;
            }
            small
        }
    };
    let small = 0.5 * (&small + small.transpose());
    Ok(small.symmetric_eigen().eigenvalues.max().max(0.0))
}

/// The rigid motions of an element at its control points `points`: the
/// columns are u = (1, 0), u = (0, 1) and u = (−(y − ȳ), x − x̄), in the
/// local order of the element stiffness (control point major).
pub fn rigid_modes(points: &[[f64; 2]]) -> nalgebra::DMatrix<f64> {
    let n = points.len() as f64;
    let c = points
        .iter()
        .fold([0.0; 2], |a, p| [a[0] + p[0] / n, a[1] + p[1] / n]);
    nalgebra::DMatrix::from_fn(2 * points.len(), 3, |i, k| {
        let (p, comp) = (points[i / 2], i % 2);
        match (k, comp) {
            (0, 0) | (1, 1) => 1.0,
            (2, 0) => -(p[1] - c[1]),
            (2, 1) => p[0] - c[0],
            _ => 0.0,
        }
    })
}

/// The sharp penalty of a point: `safety` times its stability bound, and
/// for θ = −1 (which has none) `safety` times the bound of θ = 0, the scale
/// of the contact stiffness.
pub fn sharp_penalty(trace_constant: f64, theta: f64, safety: f64) -> f64 {
    safety * stability_bound(trace_constant, theta.max(0.0))
}

/// The stability of the penalty of one pair: how many contact points have γ
/// below the bound under which the θ-family loses coercivity
/// ([`crate::contact::penalty::stability_bound`] of the point's slave
/// element), in all and among the *active* points — those with P ≤ 0 at a
/// solution ([`penalty_stability`](crate::post::penalty_stability)) or, before any solve, those where the
/// bodies first touch ([`first_touch_stability`](crate::post::first_touch_stability)) — and how far below.
///
/// Below the bound, the discrete problem restricted to an active set need
/// not be coercive, so a converged solution need not be the only one: two
/// solvers can reach different "converged" answers. An inactive point is
/// not free of the penalty either when θ > 0: its term −(θ/γ) w σ_n σ_nᵀ
/// stays in the tangent (only the bracket switches off), and a(v, v) −
/// (θ/γ)∫σ_n(v)² ≥ a(v, v)(1 − θ C_T/γ) needs γ > θ C_T there; such points
/// are counted apart ([`inactive_below`](Self::inactive_below)).
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct PenaltyStability {
    pub points: usize,
    pub below: usize,
    /// The active points (P ≤ 0, or first touch).
    pub active: usize,
    pub active_below: usize,
    /// The smallest γ / bound over the active points whose bound is
    /// positive; `None` if there is none (no active point, or θ = −1,
    /// whose bound is 0).
    pub min_active_ratio: Option<f64>,
    /// Active points whose γ exceeds the over-penalisation limit times the
    /// θ = 0 bound of their element (the scale of the contact stiffness,
    /// whatever θ).
    pub active_over: usize,
    /// The largest γ / (θ = 0 bound) over the active points; `None` if no
    /// active point has a positive bound.
    pub max_active_scale: Option<f64>,
    /// The smallest γ / (θ = 0 bound) over the active points: how loosely
    /// the gap is held where θ = −1 has no bound to fall below.
    pub min_active_scale: Option<f64>,
    /// Inactive points with γ below θ C_T (θ > 0 only; see above).
    pub inactive_below: usize,
    /// The smallest γ / (θ C_T) over the inactive points, θ > 0.
    pub min_inactive_ratio: Option<f64>,
}

impl PenaltyStability {
    /// The penalty factor that would lift every active point to its bound:
    /// `factor` / [`min_active_ratio`](Self::min_active_ratio), where
    /// `factor` is the pair's present one (γ is proportional to it, for the
    /// empirical and the sharp penalty alike). `None` when no active point
    /// is below the bound.
    pub fn factor_needed(&self, factor: f64) -> Option<f64> {
        self.min_ratio()
            .filter(|&r| r < 1.0 && self.active_below + self.inactive_below > 0)
            .map(|r| factor / r)
    }

    /// The counts of `self` and `other` together: the stability of a
    /// contact from that of its pieces.
    pub fn merge(self, other: Self) -> Self {
        let least = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        };
        let most = |a: Option<f64>, b: Option<f64>| match (a, b) {
            (Some(a), Some(b)) => Some(a.max(b)),
            (a, b) => a.or(b),
        };
        Self {
            points: self.points + other.points,
            below: self.below + other.below,
            active: self.active + other.active,
            active_below: self.active_below + other.active_below,
            min_active_ratio: least(self.min_active_ratio, other.min_active_ratio),
            active_over: self.active_over + other.active_over,
            max_active_scale: most(self.max_active_scale, other.max_active_scale),
            min_active_scale: least(self.min_active_scale, other.min_active_scale),
            inactive_below: self.inactive_below + other.inactive_below,
            min_inactive_ratio: least(self.min_inactive_ratio, other.min_inactive_ratio),
        }
    }

    /// The smallest γ over the bound that applies, active and inactive
    /// points together.
    pub fn min_ratio(&self) -> Option<f64> {
        match (self.min_active_ratio, self.min_inactive_ratio) {
            (Some(a), Some(b)) => Some(a.min(b)),
            (a, b) => a.or(b),
        }
    }
}

/// [`PenaltyStability`] of every pair of `points` (`pairs` pairs), the
/// active points being those for which `active(index, point)` holds, and
/// `over` the γ / (θ = 0 bound) beyond which an active point counts as
/// over-penalised.
pub fn stability_of(
    points: &[ContactPoint],
    pairs: usize,
    active: impl Fn(usize, &ContactPoint) -> bool,
    over: f64,
) -> Vec<PenaltyStability> {
    let mut out = vec![PenaltyStability::default(); pairs];
    for (q, cp) in points.iter().enumerate() {
        let s = &mut out[cp.pair];
        s.points += 1;
        // where the map is singular, C_T (from σ_n ∝ 1/det J) says nothing
        // about the penalty: such points are counted, never judged
        let judged = cp.regular;
        let bound = cp.stability_bound();
        let below = judged && cp.gamma < bound;
        s.below += usize::from(below);
        if active(q, cp) {
            s.active += 1;
            s.active_below += usize::from(below);
            if judged && bound > 0.0 {
                let r = cp.gamma / bound;
                s.min_active_ratio = Some(s.min_active_ratio.map_or(r, |m: f64| m.min(r)));
            }
            // against the whole weight: the halves of the unbiased form
            // add to one penalty γ on one gap
            let scale = stability_bound(cp.trace_constant / cp.share, 0.0);
            if judged && scale > 0.0 {
                let r = cp.gamma / scale;
                s.active_over += usize::from(r > over);
                s.max_active_scale = Some(s.max_active_scale.map_or(r, |m: f64| m.max(r)));
                s.min_active_scale = Some(s.min_active_scale.map_or(r, |m: f64| m.min(r)));
            }
        } else if judged && cp.theta > 0.0 && cp.trace_constant > 0.0 {
            let r = cp.gamma / (cp.theta * cp.trace_constant);
            s.inactive_below += usize::from(r < 1.0);
            s.min_inactive_ratio = Some(s.min_inactive_ratio.map_or(r, |m: f64| m.min(r)));
        }
    }
    out
}

/// Which of `points` (of `pairs` pairs) are where the bodies first touch:
/// the points of least initial gap g₀ of their pair (to within 10⁻⁶ of the
/// pair's range of g₀, so that a flat contact counts all its points).
/// Contact begins there, whatever the load; the points far from it (such
/// as the degenerate corner of the nine-point disk) touch only under a load
/// that closes their gap.
pub fn first_touch(points: &[ContactPoint], pairs: usize) -> Vec<bool> {
    first_touch_of(points, &Contacts::each_pair(pairs))
}

/// As [`first_touch`], over each contact of `contacts` as a whole: where
/// a slave boundary runs over several patches, the least gap of a piece
/// far from the touch (at its join with the next) is no place of first
/// touch.
pub fn first_touch_of(points: &[ContactPoint], contacts: &Contacts) -> Vec<bool> {
    let mut range = vec![(f64::INFINITY, f64::NEG_INFINITY); contacts.len()];
    for cp in points {
        let r = &mut range[contacts.of(cp.pair)];
        *r = (r.0.min(cp.g0), r.1.max(cp.g0));
    }
    points
        .iter()
        .map(|cp| {
            let (lo, hi) = range[contacts.of(cp.pair)];
            cp.g0 <= lo + 1e-6 * (hi - lo)
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;
    use nalgebra::DMatrix;

    /// The generalised eigenvalue against a brute-force search: for random
    /// v, B(v, v)/A(v, v) never exceeds λ, and the maximising direction
    /// attains it.
    #[test]
    fn trace_constant_is_the_largest_rayleigh_quotient() {
        let n = 6;
        let mut seed = 7u64;
        let mut rnd = || {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        };
        // a stiffness with a two-dimensional null space spanned by r1, r2 …
        let r = DMatrix::from_fn(n, 2, |_, _| rnd());
        let m = DMatrix::from_fn(n, n, |_, _| rnd());
        let p = DMatrix::<f64>::identity(n, n)
            - &r * (r.transpose() * &r).try_inverse().unwrap() * r.transpose();
        let a = &p * (&m * m.transpose() + DMatrix::identity(n, n)) * &p;
        // … and functionals that vanish on it, like σ_n on rigid motions
        let s: Vec<Vec<f64>> = (0..3)
            .map(|_| {
                let v = nalgebra::DVector::from_fn(n, |_, _| rnd());
                (&p * v).as_slice().to_vec()
            })
            .collect();
        let w = [0.3, 0.5, 0.2];
        let lambda = trace_constant(
            &a,
            &r,
            w.iter().copied().zip(s.iter().map(|v| v.as_slice())),
        )
        .unwrap();
        // independently: B = W Wᵀ with W = [√w_q s_q], so λ is the largest
        // eigenvalue of the small Wᵀ A⁺ W, A⁺ the SVD pseudo-inverse
        let wm = DMatrix::from_fn(n, 3, |i, q| w[q].sqrt() * s[q][i]);
        let pinv = a.clone().pseudo_inverse(1e-10).unwrap();
        let small = wm.transpose() * pinv * &wm;
        let want = small.symmetric_eigen().eigenvalues.max();
        assert!((lambda - want).abs() <= 1e-9 * want, "{lambda} vs {want}");
        // and no direction exceeds it: B(v, v) ≤ λ A(v, v)
        for _ in 0..1000 {
            let v = &p * nalgebra::DVector::from_fn(n, |_, _| rnd());
            let bv: f64 = (wm.transpose() * &v).norm_squared();
            assert!(bv <= lambda * (v.transpose() * &a * &v)[0] * (1.0 + 1e-10));
        }
        // the thresholds of the three variants
        assert_eq!(stability_bound(4.0, 1.0), 4.0);
        assert_eq!(stability_bound(4.0, 0.0), 1.0);
        assert_eq!(stability_bound(4.0, -1.0), 0.0);
        assert_eq!(sharp_penalty(4.0, -1.0, 2.0), 2.0);
    }
}
