//! The empirical penalty of Eq. (11).
//!
//! γ is a *stiffness* here, γ = 0.1 · E · (p+1)(p+d) · (1/h₁ + 1/h₂): it grows
//! with the modulus and shrinks with the element size, like the largest
//! eigenvalue of the boundary trace inequality it replaces. (GetFEM and
//! Chouly–Hild write the reciprocal, a compliance γ₀h, so "small γ" there
//! means a large one here.)

/// Inputs of Eq. (11) at one contact quadrature point.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct PenaltyInputs {
    /// E = max(E¹, E²).
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
