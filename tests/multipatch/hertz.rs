//! The multi-patch Hertz scenes against the closed form and against the
//! one-patch scene: p₀ and a as accurate on comparable meshes, the full
//! disk on point supports as its symmetric half, the half-width the same
//! whichever way a boundary's pieces run, and one profile per contact.

use crate::common::shipped_text;
use crate::{measured, rel, run, R};
use iga_contact::material::{Material, Plane};
use iga_contact::post::hertz::{Cylinder, Hertz};
use iga_contact::scene::{RefineSpec, Scene, SupportAt};
use iga_contact::solver::solve;
use std::f64::consts::PI;

/// Hertz's p₀ and a for the disk of the Hertz scenes under `factor` times
/// their load (the full disk's load: twice the half model's).
fn hertz(factor: f64) -> Hertz {
    let material = Material::new(2.0e7, 0.1, Plane::Strain).unwrap();
    let load = factor * 1.3e6 * PI * R * R;
    Hertz::new(
        Cylinder::Elastic {
            radius: R,
            material,
        },
        Cylinder::RigidPlane,
        load,
    )
}

#[test]
fn hertz_multipatch_matches_hertz_like_the_one_patch_scene() {
    // Both scenes put n elements on the 45° of arc next to the lowest
    // point, where the contact zone lies: comparable meshes.
    let h = hertz(1.0);
    let err = |p0: f64, a: f64| rel(p0, h.p0).max(rel(a, h.half_width));
    let mut errors = Vec::new();
    for n in [8, 16] {
        let (p0, a, zones, _) = run("hertz_multipatch.toml", n, 1.0);
        let (q0, b, _, _) = run("hertz.toml", n, 1.0);
        let (multi, single) = (err(p0, a), err(q0, b));
        assert_eq!(zones, 1);
        assert!(
            multi <= 1.25 * single,
            "{n} × {n}: multi-patch error {multi:e} against one patch {single:e}"
        );
        errors.push(multi);
    }
    // and it falls under refinement, at least as h² (the measures'
    // sampling adds its own share)
    assert!(errors[1] < 0.25 * errors[0], "{errors:?}");
}

/// The full five-patch disk of `disk_full.toml`, held in x at two points
/// of its vertical centre line only, against the four-patch half disk with
/// its symmetry support (`hertz_multipatch.toml`), at the same penalty and
/// the same element density near the lowest point (n elements on a quarter
/// of the full disk's circle, n/2 on the half disk's 45° patch): p₀ and a
/// agree to discretisation accuracy, and more closely on the finer mesh;
/// the shipped scene runs without a warning and its contact force
/// balances the load on the whole disk.
#[test]
fn the_full_disk_on_point_supports_matches_the_half_disk_with_symmetry() {
    let measure = |file: &str, elements: [usize; 2]| {
        let scene = companion::shipped(file)
            .unwrap()
            .refined("disk", RefineSpec::iga(2, elements))
            .unwrap()
            .with_nitsche(|x| x.penalty_factor = 3.0);
        let (m, warnings) = measured(&scene).unwrap();
        (m.p0, m.half_width, warnings)
    };
    let shipped = companion::shipped("disk_full.toml").unwrap();
    assert!(shipped
        .supports
        .iter()
        .all(|s| matches!(s.at, SupportAt::Point(_))));
    let mut gaps = Vec::new();
    for n in [16, 32] {
        let (p_full, a_full, w) = measure("disk_full.toml", [n, n / 2]);
        assert!(w.is_empty(), "{n}: {w:?}");
        let (p_half, a_half, _) = measure("hertz_multipatch.toml", [n / 2, n / 2]);
        gaps.push((rel(p_full, p_half), rel(a_full, a_half)));
    }
    let (coarse, fine) = (gaps[0], gaps[1]);
    assert!(fine.0 < 1e-3 && fine.0 < 0.25 * coarse.0, "p₀: {gaps:?}");
    assert!(fine.1 < 0.02 && fine.1 < coarse.1, "a: {gaps:?}");
    let report = shipped
        .check(&iga_contact::resources::Budget::from_machine())
        .unwrap();
    assert!(report.warnings.is_empty(), "{:?}", report.warnings);
    let problem = shipped.build().unwrap();
    let sol = solve(&problem, &shipped.solver).unwrap();
    assert!(sol.warnings.is_empty(), "{:?}", sol.warnings);
    let f = iga_contact::post::contact_resultant(&problem, &sol.full);
    let load = 1.3e6 * PI * R * R;
    assert!(rel(f[1], load) < 1e-8 && f[0].abs() < 1e-8 * load, "{f:?}");
}

#[test]
fn the_profile_names_the_contact_not_the_patch_piece() {
    // hertz_multipatch.toml: one [[contact]] whose slave boundary crosses
    // patch sides, so several pairs; the CSV and summary.toml both say 0
    let mut scene = companion::shipped("hertz_multipatch.toml").unwrap();
    let problem = scene.build().unwrap();
    assert!(problem.contacts.pieces(0).len() > 1, "needs several pieces");
    let dir = std::env::temp_dir().join(format!("iga-mp-profile-{}", std::process::id()));
    scene.output = iga_contact::scene::OutputSpec {
        summary: true,
        pressure_profile: true,
        ..Default::default()
    };
    scene.run(&dir).unwrap();
    let csv = std::fs::read_to_string(dir.join("pressure_profile.csv")).unwrap();
    let mut lines = csv.lines();
    assert_eq!(lines.next(), Some("contact,x,y,bracket,pressure,regular"));
    let contacts: std::collections::BTreeSet<&str> =
        lines.map(|l| l.split(',').next().unwrap()).collect();
    assert_eq!(contacts.into_iter().collect::<Vec<_>>(), ["0"]);
    let summary: toml::Table =
        toml::from_str(&std::fs::read_to_string(dir.join("summary.toml")).unwrap()).unwrap();
    assert_eq!(summary["contact"].as_array().unwrap().len(), 1);
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn the_half_width_of_a_boundary_is_the_same_whichever_way_its_pieces_run() {
    // hertz_multipatch.toml mirrored: the whole `arc` as the slave, pushed
    // up against a ceiling at y = 0.4. The profile is the floor's mirror
    // image, so p₀ and the half-width must agree with the floor's; the
    // zone lies on a piece whose side runs against the boundary, which
    // cut the zone into runs out of order (half_width 0.0187, not 0.0470)
    let base = shipped_text("hertz_multipatch.toml");
    let ceiling = base
        .replacen(
            "slave_boundary = \"arc_lower\"",
            "slave_boundary = \"arc\"",
            1,
        )
        .replacen(
            "from = [-0.2, 0.0], to = [0.4, 0.0]",
            "from = [0.4, 0.4], to = [-0.2, 0.4]",
            1,
        )
        .replacen("force = [0.0, -1.3e6]", "force = [0.0, 1.3e6]", 1);
    assert_ne!(ceiling, base);
    let measure = |text: &str| measured(&Scene::from_toml_str(text).unwrap()).unwrap().0;
    let (floor, up) = (measure(&base), measure(&ceiling));
    assert!(
        rel(up.p0, floor.p0) < 1e-9,
        "{} against {}",
        up.p0,
        floor.p0
    );
    assert!(
        rel(up.half_width, floor.half_width) < 1e-9,
        "{} against {}",
        up.half_width,
        floor.half_width
    );
    assert_eq!((up.zones, floor.zones), (1, 1));
}
