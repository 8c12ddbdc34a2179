//! The post-processing layer on real solutions: IGA against FEM on the
//! paper's mesh, and the pressure-profile error under refinement.

mod common;
#[path = "../examples/common/hertz.rs"]
mod setup;

use common::hertz_scene;
use iga_contact::contact::Theta;
use iga_contact::post::{self, relative, PressureProfile, Reference};
use iga_contact::scene::RefineSpec;
use iga_contact::solver::{solve, SolverKind, SolverOptions};

/// p₀ error against Hertz of a discretisation of the Hertz scene (Newton).
fn p0_error(refine: RefineSpec) -> f64 {
    let scene = setup::scene(refine).unwrap();
    let p = scene.build().unwrap();
    let s = solve(&p, &SolverOptions::with_kind(SolverKind::Newton)).unwrap();
    let m = PressureProfile::dense(&p, &s.full).unwrap().measures(0);
    assert!(m.p0 > 0.0 && m.half_width > 0.0);
    relative(m.p0, setup::analytic(&scene).unwrap().p0).abs()
}

/// The paper's claim on its 8×8 mesh: IGA p = 2 is more accurate than FEM
/// Q1 in the peak pressure.
#[test]
fn hertz_8x8_iga_p2_beats_fem_q1_in_peak_pressure() {
    let iga = p0_error(RefineSpec::iga(2, [8, 8]));
    let q1 = p0_error(RefineSpec::lagrange(1, [8, 8]));
    assert!(iga < q1, "IGA p = 2 {iga} against Q1 {q1}");
}

/// The pressure L2 error against a fine reference falls under refinement,
/// and the reference measured against itself has no error.
#[test]
fn refining_iga_p2_reduces_the_pressure_l2_error() {
    let reference = {
        let p = common::hertz(3, 64, Theta::Incomplete);
        let s = solve(&p, &SolverOptions::with_kind(SolverKind::Newton)).unwrap();
        let r = Reference::new(&p, &s.u, &s.full).unwrap();
        let own = r.errors(&p, &s.u, &s.full).unwrap();
        assert_eq!(
            (own.p0, own.half_width, own.pressure_l2, own.energy),
            (0.0, 0.0, 0.0, 0.0)
        );
        r
    };
    let errors: Vec<f64> = [8, 16, 32]
        .iter()
        .map(|&n| {
            let p = common::hertz(2, n, Theta::Incomplete);
            let s = solve(&p, &SolverOptions::default()).unwrap();
            reference.errors(&p, &s.u, &s.full).unwrap().pressure_l2
        })
        .collect();
    assert!(errors[0] > errors[1] && errors[1] > errors[2], "{errors:?}");
}

/// The contact resultant balances the applied load, per pair, on both
/// benchmarks (a conservation law of the converged Nitsche solution).
#[test]
fn the_contact_resultant_balances_the_load() {
    for scene in [
        hertz_scene(2, 16, Theta::Incomplete),
        common::taylor_scene(Default::default(), Theta::Incomplete),
    ] {
        let p = scene.build().unwrap();
        let s = solve(&p, &SolverOptions::default()).unwrap();
        let [fx, fy] = post::contact_resultant(&p, &s.full);
        let [lx, ly] = post::applied_resultant(&p).unwrap();
        let scale = lx.hypot(ly);
        assert!(
            (fx + lx).hypot(fy + ly) <= 1e-8 * scale,
            "({fx}, {fy}) against ({lx}, {ly})"
        );
    }
}
