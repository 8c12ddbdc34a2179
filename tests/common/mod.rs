//! Helpers shared by the integration tests.

use iga_contact::problem::Problem;
use iga_contact::solver::history::History;
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

/// Asserts that `a` and `b` record the same iteration: the same active
/// points and events row by row, residuals to 1e-4 (rows at the round-off
/// floor excepted). The last row, a confirmation at the round-off floor,
/// may come one iteration apart.
#[allow(dead_code)] // not every test crate compares histories
pub fn assert_same_iteration(a: &History, b: &History, what: &str) {
    let (la, lb) = (a.len(), b.len());
    assert!(la.abs_diff(lb) <= 1, "{what}: {la} against {lb} iterations");
    for (x, y) in a.rows.iter().zip(&b.rows).take(la.min(lb) - 1) {
        assert_eq!(
            x.active_points, y.active_points,
            "{what}, row {}",
            x.iteration
        );
        assert_eq!(x.events, y.events, "{what}, row {}", x.iteration);
        let rel = (x.residual - y.residual).abs() / y.residual.max(1e-300);
        assert!(
            rel <= 1e-4 || y.relative_residual < 1e-9,
            "{what}, row {}: residuals {:.6e} and {:.6e}",
            x.iteration,
            x.residual,
            y.residual
        );
    }
}
