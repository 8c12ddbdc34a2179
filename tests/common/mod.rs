//! Helpers shared by the integration tests.

use iga_contact::problem::Problem;
use iga_contact::solver::{solve, SolverKind, SolverOptions};

/// n deterministic pseudo-random values in [−½, ½) (a 64-bit LCG).
pub fn rough(n: usize, mut seed: u64) -> Vec<f64> {
    (0..n)
        .map(|_| {
            seed = seed
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            ((seed >> 11) as f64 / (1u64 << 53) as f64) - 0.5
        })
        .collect()
}

/// The Newton solution of `p` plus `amplitude` · max|u| · `rough(n, seed)`.
pub fn perturbed_solution(p: &Problem, amplitude: f64, seed: u64) -> Vec<f64> {
    let s = solve(p, &SolverOptions::with_kind(SolverKind::Newton)).expect("converges");
    let umax = s.u.iter().fold(0.0f64, |m, v| m.max(v.abs()));
    s.u.iter()
        .zip(rough(p.n(), seed))
        .map(|(v, e)| v + amplitude * umax * e)
        .collect()
}
