//! Everything that leaves the solver: files (VTU, CSV and Markdown tables)
//! and figures. Nothing here feeds back into the computation.

pub mod atomic;
pub mod drawing;
pub mod history;
pub mod plot;
pub mod table;
pub mod vtu;
pub(crate) mod xml;
