//! The chapter's tables: the solver ladder and its failures (H5, H6), the
//! two 8×8 iteration histories (H1, H2), the convergence study and the
//! reference (H3, H4).

use crate::convergence::{Convergence, Measured};
use crate::ladder::{Failure, Ladder, Run};
use crate::REFERENCE;
use companion::chapter::Chapter;
use iga_contact::error::Result;
use iga_contact::post::hertz::Hertz;
use iga_contact::post::relative;
use iga_contact::report::history::history_table;
use iga_contact::report::table::{Cell, Column, Format, Table, Unit, CONTACT_ERRORS};

/// "The solver ladder": Tables H5 (with the wall time of each run in the
/// CSV) and H6.
pub fn write_ladder(chapter: &mut Chapter, ladder: &Ladder) -> Result<()> {
    chapter.table("ladder", &ladder_table(&ladder.runs)?)?;
    chapter.timed("ladder.csv"); // its `seconds` column
    chapter.table("failures", &failure_table(&ladder.failures)?)
}

/// Tables H1 and H2 (the paper's Table 2): the paper's iteration and the
/// default on 8×8, p = 2.
pub fn write_histories(chapter: &mut Chapter, paper: &Run, default: &Run) -> Result<()> {
    for (name, r) in [("iterations_8x8_paper", paper), ("iterations_8x8", default)] {
        chapter.table(
            name,
            &history_table(&r.solution.history, Unit::NewtonPerMetre, Unit::Millimetre)?,
        )?;
    }
    Ok(())
}

/// "Convergence under refinement": Tables H3 and H4, against Hertz and
/// against the reference.
pub fn write_convergence(chapter: &mut Chapter, study: &Convergence, exact: &Hertz) -> Result<()> {
    chapter.table("convergence", &convergence_table(study, exact)?)?;
    chapter.table("reference", &reference_table(exact, study.reference)?)
}

// ANCHOR: tables
fn ladder_table(ladder: &[Run]) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs").csv_only(),
        Column::plain("solver", "solver"),
        Column::plain("iterations", "its"),
        Column::plain("corrections", "corr."),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(2)),
        Column::new(
            "contact_force",
            "F_c",
            Unit::NewtonPerMetre,
            Format::Fixed(0),
        )
        .csv_only(),
        Column::new(
            "applied_force",
            "F_app",
            Unit::NewtonPerMetre,
            Format::Fixed(0),
        )
        .csv_only(),
        Column::new("seconds", "seconds", Unit::Second, Format::Fixed(3)).csv_only(),
    ]);
    for r in ladder {
        t.push(vec![
            r.degree.into(),
            r.elements.into(),
            r.problem.n().into(),
            r.solver.key().into(),
            r.solution.history.len().into(),
            r.solution.history.corrections().into(),
            r.p0.into(),
            r.half_width.into(),
            r.contact_force.into(),
            (-r.applied_force).into(),
            r.seconds.into(),
        ])?;
    }
    Ok(t)
}
// ANCHOR_END: tables

fn failure_table(failures: &[Failure]) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("solver", "solver"),
        Column::plain("iterations", "iterations"),
        Column::plain("corrections", "corrections"),
        Column::plain("reason", "reason"),
    ]);
    for f in failures {
        t.push(vec![
            f.degree.into(),
            f.elements.into(),
            f.solver.key().into(),
            f.history.len().into(),
            f.history.corrections().into(),
            f.reason.clone().into(),
        ])?;
    }
    Ok(t)
}

fn convergence_table(study: &Convergence, exact: &Hertz) -> Result<Table> {
    let reference = study.reference;
    let mut columns = vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs"),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(3)),
    ];
    columns.extend(CONTACT_ERRORS);
    let mut t = Table::new(columns);
    for rung in &study.rows {
        let (p, n, m) = (rung.degree, rung.elements, rung.measured);
        // The reference measured against itself is no result: its row says
        // so instead of showing a zero error.
        let against_reference = |v: f64, r: f64| -> Cell {
            if (p, n) == REFERENCE {
                "reference".into()
            } else {
                relative(v, r).into()
            }
        };
        t.push(vec![
            p.into(),
            n.into(),
            m.dofs.into(),
            m.p0.into(),
            m.half_width.into(),
            relative(m.p0, exact.p0).into(),
            relative(m.half_width, exact.half_width).into(),
            against_reference(m.p0, reference.p0),
            against_reference(m.half_width, reference.half_width),
        ])?;
    }
    Ok(t)
}

fn reference_table(exact: &Hertz, reference: Measured) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("solution", "solution"),
        Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(4)),
        Column::new("half_width", "a", Unit::Millimetre, Format::Fixed(3)),
        Column::plain("dofs", "DOFs"),
    ]);
    t.push(vec![
        "Hertz".into(),
        exact.p0.into(),
        exact.half_width.into(),
        Cell::Empty,
    ])?;
    let name = format!("reference, p = {}, {}²", REFERENCE.0, REFERENCE.1);
    t.push(vec![
        name.into(),
        reference.p0.into(),
        reference.half_width.into(),
        reference.dofs.into(),
    ])?;
    Ok(t)
}
