//! What a figure shows, described without drawing: the series, polylines,
//! cells, labels and legend entries a chapter hands to the figure kinds.

use super::bounds::Bounds;
use super::palette::{Color, BLACK_INDEX};

/// One curve of a [`line_chart`](super::line_chart).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Series {
    /// Legend text; an empty label keeps the series out of the legend.
    pub label: String,
    pub points: Vec<(f64, f64)>,
    /// Draw a marker at every point (the shape cycles with the series index,
    /// so curves stay distinguishable in greyscale print).
    pub markers: bool,
    pub stroke: Stroke,
    /// Index into the palette; `None`: the series index, so that each curve
    /// has its own colour. Curves that belong together (one degree's two
    /// errors and its reference slopes) share one.
    pub color: Option<usize>,
    /// Marker shape; `None`: the series index.
    pub shape: Option<usize>,
}

/// How a [`Series`] is stroked: data solid, guides dashed or dotted, so
/// that measured curves and reference lines cannot be mistaken for each
/// other.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum Stroke {
    #[default]
    Solid,
    Dashed,
    Dotted,
}

impl Stroke {
    /// Dash and gap lengths in pixels, for the dashed kinds.
    pub(super) fn pattern(self) -> Option<(u32, u32)> {
        match self {
            Stroke::Solid => None,
            Stroke::Dashed => Some((8, 5)),
            Stroke::Dotted => Some((2, 4)),
        }
    }
}

impl Series {
    /// A solid line without markers.
    pub fn line(label: impl Into<String>, points: Vec<(f64, f64)>) -> Self {
        Series {
            label: label.into(),
            points,
            markers: false,
            stroke: Stroke::Solid,
            color: None,
            shape: None,
        }
    }

    pub fn with_markers(mut self) -> Self {
        self.markers = true;
        self
    }

    pub fn dashed(mut self) -> Self {
        self.stroke = Stroke::Dashed;
        self
    }

    pub fn dotted(mut self) -> Self {
        self.stroke = Stroke::Dotted;
        self
    }

    pub fn colored(mut self, palette_index: usize) -> Self {
        self.color = Some(palette_index);
        self
    }

    /// Markers of the given shape.
    pub fn with_shape(mut self, shape: usize) -> Self {
        self.markers = true;
        self.shape = Some(shape);
        self
    }
}

/// Titles and scales of a [`line_chart`](super::line_chart).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Axes {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    pub log_x: bool,
    pub log_y: bool,
}

/// How a [`Polyline`] is stroked.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq, Hash)]
pub enum LineKind {
    /// 2 px solid: body outlines, element boundaries of coarse meshes.
    #[default]
    Solid,
    /// 2 px dashed: reference or undeformed configurations.
    Dashed,
    /// 1 px dashed with a marker at every point: NURBS control polygons.
    ControlNet,
    /// 1 px solid: dense meshes and overlays on a field, where 2 px lines
    /// would hide what they sit on.
    Thin,
}

/// Stroke width, dashing and markers of a line kind.
pub(super) fn stroke_of(kind: LineKind) -> (u32, bool, bool) {
    match kind {
        LineKind::Solid => (2, false, false),
        LineKind::Dashed => (2, true, false),
        LineKind::ControlNet => (1, true, true),
        LineKind::Thin => (1, false, false),
    }
}

/// A polyline of a [`geometry_figure`](super::geometry_figure) or an
/// overlay of a [`field_figure`](super::field_figure).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Polyline {
    pub points: Vec<[f64; 2]>,
    pub style: LineKind,
    /// Index into [`PALETTE`](super::PALETTE) (taken modulo its length).
    pub color: usize,
    /// Legend text. Polylines sharing a label share one legend entry (the
    /// first one's style), so every element boundary can carry "elements".
    pub label: Option<String>,
}

impl Polyline {
    pub fn new(points: Vec<[f64; 2]>, style: LineKind, color: usize) -> Self {
        Polyline {
            points,
            style,
            color,
            label: None,
        }
    }

    pub fn labelled(mut self, label: impl Into<String>) -> Self {
        self.label = Some(label.into());
        self
    }
}

/// One quadrilateral of a [`field_figure`](super::field_figure): corners in
/// cyclic order (either orientation) and the value it is filled with.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct FieldCell {
    pub corners: [[f64; 2]; 4],
    pub value: f64,
}

impl FieldCell {
    /// A cell whose colour is the mean of its four corner values.
    pub fn from_corner_values(corners: [[f64; 2]; 4], values: [f64; 4]) -> Self {
        FieldCell {
            corners,
            value: values.iter().sum::<f64>() / 4.0,
        }
    }
}

/// One entry of a figure's legend: a short sample of the line (and marker)
/// beside its label.
#[derive(Clone, Debug, PartialEq)]
pub struct LegendEntry {
    pub label: String,
    pub color: Color,
    /// Line width of the sample, in pixels.
    pub width: u32,
    pub stroke: Stroke,
    /// Marker shape drawn on the sample (see [`Series::shape`]).
    pub marker: Option<usize>,
}

/// Where a [`Label`] sits relative to its point.
#[derive(Clone, Copy, Debug, Default, PartialEq, Eq)]
pub enum LabelSide {
    #[default]
    Right,
    Left,
    Above,
    Below,
}

/// A text placed beside a point of an
/// [`annotated_figure`](super::annotated_figure), in data coordinates.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct Label {
    pub at: [f64; 2],
    pub text: String,
    pub side: LabelSide,
    /// Index into [`PALETTE`](super::PALETTE).
    pub color: usize,
}

impl Label {
    pub fn new(at: [f64; 2], text: impl Into<String>, side: LabelSide) -> Self {
        Label {
            at,
            text: text.into(),
            side,
            color: BLACK_INDEX,
        }
    }

    pub fn colored(mut self, color: usize) -> Self {
        self.color = color;
        self
    }
}

/// A figure of its own on linear axes, for what the kinds above do not
/// draw: the chapter gives the ranges, the legend and the lines, and
/// [`chart`](super::chart) lays it out and draws it as a line chart is.
#[derive(Clone, Debug, PartialEq)]
pub struct Chart {
    pub title: String,
    pub x_label: String,
    pub y_label: String,
    /// The plotted ranges, used as given (no margin is added).
    pub x_range: Bounds,
    pub y_range: Bounds,
    pub legend: Vec<LegendEntry>,
    /// Drawn in order, so that later lines lie on top.
    pub lines: Vec<ChartLine>,
}

/// One line of a [`Chart`], in data coordinates.
#[derive(Clone, Debug, PartialEq)]
pub struct ChartLine {
    pub points: Vec<(f64, f64)>,
    pub color: Color,
    /// Line width in pixels.
    pub width: u32,
    /// Dash and gap lengths in pixels; `None`: solid.
    pub dash: Option<(u32, u32)>,
}
