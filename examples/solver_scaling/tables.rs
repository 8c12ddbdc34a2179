//! The tables `scaling` (the totals), `phases` (the split of the
//! in-process time) and `cli` (the split of the command-line run).

use crate::measure::{InProcess, Row};
use iga_contact::report::table::{Cell, Column, Format, Table, Unit};

/// A cell of an in-process figure, empty where the case ran only through
/// the command line.
fn cell(row: &Row, f: impl Fn(&InProcess) -> Cell) -> Cell {
    row.solve.as_ref().map_or(Cell::Empty, f)
}

/// The columns of the tables `scaling`, `phases` and `cli`. C is the
/// fastest reference Cholesky factorisation, C₁ the first of its process;
/// times are in seconds. The page shows eight columns at most (the text
/// column is about 750 px wide); the others are in the CSV files.
fn columns() -> [Table; 3] {
    let seconds = |key, header| Column::new(key, header, Unit::None, Format::Fixed(2));
    let ratio = |key, header| Column::new(key, header, Unit::None, Format::Times(2));
    let scaling = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        Column::plain("dofs", "DOFs").csv_only(),
        Column::plain("layer", "layer ℓ").csv_only(),
        Column::plain("iterations", "its"),
        seconds("total", "total").csv_only(),
        ratio("ratio", "solve ÷ C"),
        ratio("cpu_ratio", "solve ÷ C, CPU").csv_only(),
        Column::new("peak_gb", "peak", Unit::Gigabyte, Format::Fixed(2)).csv_only(),
        seconds("cli_wall", "CLI").csv_only(),
        ratio("cli_ratio", "CLI ÷ C"),
        ratio("cli_ratio_first", "CLI ÷ C₁"),
        ratio("cli_cpu_ratio", "CLI ÷ C, CPU"),
        Column::new("cli_peak_gb", "CLI peak", Unit::Gigabyte, Format::Fixed(2)),
        Column::new("force_error", "force error", Unit::None, Format::Sci(1)).csv_only(),
    ]);
    let phases = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        seconds("assembly", "assemble"),
        seconds("one_cholesky", "C"),
        seconds("first_cholesky", "C₁"),
        seconds("condensation", "condense"),
        seconds("iterations_seconds", "iterate"),
        Column::new("back_substitution", "recover", Unit::None, Format::Fixed(3)).csv_only(),
        Column::new("route_b_estimate", "B", Unit::None, Format::Fixed(1)),
    ]);
    let cli = Table::new(vec![
        Column::plain("degree", "p"),
        Column::new("elements", "mesh", Unit::None, Format::Mesh),
        seconds("parse_and_build", "parse, build").csv_only(),
        seconds("contact_setup", "contact").csv_only(),
        seconds("assembly", "assemble"),
        seconds("factorisation", "factorise"),
        seconds("iterations", "iterate"),
        seconds("post_processing", "post"),
        seconds("output", "output").csv_only(),
        seconds("parts", "sum"),
        seconds("wall", "wall"),
        seconds("one_cholesky", "C").csv_only(),
    ]);
    [scaling, phases, cli]
}

/// The totals (`scaling`), the split of the in-process time (`phases`) and
/// of the command-line run (`cli`), a row per case.
pub fn tables(rows: &[Row]) -> iga_contact::Result<[Table; 3]> {
    let [mut scaling, mut phases, mut cli] = columns();
    for r in rows {
        let t = &r.cli.timing;
        scaling.push(vec![
            r.p.into(),
            r.n.into(),
            r.dofs.into(),
            r.layer.into(),
            r.solve
                .as_ref()
                .map_or(r.cli.iterations, |s| s.iterations)
                .into(),
            cell(r, |s| s.total.into()),
            cell(r, |s| (s.total / r.cholesky).into()),
            cell(r, |s| (s.total_cpu / r.cholesky_cpu).into()),
            cell(r, |s| (s.peak * 1e9).into()),
            r.cli.wall.into(),
            (r.cli.wall / r.cholesky).into(),
            (r.cli.wall / r.cholesky_first).into(),
            (r.cli.cpu / r.cholesky_cpu).into(),
            r.cli.peak.into(),
            cell(r, |s| s.force_error.into()),
        ])?;
        phases.push(vec![
            r.p.into(),
            r.n.into(),
            r.assembly.into(),
            r.cholesky.into(),
            r.cholesky_first.into(),
            cell(r, |s| s.condensation.into()),
            cell(r, |s| s.iterations_s.into()),
            cell(r, |s| s.recovery.into()),
            r.route_b.into(),
        ])?;
        cli.push(vec![
            r.p.into(),
            r.n.into(),
            t.parse_and_build.into(),
            t.contact_setup.into(),
            t.assembly.into(),
            t.factorisation.into(),
            t.iterations.into(),
            t.post_processing.into(),
            t.output.into(),
            t.sum().into(),
            r.cli.wall.into(),
            r.cholesky.into(),
        ])?;
    }
    Ok([scaling, phases, cli])
}
