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
use crate::contact::{contact_points, ContactPair, Master, Nitsche};
use crate::dofs::{Body, DofMap};
use crate::error::{Error, Result};
use crate::geometry;
use crate::material::{Formulation, Material, Plane};
use crate::nurbs::{KnotVector, NurbsPatch, Side};
use crate::post::{self, PenaltyStability, PressureProfile};
use crate::problem::Problem;
use crate::report::atomic::OutputSet;
use crate::report::history::history_table_noted;
use crate::report::table::{Column, Format, Table, Unit};
use crate::report::{plot, vtu};
use crate::resources::{human_bytes, human_count, BodySize, Budget, Estimate, Factoring, PairSize};
use crate::solver::history::History;
use crate::solver::{self, Factorisation, SolverOptions};
use crate::space::Space;
use crate::timing::{Phase, PhaseTimes, Stopwatch};
use crate::wellposed;
use serde::{Deserialize, Serialize};
use std::collections::HashMap;
use std::fmt;
use std::path::{Path, PathBuf};

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
    /// Accept body `quadrature` and contact `gauss_points` below the
    /// minimum the degree needs ([`wellposed::min_quadrature`],
    /// [`wellposed::min_contact_gauss_points`]), e.g. to study what
    /// under-integration does. Off by default.
    #[serde(default)]
    pub allow_underintegration: bool,
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
    /// `"displacement"` (default, the paper's), `"mixed"` (locking-free, for
    /// nearly incompressible plane-strain bodies) or `"local_mixed"` (its
    /// element-local variant, which still locks): see
    /// [`crate::material::Formulation`]; the mixed ones are refused in plane
    /// stress.
    #[serde(default)]
    pub formulation: Formulation,
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
    /// The disk as five patches without a singular point
    /// ([`geometry::disk_5`]); boundaries `arc`, `arc_bottom`, `arc_right`,
    /// `arc_top`, `arc_left`, `arc_lower`.
    #[serde(rename = "disk_5")]
    Disk5 { center: [f64; 2], radius: f64 },
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
    /// A side of a one-patch body.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub side: Option<Side>,
    /// A named boundary of a multi-patch body (every piece of it).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub boundary: Option<String>,
    /// A point: the control point of the body nearest it, accepted only
    /// where that control point lies on the body (a patch corner).
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub point: Option<[f64; 2]>,
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
    /// A side of a one-patch slave.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slave_side: Option<Side>,
    /// A named boundary of a multi-patch slave: one contact pair per
    /// piece, in order along the boundary.
    #[serde(default, skip_serializing_if = "Option::is_none")]
    pub slave_boundary: Option<String>,
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
    /// `pressure_profile.csv`: pair, x, y, the bracket P, the pressure
    /// −\[P\]₋ on the dense profile ([`crate::post::PressureProfile::dense`]),
    /// and whether the map is regular there ([`crate::post::ProfileSample::regular`]).
    pub pressure_profile: bool,
    /// `summary.toml`: iterations, forces, per contact pair p0 and
    /// half_width, and the run's warnings.
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
    /// The names of the files requested, in the output directory.
    pub fn file_names(&self) -> Vec<&'static str> {
        [
            (self.vtu, files::VTU),
            (self.iterations, files::ITERATIONS),
            (self.pressure_profile, files::PRESSURE_PROFILE),
            (self.summary, files::SUMMARY),
            (self.figures, files::FIGURE),
        ]
        .into_iter()
        .filter_map(|(on, name)| on.then_some(name))
        .collect()
    }

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
    /// Files written (committed together), sorted by name.
    pub files: Vec<PathBuf>,
    /// Wall-clock time of build, solve and output.
    pub seconds: f64,
    /// The same, split by phase ([`PhaseTimes`]).
    pub timing: PhaseTimes,
    /// What the solution may not be ([`solver::Warning`]), one per cause,
    /// each with one remedy: a converged run is reported with them, never
    /// silently.
    pub warnings: Vec<solver::Warning>,
}

impl fmt::Display for RunReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "converged in {} iteration{} ({} correction{}), {} DOFs, {}/{} contact points active, \
             contact force ({:.6e}, {:.6e}), {:.2} s",
            self.iterations,
            if self.iterations == 1 { "" } else { "s" },
            self.corrections,
            if self.corrections == 1 { "" } else { "s" },
            self.dofs,
            self.active_points,
            self.contact_points,
            self.contact_force[0],
            self.contact_force[1],
            self.seconds
        )?;
        // The warnings are lines of their own (the tool prints them on
        // stderr), so that the place written to follows the files.
        match self.files.len() {
            0 => write!(f, "; no outputs requested"),
            1 => write!(f, "; wrote 1 file"),
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
    /// The run's warnings ([`solver::Warning`]), one line per cause; absent
    /// when there is none.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    warnings: Vec<String>,
    /// The solver options as TOML (a `usize::MAX` limit, which TOML cannot
    /// hold, is written as the largest TOML integer).
    solver: toml::Value,
    /// Seconds per phase of the run up to this file, and the wall time;
    /// the file's own writing and the commit of the outputs come after.
    timing: PhaseTimes,
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
    /// Active contact points whose penalty γ lies below the stability bound
    /// of the pair's θ ([`post::penalty_stability`]); 0 is the safe answer.
    penalty_below_bound_points: usize,
    /// The smallest γ / bound over the active points (below 1: unstable);
    /// absent when no active point has a positive bound (θ = −1).
    #[serde(skip_serializing_if = "Option::is_none")]
    min_penalty_ratio: Option<f64>,
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

/// [`wellposed::representable`] for a magnitude implied by the input
/// value at `field`, showing that value.
fn check_scale(field: &str, value: f64, implied: f64, what: &str) -> Result<()> {
    wellposed::representable(field, implied, what).map_err(|e| match e {
        Error::InvalidInput { field, reason, .. } => Error::invalid(field, show(value), reason),
        other => other,
    })
}

impl BodySpec {
    /// The degree of the discretised body (the larger of its two directions).
    fn degree(&self) -> usize {
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
            GeometrySpec::Nurbs(_) => "nurbs",
        }
    }

    /// The diameter of the body, from the geometry's parameters.
    fn size(&self) -> f64 {
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
            GeometrySpec::Nurbs(n) => span(&mut n.control_points.iter().copied()),
        }
    }

    /// The key that sets [`GeometrySpec::size`], and its value if a number.
    fn size_key(&self) -> (&'static str, Option<f64>) {
        match self {
            GeometrySpec::Rectangle { x1, .. } => ("x1", Some(*x1)),
            GeometrySpec::Quadrilateral { .. } => ("corners", None),
            GeometrySpec::FullDisk { radius, .. }
            | GeometrySpec::HalfDisk { radius, .. }
            | GeometrySpec::Disk5 { radius, .. }
            | GeometrySpec::HalfDisk4 { radius, .. } => ("radius", Some(*radius)),
            GeometrySpec::QuarterAnnulus { outer_radius, .. } => {
                ("outer_radius", Some(*outer_radius))
            }
            GeometrySpec::Nurbs(_) => ("control_points", None),
        }
    }

    /// The largest degree of the exact (unrefined) patch.
    fn degree(&self) -> usize {
        match self {
            GeometrySpec::Rectangle { .. } | GeometrySpec::Quadrilateral { .. } => 1,
            GeometrySpec::FullDisk { .. }
            | GeometrySpec::HalfDisk { .. }
            | GeometrySpec::Disk5 { .. }
            | GeometrySpec::HalfDisk4 { .. }
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
            | GeometrySpec::HalfDisk { center, radius }
            | GeometrySpec::Disk5 { center, radius }
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

    /// The patches and named boundaries of a multi-patch kind; `None`
    /// for the one-patch kinds.
    pub fn multipatch(&self) -> Option<Result<geometry::MultiPatch>> {
        match *self {
            GeometrySpec::Disk5 { center, radius } => Some(geometry::disk_5(center, radius)),
            GeometrySpec::HalfDisk4 { center, radius } => {
                Some(geometry::half_disk_4(center, radius))
            }
            _ => None,
        }
    }

    /// The exact patch; `f` is the path of the geometry table.
    fn patch(&self, f: &str) -> Result<NurbsPatch> {
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

    /// Refuses fewer quadrature points than `need`, unless the scene allows
    /// under-integration.
    /// The contact pairs of every `[[contact]]`, in order: one for a
    /// slave side, one per piece of a slave boundary.
    pub fn pair_ranges(&self) -> Vec<std::ops::Range<usize>> {
        let mut at = 0;
        self.contacts
            .iter()
            .map(|c| {
                let n = match (&c.slave_boundary, c.slave.as_str()) {
                    (Some(name), slave) => self
                        .bodies
                        .iter()
                        .find(|b| b.name == slave)
                        .and_then(|b| b.geometry.multipatch())
                        .and_then(|mp| mp.ok())
                        .and_then(|mp| mp.boundary(name).map(<[_]>::len))
                        .unwrap_or(1),
                    (None, _) => 1,
                };
                at += n;
                at - n..at
            })
            .collect()
    }

    /// Refuses a patch side on body `b` when it has several patches.
    fn one_patch(&self, b: usize, field: &str, side: &str) -> Result<()> {
        match self.bodies[b].geometry.multipatch() {
            None => Ok(()),
            Some(mp) => {
                let names = mp?.boundary_names().join(", ");
                Err(Error::invalid(
                    field,
                    side,
                    format!(
                        "body {:?} has several patches: name one of its boundaries ({names}) \
                         with `boundary` / `slave_boundary`",
                        self.bodies[b].name
                    ),
                ))
            }
        }
    }

    /// The pieces (patch of the body, side) of boundary `name` of body `b`.
    fn boundary_of(&self, b: usize, field: &str, name: &str) -> Result<Vec<(usize, Side)>> {
        let body = &self.bodies[b];
        let Some(mp) = body.geometry.multipatch() else {
            return Err(Error::invalid(
                field,
                format!("{name:?}"),
                format!(
                    "body {:?} is one patch: name a side with `side` / `slave_side`",
                    body.name
                ),
            ));
        };
        let mp = mp?;
        mp.boundary(name).map(<[_]>::to_vec).ok_or_else(|| {
            Error::invalid(
                field,
                format!("{name:?}"),
                format!(
                    "body {:?} has the boundaries {}",
                    body.name,
                    mp.boundary_names().join(", ")
                ),
            )
        })
    }

    fn enough_points(&self, field: String, n: usize, need: usize, why: String) -> Result<()> {
        if n >= need || self.allow_underintegration {
            return Ok(());
        }
        Err(Error::invalid(
            field,
            n,
            format!(
                "below the {need} Gauss points {why}; set `allow_underintegration = true` at \
                 the top of the scene to run it anyway"
            ),
        ))
    }

    /// Checks that the magnitudes of the input, and the displacements they
    /// imply, are ones double precision can carry ([`wellposed::representable`]).
    fn validate_scales(&self) -> Result<()> {
        let names = self.body_index();
        let mut size = Vec::with_capacity(self.bodies.len());
        for (i, b) in self.bodies.iter().enumerate() {
            let f = format!("body[{i}]");
            let young = b.material.young;
            wellposed::representable(&format!("{f}.material.young"), young, "the stiffness")?;
            let l = b.geometry.size();
            let (key, value) = b.geometry.size_key();
            let g = format!("{f}.geometry.{}.{key}", b.geometry.kind());
            check_scale(&g, value.unwrap_or(l), l, "the body size")?;
            size.push(l);
        }
        for (i, l) in self.loads.iter().enumerate() {
            let b = names[l.body().as_str()];
            let (key, value, force) = match l {
                Load::BodyForce { force, .. } => {
                    let m = force[0].hypot(force[1]);
                    ("force", m, m * size[b] * size[b])
                }
                Load::Traction { traction, .. } => {
                    let m = traction[0].hypot(traction[1]);
                    ("traction", m, m * size[b])
                }
                Load::Pressure { pressure, .. } => ("pressure", *pressure, pressure * size[b]),
            };
            let field = format!("load[{i}].{}.{key}", load_kind(l));
            check_scale(&field, value, force, "the load resultant")?;
            let young = self.bodies[b].material.young;
            check_scale(&field, value, force / young, "the displacements")?;
        }
        for (i, s) in self.supports.iter().enumerate() {
            let b = names[s.body.as_str()];
            let young = self.bodies[b].material.young;
            let field = format!("support[{i}].value");
            check_scale(&field, s.value, s.value, "the prescribed displacement")?;
            check_scale(&field, s.value, s.value * young, "the support reactions")?;
        }
        Ok(())
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
                if let (Some(q), Some(_)) = (r.lagrange, b.geometry.multipatch()) {
                    return Err(Error::invalid(
                        format!("{f}.refine.lagrange"),
                        q,
                        "a body of several patches is refined by `degree` only",
                    ));
                }
            }
            if b.formulation != Formulation::Displacement && b.geometry.multipatch().is_some() {
                return Err(Error::invalid(
                    format!("{f}.formulation"),
                    format!("{:?}", b.formulation.name()),
                    "the mixed formulations are built for one-patch bodies only",
                ));
            }
            b.material.validate(&format!("{f}.material"))?;
            if b.formulation != Formulation::Displacement && b.material.plane != Plane::Strain {
                return Err(Error::invalid(
                    format!("{f}.formulation"),
                    format!("{:?}", b.formulation.name()),
                    "the mixed formulation is for plane strain; plane stress does not lock (σ_zz = 0 frees the thickness), so use formulation = \"displacement\"",
                ));
            }
            if let Some(q) = b.quadrature {
                in_range(format!("{f}.quadrature"), q, 1, 30)?;
                let p = b.degree();
                self.enough_points(
                    format!("{f}.quadrature"),
                    q,
                    wellposed::min_quadrature(p),
                    format!("a body of degree {p} needs per direction (p + 1: the stiffness is exact on affine elements; fewer may leave zero-energy modes)"),
                )?;
            }
        }
        let names = self.body_index();
        for (i, s) in self.supports.iter().enumerate() {
            let f = format!("support[{i}]");
            let b = self.resolve(&names, format!("{f}.body"), &s.body)?;
            finite(format!("{f}.value"), s.value)?;
            match (s.side, &s.boundary, s.point) {
                (Some(side), None, None) => self.one_patch(b, &format!("{f}.side"), side.name())?,
                (None, Some(name), None) => {
                    self.boundary_of(b, &format!("{f}.boundary"), name)?;
                }
                (None, None, Some(x)) => finite_point(&format!("{f}.point"), x)?,
                _ => {
                    return Err(Error::invalid(
                        f,
                        format!("body {:?}", s.body),
                        "needs exactly one of `side`, `boundary` or `point`",
                    ))
                }
            }
        }
        for (i, l) in self.loads.iter().enumerate() {
            let f = format!("load[{i}].{}", load_kind(l));
            let b = self.resolve(&names, format!("{f}.body"), l.body())?;
            if let Load::Traction { side, .. } | Load::Pressure { side, .. } = l {
                self.one_patch(b, &format!("{f}.side"), side.name())?;
            }
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
            match (c.slave_side, &c.slave_boundary) {
                (Some(side), None) => {
                    self.one_patch(slave, &format!("{f}.slave_side"), side.name())?
                }
                (None, Some(name)) => {
                    self.boundary_of(slave, &format!("{f}.slave_boundary"), name)?;
                }
                _ => {
                    return Err(Error::invalid(
                        format!("{f}.slave_side"),
                        format!("slave {:?}", c.slave),
                        "needs exactly one of `slave_side` (a one-patch body) or `slave_boundary` \
                         (a multi-patch body)",
                    ))
                }
            }
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
                (None, Some(name), Some(side)) => {
                    let master = self.resolve(&names, format!("{f}.master.body"), name)?;
                    self.one_patch(master, &format!("{f}.master.side"), side.name())?;
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
            if let Some(n) = c.nitsche.gauss_points {
                let mut p = self.bodies[slave].degree();
                if let Some(m) = c.master.body.as_ref().and_then(|m| names.get(m.as_str())) {
                    p = p.max(self.bodies[*m].degree());
                }
                self.enough_points(
                    format!("{f}.nitsche.gauss_points"),
                    n,
                    wellposed::min_contact_gauss_points(p),
                    format!("a contact side of degree {p} needs (p + 1: the products of two traces are exact on straight sides)"),
                )?;
            }
        }
        self.validate_scales()?;
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

/// Whether [`Scene::discretise`] evaluates the map of every body at every
/// quadrature point. The assembly evaluates it there anyway, so a run
/// checks only when the assembly fails, for the message; a check, which
/// assembles nothing, checks up front.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
enum MapCheck {
    EveryPoint,
    OnFailure,
}

/// The discretised scene before anything of the size of the system is
/// assembled: bodies, DOF numbering, loads and contact pairs.
struct Discrete {
    bodies: Vec<Body>,
    map: DofMap,
    loads: Vec<Load>,
    pairs: Vec<ContactPair>,
}

/// What [`Scene::check`] found: the scene is valid, fits the memory
/// budget, and is well posed.
#[derive(Clone, Debug, PartialEq)]
pub struct CheckReport {
    pub bodies: usize,
    /// Free degrees of freedom.
    pub dofs: usize,
    pub contact_points: usize,
    /// The resource estimate the budget was checked against.
    pub estimate: Estimate,
    /// What may make a run's answer doubtful, known before solving
    /// ([`solver::warning::before_solve`]): the choice of slave, locking,
    /// and the penalty where the bodies first touch.
    pub warnings: Vec<solver::Warning>,
}

impl fmt::Display for CheckReport {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "ok ({} bod{}, {} free DOFs, {} contact points; a run needs about {} of memory, \
             {} matrix non-zeros)",
            self.bodies,
            if self.bodies == 1 { "y" } else { "ies" },
            self.dofs,
            self.contact_points,
            human_bytes(self.estimate.peak_bytes()),
            human_count(self.estimate.nonzeros)
        )
    }
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

/// The control point of the patches `patches` nearest `x`, as (patch,
/// control point), accepted only where it lies on the body: at a patch
/// corner, where the basis interpolates (elsewhere a control point is off
/// the body and fixing it is no point support). Support `i` of body `name`.
fn corner_at(
    bodies: &[Body],
    patches: std::ops::Range<usize>,
    x: [f64; 2],
    i: usize,
    name: &str,
) -> Result<(usize, usize)> {
    let mut best = (f64::INFINITY, 0, 0);
    for p in patches {
        for (a, y) in bodies[p].space.patch.points.iter().enumerate() {
            let d = (y[0] - x[0]).hypot(y[1] - x[1]);
            if d < best.0 {
                best = (d, p, a);
            }
        }
    }
    let (d, p, a) = best;
    let patch = &bodies[p].space.patch;
    let [n0, n1] = patch.n();
    let (ia, ja) = (a % n0, a / n0);
    let corner = (ia == 0 || ia == n0 - 1) && (ja == 0 || ja == n1 - 1);
    let size = crate::interface::extent(patch);
    if !corner || d > 1e-9 * size {
        return Err(Error::invalid(
            format!("support[{i}].point"),
            format!("{x:?}"),
            format!(
                "the nearest control point of body {name:?}, {:?}, is {} away{}; a point \
                 support needs a patch corner, where the control point lies on the body",
                patch.points[a],
                show(d),
                if corner {
                    ""
                } else {
                    " and not a patch corner"
                }
            ),
        ));
    }
    Ok((p, a))
}

/// An error of the geometry layer, retold with the scene key path of body
/// `i` (`geometry` the path of its geometry table): library field names
/// such as `radius` or `patch.control_points[0]` are not scene keys.
fn in_body(e: Error, i: usize, name: &str, geometry: &str) -> Error {
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
        Error::Geometry(m) => Error::Geometry(format!("body[{i}] ({name:?}): {m}")),
        other => other,
    }
}

impl Scene {
    /// The exact patch of body `i`, errors naming the body.
    fn exact_patch(&self, i: usize) -> Result<NurbsPatch> {
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
        let refined = match &b.refine {
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
    fn body_patches(&self, i: usize) -> Result<Vec<NurbsPatch>> {
        let b = &self.bodies[i];
        let Some(mp) = b.geometry.multipatch() else {
            return Ok(vec![self.body_patch(i)?]);
        };
        let f = format!("body[{i}].geometry.{}", b.geometry.kind());
        let mp = mp.map_err(|e| in_body(e, i, &b.name, &f))?;
        match &b.refine {
            None => Ok(mp.patches),
            Some(RefineSpec {
                degree: Some(p),
                elements,
                ..
            }) => mp.refined(*p, *elements).map_err(|e| match e {
                Error::InvalidInput { value, reason, .. } => Error::invalid(
                    format!("body[{i}].refine"),
                    value,
                    format!("{reason} (in the refined patches of body {:?})", b.name),
                ),
                other => in_body(other, i, &b.name, ""),
            }),
            Some(_) => unreachable!("validated: a multi-patch body is refined by degree"),
        }
    }

    /// The sizes of body `i`'s discretisation (one per patch), from its
    /// knot vectors alone.
    fn body_sizes(&self, i: usize) -> Result<Vec<BodySize>> {
        let b = &self.bodies[i];
        match b.geometry.multipatch() {
            None => Ok(vec![self.patch_size(i, &self.exact_patch(i)?, None)?]),
            Some(mp) => {
                let mp = mp.map_err(|e| in_body(e, i, &b.name, ""))?;
                mp.patches
                    .iter()
                    .zip(&mp.counts)
                    .map(|(patch, c)| {
                        let elements = b.refine.as_ref().map(|r| mp.divisions(c, r.elements));
                        self.patch_size(i, patch, elements)
                    })
                    .collect()
            }
        }
    }

    /// The size of one exact patch of body `i` once refined, with the
    /// element counts `elements` instead of the body's (a multi-patch
    /// body's per patch).
    fn patch_size(
        &self,
        i: usize,
        exact: &NurbsPatch,
        elements: Option<[usize; 2]>,
    ) -> Result<BodySize> {
        let b = &self.bodies[i];
        // Per direction: basis functions and elements after refinement.
        let count = |kv: &KnotVector, d: usize| -> (usize, usize, usize) {
            let spans = kv.spans().len();
            let elements = elements.or(b.refine.as_ref().map(|r| r.elements));
            let elements = &elements.unwrap_or([1, 1]);
            match &b.refine {
                None => (kv.n_basis(), spans, kv.degree()),
                Some(RefineSpec {
                    degree: Some(p), ..
                }) => {
                    let p = (*p).max(kv.degree());
                    let mult = kv.multiplicities();
                    let raise = p - kv.degree();
                    let interior: usize = mult[1..mult.len() - 1].iter().map(|m| m + raise).sum();
                    (
                        p + 1 + interior + spans * (elements[d] - 1),
                        spans * elements[d],
                        p,
                    )
                }
                Some(RefineSpec {
                    lagrange: Some(q), ..
                }) => (elements[d] * q + 1, elements[d], *q),
                Some(_) => unreachable!("validated: degree or lagrange"),
            }
        };
        let (n0, e0, p0) = count(&exact.knots[0], 0);
        let (n1, e1, p1) = count(&exact.knots[1], 1);
        let (field, value) = match &b.refine {
            Some(r) => (
                format!("body[{i}].refine.elements"),
                format!("{:?}", r.elements),
            ),
            None => (
                format!("body[{i}].geometry"),
                format!("{n0} × {n1} control points"),
            ),
        };
        Ok(BodySize {
            field,
            value,
            n: [n0, n1],
            degree: [p0, p1],
            elements: [e0, e1],
            side_elements: [e1, e0],
            formulation: b.formulation,
        })
    }

    /// Estimates DOFs, non-zeros and peak memory of a run from the scene
    /// alone, allocating nothing of the size of the discretisation.
    pub fn estimate(&self) -> Result<Estimate> {
        self.validate()?;
        let per_body = (0..self.bodies.len())
            .map(|i| self.body_sizes(i))
            .collect::<Result<Vec<_>>>()?;
        // the first patch of every body among all patches' sizes
        let first: Vec<usize> = per_body
            .iter()
            .scan(0, |n, v| {
                let at = *n;
                *n += v.len();
                Some(at)
            })
            .collect();
        let sizes: Vec<BodySize> = per_body.into_iter().flatten().collect();
        let names = self.body_index();
        // one pair per piece of a slave boundary
        let mut pieces = Vec::new();
        for c in &self.contacts {
            let b = names[c.slave.as_str()];
            match (c.slave_side, &c.slave_boundary) {
                (Some(side), _) => pieces.push((c, first[b], side)),
                (None, Some(name)) => {
                    for (p, side) in self.boundary_of(b, "slave_boundary", name)? {
                        pieces.push((c, first[b] + p, side));
                    }
                }
                (None, None) => unreachable!("validated: a slave side or boundary"),
            }
        }
        let pairs = pieces
            .into_iter()
            .map(|(c, slave, slave_side)| {
                let s = &sizes[slave];
                let along = slave_side.along();
                let mut degree = s.degree[0].max(s.degree[1]);
                let mut coupled = s.element_points();
                let mut master_breaks = 2.0;
                // Two rows of slave control points reach the normal stress.
                let mut layer = 4.0 * s.n[along] as f64;
                if let (Some(name), Some(side)) = (&c.master.body, c.master.side) {
                    let m = &sizes[first[names[name.as_str()]]];
                    degree = degree.max(m.degree[0].max(m.degree[1]));
                    coupled += m.element_points();
                    master_breaks = m.elements[side.along()] as f64 + 1.0;
                    layer += 2.0 * m.n[side.along()] as f64;
                }
                let g = c.nitsche.points(degree) as f64;
                PairSize {
                    points: g * (s.elements[along] as f64 + master_breaks),
                    dofs_per_point: 2.0 * coupled,
                    layer,
                }
            })
            .collect();
        // The bulk is factorised by Cholesky whatever θ (the layer's dense
        // kernels take the non-symmetric part), by LU only if asked.
        let lu = self.solver.factorisation == Factorisation::Lu;
        let vtu = self.output.vtu.then_some(self.output.vtu_subdivisions);
        let factoring = if lu {
            Factoring::Lu
        } else {
            Factoring::Cholesky
        };
        Ok(Estimate::new(sizes, pairs, vtu, factoring))
    }

    /// Refines every body (with [`MapCheck::EveryPoint`], checking its map
    /// at every quadrature point and naming the body where it folds),
    /// numbers the DOFs and resolves loads and contact pairs; assembles
    /// nothing.
    fn discretise(&self, check: MapCheck) -> Result<Discrete> {
        self.validate()?;
        let names = self.body_index();
        // every body is one or more patches: `first[i]` is the patch index
        // (into `bodies`) of scene body i's first
        let mut first = Vec::with_capacity(self.bodies.len());
        let mut bodies = Vec::with_capacity(self.bodies.len());
        for (i, b) in self.bodies.iter().enumerate() {
            first.push(bodies.len());
            for patch in self.body_patches(i)? {
                let space =
                    Space::new(patch, b.quadrature).map_err(|e| in_body(e, i, &b.name, ""))?;
                if check == MapCheck::EveryPoint {
                    for e in &space.elements {
                        space
                            .quadrature(e)
                            .map_err(|e| in_body(e, i, &b.name, ""))?;
                    }
                }
                bodies.push(Body {
                    name: b.name.clone(),
                    space,
                    material: b.material,
                    formulation: b.formulation,
                });
            }
        }
        first.push(bodies.len());
        let idx = |name: &str| first[names[name]];
        let patches_of = |name: &str| first[names[name]]..first[names[name] + 1];
        let mut dofs = DofMap::builder(&bodies);
        for b in &self.bodies {
            let patches: Vec<usize> = patches_of(&b.name).collect();
            if patches.len() > 1 {
                dofs.join(&b.name, &patches)?;
            }
        }
        for (i, s) in self.supports.iter().enumerate() {
            let c = s.component.index();
            match (s.side, &s.boundary, s.point) {
                (Some(side), _, _) => {
                    dofs.fix_side(idx(&s.body), side, c, s.value)?;
                }
                (None, Some(name), _) => {
                    let f = format!("support[{i}].boundary");
                    for (p, side) in self.boundary_of(names[s.body.as_str()], &f, name)? {
                        dofs.fix_side(idx(&s.body) + p, side, c, s.value)?;
                    }
                }
                (None, None, Some(x)) => {
                    let (p, cp) = corner_at(&bodies, patches_of(&s.body), x, i, &s.body)?;
                    dofs.fix(p, cp, c, s.value)?;
                }
                (None, None, None) => unreachable!("validated: a side, boundary or point"),
            }
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
            match l {
                // a body force acts on every patch of its body
                Load::BodyForce { body, force } => {
                    for p in patches_of(body) {
                        loads.push(Load::BodyForce {
                            body: p,
                            force: *force,
                        });
                    }
                }
                _ => loads.push(l.map_body(|b| idx(b))),
            }
        }
        let mut pairs = Vec::with_capacity(self.contacts.len());
        for (i, c) in self.contacts.iter().enumerate() {
            let pieces = match (c.slave_side, &c.slave_boundary) {
                (Some(side), _) => {
                    let slave = idx(&c.slave);
                    if degenerate_side(&bodies[slave].space.patch, side) {
                        return Err(Error::invalid(
                            format!("contact[{i}].slave_side"),
                            side.name(),
                            format!("this side of body {:?} is collapsed to a point", c.slave),
                        ));
                    }
                    vec![(slave, side)]
                }
                (None, Some(name)) => {
                    let f = format!("contact[{i}].slave_boundary");
                    self.boundary_of(names[c.slave.as_str()], &f, name)?
                        .into_iter()
                        .map(|(p, side)| (idx(&c.slave) + p, side))
                        .collect()
                }
                (None, None) => unreachable!("validated: a slave side or boundary"),
            };
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
            for (slave, slave_side) in pieces {
                pairs.push(ContactPair {
                    slave,
                    slave_side,
                    master: master.clone(),
                    nitsche: c.nitsche,
                });
            }
        }
        Ok(Discrete {
            bodies,
            map,
            loads,
            pairs,
        })
    }

    /// Discretises, builds the contact points and checks the rigid modes on
    /// them (before the assembly: the points cost only the boundary), then
    /// assembles the problem on those same points, with the time of each
    /// step charged to `clock`.
    fn assemble(&self, clock: &mut Stopwatch) -> Result<Problem> {
        let Discrete {
            bodies,
            map,
            loads,
            pairs,
        } = self.discretise(MapCheck::OnFailure)?;
        clock.lap(Phase::ParseAndBuild);
        let points = contact_points(&bodies, &map, &pairs)
            .and_then(|points| {
                wellposed::check_rigid_modes(&bodies, &map, &points)?;
                Ok(points)
            })
            .map_err(|e| self.map_error_or(e))?;
        clock.lap(Phase::ContactSetup);
        let problem = Problem::with_points(bodies, map, &loads, pairs, points)
            .map_err(|e| self.map_error_or(e))?;
        clock.lap(Phase::Assembly);
        Ok(problem)
    }

    /// A failure after a discretisation without the map check: the map's
    /// error (naming the body where it folds) when there is one, as the
    /// check up front would have reported it, else `e`.
    fn map_error_or(&self, e: Error) -> Error {
        match self.discretise(MapCheck::EveryPoint) {
            Err(map) => map,
            Ok(_) => e,
        }
    }

    /// Validates the scene and assembles its [`Problem`] (no solve),
    /// rejecting rigid motions nothing holds
    /// ([`wellposed::check_rigid_modes`]).
    pub fn build(&self) -> Result<Problem> {
        self.assemble(&mut Stopwatch::start())
    }

    /// Everything [`Scene::run`] checks before it solves — validity, the
    /// resource estimate against `budget`, the geometric map of every
    /// body at every quadrature point, the contact points and the rigid
    /// modes — without assembling or solving anything.
    pub fn check(&self, budget: &Budget) -> Result<CheckReport> {
        let estimate = self.estimate()?;
        estimate.check(budget, "output.vtu_subdivisions")?;
        let d = self.discretise(MapCheck::EveryPoint)?;
        let points = contact_points(&d.bodies, &d.map, &d.pairs)?;
        wellposed::check_rigid_modes(&d.bodies, &d.map, &points)?;
        let warnings = solver::warning::before_solve(&d.bodies, &d.pairs, &points);
        Ok(CheckReport {
            bodies: d.bodies.len(),
            dofs: d.map.n_free(),
            contact_points: points.len(),
            estimate,
            warnings,
        })
    }

    /// Builds, solves, and writes the outputs requested in `[output]` into
    /// `out_dir`, within the default memory budget
    /// ([`Budget::from_machine`]). See [`Scene::run_within`].
    pub fn run(&self, out_dir: impl AsRef<Path>) -> Result<RunReport> {
        self.run_within(out_dir, &Budget::from_machine())
    }

    /// Builds, solves, and writes the outputs requested in `[output]` into
    /// `out_dir` — nothing else: a scene without outputs writes no file and
    /// does not even create the directory.
    ///
    /// Before any work: the scene is validated, its estimated peak memory
    /// is checked against `budget`, and the output directory is checked
    /// (it must be creatable and replaceable). The outputs are one
    /// transaction ([`OutputSet`]): staged beside `out_dir` and swapped in
    /// as a whole, so a failed or interrupted run leaves the earlier
    /// results exactly as they were.
    pub fn run_within(&self, out_dir: impl AsRef<Path>, budget: &Budget) -> Result<RunReport> {
        self.run_timed(out_dir, budget, Stopwatch::start())
    }

    /// As [`Scene::run_within`], charging the time of every phase to
    /// `clock` (started by the caller, e.g. before it read the scene):
    /// the phases are reported in [`RunReport::timing`] and in the
    /// `[timing]` table of `summary.toml`.
    pub fn run_timed(
        &self,
        out_dir: impl AsRef<Path>,
        budget: &Budget,
        mut clock: Stopwatch,
    ) -> Result<RunReport> {
        self.estimate()?.check(budget, "output.vtu_subdivisions")?;
        let o = &self.output;
        let set = if o.is_empty() {
            None
        } else {
            Some(OutputSet::begin_expecting(out_dir, &o.file_names())?)
        };
        let problem = self.assemble(&mut clock)?;
        let solution = solver::solve(&problem, &self.solver)?;
        let solve = clock.take();
        let factorisation = solution.phases.condensation.min(solve);
        clock.charge(Phase::Factorisation, factorisation);
        clock.charge(Phase::Iterations, solve - factorisation);
        let full = &solution.full;
        let contact_force = post::contact_resultant(&problem, full).map(no_negative_zero);
        let active_points = problem.active_points(&solution.u);
        let stability = post::penalty_stability(&problem, full);
        let history = &solution.history;
        let title = self.title.as_deref().unwrap_or("scene");
        let applied_force = if o.summary {
            Some(post::applied_resultant(&problem)?.map(no_negative_zero))
        } else {
            None
        };
        let files = match set {
            None => {
                clock.lap(Phase::PostProcessing);
                Vec::new()
            }
            Some(mut set) => {
                let outputs = Outputs {
                    title,
                    contact_force,
                    applied_force,
                    active_points,
                    stability: &stability,
                };
                self.stage_outputs(&mut set, &problem, &solution, &outputs, &mut clock)?;
                let files = set.commit()?;
                clock.lap(Phase::Output);
                files
            }
        };
        let timing = clock.times();
        Ok(RunReport {
            dofs: problem.n(),
            iterations: history.len(),
            corrections: history.corrections(),
            active_points,
            contact_points: problem.points.len(),
            contact_force,
            applied_force,
            files,
            seconds: timing.wall,
            timing,
            warnings: solution.warnings.clone(),
        })
    }

    /// Computes and stages every requested output: first what they are
    /// computed from (charged to post-processing), then the files (charged
    /// to output, up to the summary, which reports the times so far).
    fn stage_outputs(
        &self,
        set: &mut OutputSet,
        problem: &Problem,
        solution: &solver::Solution,
        out: &Outputs,
        clock: &mut Stopwatch,
    ) -> Result<()> {
        let Outputs {
            title,
            contact_force,
            applied_force,
            active_points,
            stability,
        } = *out;
        let o = &self.output;
        let full = &solution.full;
        let history = &solution.history;
        let profile = if o.pressure_profile || o.figures || o.summary {
            Some(PressureProfile::dense(problem, full)?)
        } else {
            None
        };
        let contact = match (applied_force, &profile) {
            (Some(_), Some(profile)) => {
                let forces = post::contact_resultants(problem, full);
                // one entry per [[contact]], over the pairs of its pieces
                self.pair_ranges()
                    .into_iter()
                    .map(|r| {
                        let m = profile.measures_joined(r.clone());
                        let f = forces[r.clone()]
                            .iter()
                            .fold([0.0, 0.0], |a, f| [a[0] + f[0], a[1] + f[1]]);
                        let st = &stability[r];
                        PairSummary {
                            p0: no_negative_zero(m.p0),
                            half_width: no_negative_zero(m.half_width),
                            zones: m.zones,
                            contact_force: f.map(no_negative_zero),
                            penalty_below_bound_points: st.iter().map(|s| s.active_below).sum(),
                            min_penalty_ratio: st
                                .iter()
                                .filter_map(|s| s.min_active_ratio)
                                .reduce(f64::min),
                        }
                    })
                    .collect()
            }
            _ => Vec::new(),
        };
        clock.lap(Phase::PostProcessing);
        if let (true, Some(profile)) = (o.figures, &profile) {
            let pairs = self.contacts.len();
            let ranges = self.pair_ranges();
            let series: Vec<plot::Series> = (0..pairs)
                .map(|k| {
                    // where the map is singular the bracket is not a pressure
                    let points = ranges[k]
                        .clone()
                        .flat_map(|r| profile.pair(r))
                        .filter(|p| p.regular)
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
            plot::line_chart(set.dir().join(files::FIGURE), &axes, &series)?;
        }
        if o.iterations {
            let notes: Vec<String> = solution
                .warnings
                .iter()
                .filter_map(solver::Warning::note)
                .collect();
            let table = history_table_noted(history, Unit::None, Unit::None, &notes)?;
            set.stage(files::ITERATIONS, table.to_csv().as_bytes())?;
        }
        if let (true, Some(profile)) = (o.pressure_profile, &profile) {
            set.stage(
                files::PRESSURE_PROFILE,
                profile_table(profile)?.to_csv().as_bytes(),
            )?;
        }
        if o.vtu {
            let mesh = vtu::sample_bodies(&problem.bodies, &problem.map, full, o.vtu_subdivisions)?;
            mesh.validate()?;
            let xml = mesh.to_xml();
            drop(mesh);
            set.stage(files::VTU, xml.as_bytes())?;
        }
        if let Some(applied_force) = applied_force {
            clock.lap(Phase::Output);
            let summary = Summary {
                title,
                dofs: problem.n(),
                iterations: history.len(),
                corrections: history.corrections(),
                relative_residual: no_negative_zero(final_relative_residual(history)),
                contact_points: problem.points.len(),
                active_points,
                contact_force,
                applied_force,
                contact,
                warnings: solution.warnings.iter().map(|w| w.to_string()).collect(),
                solver: solver_table(&self.solver),
                timing: clock.times(),
            };
            let text = toml::to_string(&summary)
                .map_err(|e| Error::invalid("output.summary", title, e.to_string()))?;
            set.stage(files::SUMMARY, text.as_bytes())?;
        }
        Ok(())
    }
}

/// The figures of a run that go into its outputs.
struct Outputs<'a> {
    title: &'a str,
    contact_force: [f64; 2],
    applied_force: Option<[f64; 2]>,
    active_points: usize,
    stability: &'a [PenaltyStability],
}

/// The relative residual a converged run ends with; a run that needed no
/// iteration (nothing to balance: zero load) ends with 0, not 1.
fn final_relative_residual(h: &History) -> f64 {
    match h.rows.last() {
        Some(r) => r.relative_residual,
        None if h.initial_residual == 0.0 => 0.0,
        None => 1.0,
    }
}

/// `v` with a negative zero turned into +0 (IEEE: −0 + 0 = +0), so that no
/// output shows `-0`.
fn no_negative_zero(v: f64) -> f64 {
    v + 0.0
}

/// The dense pressure profile as a table: pair, position, bracket, pressure,
/// and whether the map is regular there (1) or singular (0: the bracket is
/// 1/det J of the stress, and the measures of `summary.toml` skip it).
fn profile_table(profile: &PressureProfile) -> Result<Table> {
    let mut t = Table::new(vec![
        Column::plain("pair", "pair"),
        Column::new("x", "x", Unit::None, Format::Sci(6)),
        Column::new("y", "y", Unit::None, Format::Sci(6)),
        Column::new("bracket", "P", Unit::None, Format::Sci(6)),
        Column::new("pressure", "pressure", Unit::None, Format::Sci(6)),
        Column::plain("regular", "regular map"),
    ]);
    for s in profile.samples() {
        t.push(vec![
            s.pair.into(),
            s.x[0].into(),
            s.x[1].into(),
            s.bracket.into(),
            s.pressure().into(),
            usize::from(s.regular).into(),
        ])?;
    }
    Ok(t)
}
