//! A solver's iteration history as a [`Table`].

use super::table::{Cell, Column, Format, Table, Unit};
use crate::error::Result;
use crate::history::History;

/// One row per iteration: residual, relative residual, update, the largest
/// displacement, active contact points and events, with residuals shown in
/// the unit `force` and displacements in `length` (the book's benchmarks:
/// N/m and m or mm; a scene's own units: [`Unit::None`]).
pub fn history_table(h: &History, force: Unit, length: Unit) -> Result<Table> {
    history_table_noted(h, force, length, &[])
}

/// [`history_table`] with `notes` added to the events of the last
/// iteration: findings about the converged solution that the solver does
/// not record itself (a penalty below its stability bound). A history
/// without iterations has no row to carry them.
pub fn history_table_noted(
    h: &History,
    force: Unit,
    length: Unit,
    notes: &[String],
) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("iteration", "it."),
        Column::new("residual", "‖R‖", force, Format::Sci(2)),
        Column::new("relative_residual", "‖R‖/‖R₀‖", Unit::None, Format::Sci(2)),
        Column::new("update", "‖Δu‖", length, Format::Sci(2)),
        Column::new("max_displacement", "max u", length, Format::Sci(4)),
        Column::plain("active_points", "active"),
        Column::plain("events", "events"),
    ]);
    let last = h.rows.len().saturating_sub(1);
    for (k, r) in h.rows.iter().enumerate() {
        let mut events: Vec<String> = r.events.iter().map(|e| e.to_string()).collect();
        if k == last {
            events.extend(notes.iter().cloned());
        }
        t.push(vec![
            r.iteration.into(),
            r.residual.into(),
            r.relative_residual.into(),
            r.update.into(),
            r.max_displacement.into(),
            r.active_points.into(),
            Cell::Text(events.join("; ")),
        ])?;
    }
    Ok(t)
}
