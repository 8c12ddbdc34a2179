//! NURBS: knot vectors, the B-spline and rational bases, curves, patches
//! and exact refinement (Eq. 1).

pub mod curve;
pub mod interpolate;
pub mod knots;
pub mod patch;
pub mod refine;

pub use curve::NurbsCurve;
pub use knots::KnotVector;
pub use patch::{NurbsPatch, PatchBasis, Side};
