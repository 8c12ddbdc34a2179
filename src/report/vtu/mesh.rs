//! The grid a VTU file holds: points, cells and point data, and the checks
//! that keep a reader from tripping over it.

use crate::error::{Error, Result};

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
}

#[cfg(test)]
pub(super) mod tests {
    use super::*;

    /// One unit quad with a scalar whose name needs escaping and whose
    /// values need every digit.
    pub(in crate::report::vtu) fn tiny() -> VtuMesh {
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
}
