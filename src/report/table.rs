//! Tables declared once: a [`Table`] knows its columns (CSV key, Markdown
//! header, unit and number format) and renders itself both as CSV, for
//! programs, and as a Markdown table, for the book.
//!
//! Values are given in SI base units. CSV files keep them so, at full
//! precision, under the column's key; the Markdown table shows each column
//! in its display unit (mm, MPa, ...), named in its header.
//!
//! Number formatting (fixed, scientific, percent, typographic minus, no
//! negative zero) and CSV quoting live here and nowhere else.

use crate::error::{Error, Result};
use std::fmt::Write;

/// The unit a column is shown in in Markdown. Values are given in SI base
/// units and converted for display.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Unit {
    /// A pure number (counts, ratios, relative errors).
    None,
    Metre,
    Millimetre,
    Pascal,
    Megapascal,
    /// Force per unit thickness, N/m.
    NewtonPerMetre,
    Second,
    Millisecond,
    /// Joule per metre of thickness, J/m.
    JoulePerMetre,
    Megabyte,
    Gigabyte,
}

impl Unit {
    /// What a value given in SI is multiplied by.
    pub fn scale(self) -> f64 {
        match self {
            Unit::Millimetre | Unit::Millisecond => 1e3,
            Unit::Megapascal | Unit::Megabyte => 1e-6,
            Unit::Gigabyte => 1e-9,
            _ => 1.0,
        }
    }

    /// The symbol; empty for [`Unit::None`].
    pub fn symbol(self) -> &'static str {
        match self {
            Unit::None => "",
            Unit::Metre => "m",
            Unit::Millimetre => "mm",
            Unit::Pascal => "Pa",
            Unit::Megapascal => "MPa",
            Unit::NewtonPerMetre => "N/m",
            Unit::Second => "s",
            Unit::Millisecond => "ms",
            Unit::JoulePerMetre => "J/m",
            Unit::Megabyte => "MB",
            Unit::Gigabyte => "GB",
        }
    }
}

/// How a number is written in the Markdown table (CSV always carries the
/// full precision).
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Format {
    /// Text, or an integer.
    Plain,
    /// A fixed number of decimals.
    Fixed(usize),
    /// Scientific, this many decimals in the mantissa: 2.69e−2.
    Sci(usize),
    /// Scientific for prose, with a power of ten: 2.69×10⁻².
    Pow10(usize),
    /// A fraction shown in percent with this many decimals: 2.69 %.
    Percent(usize),
    /// A signed fraction in percent: +2.69 %, −1.37 %.
    SignedPercent(usize),
    /// A ratio: 3.1×.
    Times(usize),
    /// Elements per direction n, shown as n².
    Mesh,
}

impl Format {
    /// The number `v` as the book writes it.
    pub fn render(self, v: f64) -> String {
        let v = if v == 0.0 { 0.0 } else { v }; // no negative zero
        let s = match self {
            Format::Plain => {
                if v.fract() == 0.0 && v.abs() < 1e15 {
                    format!("{}", v as i64)
                } else {
                    format!("{v}")
                }
            }
            Format::Fixed(d) => format!("{v:.d$}"),
            Format::Sci(d) => format!("{v:.d$e}"),
            Format::Pow10(d) => {
                let s = format!("{v:.d$e}");
                let (mantissa, exponent) = s.split_once('e').expect("{:e} writes an exponent");
                let sup: String = exponent
                    .chars()
                    .map(|c| match c {
                        '-' => '⁻',
                        d => "⁰¹²³⁴⁵⁶⁷⁸⁹"
                            .chars()
                            .nth(d as usize - '0' as usize)
                            .unwrap_or(d),
                    })
                    .collect();
                if exponent == "0" {
                    mantissa.to_string()
                } else {
                    format!("{mantissa}×10{sup}")
                }
            }
            Format::Percent(d) => format!("{:.d$} %", 100.0 * v),
            Format::SignedPercent(d) => format!("{:+.d$} %", 100.0 * v),
            Format::Times(d) => format!("{v:.d$}×"),
            Format::Mesh => format!("{}²", v as i64),
        };
        typographic_minus(&normalise_zero(s))
    }
}

/// "-0.00" and "-0.0e0" become "0.00" and "0.0e0": rounding must not
/// invent a sign.
fn normalise_zero(s: String) -> String {
    match s.strip_prefix('-') {
        Some(rest)
            if rest
                .split(['e', ' ', '×'])
                .next()
                .is_some_and(|m| m.chars().all(|c| c == '0' || c == '.')) =>
        {
            rest.to_string()
        }
        _ => s,
    }
}

/// Replaces the hyphen-minus by the typographic minus sign (U+2212).
pub fn typographic_minus(s: &str) -> String {
    s.replace('-', "−")
}

/// Where a column appears.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Place {
    /// In the CSV file and the Markdown table.
    Both,
    /// In the CSV file only: data for programs, too detailed for the page.
    CsvOnly,
    /// In the Markdown table only: a derived view (a rate, a mesh label)
    /// of data the CSV file already holds.
    MarkdownOnly,
}

/// One column of a [`Table`].
#[derive(Clone, Debug, PartialEq)]
pub struct Column {
    /// CSV key (`p0`); the CSV value is in SI units.
    pub key: &'static str,
    /// Markdown header, without the unit (`p₀`); shown as `p₀ (MPa)`.
    pub header: &'static str,
    pub unit: Unit,
    pub format: Format,
    pub place: Place,
}

impl Column {
    pub const fn new(key: &'static str, header: &'static str, unit: Unit, format: Format) -> Self {
        Self {
            key,
            header,
            unit,
            format,
            place: Place::Both,
        }
    }

    /// The column, in the CSV file only.
    pub const fn csv_only(mut self) -> Self {
        self.place = Place::CsvOnly;
        self
    }

    /// The column, in the Markdown table only.
    pub const fn markdown_only(mut self) -> Self {
        self.place = Place::MarkdownOnly;
        self
    }

    /// A text or integer column.
    pub const fn plain(key: &'static str, header: &'static str) -> Self {
        Self::new(key, header, Unit::None, Format::Plain)
    }

    fn md_header(&self) -> String {
        match self.unit {
            Unit::None => self.header.to_string(),
            u => format!("{} ({})", self.header, u.symbol()),
        }
    }
}

/// The four relative errors every contact ladder reports (CSV keys
/// `p0_error_hertz`, `half_width_error_hertz`, `p0_error_reference`,
/// `half_width_error_reference`): the peak pressure p₀ and the half-width a,
/// each against the closed form and against the fine-mesh reference, as
/// signed percentages. Declared once so that every chapter's columns and
/// headers agree.
pub const CONTACT_ERRORS: [Column; 4] = [
    Column::new(
        "p0_error_hertz",
        "p₀ vs Hertz",
        Unit::None,
        Format::SignedPercent(2),
    ),
    Column::new(
        "half_width_error_hertz",
        "a vs Hertz",
        Unit::None,
        Format::SignedPercent(2),
    ),
    Column::new(
        "p0_error_reference",
        "p₀ vs ref.",
        Unit::None,
        Format::SignedPercent(2),
    ),
    Column::new(
        "half_width_error_reference",
        "a vs ref.",
        Unit::None,
        Format::SignedPercent(2),
    ),
];

/// A table cell.
#[derive(Clone, Debug, PartialEq)]
pub enum Cell {
    Number(f64),
    Text(String),
    /// Nothing to report (a run that failed has no p₀).
    Empty,
}

impl From<f64> for Cell {
    fn from(v: f64) -> Self {
        Cell::Number(v)
    }
}

impl From<usize> for Cell {
    fn from(v: usize) -> Self {
        Cell::Number(v as f64)
    }
}

impl From<&str> for Cell {
    fn from(v: &str) -> Self {
        Cell::Text(v.to_string())
    }
}

impl From<String> for Cell {
    fn from(v: String) -> Self {
        Cell::Text(v)
    }
}

impl<T: Into<Cell>> From<Option<T>> for Cell {
    fn from(v: Option<T>) -> Self {
        v.map_or(Cell::Empty, Into::into)
    }
}

/// Columns and rows; see the module documentation.
#[derive(Clone, Debug, PartialEq)]
pub struct Table {
    columns: Vec<Column>,
    rows: Vec<Vec<Cell>>,
}

impl Table {
    pub fn new(columns: Vec<Column>) -> Self {
        Self {
            columns,
            rows: Vec::new(),
        }
    }

    pub fn columns(&self) -> &[Column] {
        &self.columns
    }

    pub fn rows(&self) -> &[Vec<Cell>] {
        &self.rows
    }

    /// Appends a row. Numbers must be finite: a NaN never reaches a file.
    pub fn push(&mut self, row: Vec<Cell>) -> Result<()> {
        if row.len() != self.columns.len() {
            return Err(Error::invalid(
                "table row",
                format!("{} cells", row.len()),
                format!("the table has {} columns", self.columns.len()),
            ));
        }
        for (c, cell) in self.columns.iter().zip(&row) {
            if let Cell::Number(v) = cell {
                if !v.is_finite() {
                    return Err(Error::invalid(c.key, v, "a table value must be finite"));
                }
            }
        }
        self.rows.push(row);
        Ok(())
    }

    /// The table as CSV: a header of keys, numbers in SI units at full
    /// precision, text quoted where needed.
    pub fn to_csv(&self) -> String {
        let in_csv = |c: &Column| c.place != Place::MarkdownOnly;
        let mut s = self
            .columns
            .iter()
            .filter(|c| in_csv(c))
            .map(|c| csv_field(c.key))
            .collect::<Vec<_>>()
            .join(",");
        s.push('\n');
        for row in &self.rows {
            let cells: Vec<String> = row
                .iter()
                .zip(&self.columns)
                .filter(|(_, c)| in_csv(c))
                .map(|(cell, _)| match cell {
                    Cell::Number(v) => csv_number(*v),
                    Cell::Text(t) => csv_field(t),
                    Cell::Empty => String::new(),
                })
                .collect();
            s.push_str(&cells.join(","));
            s.push('\n');
        }
        s
    }

    /// The table as Markdown, numbers in each column's format (columns
    /// marked [`Place::CsvOnly`] left out).
    pub fn to_markdown(&self) -> String {
        let shown = || {
            self.columns
                .iter()
                .enumerate()
                .filter(|(_, c)| c.place != Place::CsvOnly)
        };
        let mut s = String::from("|");
        for (_, c) in shown() {
            let _ = write!(s, " {} |", md_escape(&c.md_header()));
        }
        s.push_str("\n|");
        for _ in shown() {
            s.push_str("---|");
        }
        s.push('\n');
        for row in &self.rows {
            s.push('|');
            for (c, cell) in shown().map(|(k, c)| (c, &row[k])) {
                let text = match cell {
                    Cell::Number(v) => c.format.render(v * c.unit.scale()),
                    Cell::Text(t) => md_escape(t),
                    Cell::Empty => "–".to_string(),
                };
                let _ = write!(s, " {text} |");
            }
            s.push('\n');
        }
        s
    }

    /// The number in column `key` (CSV key without unit) of every row, in
    /// SI units; `None` where a cell is not a number.
    pub fn column(&self, key: &str) -> Option<Vec<Option<f64>>> {
        let k = self.columns.iter().position(|c| c.key == key)?;
        Some(
            self.rows
                .iter()
                .map(|r| match r[k] {
                    Cell::Number(v) => Some(v),
                    _ => None,
                })
                .collect(),
        )
    }
}

/// A number at full precision (the shortest representation that reads
/// back to the same double), never negative zero.
fn csv_number(v: f64) -> String {
    if v == 0.0 {
        "0".into()
    } else if v.fract() == 0.0 && v.abs() < 1e15 {
        format!("{}", v as i64)
    } else {
        format!("{v:e}")
    }
}

/// RFC 4180 quoting: a field with a comma, quote or line break is quoted,
/// quotes doubled.
pub fn csv_field(s: &str) -> String {
    if s.contains([',', '"', '\n', '\r']) {
        format!("\"{}\"", s.replace('"', "\"\""))
    } else {
        s.to_string()
    }
}

/// A pipe would end a Markdown cell; a line break would end the row.
fn md_escape(s: &str) -> String {
    s.replace('|', "\\|").replace(['\n', '\r'], " ")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn formats_render_as_the_book_writes_them() {
        assert_eq!(Format::Fixed(2).render(-1.234), "−1.23");
        assert_eq!(Format::Fixed(2).render(-0.001), "0.00");
        assert_eq!(Format::Sci(2).render(-0.0269), "−2.69e−2");
        assert_eq!(Format::Sci(1).render(-0.0), "0.0e0");
        assert_eq!(Format::Pow10(1).render(-0.00296), "−3.0×10⁻³");
        assert_eq!(Format::Pow10(0).render(1.2e15), "1×10¹⁵");
        assert_eq!(Format::Pow10(2).render(2.5), "2.50");
        assert_eq!(Format::Percent(2).render(0.0269), "2.69 %");
        assert_eq!(Format::SignedPercent(1).render(-0.0137), "−1.4 %");
        assert_eq!(Format::SignedPercent(1).render(0.0137), "+1.4 %");
        assert_eq!(Format::Times(1).render(3.125), "3.1×");
        assert_eq!(Format::Mesh.render(64.0), "64²");
        assert_eq!(Format::Plain.render(12.0), "12");
    }

    #[test]
    fn csv_and_markdown_from_one_declaration() {
        let mut t = Table::new(vec![
            Column::plain("solver", "solver"),
            Column::new("p0", "p₀", Unit::Megapascal, Format::Fixed(3)),
            Column::new("error", "error", Unit::None, Format::SignedPercent(2)),
        ]);
        t.push(vec!["a, \"b\"".into(), 2.29e6.into(), (-0.0137).into()])
            .unwrap();
        t.push(vec!["x|y".into(), Cell::Empty, 0.5.into()]).unwrap();
        let mut hidden = t.clone();
        hidden.columns[1] = hidden.columns[1].clone().csv_only();
        assert!(!hidden.to_markdown().contains("MPa"));
        assert_eq!(hidden.to_csv(), t.to_csv());
        let mut derived = t.clone();
        derived.columns[2] = derived.columns[2].clone().markdown_only();
        assert!(!derived.to_csv().contains("error"));
        assert!(
            derived.to_markdown().contains("−1.37 %"),
            "{}",
            derived.to_markdown()
        );
        assert_eq!(
            t.to_csv(),
            "solver,p0,error\n\"a, \"\"b\"\"\",2290000,-1.37e-2\nx|y,,5e-1\n"
        );
        let md = t.to_markdown();
        assert!(md.starts_with("| solver | p₀ (MPa) | error |\n|---|---|---|\n"));
        assert!(md.contains("| a, \"b\" | 2.290 | −1.37 % |"), "{md}");
        assert!(md.contains("| x\\|y | – | +50.00 % |"), "{md}");
        assert!(t
            .push(vec![f64::NAN.into(), 1.0.into(), 1.0.into()])
            .is_err());
        assert!(t.push(vec![1.0.into()]).is_err());
        assert_eq!(t.column("p0").unwrap(), vec![Some(2.29e6), None]);
    }
}
