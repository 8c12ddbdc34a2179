//! How a body's exact geometry is discretised (`refine = { ... }`).

use super::rules::in_range;
use super::{BodySpec, MAX_DEGREE, MAX_ELEMENTS, MAX_LAGRANGE};
use crate::error::{Error, Result};
use serde::{Deserialize, Serialize};

/// How the exact geometry is discretised: `degree` (k-refinement: elevate,
/// then split every knot span into `elements` parts) or `lagrange` (the
/// isoparametric FEM interpolant of that degree on `elements` spans).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RefineSpec {
    #[serde(default)]
    pub degree: Option<usize>,
    pub elements: [usize; 2],
    #[serde(default)]
    pub lagrange: Option<usize>,
}

impl RefineSpec {
    /// k-refinement: elevate to `degree`, split into `elements` spans.
    pub fn iga(degree: usize, elements: [usize; 2]) -> Self {
        Self {
            degree: Some(degree),
            elements,
            lagrange: None,
        }
    }

    /// The isoparametric Lagrange (FEM) interpolant of `degree`.
    pub fn lagrange(degree: usize, elements: [usize; 2]) -> Self {
        Self {
            degree: None,
            elements,
            lagrange: Some(degree),
        }
    }

    /// `IGA p = 2`, `FEM Q1`, ...
    pub fn label(&self) -> String {
        match (self.degree, self.lagrange) {
            (_, Some(q)) => format!("FEM Q{q}"),
            (Some(p), None) => format!("IGA p = {p}"),
            (None, None) => "geometry as given".into(),
        }
    }

    pub(super) fn validate(&self, f: &str, geometry_degree: usize) -> Result<()> {
        for (d, &n) in self.elements.iter().enumerate() {
            in_range(format!("{f}.elements[{d}]"), n, 1, MAX_ELEMENTS)?;
        }
        match (self.degree, self.lagrange) {
            (Some(p), None) => {
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
            (None, Some(q)) => in_range(format!("{f}.lagrange"), q, 1, MAX_LAGRANGE)?,
            (Some(p), Some(_)) => {
                return Err(Error::invalid(
                    format!("{f}.degree"),
                    p,
                    "give either `degree` (k-refinement) or `lagrange` (FEM interpolant), not both",
                ))
            }
            (None, None) => {
                return Err(Error::invalid(
                    f,
                    format!("elements = {:?}", self.elements),
                    "needs `degree` (k-refinement) or `lagrange` (FEM interpolant)",
                ))
            }
        }
        Ok(())
    }
}

impl BodySpec {
    /// The degree of the discretised body (the larger of its two directions).
    pub(super) fn degree(&self) -> usize {
        match &self.refine {
            Some(RefineSpec {
                degree: Some(p), ..
            }) => (*p).max(self.geometry.degree()),
            Some(RefineSpec {
                lagrange: Some(q), ..
            }) => *q,
            _ => self.geometry.degree(),
        }
    }
}
