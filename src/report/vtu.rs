//! VTU (VTK XML UnstructuredGrid) output of displacement and stress fields.
//!
//! The writer is hand-written rather than taken from a crate: the format
//! needed here is a few dozen lines of XML, the available crates are stale,
//! and owning it lets us pin the details that readers are picky about
//! (Int64 connectivity and offsets, which meshio with numpy 2 needs).
//!
//! The files are ASCII with shortest round-trip floats, so they are
//! diffable, and a reader recovers every value bit for bit; the companion
//! script `scripts/check_vtu.py` checks exactly that against a
//! `NAME.expected.json` sidecar ([`VtuMesh::expected_json`]).
//!
//! NURBS elements are not VTK cells: [`sample_bodies`] evaluates the exact
//! fields on a grid inside every element and emits linear quads, which every
//! reader understands and which resolve the field as finely as asked.

use crate::assembly::{displacement_at, ElementStress};
use crate::dofs::{Body, DofMap};
use crate::error::{Error, GeometryError, Result};
use crate::material::Formulation;
use crate::pressure::SplinePressure;
use crate::space::{Element, Shape, Space};
use std::fmt::Write as _;
use std::path::Path;
use std::sync::Arc;

/// VTK cell type of the linear quadrilateral.
pub const VTK_QUAD: u8 = 9;

/// One array of values attached to the points, `components` per point
/// (1 for scalars, 3 for vectors: VTK readers only treat 3-component
/// arrays as vectors, so 2D vectors are padded with z = 0).
#[derive(Clone, Debug, PartialEq)]
pub struct PointField {
    pub name: String,
    pub components: usize,
    /// Point-major: the components of point 0, then of point 1, ...
    pub values: Vec<f64>,
}

/// An unstructured grid as VTK sees it: points, cells given by point
/// indices and a VTK cell type each, and point data.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct VtuMesh {
    pub points: Vec<[f64; 3]>,
    pub cells: Vec<Vec<i64>>,
    pub cell_types: Vec<u8>,
    pub point_data: Vec<PointField>,
}

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
    pub fn n_points(&self) -> usize {
        self.points.len()
    }

    pub fn n_cells(&self) -> usize {
        self.cells.len()
    }

    /// The point-data array called `name`, if any.
    pub fn field(&self, name: &str) -> Option<&PointField> {
        self.point_data.iter().find(|f| f.name == name)
    }

    /// Checks everything a reader would otherwise trip over later, or worse
    /// silently misread: non-finite numbers (a NaN in a plot file hides the
    /// solver failure that produced it), dangling point indices, and arrays
    /// whose lengths disagree with the number of points.
    pub fn validate(&self) -> Result<()> {
        let np = self.points.len();
        for (i, p) in self.points.iter().enumerate() {
            for (c, &v) in p.iter().enumerate() {
                if !v.is_finite() {
                    return Err(Error::invalid(
                        format!("vtu.points[{i}][{c}]"),
                        v,
                        "must be a finite number",
                    ));
                }
            }
        }
        if self.cell_types.len() != self.cells.len() {
            return Err(Error::invalid(
                "vtu.cell_types",
                format!("{} entries", self.cell_types.len()),
                format!("there are {} cells", self.cells.len()),
            ));
        }
        for (k, cell) in self.cells.iter().enumerate() {
            if cell.is_empty() {
                return Err(Error::invalid(
                    format!("vtu.cells[{k}]"),
                    "[]",
                    "a cell needs at least one point",
                ));
            }
            for &p in cell {
                if p < 0 || p as u64 >= np as u64 {
                    return Err(Error::invalid(
                        format!("vtu.cells[{k}]"),
                        p,
                        format!("point index out of range 0..{np}"),
                    ));
                }
            }
        }
        for (j, f) in self.point_data.iter().enumerate() {
            if f.name.trim().is_empty() {
                return Err(Error::invalid(
                    format!("vtu.point_data[{j}].name"),
                    format!("{:?}", f.name),
                    "must not be empty",
                ));
            }
            if self.point_data[..j].iter().any(|g| g.name == f.name) {
                return Err(Error::invalid(
                    format!("vtu.point_data[{j}].name"),
                    &f.name,
                    "is used twice; readers keep only one of the arrays",
                ));
            }
            if f.components != 1 && f.components != 3 {
                return Err(Error::invalid(
                    format!("vtu.point_data.{}.components", f.name),
                    f.components,
                    "must be 1 (scalar) or 3 (vector)",
                ));
            }
            if f.values.len() != f.components * np {
                return Err(Error::invalid(
                    format!("vtu.point_data.{}.values", f.name),
                    format!("{} values", f.values.len()),
                    format!("expected {} × {np} points", f.components),
                ));
            }
            if let Some(i) = f.values.iter().position(|v| !v.is_finite()) {
                return Err(Error::invalid(
                    format!("vtu.point_data.{}[{i}]", f.name),
                    f.values[i],
                    "must be a finite number",
                ));
            }
        }
        Ok(())
    }

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

/// Relative inward nudges tried, in order, where the geometric map is
/// singular. A nudge δ trades two errors: the point moves by δ·h, and the
/// gradients, divided by det J ∝ δ, lose about 1e-15/δ relative accuracy
/// (measured at the half-disk corners: gradients 1e-7 off for δ = 1e-8,
/// 1e-9 for δ = 1e-6; the stress of an affine field with a rigid
/// translation, 1.4e-8 for δ = 1e-6). Stress values are what people read
/// off a plot while a shift of 1e-6 element sizes is invisible, so the
/// first nudge favours the stress.
/// The larger step is a fallback for maps that degenerate more steeply.
const NUDGES: [f64; 2] = [1e-6, 1e-4];

/// A det J this much smaller than at the element centre counts as singular
/// even though it is positive: at the corners of the nine-point disk
/// rounding leaves det J ≈ 1e-15 of the centre value instead of 0, so
/// [`Space::shape`] succeeds but its gradients are noise. The first nudge
/// gives a ratio of about 2e-6, safely above.
const SINGULAR_RATIO: f64 = 1e-8;

/// Shape functions at (ξ, η), moved slightly towards the element centre
/// where the map is singular (the disk corners), so that one degenerate
/// point does not prevent viewing a whole solution.
fn sample_shape(space: &Space, e: &Element, xi: f64, eta: f64, det_ref: f64) -> Result<Shape> {
    let ok = |s: &Shape| s.det_j >= SINGULAR_RATIO * det_ref;
    let first = space.shape(e, xi, eta);
    if let Ok(s) = &first {
        if ok(s) {
            return first;
        }
    }
    let c = [
        0.5 * (e.range[0][0] + e.range[0][1]),
        0.5 * (e.range[1][0] + e.range[1][1]),
    ];
    for d in NUDGES {
        // Scaling about the centre by (1 − 2δ) moves a corner by δ·h in
        // each direction and keeps the point inside the element.
        let x = c[0] + (1.0 - 2.0 * d) * (xi - c[0]);
        let y = c[1] + (1.0 - 2.0 * d) * (eta - c[1]);
        if let Ok(s) = space.shape(e, x, y) {
            if ok(&s) {
                return Ok(s);
            }
        }
    }
    match first {
        Ok(s) => Err(GeometryError::NearlySingular {
            xi,
            eta,
            det_j: s.det_j,
            centre: det_ref,
        }
        .into()),
        Err(e) => Err(e),
    }
}

/// von Mises stress including σ_zz, which plane strain makes non-zero:
/// leaving it out would understate the equivalent stress.
fn von_mises(s: [f64; 3], szz: f64) -> f64 {
    let [sxx, syy, sxy] = s;
    (0.5 * ((sxx - syy).powi(2) + (syy - szz).powi(2) + (szz - sxx).powi(2)) + 3.0 * sxy * sxy)
        .sqrt()
}

/// Samples every element of every body on a (`subdivisions` + 1)² grid of
/// parametric points and returns linear quads carrying the exact NURBS
/// fields at their corners: "displacement" (x, y, 0), "stress" (σxx, σyy,
/// σxy), "von_mises" and "body" (the body index).
///
/// Points are the undeformed positions (warp by "displacement" to see the
/// deformed shape). They are not shared between elements: stress is
/// discontinuous across C⁰ element edges, and duplicating points keeps each
/// element's own values instead of an arbitrary one.
pub fn sample_bodies(
    bodies: &[Body],
    map: &DofMap,
    u_full: &[f64],
    subdivisions: usize,
) -> Result<VtuMesh> {
    if subdivisions == 0 {
        return Err(Error::invalid("vtu.subdivisions", 0, "must be at least 1"));
    }
    if u_full.len() != map.n_total() {
        return Err(Error::invalid(
            "vtu.displacement",
            format!("{} values", u_full.len()),
            format!("the DOF map has {} DOFs", map.n_total()),
        ));
    }
    let n_dofs: usize = bodies.iter().map(|b| 2 * b.space.n_cp()).sum();
    if n_dofs != map.n_total() {
        return Err(Error::invalid(
            "vtu.bodies",
            format!("{} bodies with {n_dofs} DOFs", bodies.len()),
            format!("the DOF map has {} DOFs", map.n_total()),
        ));
    }
    if let Some(g) = u_full.iter().position(|v| !v.is_finite()) {
        return Err(Error::invalid(
            format!("vtu.displacement[{g}]"),
            u_full[g],
            "must be a finite number",
        ));
    }

    let s = subdivisions;
    let per_el = (s + 1) * (s + 1);
    let n_el: usize = bodies.iter().map(|b| b.space.elements.len()).sum();
    let np = n_el * per_el;
    let mut mesh = VtuMesh {
        points: Vec::with_capacity(np),
        cells: Vec::with_capacity(n_el * s * s),
        cell_types: Vec::with_capacity(n_el * s * s),
        point_data: Vec::new(),
    };
    let mut disp = Vec::with_capacity(3 * np);
    let mut stress = Vec::with_capacity(3 * np);
    let mut vm = Vec::with_capacity(np);
    let mut body_id = Vec::with_capacity(np);

    for (bi, body) in bodies.iter().enumerate() {
        let space = &body.space;
        // the stress of the body's formulation (mixed: one pressure space
        // per body, shared by its elements)
        let pressure = match body.formulation {
            Formulation::Mixed => Some(Arc::new(SplinePressure::new(body)?)),
            _ => None,
        };
        for (ei, e) in space.elements.iter().enumerate() {
            let stress_of = ElementStress::with_pressure(body, ei, pressure.as_ref())?;
            let [[xa, xb], [ya, yb]] = e.range;
            let det_ref = space
                .shape(e, 0.5 * (xa + xb), 0.5 * (ya + yb))
                .map_err(|err| {
                    err.map_geometry(|cause| GeometryError::Element {
                        body: body.name.clone(),
                        spans: e.spans,
                        cause: Box::new(cause),
                    })
                })?
                .det_j;
            let base = mesh.points.len() as i64;
            for j in 0..=s {
                // Exact end values, so neighbouring elements meet exactly.
                let eta = if j == s {
                    yb
                } else {
                    ya + (yb - ya) * j as f64 / s as f64
                };
                for i in 0..=s {
                    let xi = if i == s {
                        xb
                    } else {
                        xa + (xb - xa) * i as f64 / s as f64
                    };
                    let shape = sample_shape(space, e, xi, eta, det_ref).map_err(|err| {
                        err.map_geometry(|cause| GeometryError::Sample {
                            body: body.name.clone(),
                            cause: Box::new(cause),
                        })
                    })?;
                    let u = displacement_at(map, u_full, bi, &e.cps, &shape);
                    let (sig, szz) = stress_of.stress(map, u_full, bi, &shape, xi, eta);
                    mesh.points.push([shape.x[0], shape.x[1], 0.0]);
                    disp.extend([u[0], u[1], 0.0]);
                    stress.extend(sig);
                    vm.push(von_mises(sig, szz));
                    body_id.push(bi as f64);
                }
            }
            let w = (s + 1) as i64;
            for j in 0..s as i64 {
                for i in 0..s as i64 {
                    let p = base + i + j * w;
                    mesh.cells.push(vec![p, p + 1, p + 1 + w, p + w]);
                    mesh.cell_types.push(VTK_QUAD);
                }
            }
        }
    }
    mesh.point_data = vec![
        PointField {
            name: "displacement".into(),
            components: 3,
            values: disp,
        },
        PointField {
            name: "stress".into(),
            components: 3,
            values: stress,
        },
        PointField {
            name: "von_mises".into(),
            components: 1,
            values: vm,
        },
        PointField {
            name: "body".into(),
            components: 1,
            values: body_id,
        },
    ];
    // Finite inputs can still give non-finite outputs (an overflowing
    // displacement): catch it here, naming the field, not at write time.
    mesh.validate()?;
    Ok(mesh)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn tiny() -> VtuMesh {
        VtuMesh {
            points: vec![
                [0.0, 0.0, 0.0],
                [1.0, 0.0, 0.0],
                [1.0, 1.0, 0.0],
                [0.0, 1.0, 0.0],
            ],
            cells: vec![vec![0, 1, 2, 3]],
            cell_types: vec![VTK_QUAD],
            point_data: vec![PointField {
                name: "a\"b".into(),
                components: 1,
                values: vec![0.1, 1e-300, -2.5e17, 1.0 / 3.0],
            }],
        }
    }

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

    #[test]
    fn validation_names_the_offending_field() {
        let mut m = tiny();
        m.point_data[0].values[2] = f64::INFINITY;
        let err = m.validate().unwrap_err().to_string();
        assert!(err.contains("vtu.point_data.a\"b[2]"), "{err}");
        let mut m = tiny();
        m.cells[0][3] = 4;
        assert!(m.validate().unwrap_err().to_string().contains("cells[0]"));
        let mut m = tiny();
        m.point_data[0].components = 2;
        assert!(m.validate().is_err());
    }

    #[test]
    fn von_mises_of_pure_shear_and_hydrostatic_state() {
        assert!((von_mises([0.0, 0.0, 1.0], 0.0) - 3f64.sqrt()).abs() < 1e-15);
        assert_eq!(von_mises([2.0, 2.0, 0.0], 2.0), 0.0);
    }
}
