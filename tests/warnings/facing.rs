//! A slave that closes where it faces away from its master (or edge on to
//! it) is warned, and the advised slave side fixes the answer.

use crate::{outcome, RIGHT};
use iga_contact::scene::{Scene, SlaveAt};
use iga_contact::solver::warning::PenaltyRemedy;
use iga_contact::solver::{solve, Warning};

#[test]
fn a_slave_that_closes_where_it_faces_away_is_warned_and_the_advice_fixes_it() {
    // the full disk's upper half as the slave against the floor under it:
    // open at the start (its gaps run down through the disk), it closes
    // once the disk has fallen its diameter, where its normals point up,
    // away from the floor; only that warning is given (the penalty counted
    // on such gaps would be advice that leaves the answer as wrong)
    let shipped = companion::shipped("disk_full.toml").unwrap();
    let mut upper = shipped.clone();
    upper.contacts[0].slave_at = SlaveAt::Boundary("arc_upper".into());
    upper.output = Default::default();
    let problem = upper.build().unwrap();
    let sol = solve(&problem, &upper.solver).unwrap();
    assert!(
        matches!(&sol.warnings[..], [Warning::ClosedFacingAway { contact: 0, away, active, .. }] if away == active && *active > 0),
        "{:?}",
        sol.warnings
    );
    let text = sol.warnings[0].to_string();
    assert!(text.contains("faces away from its master"), "{text}");
    // followed: the side of the disk that faces the floor
    let mut lower = upper.clone();
    lower.contacts[0].slave_at = SlaveAt::Boundary("arc_lower".into());
    let (warnings, error) = outcome(&lower);
    assert!(warnings.is_empty(), "{warnings:?}");
    assert!(error.abs() < RIGHT, "p₀ {error:+.3e} off Hertz");
}

#[test]
fn a_slave_side_edge_on_to_its_master_is_warned_and_the_advice_fixes_it() {
    // the block's right side as the slave against the floor under it: the
    // block sinks until the side's lowest points pass the floor; the
    // bottom, which faces the floor, carries the uniform pressure
    let text = String::from(
        "title = \"block side against floor\"\n\
           [[body]]\nname = \"block\"\n\
           geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }\n\
           refine = { degree = 2, elements = [4, 16] }\n\
           material = { young = 1.0e7, poisson = 0.3, plane = \"strain\" }\n\
           [[support]]\nbody = \"block\"\nside = \"xi_min\"\ncomponent = \"x\"\n\
           [[load]]\npressure = { body = \"block\", side = \"eta_max\", pressure = 1.0e4 }\n\
           [[contact]]\nslave = \"block\"\nslave_side = \"xi_max\"\n\
           master = { rigid_segment = { from = [-0.5, 0.0], to = [1.5, 0.0] } }\n",
    );
    let solved = |text: &str| {
        let scene = Scene::from_toml_str(text).unwrap();
        let problem = scene.build().unwrap();
        let sol = solve(&problem, &scene.solver).unwrap();
        let f = iga_contact::post::contact_resultant(&problem, &sol.full);
        (sol.warnings, f)
    };
    let (w, _) = solved(&text);
    assert!(
        w.iter()
            .any(|w| matches!(w, Warning::ClosedFacingAway { .. })),
        "{w:?}"
    );
    // the side tilted 6° from upright grazes the floor: warned too
    let tilted = text.replace(
        "geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 0.5 } }",
        "geometry = { quadrilateral = { corners = [[0.0, 0.0], [1.0, 0.0], [1.05, 0.5], [0.0, 0.5]] } }",
    );
    assert_ne!(tilted, text);
    let (w, _) = solved(&tilted);
    assert!(
        w.iter()
            .any(|w| matches!(w, Warning::ClosedFacingAway { .. })),
        "{w:?}"
    );
    // followed: the bottom; that side's own penalty warning is then
    // followed too (its factor is judged on real gaps now)
    let bottom = text.replace("slave_side = \"xi_max\"", "slave_side = \"eta_min\"");
    let (w, _) = solved(&bottom);
    let factor = match &w[..] {
        [Warning::PenaltyBelowBound {
            remedy: PenaltyRemedy::Factor(f),
            ..
        }] => *f,
        [] => 1.0,
        other => panic!("{other:?}"),
    };
    let (w, f) = solved(&format!(
        "{bottom}nitsche = {{ penalty_factor = {factor:?} }}\n"
    ));
    assert!(w.is_empty(), "{w:?}");
    assert!((f[1] - 1.0e4).abs() < 1e-8 * 1.0e4, "{f:?}");
}
