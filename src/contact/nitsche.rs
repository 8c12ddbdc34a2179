//! The Nitsche terms of the θ-family, Eq. (9)–(10), (13) and (17)–(19), at
//! one contact quadrature point.
//!
//! With P(u) = σ_n(u) + γ g_n(u) and P_θ(v) = θ σ_n(v) − γ ⟦v_n⟧, the
//! contact work is
//!   − (θ/γ) ∫ σ_n(u) σ_n(v) + (1/γ) ∫ [P(u)]₋ P_θ(v),
//! which for θ = 0 is the paper's − ∫ \[P(u)\]₋ ⟦v_n⟧.

use super::point::ContactPoint;
use nalgebra::DMatrix;

/// The projection of Eq. (10): \[x\]₋ = x for x ≤ 0, else 0.
pub fn negative_part(x: f64) -> f64 {
    x.min(0.0)
}

/// The Heaviside function of Eq. (19): 1 for x ≤ 0, else 0.
pub fn heaviside(x: f64) -> f64 {
    if x <= 0.0 {
        1.0
    } else {
        0.0
    }
}

/// Which force law a contact point follows.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Law {
    /// Frictionless contact, Eq. (13): the force of \[P\]₋.
    Contact,
    /// Bonded in the normal direction: \[P\]₋ replaced by P, the law whose
    /// tangent is the tied matrix (17). The floating guard uses it to pull
    /// the nearest points of a floating body onto the obstacle.
    Tied,
}

/// Adds the contact part of the internal force at one point to `g` (a
/// vector over the point's local DOFs), for the full displacement `u`.
/// Returns P(u).
pub fn add_internal_force(cp: &ContactPoint, u: &[f64], g: &mut [f64]) -> f64 {
    add_force(cp, u, g, Law::Contact)
}

/// [`add_internal_force`] under the force law `law`.
pub fn add_force(cp: &ContactPoint, u: &[f64], g: &mut [f64], law: Law) -> f64 {
    let (sigma_n, jump) = cp.normal_stress_and_jump(u);
    add_force_at(cp, sigma_n, jump, g, law)
}

/// [`add_force`] from the point's σ_n(u) and ⟦u_n⟧(u).
pub fn add_force_at(cp: &ContactPoint, sigma_n: f64, jump: f64, g: &mut [f64], law: Law) -> f64 {
    let p = sigma_n + cp.gamma * (cp.g0 - jump);
    let (th, ga, w) = (cp.theta, cp.gamma, cp.weight);
    let pm = match law {
        Law::Contact => negative_part(p),
        Law::Tied => p,
    };
    for k in 0..cp.dofs.len() {
        let p_theta = th * cp.sn[k] - ga * cp.jn[k];
        g[k] += -(th / ga) * w * sigma_n * cp.sn[k] + (w / ga) * pm * p_theta;
    }
    p
}

/// Adds to `size` (over the point's local DOFs) the magnitudes that the
/// round-off of [`add_force_at`] scales with: the two terms of the force
/// separately, and P with the sizes of the sums behind it. `sigma_size` and
/// `jump_size` are Σ|s_k u_k| and Σ|j_k u_k|, the sums that give σ_n and
/// ⟦u_n⟧; `p` is P as returned by [`add_force_at`].
///
/// Why not |force|: for an active point the two terms cancel to
/// θ w g_n s + …, each of them of size w|σ_n|/γ, so when γ is small
/// (or σ_n large) the computed force carries round-off of that larger size.
pub fn add_force_size_at(
    cp: &ContactPoint,
    sigma_size: f64,
    jump_size: f64,
    p: f64,
    law: Law,
    size: &mut [f64],
) {
    let (th, ga, w) = (cp.theta, cp.gamma, cp.weight);
    let p_size = sigma_size + ga * (cp.g0.abs() + jump_size);
    let active = law == Law::Tied || p <= 0.0;
    for (k, s) in size.iter_mut().enumerate() {
        *s += (th / ga).abs() * w * sigma_size * cp.sn[k].abs();
        if active {
            *s += (w / ga) * p_size.max(p.abs()) * ((th * cp.sn[k]).abs() + ga * cp.jn[k].abs());
        }
    }
}

/// The local matrix of a point (rows: test functions, columns: trial):
///   −(θ/γ) w sn snᵀ + h (w/γ) (θ sn − γ jn)(sn − γ jn)ᵀ.
/// With h = 1 this is the tied matrix (17); with h = H(P(u_k)) it is the
/// secant / generalised Newton matrix (18)–(19).
pub fn local_matrix(cp: &ContactPoint, h: f64) -> DMatrix<f64> {
    let n = cp.dofs.len();
    let (th, ga, w) = (cp.theta, cp.gamma, cp.weight);
    DMatrix::from_fn(n, n, |a, b| {
        let test = th * cp.sn[a] - ga * cp.jn[a];
        let trial = cp.sn[b] - ga * cp.jn[b];
        -(th / ga) * w * cp.sn[a] * cp.sn[b] + h * (w / ga) * test * trial
    })
}
