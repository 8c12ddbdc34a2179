//! The coercivity bound of the θ-family on γ: a file of its own because
//! both the contact points (their own check) and the penalty rules use it.

/// The penalty below which the θ-family loses coercivity, for the trace
/// constant C_T of an element: the contact terms of the tied form add
/// −(1 + θ)∫σ_n(v)⟦v_n⟧ + ∫γ⟦v_n⟧² to a(v, v), which Young's inequality bounds
/// below by a(v, v)(1 − (1 + θ)² C_T / (4γ)). So γ > C_T for θ = 1,
/// γ > C_T/4 for θ = 0, and any γ > 0 for θ = −1 (bound 0).
pub fn stability_bound(trace_constant: f64, theta: f64) -> f64 {
    (1.0 + theta).powi(2) / 4.0 * trace_constant
}
