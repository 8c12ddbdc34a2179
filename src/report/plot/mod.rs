//! The paper's figures: line charts (convergence histories, contact
//! pressures), geometry drawings (meshes, control nets) and filled scalar
//! fields (stresses on the deformed body).
//!
//! Every figure is an SVG file by default and a PNG file when the path ends in
//! `.png`. Output is deterministic: identical input gives identical bytes, so
//! figures can be committed and diffed. Files are written atomically, and all
//! input is validated before anything is drawn, so an error never leaves a
//! half-written or misleading figure behind.
//!
//! Layout is computed here rather than left to plotters' defaults: the label
//! areas are sized from the measured tick labels, the legend sits in its own
//! strip between title and plot (so it can never hide data), and geometry is
//! drawn with an equal aspect ratio by sizing the figure to the body.
//!
//! ```no_run
//! use iga_contact::report::plot::{line_chart, Axes, Series};
//! let axes = Axes {
//!     title: "Convergence".into(),
//!     x_label: "iteration".into(),
//!     y_label: "relative residual".into(),
//!     log_x: false,
//!     log_y: true,
//! };
//! let history = Series::line("BFGS", vec![(0.0, 1.0), (1.0, 1e-3), (2.0, 1e-8)]).with_markers();
//! line_chart("convergence.svg", &axes, &[history])?;
//! # Ok::<(), iga_contact::error::Error>(())
//! ```
//!
//! A figure is described by plain data ([`Series`], [`Polyline`],
//! [`FieldCell`], [`Label`], [`Chart`]) and drawn by one function per kind:
//! [`line_chart`], [`geometry_figure`], [`field_figure`],
//! [`annotated_figure`], and [`chart`] for a chart a chapter composes itself.
//! Everything a chapter needs is re-exported here, so a chapter's figures
//! can live outside this crate.

mod annotated;
mod bounds;
mod chart;
mod field;
mod figure;
mod font;
mod geometry;
mod layout;
mod legend;
mod line_chart;
mod palette;
mod render;
mod ticks;

pub use annotated::annotated_figure;
pub use bounds::Bounds;
pub use chart::chart;
pub use field::field_figure;
pub use figure::{
    Axes, Chart, ChartLine, FieldCell, Label, LabelSide, LegendEntry, LineKind, Polyline, Series,
    Stroke,
};
pub use geometry::geometry_figure;
pub use line_chart::{line_chart, line_chart_svg};
pub use palette::{viridis, Color, BLACK_INDEX, PALETTE, WHITE_INDEX};
pub use ticks::typographic_minus;
