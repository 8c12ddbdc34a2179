//! A cheap slice of the stability atlas: every case ends converged or in a
//! typed, diagnosed error — never a panic or a NaN.

use iga_contact::studies::stability::atlas_where;

#[test]
fn extreme_cases_end_in_a_result_or_a_diagnosed_error() {
    let keep = |name: &str| {
        name.starts_with("taylor_penalty")
            || name.starts_with("taylor_contrast")
            || name.starts_with("taylor_open")
            || name.starts_with("taylor_initial")
            || name == "hertz_lifted_and_pulled_up"
            || name == "hertz_p2_4x4"
            || name == "hertz_p1_1x1"
    };
    let rows = atlas_where(keep, |_, _, _| {}).unwrap();
    assert!(rows.len() >= 40, "{} cases", rows.len());
    for r in &rows {
        assert_ne!(r.error_kind, "panic", "{}", r.case);
        assert_ne!(r.error_kind, "nan", "{}", r.case);
        if r.status == "failed" {
            assert!(
                !r.error_kind.is_empty() && !r.diagnosis.is_empty(),
                "{} failed without a diagnosis",
                r.case
            );
        }
        if let Some(e) = r.error_vs_reference {
            assert!(e.is_finite(), "{}", r.case);
        }
    }
    let row = |name: &str, theta: f64| {
        rows.iter()
            .find(|r| r.case == name && r.theta == theta)
            .unwrap()
    };
    // the paper's setting passes the patch test
    assert!(row("taylor_penalty_1e0", 0.0).error_vs_reference.unwrap() < 1e-8);
    // an open, unloaded gap stays open
    assert_eq!(row("taylor_open_gap_unloaded", 0.0).status, "no_contact");
    // a disk pulled away from the floor is diagnosed, not iterated forever
    let floating = row("hertz_lifted_and_pulled_up", 0.0);
    assert_eq!(floating.error_kind, "floating_body");
    assert!(floating.diagnosis.contains("floats"));
}
