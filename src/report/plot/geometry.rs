//! Geometry drawings: meshes, control nets and bodies, with equal aspect.

use super::bounds::{check_polylines, polyline_bounds, square_pad};
use super::layout::{Frame, WIDTH};
use super::legend::polyline_legend;
use super::render::{
    chart_region, draw_axes, draw_box, draw_header, draw_polylines, render, DrawResult, Figure,
};
use super::Polyline;
use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// A drawing of geometry with equal aspect ratio; the figure's height follows
/// the body's proportions (within limits).
pub fn geometry_figure(path: impl AsRef<Path>, title: &str, lines: &[Polyline]) -> Result<()> {
    let fig = GeometryFigure::new(title, lines)?;
    render(path.as_ref(), &fig)
}

pub(super) struct GeometryFigure {
    pub(super) frame: Frame,
    pub(super) lines: Vec<Polyline>,
}

impl GeometryFigure {
    pub(super) fn new(title: &str, lines: &[Polyline]) -> Result<GeometryFigure> {
        check_polylines("lines", lines)?;
        let Some((bx, by)) = polyline_bounds(lines) else {
            return Err(Error::invalid(
                "lines",
                format!("{} polylines", lines.len()),
                "a geometry figure needs at least one point",
            ));
        };
        let (bx, by) = square_pad(bx, by)?;
        let frame = Frame::equal_aspect(WIDTH, 0, title, polyline_legend(lines), bx, by);
        Ok(GeometryFigure {
            frame,
            lines: lines.to_vec(),
        })
    }
}

impl Figure for GeometryFigure {
    fn frame(&self) -> &Frame {
        &self.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        draw_header(root, &self.frame)?;
        let region = chart_region(root, &self.frame);
        let mut chart = draw_axes(&region, &self.frame, true)?;
        draw_polylines(&mut chart, &self.lines)?;
        draw_box(root, &self.frame)
    }
}
