//! Charts a chapter composes itself: given ranges, legend and lines on
//! linear axes, laid out and drawn as a line chart is.

use super::bounds::{check_finite, Bounds};
use super::layout::{Frame, LINE_CHART_HEIGHT, WIDTH};
use super::render::{chart_region, draw_axes, draw_box, draw_header, render, DrawResult, Figure};
use super::{Chart, ChartLine};
use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use std::path::Path;

/// Draws `chart` to `path` (SVG, or PNG when the path ends in `.png`).
pub fn chart(path: impl AsRef<Path>, chart: &Chart) -> Result<()> {
    check_range("x_range", chart.x_range)?;
    check_range("y_range", chart.y_range)?;
    for (i, line) in chart.lines.iter().enumerate() {
        for (j, &(x, y)) in line.points.iter().enumerate() {
            check_finite(|| format!("lines[{i}].points[{j}].x"), x)?;
            check_finite(|| format!("lines[{i}].points[{j}].y"), y)?;
        }
    }
    let frame = Frame::fixed(
        (WIDTH, LINE_CHART_HEIGHT),
        &chart.title,
        chart.legend.clone(),
        &chart.x_label,
        &chart.y_label,
        chart.x_range,
        chart.y_range,
        (false, false),
    );
    let fig = ChartFigure {
        frame,
        lines: chart.lines.clone(),
    };
    render(path.as_ref(), &fig)
}

fn check_range(what: &str, b: Bounds) -> Result<()> {
    if b.lo.is_finite() && b.hi.is_finite() && b.lo < b.hi && b.span().is_finite() {
        Ok(())
    } else {
        Err(Error::invalid(
            what,
            format!("[{:e}, {:e}]", b.lo, b.hi),
            "must be finite with lo < hi",
        ))
    }
}

struct ChartFigure {
    frame: Frame,
    lines: Vec<ChartLine>,
}

impl Figure for ChartFigure {
    fn frame(&self) -> &Frame {
        &self.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        draw_header(root, &self.frame)?;
        let region = chart_region(root, &self.frame);
        let mut chart = draw_axes(&region, &self.frame, true)?;
        for line in &self.lines {
            let style = ShapeStyle::from(&line.color.rgb()).stroke_width(line.width);
            let points = line.points.clone();
            if let Some((dash, gap)) = line.dash {
                chart.draw_series(DashedLineSeries::new(points, dash, gap, style))?;
            } else {
                chart.draw_series(LineSeries::new(points, style))?;
            }
        }
        draw_box(root, &self.frame)
    }
}
