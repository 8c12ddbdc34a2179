//! A zone that reaches the end of its slave side, and the roots where the
//! default and the plain growth part: the wrong or doubtful one is warned.

use crate::{heavy, hertz, p0_and_warnings};
use iga_contact::material::Formulation;
use iga_contact::post::relative;
use iga_contact::solver::warning::SideEnd;
use iga_contact::solver::{solve, Growth, Warning};

/// Under eight times the load (penalty factor 2, which keeps every regular
/// element above its bound: at factor 1 the element next to the corner is
/// just below it, and that warning comes first) the zone of the 32×32 disk
/// reaches the end of its slave side, the collapsed corner of the
/// nine-point disk where the boundary goes on smoothly: warned, once. A flat block on a floor (Taylor),
/// whose zone ends at the body's corners, and the symmetry end of the
/// Hertz half disk are not. This load has two roots: the plain iteration
/// (`growth = "full"`) ends on one whose zone (86 points) has the corner's
/// point active; the default's cut growth ends on one whose zone runs on to
/// 94 points and leaves the corner open, unwarned (which of the two is
/// right: [`where_the_growths_part_the_wrong_or_doubtful_root_is_warned`]).
#[test]
fn a_zone_that_reaches_the_end_of_the_slave_side_is_warned() {
    let heavy = heavy(32, Growth::Full);
    let problem = heavy.build().unwrap();
    let s = solve(&problem, &heavy.solver).unwrap();
    let at_end: Vec<_> = s
        .warnings
        .iter()
        .filter(|w| {
            matches!(
                w,
                Warning::ZoneAtSideEnd {
                    end: SideEnd::End,
                    ..
                }
            )
        })
        .collect();
    assert_eq!(at_end.len(), 1, "{:?}", s.warnings);
    for scene in [hertz(16), {
        let mut t = companion::shipped("taylor.toml").unwrap();
        t.output = Default::default();
        t
    }] {
        let problem = scene.build().unwrap();
        let s = solve(&problem, &scene.solver).unwrap();
        assert!(
            !s.warnings
                .iter()
                .any(|w| matches!(w, Warning::ZoneAtSideEnd { .. })),
            "{:?}",
            s.warnings
        );
    }
}

/// Where the default (`growth = "auto"`) and the plain iteration
/// (`growth = "full"`) end on different roots, the wrong or doubtful one is
/// warned.
///
/// Hertz under 8× load at penalty factor 2: on 32² the plain iteration ends
/// on a root with the collapsed corner's point active (det J = 0 there, so
/// its bracket is not a contact pressure), p₀ 4.6 % below the default's;
/// the default's root lies on the mesh sequence (its p₀ within 0.2 % of the
/// 64² one, where the plain iteration's 64² root is again the corner's). The
/// corner root carries the zone-at-side-end warning, the default's none.
///
/// ν = 0.4999: the two roots differ (7 and 10 active points), and both carry
/// the locking warning; following it (`formulation = "mixed"`) both growths
/// reach the same root, which the finer mesh confirms.
#[test]
fn where_the_growths_part_the_wrong_or_doubtful_root_is_warned() {
    let at_end = |w: &[Warning]| {
        w.iter()
            .any(|w| matches!(w, Warning::ZoneAtSideEnd { singular: true, .. }))
    };
    let (auto32, w) = p0_and_warnings(&heavy(32, Growth::Auto));
    assert!(!at_end(&w), "{w:?}");
    let (auto64, w) = p0_and_warnings(&heavy(64, Growth::Auto));
    assert!(!at_end(&w), "{w:?}");
    assert!(relative(auto32, auto64).abs() < 2e-3, "{auto32} {auto64}");
    let (full32, w) = p0_and_warnings(&heavy(32, Growth::Full));
    assert!(at_end(&w), "{w:?}");
    assert!(relative(full32, auto64) < -0.03, "{full32} {auto64}");

    let nearly = |n: usize, growth: Growth, formulation: Formulation| {
        let mut s = hertz(n);
        s.solver.growth = growth;
        let disk = s.body_mut("disk").unwrap();
        disk.material.poisson = 0.4999;
        disk.formulation = formulation;
        p0_and_warnings(&s)
    };
    let locks = |w: &[Warning]| {
        w.iter()
            .any(|w| matches!(w, Warning::NearlyIncompressible { .. }))
    };
    let (a, wa) = nearly(16, Growth::Auto, Formulation::Displacement);
    let (b, wb) = nearly(16, Growth::Full, Formulation::Displacement);
    assert!(relative(a, b).abs() > 0.01, "{a} {b}");
    assert!(locks(&wa) && locks(&wb), "{wa:?} {wb:?}");
    let (a, wa) = nearly(16, Growth::Auto, Formulation::Mixed);
    let (b, wb) = nearly(16, Growth::Full, Formulation::Mixed);
    assert!(!locks(&wa) && !locks(&wb), "{wa:?} {wb:?}");
    assert!(relative(a, b).abs() < 1e-8, "{a} {b}");
    let (fine, _) = nearly(32, Growth::Auto, Formulation::Mixed);
    assert!(relative(a, fine).abs() < 0.01, "{a} {fine}");
}
