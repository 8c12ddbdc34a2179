//! Element-by-element assembly of Eq. (3), a(u, v) = L(v), into sparse
//! triplets over the free DOFs.
//!
//! One file a concern: the element integrals (`element.rs`), the pressure
//! terms of the mixed formulations (`mixed.rs`), stress recovery
//! (`stress.rs`), loads (`load.rs`), the Nitsche tie of non-matching patch
//! interfaces (`tie.rs`), and the two global paths: triplets
//! (`triplets.rs`, simple, the reference) and compressed columns (`csc.rs`,
//! in place and in parallel: what the problem uses).

mod csc;
mod element;
mod load;
mod mixed;
mod stress;
mod tie;
mod triplets;

pub use crate::sparse::Triplets;
pub use csc::{stiffness_matrix, Bulk};
pub use element::{btdb, element_stiffness, element_stiffness_with};
pub use load::{load_vector, split_body_forces, Load};
pub use mixed::{pressure_basis, volumetric_terms};
pub use stress::{displacement_at, strain_at, strain_stress, ElementStress};
pub use tie::tie_stiffness;
pub use triplets::stiffness;
