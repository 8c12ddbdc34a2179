//! The discretised patches of a body: its exact geometry, refined as its
//! `refine` table says, with the errors of the geometry layer retold in the
//! scene's key paths.

use super::{RefineSpec, Scene};
use crate::error::{Error, GeometryError, Result};
use crate::geometry;
use crate::nurbs::NurbsPatch;

/// The interpolant is built for one patch; a body of several is refused
/// (by validation, and here for a scene changed since).
pub(super) fn multipatch_lagrange(i: usize, degree: usize) -> Error {
    Error::invalid(
        format!("body[{i}].refine.lagrange"),
        degree,
        "a body of several patches is refined by `degree` only",
    )
}

/// An error of the geometry layer, retold with the scene key path of body
/// `i` (`geometry` the path of its geometry table): library field names
/// such as `radius` or `patch.control_points[0]` are not scene keys.
pub(super) fn in_body(e: Error, i: usize, name: &str, geometry: &str) -> Error {
    match e {
        Error::InvalidInput {
            field,
            value,
            reason,
        } => {
            let key = field.split(['.', '[']).next().unwrap_or("");
            let scene_key = matches!(
                key,
                "x0" | "y0" | "x1" | "y1" | "center" | "radius" | "inner_radius" | "outer_radius"
            );
            let field = if scene_key {
                format!("{geometry}.{field}")
            } else {
                format!("body[{i}].geometry")
            };
            Error::invalid(field, value, format!("{reason} (body {name:?})"))
        }
        other => other.map_geometry(|cause| GeometryError::Body {
            index: i,
            name: name.to_string(),
            cause: Box::new(cause),
        }),
    }
}

/// An error of discretising body `i` (named `name`, geometry kind `kind`):
/// a map that folds or degenerates at a quadrature point is a fault of the
/// scene's geometry, so an invalid input naming `body[i].geometry`, not a
/// failure of the run; anything else as [`in_body`] retells it.
pub(super) fn discretise_error(e: Error, i: usize, name: &str, kind: &str) -> Error {
    match e {
        Error::Geometry(g) if g.is_map_fault() => Error::invalid(
            format!("body[{i}].geometry"),
            kind,
            format!(
                "{g} (body {name:?}): the map must be invertible at every quadrature point; move the control \
                 points (or corners) so that it does not fold"
            ),
        ),
        other => in_body(other, i, name, ""),
    }
}

impl Scene {
    /// The exact patch of body `i`, errors naming the body.
    pub(super) fn exact_patch(&self, i: usize) -> Result<NurbsPatch> {
        let b = &self.bodies[i];
        let f = format!("body[{i}].geometry");
        b.geometry
            .patch(&f)
            .map_err(|e| in_body(e, i, &b.name, &format!("{f}.{}", b.geometry.kind())))
    }

    /// The discretised patch of body `i`.
    fn body_patch(&self, i: usize) -> Result<NurbsPatch> {
        let b = &self.bodies[i];
        let exact = self.exact_patch(i)?;
        let refined = match b.refine {
            None => Ok(exact),
            Some(RefineSpec::KRefine { degree, elements }) => exact.k_refined(degree, elements),
            Some(RefineSpec::Lagrange { degree, elements }) => {
                geometry::lagrange_interpolant(&exact, degree, elements)
            }
        };
        refined.map_err(|e| match e {
            Error::InvalidInput { value, reason, .. } => Error::invalid(
                format!("body[{i}].refine"),
                value,
                format!("{reason} (in the refined patch of body {:?})", b.name),
            ),
            other => in_body(other, i, &b.name, ""),
        })
    }

    /// The discretised patches of body `i`: one for the one-patch kinds;
    /// for a multi-patch kind each refined with its share of `elements`
    /// ([`geometry::MultiPatch::refined`]).
    pub(super) fn body_patches(&self, i: usize) -> Result<Vec<NurbsPatch>> {
        let b = &self.bodies[i];
        let Some(mp) = b.geometry.multipatch() else {
            return Ok(vec![self.body_patch(i)?]);
        };
        let f = format!("body[{i}].geometry.{}", b.geometry.kind());
        let mp = mp.map_err(|e| in_body(e, i, &b.name, &f))?;
        match b.refine {
            None => Ok(mp.patches),
            Some(RefineSpec::KRefine { degree, elements }) => {
                mp.refined(degree, elements).map_err(|e| match e {
                    Error::InvalidInput { value, reason, .. } => Error::invalid(
                        format!("body[{i}].refine"),
                        value,
                        format!("{reason} (in the refined patches of body {:?})", b.name),
                    ),
                    other => in_body(other, i, &b.name, ""),
                })
            }
            Some(RefineSpec::Lagrange { degree, .. }) => Err(multipatch_lagrange(i, degree)),
        }
    }
}
