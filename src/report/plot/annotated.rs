//! Geometry drawings with text labels at data points: names of points,
//! weights of control points.

use super::bounds::check_finite;
use super::font::font;
use super::geometry::GeometryFigure;
use super::layout::Frame;
use super::palette::palette;
use super::render::{
    chart_region, draw_axes, draw_box, draw_header, draw_polylines, render, DrawResult, Figure,
};
use super::{Label, LabelSide, Polyline};
use crate::error::Result;
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

const LABEL_SIZE: f64 = 16.0;
/// Pixels between a labelled point and its text.
const LABEL_OFFSET: i32 = 7;

/// A [`geometry_figure`](super::geometry_figure) with text labels at data
/// points (names of points, weights of control points). Labels do not widen
/// the plotted range.
pub fn annotated_figure(
    path: impl AsRef<Path>,
    title: &str,
    lines: &[Polyline],
    labels: &[Label],
) -> Result<()> {
    check_labels(labels)?;
    let fig = AnnotatedFigure {
        geometry: GeometryFigure::new(title, lines)?,
        labels: labels.to_vec(),
    };
    render(path.as_ref(), &fig)
}

fn check_labels(labels: &[Label]) -> Result<()> {
    for (i, l) in labels.iter().enumerate() {
        for (k, &v) in l.at.iter().enumerate() {
            check_finite(|| format!("labels[{i}].at[{k}]"), v)?;
        }
    }
    Ok(())
}

struct AnnotatedFigure {
    geometry: GeometryFigure,
    labels: Vec<Label>,
}

impl Figure for AnnotatedFigure {
    fn frame(&self) -> &Frame {
        &self.geometry.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        let frame = &self.geometry.frame;
        draw_header(root, frame)?;
        let region = chart_region(root, frame);
        let mut chart = draw_axes(&region, frame, true)?;
        draw_polylines(&mut chart, &self.geometry.lines)?;
        for l in &self.labels {
            let (h, v, dx, dy) = match l.side {
                LabelSide::Right => (HPos::Left, VPos::Center, LABEL_OFFSET, 0),
                LabelSide::Left => (HPos::Right, VPos::Center, -LABEL_OFFSET, 0),
                LabelSide::Above => (HPos::Center, VPos::Bottom, 0, -LABEL_OFFSET),
                LabelSide::Below => (HPos::Center, VPos::Top, 0, LABEL_OFFSET),
            };
            let style = font(LABEL_SIZE)
                .color(&palette(l.color))
                .pos(Pos::new(h, v));
            chart.draw_series(std::iter::once(
                EmptyElement::at((l.at[0], l.at[1])) + Text::new(l.text.clone(), (dx, dy), style),
            ))?;
        }
        draw_box(root, frame)
    }
}
