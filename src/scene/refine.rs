//! How a body's exact geometry is discretised (`refine = { ... }`).
//!
//! The table has `elements` and exactly one of `degree` and `lagrange`;
//! which one it has is read into the variant of [`RefineSpec`] when the
//! scene is parsed, so nothing downstream asks again.

use super::parse::TableError;
use super::rules::in_range;
use super::{BodySpec, MAX_DEGREE, MAX_ELEMENTS, MAX_LAGRANGE};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// How the exact geometry is discretised: `degree` (k-refinement: elevate,
/// then split every knot span into `elements` parts) or `lagrange` (the
/// isoparametric FEM interpolant of that degree on `elements` spans).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawRefine", into = "RawRefine")]
pub enum RefineSpec {
    /// `{ degree = p, elements = [n, m] }`: elevate to p, then split.
    KRefine { degree: usize, elements: [usize; 2] },
    /// `{ lagrange = q, elements = [n, m] }`: the Lagrange interpolant of
    /// degree q.
    Lagrange { degree: usize, elements: [usize; 2] },
}

/// The `refine` table as written, before the choice of key is read.
#[derive(Clone, Serialize, Deserialize)]
// type errors name the type it reads into, as they did before it existed
#[serde(deny_unknown_fields, expecting = "struct RefineSpec")]
struct RawRefine {
    #[serde(default)]
    degree: Option<usize>,
    elements: [usize; 2],
    #[serde(default)]
    lagrange: Option<usize>,
}

impl TryFrom<RawRefine> for RefineSpec {
    type Error = TableError;

    fn try_from(r: RawRefine) -> std::result::Result<Self, TableError> {
        let elements = r.elements;
        match (r.degree, r.lagrange) {
            (Some(degree), None) => Ok(RefineSpec::KRefine { degree, elements }),
            (None, Some(degree)) => Ok(RefineSpec::Lagrange { degree, elements }),
            (Some(p), Some(_)) => Err(TableError::new(
                "degree",
                p,
                "give either `degree` (k-refinement) or `lagrange` (FEM interpolant), not both",
            )),
            (None, None) => Err(TableError::new(
                "",
                format!("elements = {elements:?}"),
                "needs `degree` (k-refinement) or `lagrange` (FEM interpolant)",
            )),
        }
    }
}

impl From<RefineSpec> for RawRefine {
    fn from(r: RefineSpec) -> Self {
        match r {
            RefineSpec::KRefine { degree, elements } => RawRefine {
                degree: Some(degree),
                elements,
                lagrange: None,
            },
            RefineSpec::Lagrange { degree, elements } => RawRefine {
                degree: None,
                elements,
                lagrange: Some(degree),
            },
        }
    }
}

impl RefineSpec {
    /// k-refinement: elevate to `degree`, split into `elements` spans.
    pub fn iga(degree: usize, elements: [usize; 2]) -> Self {
        RefineSpec::KRefine { degree, elements }
    }

    /// The isoparametric Lagrange (FEM) interpolant of `degree`.
    pub fn lagrange(degree: usize, elements: [usize; 2]) -> Self {
        RefineSpec::Lagrange { degree, elements }
    }

    /// Elements per direction (per knot span of the exact geometry for
    /// k-refinement).
    pub fn elements(&self) -> [usize; 2] {
        match *self {
            RefineSpec::KRefine { elements, .. } | RefineSpec::Lagrange { elements, .. } => {
                elements
            }
        }
    }

    /// The degree asked for: the k-refinement's or the interpolant's.
    pub fn degree(&self) -> usize {
        match *self {
            RefineSpec::KRefine { degree, .. } | RefineSpec::Lagrange { degree, .. } => degree,
        }
    }

    /// `IGA p = 2`, `FEM Q1`, ...
    pub fn label(&self) -> String {
        match self {
            RefineSpec::KRefine { degree, .. } => format!("IGA p = {degree}"),
            RefineSpec::Lagrange { degree, .. } => format!("FEM Q{degree}"),
        }
    }

    /// Checks the numbers; `f` is the path of the `refine` table.
    pub(super) fn validate(&self, f: &str, geometry_degree: usize) -> Result<()> {
        for (d, &n) in self.elements().iter().enumerate() {
            in_range(format!("{f}.elements[{d}]"), n, 1, MAX_ELEMENTS)?;
        }
        match *self {
            RefineSpec::KRefine { degree: p, .. } => {
                in_range(format!("{f}.degree"), p, 1, MAX_DEGREE)?;
                if p < geometry_degree {
                    return Err(Error::invalid(
                        format!("{f}.degree"),
                        p,
                        format!(
                            "below the geometry's degree {geometry_degree}: k-refinement only \
                             elevates (use `lagrange` for a low-order FEM mesh)"
                        ),
                    ));
                }
            }
            RefineSpec::Lagrange { degree: q, .. } => {
                in_range(format!("{f}.lagrange"), q, 1, MAX_LAGRANGE)?
            }
        }
        Ok(())
    }
}

impl BodySpec {
    /// The degree of the discretised body (the larger of its two directions).
    pub(super) fn degree(&self) -> usize {
        match self.refine {
            Some(RefineSpec::KRefine { degree, .. }) => degree.max(self.geometry.degree()),
            Some(RefineSpec::Lagrange { degree, .. }) => degree,
            None => self.geometry.degree(),
        }
    }
}
