//! The exact geometry of a body: its scene table, the checks of its
//! parameters, and the patch (or patches) it describes.

use super::rules::{finite, finite_point, in_range, positive, show};
use super::MAX_DEGREE;
use crate::error::{Error, Result};
use crate::geometry;
use crate::nurbs::{KnotVector, NurbsPatch};
use serde::{Deserialize, Serialize};

/// The exact geometry of a body, one of the builders of [`crate::geometry`]
/// or a general NURBS patch. Written as a table with one key, the kind:
/// `geometry = { half_disk = { center = [0.0, 0.2], radius = 0.2 } }`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case", deny_unknown_fields)]
pub enum GeometrySpec {
    /// [x0, x1] × [y0, y1], bilinear.
    Rectangle { x0: f64, y0: f64, x1: f64, y1: f64 },
    /// A convex bilinear quadrilateral, corners counter-clockwise.
    Quadrilateral { corners: [[f64; 2]; 4] },
    /// The nine-point quadratic disk.
    FullDisk { center: [f64; 2], radius: f64 },
    /// The half x ≥ center.x of the disk.
    HalfDisk { center: [f64; 2], radius: f64 },
    /// The disk as five patches without a singular point: with
    /// `layout = "axes"` (the default) the core's sides face the axes
    /// ([`geometry::disk_5`]; boundaries `arc`, `arc_bottom`, `arc_right`,
    /// `arc_top`, `arc_left`, `arc_lower`); with `"diagonal"` its corners
    /// do, so that patch corners lie on the vertical centre line
    /// ([`geometry::disk_5_diagonal`]; boundaries `arc`, `arc_lower`,
    /// `arc_upper`, `arc_right`, `arc_left`).
    #[serde(rename = "disk_5")]
    Disk5 {
        center: [f64; 2],
        radius: f64,
        #[serde(default)]
        layout: DiskLayout,
    },
    /// The half x ≥ center.x of the disk as four patches without a
    /// singular point ([`geometry::half_disk_4`]); boundaries `straight`,
    /// `arc`, `arc_lower`, `arc_bottom`.
    #[serde(rename = "half_disk_4")]
    HalfDisk4 { center: [f64; 2], radius: f64 },
    /// The quarter annulus in the first quadrant about the origin.
    QuarterAnnulus {
        inner_radius: f64,
        outer_radius: f64,
    },
    /// The half x ≥ center.x of the annulus inner_radius ≤ |x − center| ≤
    /// outer_radius, one patch ([`geometry::half_annulus`]): sides `eta_min`
    /// (inner arc), `eta_max` (outer arc), `xi_min` (lower cut on
    /// x = center.x), `xi_max` (upper cut).
    HalfAnnulus {
        center: [f64; 2],
        inner_radius: f64,
        outer_radius: f64,
    },
    /// A general patch: control point (i, j) at index i + j·n_ξ.
    Nurbs(NurbsSpec),
}

/// How the five patches of `disk_5` sit.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum DiskLayout {
    /// The core's sides face the axes: arc patches centred below, right,
    /// above and left of the centre.
    #[default]
    Axes,
    /// The core's corners face the axes: the arc patches are the quadrants.
    Diagonal,
}

/// A general NURBS patch.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct NurbsSpec {
    /// [p, q]: degrees in ξ and η.
    pub degree: [usize; 2],
    pub knots_xi: Vec<f64>,
    pub knots_eta: Vec<f64>,
    /// n_ξ · n_η points, ξ index fastest.
    pub control_points: Vec<[f64; 2]>,
    /// One positive weight per control point; absent: all 1 (a B-spline).
    #[serde(default)]
    pub weights: Option<Vec<f64>>,
}

fn cross(o: [f64; 2], a: [f64; 2], b: [f64; 2]) -> f64 {
    (a[0] - o[0]) * (b[1] - o[1]) - (a[1] - o[1]) * (b[0] - o[0])
}

impl GeometrySpec {
    /// The key of this kind in a scene file.
    pub fn kind(&self) -> &'static str {
        match self {
            GeometrySpec::Rectangle { .. } => "rectangle",
            GeometrySpec::Quadrilateral { .. } => "quadrilateral",
            GeometrySpec::FullDisk { .. } => "full_disk",
            GeometrySpec::HalfDisk { .. } => "half_disk",
            GeometrySpec::Disk5 { .. } => "disk_5",
            GeometrySpec::HalfDisk4 { .. } => "half_disk_4",
            GeometrySpec::QuarterAnnulus { .. } => "quarter_annulus",
            GeometrySpec::HalfAnnulus { .. } => "half_annulus",
            GeometrySpec::Nurbs(_) => "nurbs",
        }
    }

    /// The diameter of the body, from the geometry's parameters.
    pub(super) fn size(&self) -> f64 {
        let span = |pts: &mut dyn Iterator<Item = [f64; 2]>| {
            let (mut lo, mut hi) = ([f64::INFINITY; 2], [f64::NEG_INFINITY; 2]);
            for p in pts {
                for c in 0..2 {
                    lo[c] = lo[c].min(p[c]);
                    hi[c] = hi[c].max(p[c]);
                }
            }
            (hi[0] - lo[0]).hypot(hi[1] - lo[1])
        };
        match self {
            GeometrySpec::Rectangle { x0, y0, x1, y1 } => (x1 - x0).hypot(y1 - y0),
            GeometrySpec::Quadrilateral { corners } => span(&mut corners.iter().copied()),
            GeometrySpec::FullDisk { radius, .. }
            | GeometrySpec::HalfDisk { radius, .. }
            | GeometrySpec::Disk5 { radius, .. }
            | GeometrySpec::HalfDisk4 { radius, .. } => 2.0 * radius,
            GeometrySpec::QuarterAnnulus { outer_radius, .. } => outer_radius * 2f64.sqrt(),
            GeometrySpec::HalfAnnulus { outer_radius, .. } => 2.0 * outer_radius,
            GeometrySpec::Nurbs(n) => span(&mut n.control_points.iter().copied()),
        }
    }

    /// The key that sets [`GeometrySpec::size`], and its value if a number.
    pub(super) fn size_key(&self) -> (&'static str, Option<f64>) {
        match self {
            GeometrySpec::Rectangle { x1, .. } => ("x1", Some(*x1)),
            GeometrySpec::Quadrilateral { .. } => ("corners", None),
            GeometrySpec::FullDisk { radius, .. }
            | GeometrySpec::HalfDisk { radius, .. }
            | GeometrySpec::Disk5 { radius, .. }
            | GeometrySpec::HalfDisk4 { radius, .. } => ("radius", Some(*radius)),
            GeometrySpec::QuarterAnnulus { outer_radius, .. }
            | GeometrySpec::HalfAnnulus { outer_radius, .. } => {
                ("outer_radius", Some(*outer_radius))
            }
            GeometrySpec::Nurbs(_) => ("control_points", None),
        }
    }

    /// The largest degree of the exact (unrefined) patch.
    pub(super) fn degree(&self) -> usize {
        match self {
            GeometrySpec::Rectangle { .. } | GeometrySpec::Quadrilateral { .. } => 1,
            GeometrySpec::FullDisk { .. }
            | GeometrySpec::HalfDisk { .. }
            | GeometrySpec::Disk5 { .. }
            | GeometrySpec::HalfDisk4 { .. }
            | GeometrySpec::QuarterAnnulus { .. }
            | GeometrySpec::HalfAnnulus { .. } => 2,
            GeometrySpec::Nurbs(n) => n.degree[0].max(n.degree[1]),
        }
    }

    /// Checks the parameters; `f` is the path of the geometry table.
    pub(super) fn validate(&self, f: &str) -> Result<()> {
        let f = format!("{f}.{}", self.kind());
        match self {
            GeometrySpec::Rectangle { x0, y0, x1, y1 } => {
                for (k, v) in [("x0", x0), ("y0", y0), ("x1", x1), ("y1", y1)] {
                    finite(format!("{f}.{k}"), *v)?;
                }
                if x1 <= x0 || !(x1 - x0).is_finite() {
                    return Err(Error::invalid(
                        format!("{f}.x1"),
                        show(*x1),
                        format!("must exceed x0 = {x0} by a finite width"),
                    ));
                }
                if y1 <= y0 || !(y1 - y0).is_finite() {
                    return Err(Error::invalid(
                        format!("{f}.y1"),
                        show(*y1),
                        format!("must exceed y0 = {y0} by a finite height"),
                    ));
                }
            }
            GeometrySpec::Quadrilateral { corners } => {
                for (i, c) in corners.iter().enumerate() {
                    finite_point(&format!("{f}.corners[{i}]"), *c)?;
                }
                for i in 0..4 {
                    let turn = cross(corners[i], corners[(i + 1) % 4], corners[(i + 3) % 4]);
                    if !(turn.is_finite() && turn > 0.0) {
                        return Err(Error::invalid(
                            format!("{f}.corners[{i}]"),
                            format!("{:?}", corners[i]),
                            "the corners must be counter-clockwise and form a convex quadrilateral \
                             (the bilinear map folds otherwise)",
                        ));
                    }
                }
            }
            GeometrySpec::FullDisk { center, radius }
            | GeometrySpec::HalfDisk { center, radius }
            | GeometrySpec::Disk5 { center, radius, .. }
            | GeometrySpec::HalfDisk4 { center, radius } => {
                finite_point(&format!("{f}.center"), *center)?;
                positive(format!("{f}.radius"), *radius)?;
                finite_point(
                    &format!("{f}.center"),
                    [center[0] + 2.0 * radius, center[1] + 2.0 * radius],
                )
                .map_err(|_| {
                    Error::invalid(
                        format!("{f}.radius"),
                        show(*radius),
                        "too large for the center: the control points overflow",
                    )
                })?;
            }
            GeometrySpec::QuarterAnnulus {
                inner_radius,
                outer_radius,
            } => annulus_radii(&f, *inner_radius, *outer_radius)?,
            GeometrySpec::HalfAnnulus {
                center,
                inner_radius,
                outer_radius,
            } => {
                finite_point(&format!("{f}.center"), *center)?;
                annulus_radii(&f, *inner_radius, *outer_radius)?;
                finite_point(
                    &format!("{f}.center"),
                    [
                        center[0] + 2.0 * outer_radius,
                        center[1] + 2.0 * outer_radius,
                    ],
                )
                .map_err(|_| {
                    Error::invalid(
                        format!("{f}.outer_radius"),
                        show(*outer_radius),
                        "too large for the center: the control points overflow",
                    )
                })?;
            }
            GeometrySpec::Nurbs(n) => {
                n.knot_vectors(&f)?;
            }
        }
        Ok(())
    }

    /// The patches and named boundaries of a multi-patch kind; `None`
    /// for the one-patch kinds.
    pub fn multipatch(&self) -> Option<Result<geometry::MultiPatch>> {
        match *self {
            GeometrySpec::Disk5 {
                center,
                radius,
                layout: DiskLayout::Axes,
            } => Some(geometry::disk_5(center, radius)),
            GeometrySpec::Disk5 {
                center,
                radius,
                layout: DiskLayout::Diagonal,
            } => Some(geometry::disk_5_diagonal(center, radius)),
            GeometrySpec::HalfDisk4 { center, radius } => {
                Some(geometry::half_disk_4(center, radius))
            }
            _ => None,
        }
    }

    /// The exact patch; `f` is the path of the geometry table.
    pub(super) fn patch(&self, f: &str) -> Result<NurbsPatch> {
        match *self {
            GeometrySpec::Disk5 { .. } | GeometrySpec::HalfDisk4 { .. } => Err(Error::invalid(
                f,
                self.kind(),
                "is a body of several patches (no single patch)",
            )),
            GeometrySpec::Rectangle { x0, y0, x1, y1 } => geometry::rectangle(x0, y0, x1, y1),
            GeometrySpec::Quadrilateral { corners } => geometry::quadrilateral(corners),
            GeometrySpec::FullDisk { center, radius } => geometry::full_disk(center, radius),
            GeometrySpec::HalfDisk { center, radius } => geometry::half_disk(center, radius),
            GeometrySpec::QuarterAnnulus {
                inner_radius,
                outer_radius,
            } => geometry::quarter_annulus(inner_radius, outer_radius),
            GeometrySpec::HalfAnnulus {
                center,
                inner_radius,
                outer_radius,
            } => geometry::half_annulus(center, inner_radius, outer_radius),
            GeometrySpec::Nurbs(ref n) => {
                let f = format!("{f}.nurbs");
                let knots = n.knot_vectors(&f)?;
                let count = knots[0].n_basis() * knots[1].n_basis();
                let weights = n.weights.clone().unwrap_or_else(|| vec![1.0; count]);
                NurbsPatch::new(knots, n.control_points.clone(), weights)
            }
        }
    }
}

/// The radii of an annulus: both positive and finite, the outer one the
/// larger; `f` is the path of the geometry's table.
fn annulus_radii(f: &str, inner: f64, outer: f64) -> Result<()> {
    positive(format!("{f}.inner_radius"), inner)?;
    positive(format!("{f}.outer_radius"), outer)?;
    if outer <= inner {
        return Err(Error::invalid(
            format!("{f}.outer_radius"),
            show(outer),
            format!("must exceed inner_radius = {inner}"),
        ));
    }
    Ok(())
}

impl NurbsSpec {
    /// Validates degrees, knots, control net and weights; `f` is the path
    /// of the `nurbs` table.
    fn knot_vectors(&self, f: &str) -> Result<[KnotVector; 2]> {
        for (d, &p) in self.degree.iter().enumerate() {
            in_range(format!("{f}.degree[{d}]"), p, 1, MAX_DEGREE)?;
        }
        let kx = KnotVector::validated(
            self.knots_xi.clone(),
            self.degree[0],
            &format!("{f}.knots_xi"),
        )?;
        let ky = KnotVector::validated(
            self.knots_eta.clone(),
            self.degree[1],
            &format!("{f}.knots_eta"),
        )?;
        let count = kx.n_basis() * ky.n_basis();
        if self.control_points.len() != count {
            return Err(Error::invalid(
                format!("{f}.control_points"),
                format!("{} points", self.control_points.len()),
                format!(
                    "the knot vectors need {} × {} = {count} control points",
                    kx.n_basis(),
                    ky.n_basis()
                ),
            ));
        }
        for (i, p) in self.control_points.iter().enumerate() {
            finite_point(&format!("{f}.control_points[{i}]"), *p)?;
        }
        if let Some(w) = &self.weights {
            if w.len() != count {
                return Err(Error::invalid(
                    format!("{f}.weights"),
                    format!("{} weights", w.len()),
                    format!("the knot vectors need {count} weights"),
                ));
            }
            for (i, &v) in w.iter().enumerate() {
                positive(format!("{f}.weights[{i}]"), v)?;
            }
        }
        Ok([kx, ky])
    }
}
