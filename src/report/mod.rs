//! Everything that leaves the solver: files (VTU, CSV, Markdown tables) and
//! figures. Nothing here feeds back into the computation.

pub mod atomic;
pub mod plot;
pub mod vtu;
