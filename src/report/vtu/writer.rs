//! The VTU file itself (ASCII XML) and its `NAME.expected.json` sidecar:
//! shortest round-trip floats, escaped names, Int64 connectivity.

use super::mesh::VtuMesh;
use crate::error::Result;
use std::fmt::Write as _;
use std::path::Path;

/// Appends `v` with the shortest digits that parse back to the same f64, so
/// the file is exact without the noise of 17 fixed digits.
fn push_f64(out: &mut String, v: f64) {
    // + 0.0 turns −0 into +0: no output shows a negative zero.
    let _ = write!(out, "{:?}", v + 0.0);
}

/// Field names end up in XML attributes and JSON strings; escaping here
/// keeps a name with a quote or ampersand from corrupting the file.
fn xml_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '&' => out.push_str("&amp;"),
            '<' => out.push_str("&lt;"),
            '>' => out.push_str("&gt;"),
            '"' => out.push_str("&quot;"),
            '\'' => out.push_str("&apos;"),
            // In an attribute, white space would be normalised away.
            '\t' | '\n' | '\r' => {
                let _ = write!(out, "&#{};", c as u32);
            }
            c if !crate::report::xml::xml_char_allowed(c) => out.push('\u{FFFD}'),
            c => out.push(c),
        }
    }
    out
}

fn json_escape(s: &str) -> String {
    let mut out = String::with_capacity(s.len());
    for c in s.chars() {
        match c {
            '"' => out.push_str("\\\""),
            '\\' => out.push_str("\\\\"),
            c if (c as u32) < 0x20 => {
                let _ = write!(out, "\\u{:04x}", c as u32);
            }
            c => out.push(c),
        }
    }
    out
}

/// Writes a list of floats, a fixed number per line, so that a large file
/// stays readable in an editor and diffs locally.
fn push_float_lines(out: &mut String, values: impl IntoIterator<Item = f64>, per_line: usize) {
    for (k, v) in values.into_iter().enumerate() {
        if k % per_line == 0 {
            out.push_str("          ");
        } else {
            out.push(' ');
        }
        push_f64(out, v);
        if k % per_line == per_line - 1 {
            out.push('\n');
        }
    }
    if !out.ends_with('\n') {
        out.push('\n');
    }
}

fn push_int_lines<T: std::fmt::Display>(
    out: &mut String,
    values: impl IntoIterator<Item = T>,
    per_line: usize,
) {
    for (k, v) in values.into_iter().enumerate() {
        if k % per_line == 0 {
            out.push_str("          ");
        } else {
            out.push(' ');
        }
        let _ = write!(out, "{v}");
        if k % per_line == per_line - 1 {
            out.push('\n');
        }
    }
    if !out.ends_with('\n') {
        out.push('\n');
    }
}

impl VtuMesh {
    /// The file contents. Does not validate: a NaN is printed as `NaN`,
    /// which is why [`VtuMesh::write`] validates first.
    pub fn to_xml(&self) -> String {
        let np = self.points.len();
        let nc = self.cells.len();
        let mut s = String::with_capacity(64 * np + 32 * nc + 512);
        s.push_str("<?xml version=\"1.0\"?>\n");
        s.push_str(
            "<VTKFile type=\"UnstructuredGrid\" version=\"1.0\" \
             byte_order=\"LittleEndian\" header_type=\"UInt64\">\n",
        );
        s.push_str("  <UnstructuredGrid>\n");
        let _ = writeln!(
            s,
            "    <Piece NumberOfPoints=\"{np}\" NumberOfCells=\"{nc}\">"
        );
        s.push_str("      <PointData>\n");
        for f in &self.point_data {
            let _ = writeln!(
                s,
                "        <DataArray type=\"Float64\" Name=\"{}\" NumberOfComponents=\"{}\" format=\"ascii\">",
                xml_escape(&f.name),
                f.components
            );
            push_float_lines(&mut s, f.values.iter().copied(), 3 * f.components.max(1));
            s.push_str("        </DataArray>\n");
        }
        s.push_str("      </PointData>\n");
        s.push_str("      <Points>\n");
        s.push_str(
            "        <DataArray type=\"Float64\" Name=\"Points\" NumberOfComponents=\"3\" format=\"ascii\">\n",
        );
        push_float_lines(&mut s, self.points.iter().flatten().copied(), 3);
        s.push_str("        </DataArray>\n");
        s.push_str("      </Points>\n");
        s.push_str("      <Cells>\n");
        s.push_str("        <DataArray type=\"Int64\" Name=\"connectivity\" format=\"ascii\">\n");
        for cell in &self.cells {
            s.push_str("          ");
            for (k, p) in cell.iter().enumerate() {
                if k > 0 {
                    s.push(' ');
                }
                let _ = write!(s, "{p}");
            }
            s.push('\n');
        }
        if self.cells.is_empty() {
            s.push('\n');
        }
        s.push_str("        </DataArray>\n");
        s.push_str("        <DataArray type=\"Int64\" Name=\"offsets\" format=\"ascii\">\n");
        let offsets = self.cells.iter().scan(0i64, |acc, c| {
            *acc += c.len() as i64;
            Some(*acc)
        });
        push_int_lines(&mut s, offsets, 10);
        s.push_str("        </DataArray>\n");
        s.push_str("        <DataArray type=\"UInt8\" Name=\"types\" format=\"ascii\">\n");
        push_int_lines(&mut s, self.cell_types.iter().copied(), 20);
        s.push_str("        </DataArray>\n");
        s.push_str("      </Cells>\n");
        s.push_str("    </Piece>\n");
        s.push_str("  </UnstructuredGrid>\n");
        s.push_str("</VTKFile>\n");
        s
    }

    /// Validates, then writes atomically: a rejected or failed write leaves
    /// any previous file at `path` untouched and creates none.
    pub fn write(&self, path: impl AsRef<Path>) -> Result<()> {
        self.validate()?;
        crate::report::atomic::write_text(path, &self.to_xml())
    }

    /// The sidecar `NAME.expected.json` that `scripts/check_vtu.py` compares
    /// a VTU against: the same numbers in a second, independent encoding, so
    /// a formatting regression in either the writer or a reader shows up as
    /// a mismatch instead of a subtly wrong picture.
    pub fn expected_json(&self) -> Result<String> {
        self.validate()?;
        let mut s = String::with_capacity(64 * self.points.len() + 64);
        s.push_str("{\n  \"points\": [");
        for (i, p) in self.points.iter().enumerate() {
            if i > 0 {
                s.push(',');
            }
            s.push_str("\n    [");
            for (c, &v) in p.iter().enumerate() {
                if c > 0 {
                    s.push_str(", ");
                }
                push_f64(&mut s, v);
            }
            s.push(']');
        }
        s.push_str("\n  ],\n  \"point_data\": {");
        for (j, f) in self.point_data.iter().enumerate() {
            if j > 0 {
                s.push(',');
            }
            let _ = write!(s, "\n    \"{}\": [", json_escape(&f.name));
            for (k, &v) in f.values.iter().enumerate() {
                if k > 0 {
                    s.push_str(", ");
                }
                push_f64(&mut s, v);
            }
            s.push(']');
        }
        s.push_str("\n  }\n}\n");
        Ok(s)
    }
}

#[cfg(test)]
mod tests {
    use super::super::mesh::tests::tiny;

    #[test]
    fn floats_round_trip_through_the_text() {
        let xml = tiny().to_xml();
        for v in [0.1, 1e-300, -2.5e17, 1.0 / 3.0] {
            let text = format!("{v:?}");
            assert!(xml.contains(&text), "{text} missing");
            assert_eq!(text.parse::<f64>().unwrap(), v);
        }
        assert!(xml.contains("Name=\"a&quot;b\""));
        assert!(tiny().expected_json().unwrap().contains("\"a\\\"b\""));
    }
}
