//! The scene file's tables as Rust types: what `serde` reads, key for key.
//! The either-or tables with their own reading are in `refine.rs`
//! and here ([`MasterSpec`], [`SupportSpec`]'s [`SupportAt`] and
//! [`ContactSpec`]'s [`SlaveAt`]): each is read from a raw table into an
//! enum when the scene is parsed; values are checked in `validate.rs`.

use crate::assembly::Load;
use crate::material::{Formulation, Material};
use crate::nurbs::Side;
use crate::solver::SolverOptions;
use serde::{Deserialize, Serialize};

use super::parse::TableError;
use super::{GeometrySpec, NitscheSpec, RefineSpec};
#[cfg(doc)]
use crate::wellposed;

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

/// A displacement component.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Serialize, Deserialize)]
#[serde(rename_all = "snake_case")]
pub enum Component {
    X,
    Y,
}

impl Component {
    pub(super) fn index(self) -> usize {
        match self {
            Component::X => 0,
            Component::Y => 1,
        }
    }
}

/// One `[[support]]`: `component` of every control point where it acts
/// (`at`) is prescribed to `value` (default 0).
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawSupport", into = "RawSupport")]
pub struct SupportSpec {
    pub body: String,
    /// Where it acts, read from the one of the keys `side`, `boundary` and
    /// `point` the table gives.
    pub at: SupportAt,
    pub component: Component,
    pub value: f64,
}

/// Where a `[[support]]` acts. The file names it by exactly one of three
/// keys; which one is read once, when the scene is parsed, so that a
/// support in hand always names one place and nothing after the parse
/// asks again.
#[derive(Clone, Debug, PartialEq)]
pub enum SupportAt {
    /// `side = SIDE`: a side of a one-patch body.
    Side(Side),
    /// `boundary = NAME`: a named boundary of a multi-patch body (every
    /// piece of it).
    Boundary(String),
    /// `point = [x, y]`: the control point of the body nearest it, accepted
    /// only where that control point lies on the body (a patch corner).
    Point([f64; 2]),
}

/// The `[[support]]` table as written, before the choice of keys is read.
#[derive(Clone, Serialize, Deserialize)]
// type errors name the type it reads into, as they did before it existed
#[serde(deny_unknown_fields, expecting = "struct SupportSpec")]
struct RawSupport {
    body: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    side: Option<Side>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    boundary: Option<String>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    point: Option<[f64; 2]>,
    component: Component,
    #[serde(default)]
    value: f64,
}

impl TryFrom<RawSupport> for SupportSpec {
    type Error = TableError;

    fn try_from(s: RawSupport) -> Result<Self, TableError> {
        let at = match (s.side, s.boundary, s.point) {
            (Some(side), None, None) => SupportAt::Side(side),
            (None, Some(name), None) => SupportAt::Boundary(name),
            (None, None, Some(x)) => SupportAt::Point(x),
            _ => {
                return Err(TableError::new(
                    "",
                    format!("body {:?}", s.body),
                    "needs exactly one of `side`, `boundary` or `point`",
                ))
            }
        };
        Ok(SupportSpec {
            body: s.body,
            at,
            component: s.component,
            value: s.value,
        })
    }
}

impl From<SupportSpec> for RawSupport {
    fn from(s: SupportSpec) -> Self {
        let (mut side, mut boundary, mut point) = (None, None, None);
        match s.at {
            SupportAt::Side(x) => side = Some(x),
            SupportAt::Boundary(name) => boundary = Some(name),
            SupportAt::Point(x) => point = Some(x),
        }
        RawSupport {
            body: s.body,
            side,
            boundary,
            point,
            component: s.component,
            value: s.value,
        }
    }
}

/// One `[[load]]`, a table with one key, the kind:
/// `pressure = { body = "upper", side = "eta_max", pressure = 1e8 }`; the
/// library's [`Load`] with the body given by name.
pub type LoadSpec = Load<String>;

/// The TOML key of a load's kind, for error paths.
pub(super) fn load_kind<B>(l: &Load<B>) -> &'static str {
    match l {
        Load::BodyForce { .. } => "body_force",
        Load::Traction { .. } => "traction",
        Load::Pressure { .. } => "pressure",
    }
}

/// One `[[contact]]`.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawContact", into = "RawContact")]
pub struct ContactSpec {
    /// The name of the slave body.
    pub slave: String,
    /// Where on the slave the pair is, read from the one of the keys
    /// `slave_side` and `slave_boundary` the table gives.
    pub slave_at: SlaveAt,
    pub master: MasterSpec,
    /// θ, the penalty factor and the integration rule of the pair.
    pub nitsche: NitscheSpec,
}

/// Where on its slave body a `[[contact]]` is. The file names it by exactly
/// one of two keys; which one is read once, when the scene is parsed, so
/// that a contact in hand always names one slave part and nothing after the
/// parse asks again.
#[derive(Clone, Debug, PartialEq)]
pub enum SlaveAt {
    /// `slave_side = SIDE`: a side of a one-patch slave.
    Side(Side),
    /// `slave_boundary = NAME`: a named boundary of a multi-patch slave:
    /// one contact pair per piece, in order along the boundary.
    Boundary(String),
}

/// The `[[contact]]` table as written, before the choice of keys is read.
#[derive(Clone, Serialize, Deserialize)]
// type errors name the type it reads into, as they did before it existed
#[serde(deny_unknown_fields, expecting = "struct ContactSpec")]
struct RawContact {
    slave: String,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    slave_side: Option<Side>,
    #[serde(default, skip_serializing_if = "Option::is_none")]
    slave_boundary: Option<String>,
    master: MasterSpec,
    #[serde(default)]
    nitsche: NitscheSpec,
}

impl TryFrom<RawContact> for ContactSpec {
    type Error = TableError;

    fn try_from(c: RawContact) -> Result<Self, TableError> {
        let slave_at = match (c.slave_side, c.slave_boundary) {
            (Some(side), None) => SlaveAt::Side(side),
            (None, Some(name)) => SlaveAt::Boundary(name),
            _ => {
                return Err(TableError::new(
                    "slave_side",
                    format!("slave {:?}", c.slave),
                    "needs exactly one of `slave_side` (a one-patch body) or `slave_boundary` \
                     (a multi-patch body)",
                ))
            }
        };
        Ok(ContactSpec {
            slave: c.slave,
            slave_at,
            master: c.master,
            nitsche: c.nitsche,
        })
    }
}

impl From<ContactSpec> for RawContact {
    fn from(c: ContactSpec) -> Self {
        let (slave_side, slave_boundary) = match c.slave_at {
            SlaveAt::Side(side) => (Some(side), None),
            SlaveAt::Boundary(name) => (None, Some(name)),
        };
        RawContact {
            slave: c.slave,
            slave_side,
            slave_boundary,
            master: c.master,
            nitsche: c.nitsche,
        }
    }
}

/// The master of a contact pair: either `{ rigid_segment = { from, to } }`
/// (a rigid obstacle on the right of the segment's direction) or
/// `{ body = NAME, side = SIDE }`. Which of the two a table is, is read
/// when the scene is parsed.
#[derive(Clone, Debug, PartialEq, Serialize, Deserialize)]
#[serde(try_from = "RawMaster", into = "RawMaster")]
pub enum MasterSpec {
    /// A straight rigid obstacle from `from` to `to`.
    RigidSegment { from: [f64; 2], to: [f64; 2] },
    /// Side `side` of the (one-patch) body named `body`.
    Body { body: String, side: Side },
}

impl MasterSpec {
    /// The name of the master body; `None` for a rigid master.
    pub fn body(&self) -> Option<&str> {
        match self {
            MasterSpec::Body { body, .. } => Some(body),
            MasterSpec::RigidSegment { .. } => None,
        }
    }
}

/// The `master` table as written, before the choice of keys is read.
#[derive(Clone, Serialize, Deserialize)]
// type errors name the type it reads into, as they did before it existed
#[serde(deny_unknown_fields, expecting = "struct MasterSpec")]
struct RawMaster {
    #[serde(default)]
    rigid_segment: Option<SegmentSpec>,
    #[serde(default)]
    body: Option<String>,
    #[serde(default)]
    side: Option<Side>,
}

impl TryFrom<RawMaster> for MasterSpec {
    type Error = TableError;

    fn try_from(m: RawMaster) -> Result<Self, TableError> {
        match (m.rigid_segment, m.body, m.side) {
            (Some(SegmentSpec { from, to }), None, None) => {
                Ok(MasterSpec::RigidSegment { from, to })
            }
            (None, Some(body), Some(side)) => Ok(MasterSpec::Body { body, side }),
            (None, Some(name), None) => Err(TableError::new(
                "side",
                "(absent)",
                format!("the master body {name:?} needs a `side`"),
            )),
            (Some(_), _, _) => Err(TableError::new(
                "",
                "rigid_segment and body",
                "give either `rigid_segment` or `body` and `side`, not both",
            )),
            (None, None, _) => Err(TableError::new(
                "",
                "{}",
                "needs `rigid_segment = { from, to }` or `body` and `side`",
            )),
        }
    }
}

impl From<MasterSpec> for RawMaster {
    fn from(m: MasterSpec) -> Self {
        match m {
            MasterSpec::RigidSegment { from, to } => RawMaster {
                rigid_segment: Some(SegmentSpec { from, to }),
                body: None,
                side: None,
            },
            MasterSpec::Body { body, side } => RawMaster {
                rigid_segment: None,
                body: Some(body),
                side: Some(side),
            },
        }
    }
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
    /// `pressure_profile.csv`: contact (the `[[contact]]` index), x, y, the bracket P, the pressure
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
