//! The post-processing layer on real solutions: IGA against FEM on the
//! paper's mesh, and the pressure-profile error under refinement.

mod common;
use companion::hertz as setup;

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
/// and the reference measured against itself has no error (to round-off).
#[test]
fn refining_iga_p2_reduces_the_pressure_l2_error() {
    let reference = {
        let p = common::hertz(3, 64, Theta::Incomplete);
        let s = solve(&p, &SolverOptions::with_kind(SolverKind::Newton)).unwrap();
        let r = Reference::new(&p, &s.u, &s.full).unwrap();
        let own = r.errors(&p, &s.u, &s.full).unwrap();
        // zero up to the round-off of interpolating the profile at its
        // own sample points
        let own = [own.p0, own.half_width, own.pressure_l2, own.energy];
        assert!(own.iter().all(|e| *e <= 1e-15), "{own:?}");
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

/// Under eight times the load the 32×32 disk presses towards the collapsed
/// corner of its contact side (det J = 0 there): the samples of the element
/// at that corner are marked singular, and only they; the profile's largest pressure over its
/// regular samples is the summary's p₀; and the table written by a run
/// marks the same rows. This load has two roots; the plain iteration
/// (`growth = "full"`) ends on the one with the corner's point active, the
/// default's cut growth on one whose zone stops short of the corner (the
/// right one, by the finer mesh: tests/warnings/zones.rs), so this test asks for
/// the plain iteration to have singular samples in the zone.
#[test]
fn the_profile_marks_the_singular_corner_and_agrees_with_the_summary() {
    let mut scene = hertz_scene(2, 32, Theta::Incomplete);
    for l in &mut scene.loads {
        if let iga_contact::assembly::Load::BodyForce { force, .. } = l {
            force[1] *= 8.0;
        }
    }
    scene.solver = SolverOptions {
        growth: iga_contact::solver::Growth::Full,
        ..SolverOptions::default()
    };
    let p = scene.build().unwrap();
    let s = solve(&p, &scene.solver).unwrap();
    let profile = PressureProfile::dense(&p, &s.full).unwrap();
    let m = profile.measures(0);
    let corner = p.bodies[0].space.patch.side_curve(p.pairs[0].slave_side);
    let corner = corner.point(corner.knots.last());
    let singular: Vec<_> = profile.samples().iter().filter(|q| !q.regular).collect();
    assert!(!singular.is_empty());
    // only next to the corner: within two elements of the 32 along the side
    let side_length = 0.2 * std::f64::consts::FRAC_PI_4;
    for q in &singular {
        let d = (q.x[0] - corner[0]).hypot(q.x[1] - corner[1]);
        assert!(
            d < 2.0 * side_length / 32.0,
            "a singular sample {d} from the corner"
        );
    }
    // the corner's brackets are far beyond p₀: they would have been the peak
    let wild = singular.iter().map(|q| q.pressure()).fold(0.0, f64::max);
    assert!(wild > 10.0 * m.p0, "{wild} against {}", m.p0);
    assert_eq!(profile.max_pressure(0), m.p0);

    // the run's table and summary say the same
    let dir = std::env::temp_dir().join(format!("iga-post-corner-{}", std::process::id()));
    scene.output = iga_contact::scene::OutputSpec {
        summary: true,
        pressure_profile: true,
        ..Default::default()
    };
    scene.run(&dir).unwrap();
    let csv = std::fs::read_to_string(dir.join("pressure_profile.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("contact,x,y,bracket,pressure,regular"));
    let rows: Vec<Vec<f64>> = lines
        .map(|l| l.split(',').map(|c| c.parse().unwrap()).collect())
        .collect();
    assert_eq!(rows.iter().filter(|r| r[5] == 0.0).count(), singular.len());
    let peak = rows
        .iter()
        .filter(|r| r[5] == 1.0)
        .map(|r| r[4])
        .fold(0.0, f64::max);
    let summary: toml::Table =
        toml::from_str(&std::fs::read_to_string(dir.join("summary.toml")).unwrap()).unwrap();
    let p0 = summary["contact"].as_array().unwrap()[0]["p0"]
        .as_float()
        .unwrap();
    assert!((peak - p0).abs() <= 1e-6 * p0, "{peak} against {p0}");
    let _ = std::fs::remove_dir_all(&dir);
}
