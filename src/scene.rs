//! Scene files: a whole contact problem — bodies, supports, loads, contact
//! pairs, solver options and the outputs wanted — described in TOML.
//!
//! A scene is read in three steps, each of which names the offending key
//! path (`body[0].material.young`) and value when it fails:
//!
//! 1. **syntax**: the text must be TOML (errors give line and column);
//! 2. **shape**: every table must have exactly the known keys with values of
//!    the right type (`deny_unknown_fields` everywhere, paths tracked by
//!    `serde_path_to_error`);
//! 3. **validation**: every number must be finite and in its admissible
//!    range, every name must refer to an existing body, and so on
//!    ([`Scene::validate`]).
//!
//! [`Scene::build`] then turns the scene into a [`Problem`], and
//! [`Scene::run`] solves it and writes the requested outputs — and only
//! those — atomically (see [`crate::report::atomic`]).
//!
//! ```
//! use iga_contact::scene::Scene;
//! let scene = Scene::from_toml_str(r#"
//!     [[body]]
//!     name = "block"
//!     geometry = { rectangle = { x0 = 0.0, y0 = 0.0, x1 = 1.0, y1 = 1.0 } }
//!     material = { young = -1.0, poisson = 0.3, plane = "stress" }
//! "#);
//! let err = scene.unwrap_err().to_string();
//! assert!(err.contains("`body[0].material.young` = -1"), "{err}");
//! ```

use crate::assembly::Load;
use crate::contact::{ContactPair, Master, Nitsche};
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::geometry;
use crate::material::Material;
use crate::nurbs::{KnotVector, NurbsPatch, Side};
use crate::post::{self, PressureProfile};
use crate::problem::Problem;
use crate::report::history::history_table;
use crate::report::table::{Column, Format, Table, Unit};
use crate::report::{atomic, plot, vtu};
use crate::solver::{self, SolverOptions};
use crate::space::Space;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};
use std::time::Instant;

/// Largest spline degree a scene may ask for.
pub const MAX_DEGREE: usize = 10;
/// Largest number of elements per direction a scene may ask for.
pub const MAX_ELEMENTS: usize = 4096;
/// Largest Lagrange (FEM) degree the interpolant supports.
pub const MAX_LAGRANGE: usize = 4;
/// Largest number of VTU sub-cells per element and direction.
pub const MAX_VTU_SUBDIVISIONS: usize = 64;

/// A whole scene: the top level of a scene file.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct Scene {
    /// Free text, used in figure titles and the summary.
    #[serde(default)]
    pub title: Option<String>,
    /// `[[body]]`: the elastic bodies, referred to by name elsewhere.
    #[serde(default, rename = "body")]
    pub bodies: Vec<BodySpec>,
    /// `[[support]]`: Dirichlet conditions on control points of a side.
    #[serde(default, rename = "support")]
    pub supports: Vec<SupportSpec>,
    /// `[[load]]`: body forces, tractions and pressures.
    #[serde(default, rename = "load")]
    pub loads: Vec<LoadSpec>,
    /// `[[contact]]`: contact pairs (slave side against a master).
    #[serde(default, rename = "contact")]
    pub contacts: Vec<ContactSpec>,
    /// `[solver]`: the nonlinear solver and its tolerances.
    #[serde(default)]
    pub solver: SolverOptions,
    /// `[output]`: what [`Scene::run`] writes. Nothing by default.
    #[serde(default)]
    pub output: OutputSpec,
}

/// One `[[body]]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct BodySpec {
    pub name: String,
    pub geometry: GeometrySpec,
    /// Refinement of the exact geometry; absent: the geometry as given.
    #[serde(default)]
    pub refine: Option<RefineSpec>,
    pub material: Material,
    /// Gauss points per direction; default p + 1.
    #[serde(default)]
    pub quadrature: Option<usize>,
}

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
    /// The quarter annulus in the first quadrant about the origin.
    QuarterAnnulus {
        inner_radius: f64,
        outer_radius: f64,
    },
    /// A general patch: control point (i, j) at index i + j·n_ξ.
    Nurbs(NurbsSpec),
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

/// A displacement component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Component {
    X,
    Y,
}

impl Component {
    fn index(self) -> usize {
        match self {
            Component::X => 0,
            Component::Y => 1,
        }
    }
}

/// One `[[support]]`: `component` of every control point of `side` is
/// prescribed to `value` (default 0).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SupportSpec {
    pub body: String,
    pub side: Side,
    pub component: Component,
    #[serde(default)]
    pub value: f64,
}

/// One `[[load]]`, a table with one key, the kind:
/// `pressure = { body = "upper", side = "eta_max", pressure = 1e8 }`; the
/// library's [`Load`] with the body given by name.
pub type LoadSpec = Load<String>;

/// The TOML key of a load's kind, for error paths.
fn load_kind<B>(l: &Load<B>) -> &'static str {
    match l {
        Load::BodyForce { .. } => "body_force",
        Load::Traction { .. } => "traction",
        Load::Pressure { .. } => "pressure",
    }
}

/// One `[[contact]]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct ContactSpec {
    pub slave: String,
    pub slave_side: Side,
    pub master: MasterSpec,
    /// θ, the penalty factor and the integration rule of the pair.
    #[serde(default)]
    pub nitsche: Nitsche,
}

/// The master of a contact pair: either `{ rigid_segment = { from, to } }`
/// (a rigid obstacle on the right of the segment's direction) or
/// `{ body = NAME, side = SIDE }`.
#[derive(Clone, Debug, Default, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct MasterSpec {
    #[serde(default)]
    pub rigid_segment: Option<SegmentSpec>,
    #[serde(default)]
    pub body: Option<String>,
    #[serde(default)]
    pub side: Option<Side>,
}

/// A straight rigid obstacle from `from` to `to`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct SegmentSpec {
    pub from: [f64; 2],
    pub to: [f64; 2],
}

/// `[output]`: the files [`Scene::run`] writes into its output directory.
/// Everything is off by default; a scene computes only what it asks for.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(deny_unknown_fields, default)]
pub struct OutputSpec {
    /// `solution.vtu`: displacement and stress sampled on every element.
    pub vtu: bool,
    /// Sub-cells per element and direction in the VTU.
    pub vtu_subdivisions: usize,
    /// `iterations.csv`: the solver's iteration history.
    pub iterations: bool,
    /// `pressure_profile.csv`: pair, x, y, the bracket P and the pressure
    /// −\[P\]₋ on the dense profile ([`crate::post::PressureProfile::dense`]).
    pub pressure_profile: bool,
    /// `summary.toml`: iterations, forces, and per contact pair p0 and half_width.
    pub summary: bool,
    /// `pressure_profile.svg`: the pressure profile as a figure.
    pub figures: bool,
}

impl Default for OutputSpec {
    fn default() -> Self {
        Self {
            vtu: false,
            vtu_subdivisions: 4,
            iterations: false,
            pressure_profile: false,
            summary: false,
            figures: false,
        }
    }
}

impl OutputSpec {
    /// True if no output is requested.
    pub fn is_empty(&self) -> bool {
        !(self.vtu || self.iterations || self.pressure_profile || self.summary || self.figures)
    }
}

/// File names inside the output directory.
pub mod files {
    pub const VTU: &str = "solution.vtu";
    pub const ITERATIONS: &str = "iterations.csv";
    pub const PRESSURE_PROFILE: &str = "pressure_profile.csv";
    pub const SUMMARY: &str = "summary.toml";
    pub const FIGURE: &str = "pressure_profile.svg";
}

/// What a [`Scene::run`] did.
#[derive(Clone, Debug, PartialEq)]
pub struct RunReport {
    /// Free degrees of freedom.
    pub dofs: usize,
    pub iterations: usize,
    pub corrections: usize,
    /// Contact points with P ≤ 0 at the solution, and in all.
    pub active_points: usize,
    pub contact_points: usize,
    /// Resultant force the masters exert on the slaves.
    pub contact_force: [f64; 2],
    /// Resultant of the external loads (computed only for the summary).
    pub applied_force: Option<[f64; 2]>,
    /// Files written, in order.
    pub files: Vec<PathBuf>,
    /// Wall-clock time of build, solve and output.
    pub seconds: f64,
}

impl fmt::Display for RunReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "converged in {} iterations ({} correction{}), {} DOFs, {}/{} contact points active, \
             contact force ({:.6e}, {:.6e}), {:.2} s",
            self.iterations,
            self.corrections,
            if self.corrections == 1 { "" } else { "s" },
            self.dofs,
            self.active_points,
            self.contact_points,
            self.contact_force[0],
            self.contact_force[1],
            self.seconds
        )?;
        match self.files.len() {
            0 => write!(f, "; no outputs requested"),
            n => write!(f, "; wrote {n} files"),
        }
    }
}

/// The summary file, `summary.toml`.
#[derive(Serialize)]
struct Summary<'a> {
    title: &'a str,
    dofs: usize,
    iterations: usize,
    corrections: usize,
    relative_residual: f64,
    contact_points: usize,
    active_points: usize,
    contact_force: [f64; 2],
    applied_force: [f64; 2],
    /// One entry per contact pair: p0, half_width, contact force.
    contact: Vec<PairSummary>,
    /// The solver options as TOML (a `usize::MAX` limit, which TOML cannot
    /// hold, is written as the largest TOML integer).
    solver: toml::Value,
}

/// What `summary.toml` reports of one contact pair, measured by
/// [`crate::post`] on the dense pressure profile.
#[derive(Serialize)]
struct PairSummary {
    /// Peak contact pressure.
    p0: f64,
    /// Contact half-width, along the contact tangent at the peak.
    half_width: f64,
    /// Separate contact zones (1: one connected zone).
    zones: usize,
    /// Force of the master on the slave.
    contact_force: [f64; 2],
}

/// `opts` as a TOML table, saturating integers beyond TOML's i64 range.
fn solver_table(opts: &SolverOptions) -> toml::Value {
    if let Ok(v) = toml::Value::try_from(opts) {
        return v;
    }
    let mut clamped = *opts;
    for v in [
        &mut clamped.max_iter,
        &mut clamped.correction_after,
        &mut clamped.line_search_after,
    ] {
        *v = (*v).min(i64::MAX as usize);
    }
    toml::Value::try_from(clamped).unwrap_or_else(|_| toml::Value::String(format!("{opts:?}")))
}

// ---------------------------------------------------------------------------
// Parsing
// ---------------------------------------------------------------------------

/// Shortens a value shown in an error message.
fn shorten(s: String) -> String {
    const MAX: usize = 80;
    let one_line = s.replace('\n', " ");
    if one_line.chars().count() <= MAX {
        one_line
    } else {
        let cut: String = one_line.chars().take(MAX).collect();
        format!("{cut}…")
    }
}

/// The value at `path` in the parsed document, for error messages.
fn lookup<'a>(root: &'a toml::Value, path: &serde_path_to_error::Path) -> Option<&'a toml::Value> {
    use serde_path_to_error::Segment;
    let mut v = root;
    for seg in path.iter() {
        v = match seg {
            Segment::Seq { index } => v.as_array()?.get(*index)?,
            Segment::Map { key } | Segment::Enum { variant: key } => v.as_table()?.get(key)?,
            Segment::Unknown => return None,
        };
    }
    Some(v)
}

/// 1-based line and column of byte `offset` in `text`.
fn line_col(text: &str, offset: usize) -> (usize, usize) {
    let mut offset = offset.min(text.len());
    while !text.is_char_boundary(offset) {
        offset -= 1;
    }
    let before = &text[..offset];
    let line = before.matches('\n').count() + 1;
    let col = before.rsplit('\n').next().map_or(0, |l| l.chars().count()) + 1;
    (line, col)
}

fn syntax_error(text: &str, e: toml::de::Error) -> Error {
    let (field, value) = match e.span() {
        Some(span) => {
            let (line, col) = line_col(text, span.start);
            let source = text.lines().nth(line - 1).unwrap_or("").trim();
            (format!("line {line}, column {col}"), shorten(source.into()))
        }
        None => ("scene".into(), "(the scene text)".into()),
    };
    Error::invalid(
        field,
        value,
        format!("not valid TOML: {}", e.message().trim().replace('\n', " ")),
    )
}

impl Scene {
    /// Parses and validates a scene. Every error names the key path and the
    /// offending value.
    pub fn from_toml_str(text: &str) -> Result<Scene> {
        let table: toml::Table = toml::from_str(text).map_err(|e| syntax_error(text, e))?;
        let root = toml::Value::Table(table);
        let scene: Scene = serde_path_to_error::deserialize(root.clone()).map_err(|e| {
            let path = e.path().clone();
            let shown = lookup(&root, &path)
                .map(|v| shorten(v.to_string()))
                .unwrap_or_else(|| "(absent)".into());
            let message = e.into_inner().message().trim().replace('\n', " ");
            let field = match path.to_string().as_str() {
                "." => "scene".to_string(),
                p => p.to_string(),
            };
            Error::invalid(field, shown, message)
        })?;
        scene.validate()?;
        Ok(scene)
    }

    /// Reads, parses and validates a scene file.
    pub fn load(path: impl AsRef<Path>) -> Result<Scene> {
        let path = path.as_ref();
        let text = std::fs::read_to_string(path).map_err(|e| {
            Error::invalid("scene file", path.display(), format!("cannot be read: {e}"))
        })?;
        Scene::from_toml_str(&text)
    }
}

// ---------------------------------------------------------------------------
// Validation
// ---------------------------------------------------------------------------

/// A number as shown in error messages: plain, or in exponent form when
/// the plain form would be long (`1e308`, not 309 digits).
fn show(v: f64) -> String {
    let plain = v.to_string();
    if plain.len() > 16 {
        format!("{v:e}")
    } else {
        plain
    }
}

fn finite(field: impl Into<String>, v: f64) -> Result<()> {
    if v.is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(field, v, "must be a finite number"))
    }
}

fn finite_point(field: &str, p: [f64; 2]) -> Result<()> {
    for (c, &v) in p.iter().enumerate() {
        finite(format!("{field}[{c}]"), v)?;
    }
    Ok(())
}

fn positive(field: impl Into<String>, v: f64) -> Result<()> {
    if v.is_finite() && v > 0.0 {
        Ok(())
    } else {
        Err(Error::invalid(
            field,
            show(v),
            "must be positive and finite",
        ))
    }
}

fn in_range(field: impl Into<String>, v: usize, lo: usize, hi: usize) -> Result<()> {
    if (lo..=hi).contains(&v) {
        Ok(())
    } else {
        Err(Error::invalid(field, v, format!("must lie in {lo}..={hi}")))
    }
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
            GeometrySpec::QuarterAnnulus { .. } => "quarter_annulus",
            GeometrySpec::Nurbs(_) => "nurbs",
        }
    }

    /// The largest degree of the exact (unrefined) patch.
    fn degree(&self) -> usize {
        match self {
            GeometrySpec::Rectangle { .. } | GeometrySpec::Quadrilateral { .. } => 1,
            GeometrySpec::FullDisk { .. }
            | GeometrySpec::HalfDisk { .. }
            | GeometrySpec::QuarterAnnulus { .. } => 2,
            GeometrySpec::Nurbs(n) => n.degree[0].max(n.degree[1]),
        }
    }

    /// Checks the parameters; `f` is the path of the geometry table.
    fn validate(&self, f: &str) -> Result<()> {
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
            | GeometrySpec::HalfDisk { center, radius } => {
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
            } => {
                positive(format!("{f}.inner_radius"), *inner_radius)?;
                positive(format!("{f}.outer_radius"), *outer_radius)?;
                if outer_radius <= inner_radius {
                    return Err(Error::invalid(
                        format!("{f}.outer_radius"),
                        show(*outer_radius),
                        format!("must exceed inner_radius = {inner_radius}"),
                    ));
                }
            }
            GeometrySpec::Nurbs(n) => {
                n.knot_vectors(&f)?;
            }
        }
        Ok(())
    }

    /// The exact patch; `f` is the path of the geometry table.
    fn patch(&self, f: &str) -> Result<NurbsPatch> {
        match *self {
            GeometrySpec::Rectangle { x0, y0, x1, y1 } => geometry::rectangle(x0, y0, x1, y1),
            GeometrySpec::Quadrilateral { corners } => geometry::quadrilateral(corners),
            GeometrySpec::FullDisk { center, radius } => geometry::full_disk(center, radius),
            GeometrySpec::HalfDisk { center, radius } => geometry::half_disk(center, radius),
            GeometrySpec::QuarterAnnulus {
                inner_radius,
                outer_radius,
            } => geometry::quarter_annulus(inner_radius, outer_radius),
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

    fn validate(&self, f: &str, geometry_degree: usize) -> Result<()> {
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

/// The path of a scene file shipped in `data/scenes/` (in this crate's
/// source tree).
pub fn shipped_path(file: &str) -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR"))
        .join("data/scenes")
        .join(file)
}

impl Scene {
    /// A scene file shipped in `data/scenes/`: the paper's set-ups are
    /// `taylor.toml` and `hertz.toml`.
    pub fn shipped(file: &str) -> Result<Scene> {
        Scene::load(shipped_path(file))
    }

    /// The body named `name`, to change it before building.
    pub fn body_mut(&mut self, name: &str) -> Result<&mut BodySpec> {
        let known: Vec<String> = self.bodies.iter().map(|b| b.name.clone()).collect();
        self.bodies
            .iter_mut()
            .find(|b| b.name == name)
            .ok_or_else(|| {
                Error::invalid(
                    "body",
                    name,
                    format!("no such body (bodies: {})", known.join(", ")),
                )
            })
    }

    /// The Nitsche parameters of every contact pair, to change them before building.
    pub fn nitsche_mut(&mut self) -> impl Iterator<Item = &mut Nitsche> {
        self.contacts.iter_mut().map(|c| &mut c.nitsche)
    }

    /// The scene with body `name` discretised by `refine`.
    pub fn refined(mut self, name: &str, refine: RefineSpec) -> Result<Self> {
        self.body_mut(name)?.refine = Some(refine);
        Ok(self)
    }

    /// The scene with `set` applied to the Nitsche parameters of every pair.
    pub fn with_nitsche(mut self, set: impl FnMut(&mut Nitsche)) -> Self {
        self.nitsche_mut().for_each(set);
        self
    }

    /// Index of each body by name.
    fn body_index(&self) -> HashMap<&str, usize> {
        self.bodies
            .iter()
            .enumerate()
            .map(|(i, b)| (b.name.as_str(), i))
            .collect()
    }

    fn resolve(&self, names: &HashMap<&str, usize>, field: String, name: &str) -> Result<usize> {
        names.get(name).copied().ok_or_else(|| {
            let known: Vec<&str> = self.bodies.iter().map(|b| b.name.as_str()).collect();
            Error::invalid(
                field,
                format!("{name:?}"),
                format!("no body of that name (bodies: {})", known.join(", ")),
            )
        })
    }

    /// Checks every rule a scene must satisfy, naming the key path and value
    /// of the first violation. [`Scene::from_toml_str`] and [`Scene::build`]
    /// both call it.
    pub fn validate(&self) -> Result<()> {
        if self.bodies.is_empty() {
            return Err(Error::invalid(
                "body",
                "[]",
                "a scene needs at least one [[body]]",
            ));
        }
        let mut seen: HashMap<&str, usize> = HashMap::new();
        for (i, b) in self.bodies.iter().enumerate() {
            let f = format!("body[{i}]");
            if b.name.trim().is_empty() {
                return Err(Error::invalid(
                    format!("{f}.name"),
                    format!("{:?}", b.name),
                    "must not be empty",
                ));
            }
            if let Some(j) = seen.insert(b.name.as_str(), i) {
                return Err(Error::invalid(
                    format!("{f}.name"),
                    format!("{:?}", b.name),
                    format!("duplicate body name (also body[{j}])"),
                ));
            }
            b.geometry.validate(&format!("{f}.geometry"))?;
            if let Some(r) = &b.refine {
                r.validate(&format!("{f}.refine"), b.geometry.degree())?;
            }
            b.material.validate(&format!("{f}.material"))?;
            if let Some(q) = b.quadrature {
                in_range(format!("{f}.quadrature"), q, 1, 30)?;
            }
        }
        let names = self.body_index();
        for (i, s) in self.supports.iter().enumerate() {
            let f = format!("support[{i}]");
            self.resolve(&names, format!("{f}.body"), &s.body)?;
            finite(format!("{f}.value"), s.value)?;
        }
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}].{}", load_kind(l));
            self.resolve(&names, format!("{f}.body"), l.body())?;
            match l {
                Load::BodyForce { force, .. } => finite_point(&format!("{f}.force"), *force)?,
                Load::Traction { traction, .. } => {
                    finite_point(&format!("{f}.traction"), *traction)?
                }
                Load::Pressure { pressure, .. } => finite(format!("{f}.pressure"), *pressure)?,
            }
        }
        for (i, c) in self.contacts.iter().enumerate() {
            let f = format!("contact[{i}]");
            let slave = self.resolve(&names, format!("{f}.slave"), &c.slave)?;
            let m = &c.master;
            match (&m.rigid_segment, &m.body, &m.side) {
                (Some(seg), None, None) => {
                    let g = format!("{f}.master.rigid_segment");
                    finite_point(&format!("{g}.from"), seg.from)?;
                    finite_point(&format!("{g}.to"), seg.to)?;
                    let len = (seg.to[0] - seg.from[0]).hypot(seg.to[1] - seg.from[1]);
                    if !(len.is_finite() && len > 0.0) {
                        return Err(Error::invalid(
                            format!("{g}.to"),
                            format!("{:?}", seg.to),
                            "must differ from `from` by a finite distance",
                        ));
                    }
                }
                (None, Some(name), Some(_)) => {
                    let master = self.resolve(&names, format!("{f}.master.body"), name)?;
                    if master == slave {
                        return Err(Error::invalid(
                            format!("{f}.master.body"),
                            format!("{name:?}"),
                            "the master must be another body than the slave (no self-contact)",
                        ));
                    }
                }
                (None, Some(name), None) => {
                    return Err(Error::invalid(
                        format!("{f}.master.side"),
                        "(absent)",
                        format!("the master body {name:?} needs a `side`"),
                    ))
                }
                (Some(_), _, _) => {
                    return Err(Error::invalid(
                        format!("{f}.master"),
                        "rigid_segment and body",
                        "give either `rigid_segment` or `body` and `side`, not both",
                    ))
                }
                (None, None, _) => {
                    return Err(Error::invalid(
                        format!("{f}.master"),
                        "{}",
                        "needs `rigid_segment = { from, to }` or `body` and `side`",
                    ))
                }
            }
            c.nitsche.validate(&format!("{f}.nitsche"))?;
        }
        self.solver.validate("solver")?;
        let o = &self.output;
        in_range(
            "output.vtu_subdivisions",
            o.vtu_subdivisions,
            1,
            MAX_VTU_SUBDIVISIONS,
        )?;
        if self.contacts.is_empty() {
            for (k, on) in [
                ("pressure_profile", o.pressure_profile),
                ("figures", o.figures),
            ] {
                if on {
                    return Err(Error::invalid(
                        format!("output.{k}"),
                        true,
                        "needs at least one [[contact]] pair",
                    ));
                }
            }
        }
        Ok(())
    }
}

// ---------------------------------------------------------------------------
// Building and running
// ---------------------------------------------------------------------------

/// A built scene: the problem and the loads it was assembled with.
struct Built {
    problem: Problem,
}

/// True if every control point of `side` coincides with the first: the
/// side is collapsed to a point.
fn degenerate_side(patch: &NurbsPatch, side: Side) -> bool {
    let idx = patch.side_indices(side);
    let p0 = patch.points[idx[0]];
    let scale = patch
        .points
        .iter()
        .map(|p| (p[0] - p0[0]).hypot(p[1] - p0[1]))
        .fold(0.0, f64::max);
    idx.iter().all(|&i| {
        let p = patch.points[i];
        (p[0] - p0[0]).hypot(p[1] - p0[1]) <= 1e-12 * scale
    })
}

impl Scene {
    /// The discretised patch of body `i`.
    fn body_patch(&self, i: usize) -> Result<NurbsPatch> {
        let b = &self.bodies[i];
        let exact = b.geometry.patch(&format!("body[{i}].geometry"))?;
        match &b.refine {
            None => Ok(exact),
            Some(RefineSpec {
                degree: Some(p),
                elements,
                ..
            }) => exact.k_refined(*p, *elements),
            Some(RefineSpec {
                lagrange: Some(q),
                elements,
                ..
            }) => geometry::lagrange_interpolant(&exact, *q, *elements),
            Some(_) => unreachable!("validated: degree or lagrange"),
        }
    }

    fn assemble(&self) -> Result<Built> {
        self.validate()?;
        let names = self.body_index();
        let idx = |name: &str| names[name];
        let mut bodies = Vec::with_capacity(self.bodies.len());
        for (i, b) in self.bodies.iter().enumerate() {
            bodies.push(Body {
                name: b.name.clone(),
                space: Space::new(self.body_patch(i)?, b.quadrature)?,
                material: b.material,
            });
        }
        let mut dofs = DofMap::builder(&bodies);
        for s in &self.supports {
            dofs.fix_side(idx(&s.body), s.side, s.component.index(), s.value)?;
        }
        let map = dofs.build();
        let mut loads = Vec::with_capacity(self.loads.len());
        for (i, l) in self.loads.iter().enumerate() {
            if let Load::Pressure { body, side, .. } = l {
                if degenerate_side(&bodies[idx(body)].space.patch, *side) {
                    return Err(Error::invalid(
                        format!("load[{i}].pressure.side"),
                        side.name(),
                        format!("this side of body {body:?} is collapsed to a point"),
                    ));
                }
            }
            loads.push(l.map_body(|b| idx(b)));
        }
        let mut pairs = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let slave = idx(&c.slave);
            if degenerate_side(&bodies[slave].space.patch, c.slave_side) {
                return Err(Error::invalid(
                    format!("contact[{i}].slave_side"),
                    c.slave_side.name(),
                    format!("this side of body {:?} is collapsed to a point", c.slave),
                ));
            }
            let master = match (&c.master.rigid_segment, &c.master.body, c.master.side) {
                (Some(seg), _, _) => Master::Rigid(geometry::segment(seg.from, seg.to)?),
                (None, Some(name), Some(side)) => {
                    let body = idx(name);
                    if degenerate_side(&bodies[body].space.patch, side) {
                        return Err(Error::invalid(
                            format!("contact[{i}].master.side"),
                            side.name(),
                            format!("this side of body {name:?} is collapsed to a point"),
                        ));
                    }
                    Master::Body { body, side }
                }
                _ => unreachable!("validated: a rigid segment or a body and side"),
            };
            pairs.push(ContactPair {
                slave,
                slave_side: c.slave_side,
                master,
                nitsche: c.nitsche,
            });
        }
        let problem = Problem::new(bodies, map, &loads, pairs)?;
        Ok(Built { problem })
    }

    /// Validates the scene and assembles its [`Problem`] (no solve).
    pub fn build(&self) -> Result<Problem> {
        Ok(self.assemble()?.problem)
    }

    /// Builds, solves, and writes the outputs requested in `[output]` into
    /// `out_dir` — nothing else: a scene without outputs writes no file and
    /// does not even create the directory.
    ///
    /// Every output is computed in memory before the first file is
    /// written, and every file is written atomically, so a failed run
    /// (invalid scene, solver not converged, bad figure data) leaves
    /// earlier results untouched and no partial files.
    pub fn run(&self, out_dir: impl AsRef<Path>) -> Result<RunReport> {
        let start = Instant::now();
        let out_dir = out_dir.as_ref();
        let Built { problem } = self.assemble()?;
        let solution = solver::solve(&problem, &self.solver)?;
        let full = &solution.full;
        let resultants = post::contact_resultants(&problem, full);
        let contact_force = post::contact_resultant(&problem, full);
        let active_points = problem.active_points(&solution.u);
        let history = &solution.history;
        let o = &self.output;
        let title = self.title.as_deref().unwrap_or("scene");

        let profile = if o.pressure_profile || o.figures || o.summary {
            Some(PressureProfile::dense(&problem, full)?)
        } else {
            None
        };

        // Everything textual, in memory first.
        let mut texts: Vec<(&str, String)> = Vec::new();
        if o.iterations {
            texts.push((
                files::ITERATIONS,
                history_table(history, Unit::None, Unit::None)?.to_csv(),
            ));
        }
        if let (true, Some(profile)) = (o.pressure_profile, &profile) {
            texts.push((files::PRESSURE_PROFILE, profile_table(profile)?.to_csv()));
        }
        if o.vtu {
            let mesh = vtu::sample_bodies(&problem.bodies, &problem.map, full, o.vtu_subdivisions)?;
            mesh.validate()?;
            texts.push((files::VTU, mesh.to_xml()));
        }
        let applied_force = if o.summary {
            Some(post::applied_resultant(&problem)?)
        } else {
            None
        };
        if let (Some(applied_force), Some(profile)) = (applied_force, &profile) {
            let contact = resultants
                .iter()
                .enumerate()
                .map(|(k, &f)| {
                    let m = profile.measures(k);
                    PairSummary {
                        p0: m.p0,
                        half_width: m.half_width,
                        zones: m.zones,
                        contact_force: f,
                    }
                })
                .collect();
            let summary = Summary {
                title,
                dofs: problem.n(),
                iterations: history.len(),
                corrections: history.corrections(),
                relative_residual: history.last_relative_residual(),
                contact_points: problem.points.len(),
                active_points,
                contact_force,
                applied_force,
                contact,
                solver: solver_table(&self.solver),
            };
            let text = toml::to_string(&summary)
                .map_err(|e| Error::invalid("output.summary", title, e.to_string()))?;
            texts.push((files::SUMMARY, text));
        }

        let mut written = Vec::new();
        // The figure validates its data before drawing and is the only
        // output rendered straight to disk, so it goes first: if it fails,
        // nothing has been written.
        if let (true, Some(profile)) = (o.figures, &profile) {
            let pairs = self.contacts.len();
            let series: Vec<plot::Series> = (0..pairs)
                .map(|k| {
                    let points = profile
                        .pair(k)
                        .iter()
                        .map(|p| (p.x[0], p.pressure()))
                        .collect();
                    let label = if pairs > 1 {
                        format!("contact[{k}]")
                    } else {
                        String::new()
                    };
                    plot::Series::line(label, points)
                })
                .collect();
            let axes = plot::Axes {
                title: format!("{title}: contact pressure"),
                x_label: "x".into(),
                y_label: "contact pressure".into(),
                log_x: false,
                log_y: false,
            };
            let path = out_dir.join(files::FIGURE);
            plot::line_chart(&path, &axes, &series)?;
            written.push(path);
        }
        for (name, text) in texts {
            let path = out_dir.join(name);
            atomic::write_text(&path, &text)?;
            written.push(path);
        }
        Ok(RunReport {
            dofs: problem.n(),
            iterations: history.len(),
            corrections: history.corrections(),
            active_points,
            contact_points: problem.points.len(),
            contact_force,
            applied_force,
            files: written,
            seconds: start.elapsed().as_secs_f64(),
        })
    }
}

/// The dense pressure profile as a table: pair, position, bracket and pressure.
fn profile_table(profile: &PressureProfile) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("pair", "pair"),
        Column::new("x", "x", Unit::None, Format::Sci(6)),
        Column::new("y", "y", Unit::None, Format::Sci(6)),
        Column::new("bracket", "P", Unit::None, Format::Sci(6)),
        Column::new("pressure", "pressure", Unit::None, Format::Sci(6)),
    ]);
    for s in profile.samples() {
        t.push(vec![
            s.pair.into(),
            s.x[0].into(),
            s.x[1].into(),
            s.bracket.into(),
            s.pressure().into(),
        ])?;
    }
    Ok(t)
}
