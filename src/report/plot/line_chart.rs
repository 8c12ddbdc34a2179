//! Line charts: convergence histories, pressure profiles, error curves.

use super::bounds::{check_finite, Bounds};
use super::layout::{Frame, LINE_CHART_HEIGHT, WIDTH};
use super::palette::palette;
use super::render::{
    chart_region, draw_axes, draw_box, draw_header, marker_outline, render, svg_text, DrawResult,
    Figure,
};
use super::{Axes, Color, LegendEntry, Series};
use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
// plotters' colour trait, shadowed by the palette's `Color` in scope here
use plotters::style::Color as _;
use std::path::Path;

/// Line chart of several series, with a legend and an automatic range with a
/// small margin. On a logarithmic axis non-positive values are left out and
/// the curve is broken there rather than joined across the gap.
pub fn line_chart(path: impl AsRef<Path>, axes: &Axes, series: &[Series]) -> Result<()> {
    let fig = LineChart::new(axes, series)?;
    render(path.as_ref(), &fig)
}

/// [`line_chart`] as SVG text, for an output set to stage (`name` names
/// the figure in an error).
pub fn line_chart_svg(name: &Path, axes: &Axes, series: &[Series]) -> Result<String> {
    let fig = LineChart::new(axes, series)?;
    svg_text(name, &fig)
}

struct LineChart {
    frame: Frame,
    /// Per series: its connected runs, in plot coordinates.
    runs: Vec<Vec<Vec<(f64, f64)>>>,
    series: Vec<Series>,
}

impl LineChart {
    fn new(axes: &Axes, series: &[Series]) -> Result<LineChart> {
        if series.is_empty() {
            return Err(Error::invalid(
                "series",
                "[]",
                "a line chart needs at least one series",
            ));
        }
        for s in series {
            for (j, &(x, y)) in s.points.iter().enumerate() {
                check_finite(|| format!("series[{:?}].points[{j}].x", s.label), x)?;
                check_finite(|| format!("series[{:?}].points[{j}].y", s.label), y)?;
            }
        }
        let to_plot = |v: f64, log: bool| match (log, v > 0.0) {
            (false, _) => Some(v),
            (true, true) => Some(v.log10()),
            (true, false) => None,
        };
        let runs: Vec<Vec<Vec<(f64, f64)>>> = series
            .iter()
            .map(|s| {
                let mut runs = vec![Vec::new()];
                for &(x, y) in &s.points {
                    match (to_plot(x, axes.log_x), to_plot(y, axes.log_y)) {
                        (Some(px), Some(py)) => runs.last_mut().unwrap().push((px, py)),
                        _ if runs.last().is_some_and(|r| !r.is_empty()) => runs.push(Vec::new()),
                        _ => {}
                    }
                }
                runs.retain(|r| !r.is_empty());
                runs
            })
            .collect();
        let all = || runs.iter().flatten().flatten();
        let (Some(bx), Some(by)) = (
            Bounds::of(all().map(|p| p.0)),
            Bounds::of(all().map(|p| p.1)),
        ) else {
            return Err(Error::invalid(
                "series",
                format!("{} series", series.len()),
                if axes.log_x || axes.log_y {
                    "no point with positive coordinates on the logarithmic axes"
                } else {
                    "every series is empty"
                },
            ));
        };
        let x_range = bx.padded(0.03, "x range")?;
        let y_range = by.padded(0.05, "y range")?;
        let legend = series
            .iter()
            .enumerate()
            .filter(|(_, s)| !s.label.is_empty())
            .map(|(i, s)| LegendEntry {
                label: s.label.clone(),
                color: Color::Palette(s.color.unwrap_or(i % 10)),
                width: 2,
                stroke: s.stroke,
                marker: s.markers.then_some(s.shape.unwrap_or(i)),
            })
            .collect();
        let frame = Frame::fixed(
            (WIDTH, LINE_CHART_HEIGHT),
            &axes.title,
            legend,
            &axes.x_label,
            &axes.y_label,
            x_range,
            y_range,
            (axes.log_x, axes.log_y),
        );
        Ok(LineChart {
            frame,
            runs,
            series: series.to_vec(),
        })
    }
}

impl Figure for LineChart {
    fn frame(&self) -> &Frame {
        &self.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        draw_header(root, &self.frame)?;
        let region = chart_region(root, &self.frame);
        let mut chart = draw_axes(&region, &self.frame, true)?;
        for (i, (s, runs)) in self.series.iter().zip(&self.runs).enumerate() {
            let color = palette(s.color.unwrap_or(i % 10));
            let style = ShapeStyle::from(&color).stroke_width(2);
            for run in runs {
                if let Some((dash, gap)) = s.stroke.pattern() {
                    chart.draw_series(DashedLineSeries::new(run.clone(), dash, gap, style))?;
                } else {
                    chart.draw_series(LineSeries::new(run.clone(), style))?;
                }
                if s.markers {
                    let outline = marker_outline(s.shape.unwrap_or(i));
                    chart.draw_series(run.iter().map(|&p| {
                        EmptyElement::at(p) + Polygon::new(outline.clone(), color.filled())
                    }))?;
                }
            }
        }
        draw_box(root, &self.frame)
    }
}
