//! Everything that leaves the solver: files (VTU, CSV and Markdown tables,
//! the facts a chapter quotes) and figures. Nothing here feeds back into
//! the computation.

pub mod atomic;
pub mod chapter;
pub mod drawing;
pub mod facts;
pub mod history;
pub mod plot;
pub mod table;
pub mod vtu;
