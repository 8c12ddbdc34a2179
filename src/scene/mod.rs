//! Scene files: a whole contact problem — bodies, supports, loads, contact
//! pairs, solver options and the outputs wanted — described in TOML.
//!
//! A scene is read in three steps, each of which names the offending key
//! path (`body[0].material.young`) and value when it fails:
//!
//! 1. **syntax**: the text must be TOML (errors give line and column);
//! 2. **shape**: every table must have exactly the known keys with values of
//!    the right type (`deny_unknown_fields` everywhere, paths tracked by
//!    `serde_path_to_error`), and a table that names one thing by one of
//!    several keys (a support's `side`, `boundary` or `point`, a contact's
//!    `slave_side` or `slave_boundary`, a master's `rigid_segment` or
//!    `body`) must give exactly one, read into an enum ([`SupportAt`],
//!    [`SlaveAt`], [`MasterSpec`]);
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
//!
//! One concern per file, in the order a scene passes through them:
//! `schema` (the tables as types, with `geometry`, `refine` and `nitsche`
//! in files of their own); `parse` (text to [`Scene`]); `validate` with the
//! value checks of `rules` and the name lookups of `lookup`; `patches`
//! and `build` (scene to [`Problem`]); `estimate` and `check` (before a
//! run); `run` and `summary` (solving and the outputs).

mod build;
mod check;
mod estimate;
mod geometry;
mod lookup;
mod nitsche;
mod overlap;
mod parse;
mod patches;
mod refine;
mod rules;
mod run;
mod schema;
mod summary;
mod validate;

pub use check::CheckReport;
pub use geometry::{DiskLayout, GeometrySpec, NurbsSpec};
pub use nitsche::NitscheSpec;
pub use refine::RefineSpec;
pub use schema::{
    files, BodySpec, Component, ContactSpec, LoadSpec, MasterSpec, OutputSpec, Scene, SegmentSpec,
    SlaveAt, SupportAt, SupportSpec, MAX_DEGREE, MAX_ELEMENTS, MAX_LAGRANGE, MAX_VTU_SUBDIVISIONS,
};
pub use summary::RunReport;

use schema::load_kind;

#[cfg(doc)]
use crate::problem::Problem;
