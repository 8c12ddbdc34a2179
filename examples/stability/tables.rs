//! The atlas's tables: every case (`atlas.csv`), the other axes case by
//! case, the penalty × θ views and the penalty range of each θ.

use crate::atlas::{Row, Status};
use crate::cases::factors;
use iga_contact::contact::Theta;
use iga_contact::error::{Error, Result};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};

/// What the deviation of a case (by its name) is measured against: an
/// error only where that reference is exact (the patch test) or converged
/// (the fine reference); against the paper's 8×8 setting or Hertz's
/// formula it is a distance from another approximation.
fn against(case: &str) -> &'static str {
    if case.starts_with("taylor_open_gap") || case == "hertz_lifted_and_pulled_up" {
        "no contact"
    } else if case.starts_with("taylor") {
        "exact σ_yy"
    } else if case.starts_with("hertz_16x16") {
        "Hertz's formula"
    } else if case.starts_with("hertz_p") {
        "fine reference"
    } else {
        "the paper's 8×8 setting"
    }
}

/// The penalty factors at which Hertz 8×8 converges within `tol` of the
/// reference, for one θ.
fn good_factors(rows: &[Row], theta: Theta, tol: f64) -> Vec<f64> {
    rows.iter()
        .filter(|r| r.case.starts_with("hertz_8x8_penalty") && r.theta == theta)
        .filter(|r| r.status == Status::Converged && r.error.is_some_and(|e| e <= tol))
        .map(|r| r.penalty_factor)
        .collect()
}

/// The accuracy criterion of the penalty ranges.
pub const PENALTY_TOLERANCE: f64 = 0.05;

/// A cell of a penalty × θ view: the error (in `format`) and the iteration
/// count, `†` where active points have a penalty below the stability bound
/// (the solver warns), `‡` where for θ = 1 only inactive points do (their
/// term −(1/γ) w sₙsₙᵀ enters the tangent too, and the solver warns about
/// them as well).
fn penalty_cell(r: &Row, format: Format) -> String {
    let its = r.history.len();
    match (r.status, r.error) {
        (Status::Converged, Some(e)) => {
            let mark = if r.below > 0 {
                " †"
            } else if r.theta == Theta::Symmetric && r.below_inactive > 0 {
                " ‡"
            } else {
                ""
            };
            format!("{} ({its}){mark}", format.render(e))
        }
        (status, _) => format!("{} ({its})", status.key()),
    }
}

/// The penalty × θ view of the cases whose name starts with `prefix`.
pub fn penalty_view(rows: &[Row], prefix: &str, format: Format) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::new(
            "penalty_factor",
            "penalty factor",
            Unit::None,
            Format::Sci(0),
        ),
        Column::plain("t1", "θ = 1"),
        Column::plain("t0", "θ = 0"),
        Column::plain("tm1", "θ = −1"),
    ]);
    for f in factors() {
        let mut cells: Vec<Cell> = vec![f.into()];
        for theta in Theta::ALL {
            let r = rows
                .iter()
                .find(|r| r.case.starts_with(prefix) && r.theta == theta && r.penalty_factor == f)
                .ok_or_else(|| Error::invalid("case", prefix, "missing from the atlas"))?;
            cells.push(penalty_cell(r, format).into());
        }
        t.push(cells)?;
    }
    Ok(t)
}

// ANCHOR: tables
/// A text cell, empty where the text is.
fn text_cell(s: &str) -> Cell {
    if s.is_empty() {
        Cell::Empty
    } else {
        s.into()
    }
}

/// "The full atlas": every case with its solver history, active points,
/// error, warnings and diagnosis (`atlas.csv`).
pub fn atlas_table(rows: &[Row]) -> Result<Table> {
    let mut atlas = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("theta", "θ"),
        Column::new("penalty_factor", "penalty", Unit::None, Format::Sci(0)),
        Column::plain("status", "status"),
        Column::plain("iterations", "its"),
        Column::plain("corrections", "corr."),
        Column::plain("skipped_updates", "skipped"),
        Column::plain("restarted", "restarted"),
        Column::plain("active_points", "active"),
        Column::plain("active_below_bound", "below bound"),
        Column::plain("inactive_below_bound", "inactive below bound"),
        Column::plain("singular_active", "active on det J = 0"),
        Column::new(
            "error_vs_reference",
            "deviation",
            Unit::None,
            Format::Sci(1),
        ),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::plain("warnings", "warnings"),
        Column::plain("error_kind", "error kind"),
        Column::plain("diagnosis", "diagnosis"),
    ]);
    for r in rows {
        let warnings: Vec<String> = r.warnings.iter().map(|w| w.to_string()).collect();
        atlas.push(vec![
            r.case.clone().into(),
            r.theta.value().into(),
            r.penalty_factor.into(),
            r.status.key().into(),
            r.history.len().into(),
            r.history.corrections().into(),
            r.history.skipped_updates().into(),
            (if r.restarted() { "yes" } else { "no" }).into(),
            r.active.into(),
            r.below.into(),
            r.below_inactive.into(),
            r.singular_active.into(),
            r.error.into(),
            r.p0.into(),
            text_cell(&warnings.join("; ")),
            text_cell(&r.error_kind),
            text_cell(&r.diagnosis),
        ])?;
    }
    Ok(atlas)
}

/// "The full atlas" in Markdown: the axes other than the penalty, case by
/// case (the penalty axis has its views, `penalty_view`).
pub fn others_table(rows: &[Row]) -> Result<Table> {
    let mut others = Table::new(vec![
        Column::plain("case", "case"),
        Column::plain("status", "status"),
        Column::plain("iterations", "its"),
        Column::plain("active_points", "active"),
        Column::new(
            "error_vs_reference",
            "deviation",
            Unit::None,
            Format::Sci(1),
        ),
        Column::plain("against", "against"),
        Column::plain("note", "note"),
    ]);
    for r in rows.iter().filter(|r| !r.case.contains("_penalty_")) {
        others.push(vec![
            r.case.clone().into(),
            r.status.key().into(),
            r.history.len().into(),
            r.active.into(),
            r.error.into(),
            against(&r.case).into(),
            text_cell(&r.note()),
        ])?;
    }
    Ok(others)
}

/// "The penalty range of each θ": the factors at which Hertz 8×8 is within
/// the tolerance of its reference.
pub fn ranges_table(rows: &[Row]) -> Result<Table> {
    // The factors themselves, not an interval: the set need not be
    // contiguous (θ = 1 is off by more than the tolerance at factor 1,
    // between two factors within it).
    let mut ranges = Table::new(vec![
        Column::plain("theta", "θ"),
        Column::plain("factors", "factors within 5 %"),
        Column::plain("count", "count"),
    ]);
    for theta in Theta::ALL {
        let ok = good_factors(rows, theta, PENALTY_TOLERANCE);
        let list: Vec<String> = ok.iter().map(|&x| Format::Sci(0).render(x)).collect();
        ranges.push(vec![
            theta.value().into(),
            list.join(" ").into(),
            ok.len().into(),
        ])?;
    }
    Ok(ranges)
}
// ANCHOR_END: tables
