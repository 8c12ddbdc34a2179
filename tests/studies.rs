//! Fast checks of the comparison studies (IGA against FEM, error against
//! mesh size).

use iga_contact::benchmarks::HertzAnalytic;
use iga_contact::solver::SolverKind;
use iga_contact::studies::iga_vs_fem::{
    bfgs_or_newton, peak_and_half_width, percent, profile, relative_l2, timed_run, Method,
};

/// p₀ error against Hertz (%) and iterations; BFGS, or Newton where BFGS
/// fails (the accuracy is the discretisation's, not the solver's).
fn p0_error(method: Method, elements: usize) -> (f64, usize) {
    let (run, _) = bfgs_or_newton(method, elements, 1).unwrap_or_else(|e| panic!("{e}"));
    let (samples, _) = profile(&run.problem, &run.solution.full).unwrap();
    let (p0, a) = peak_and_half_width(&samples);
    assert!(p0 > 0.0 && a > 0.0);
    (
        percent(p0, HertzAnalytic::new().p0),
        run.solution.history.len(),
    )
}

#[test]
fn hertz_8x8_bfgs_converges_for_iga_p2_and_fem_q1() {
    for m in [Method::Iga(2), Method::Fem(1)] {
        if let Err(e) = timed_run(m, 8, SolverKind::Bfgs, 1) {
            panic!("BFGS on Hertz 8×8, {}: {e}", m.label());
        }
    }
}

#[test]
fn hertz_8x8_iga_p2_beats_fem_q1_in_peak_pressure() {
    let (iga, it_iga) = p0_error(Method::Iga(2), 8);
    let (q1, it_q1) = p0_error(Method::Fem(1), 8);
    eprintln!("p0 error vs Hertz: IGA p=2 {iga:.3}% ({it_iga} it), FEM Q1 {q1:.3}% ({it_q1} it)");
    // Measured: IGA p=2 2.69 %, Q1 3.11 % (the paper: 9.91 % against 28.7 %).
    assert!(iga < q1, "IGA p=2 {iga}% vs Q1 {q1}%");
}

#[test]
fn refining_iga_p2_reduces_the_pressure_l2_error() {
    let reference = {
        let run =
            timed_run(Method::Iga(3), 64, SolverKind::Newton, 1).unwrap_or_else(|e| panic!("{e}"));
        profile(&run.problem, &run.solution.full).unwrap().0
    };
    let (_, a_ref) = peak_and_half_width(&reference);
    let errors: Vec<f64> = [8, 16, 32]
        .iter()
        .map(|&n| {
            let (run, _) = bfgs_or_newton(Method::Iga(2), n, 1).unwrap_or_else(|e| panic!("{e}"));
            let s = profile(&run.problem, &run.solution.full).unwrap().0;
            relative_l2(&s, &reference, 1.2 * a_ref)
        })
        .collect();
    eprintln!("pressure L2 error, IGA p=2, 8/16/32: {errors:?}");
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
}
