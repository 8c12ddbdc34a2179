//! The kernels the iteration starts from and factorises: why the tied
//! start (17) is not the default, and the layer space's need for the
//! factorise-once kernels.

use crate::common::HertzCase;
use crate::{block, PRESSURE};
use iga_contact::solver::trace::TraceProblem;
use iga_contact::solver::{solve, IterationSpace, SolverOptions, Start};

/// Why the tied start overshoots at high degree: its θ = 0 consistency
/// term nearly cancels the penalty on a mode of the far arc, where the
/// floor's normal is tangent to the disk; a larger penalty removes it.
#[test]
fn the_tied_kernel_is_weak_on_the_far_arc_for_the_empirical_penalty() {
    let weakest = |factor: f64| {
        let p = HertzCase {
            degree: 4,
            elements: 64,
            penalty_factor: factor,
            ..HertzCase::default()
        }
        .build()
        .unwrap();
        let t = TraceProblem::new(&p).unwrap();
        let svd = t.kernel(&vec![1.0; p.points.len()]).svd().unwrap();
        let ell = t.dim();
        let smin = svd.S().column_vector()[ell - 1];
        let s0 = t
            .condensation()
            .schur()
            .self_adjoint_eigenvalues(faer::Side::Lower)
            .unwrap()[0];
        // share of the weakest mode on the last fifth of the arc (ξ ≥ 0.8)
        let n0 = p.bodies[0].space.patch.n()[0];
        let mut free_to_cp = vec![0usize; p.n()];
        for g in 0..p.map.n_total() {
            if let Some(i) = p.map.free(g) {
                free_to_cp[i] = g / 2;
            }
        }
        let v = svd.V().col(ell - 1);
        let far: f64 = t
            .condensation()
            .layer()
            .iter()
            .enumerate()
            .filter(|&(_, &i)| 5 * (free_to_cp[i] % n0) >= 4 * n0)
            .map(|(k, _)| v[k] * v[k])
            .sum();
        (smin / s0, far)
    };
    let (ratio, far) = weakest(1.0);
    assert!(ratio < 0.5, "σ_min(tied)/λ_min(S₀) = {ratio:.3}");
    assert!(far > 0.9, "far-arc share {far:.3}");
    let (ratio, _) = weakest(3.0);
    assert!(
        ratio > 0.9,
        "penalty ×3: σ_min(tied)/λ_min(S₀) = {ratio:.3}"
    );
    // the default start never ties the far arc
    assert_eq!(SolverOptions::default().start, Start::Secant);
}

#[test]
fn the_layer_space_needs_the_factorise_once_kernels() {
    let p = block(0.1, [4, 2], PRESSURE);
    let opts = SolverOptions {
        space: IterationSpace::Trace,
        factorisation: iga_contact::solver::Factorisation::Lu,
        ..SolverOptions::default()
    };
    let err = solve(&p, &opts).expect_err("invalid combination");
    assert_eq!(err.kind(), iga_contact::ErrorKind::InvalidInput);
    assert!(err.to_string().contains("solver.space"), "{err}");
    // with the body space the same kernels work
    let body = SolverOptions {
        space: IterationSpace::Body,
        ..opts
    };
    assert!(solve(&p, &body).is_ok());
}
