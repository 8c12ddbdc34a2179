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
//! reader understands and which resolve the field as finely as asked. Where
//! the geometric map is singular or folds at a sampled point, the sample is
//! taken where it is regular ([`check_sampling`] says before a solve that
//! every element has such a point).
//!
//! By concern: `mesh` (the grid and its validation), `writer` (the XML and
//! the JSON sidecar), `sample` (where samples are taken), `fields` (the
//! sampled fields).

mod fields;
mod mesh;
mod sample;
mod writer;

pub use fields::sample_bodies;
pub use mesh::{PointField, VtuMesh, VTK_QUAD};
pub use sample::check_sampling;
