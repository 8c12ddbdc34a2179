//! Filled scalar fields: stresses on the (deformed) bodies, with a viridis
//! colour bar.

use super::bounds::{check_finite, check_polylines, square_pad, Bounds};
use super::font::{font, text_size, DESC_SIZE, TICK_SIZE};
use super::layout::{Frame, TICK_MARK, WIDTH};
use super::legend::polyline_legend;
use super::render::{
    chart_region, draw_axes, draw_box, draw_header, draw_polylines, render, DrawResult, Figure,
};
use super::ticks::Ticks;
use super::{viridis, FieldCell, Polyline};
use crate::error::{Error, Result};
use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

/// A scalar field filled on quadrilateral cells (equal aspect ratio) with a
/// viridis colour bar labelled `colorbar_label`, and polylines drawn on top.
pub fn field_figure(
    path: impl AsRef<Path>,
    title: &str,
    colorbar_label: &str,
    cells: &[FieldCell],
    overlay: &[Polyline],
) -> Result<()> {
    let fig = FieldFigure::new(title, colorbar_label, cells, overlay)?;
    render(path.as_ref(), &fig)
}

const BAR_GAP: i32 = 24;
const BAR_WIDTH: i32 = 22;

struct FieldFigure {
    frame: Frame,
    label: String,
    cells: Vec<FieldCell>,
    overlay: Vec<Polyline>,
    values: Bounds,
    bar_ticks: Ticks,
}

impl FieldFigure {
    fn new(
        title: &str,
        label: &str,
        cells: &[FieldCell],
        overlay: &[Polyline],
    ) -> Result<FieldFigure> {
        for (i, c) in cells.iter().enumerate() {
            check_finite(|| format!("cells[{i}].value"), c.value)?;
            for (j, p) in c.corners.iter().enumerate() {
                for (k, &v) in p.iter().enumerate() {
                    check_finite(|| format!("cells[{i}].corners[{j}][{k}]"), v)?;
                }
            }
        }
        check_polylines("overlay", overlay)?;
        let Some(values) = Bounds::of(cells.iter().map(|c| c.value)) else {
            return Err(Error::invalid(
                "cells",
                "[]",
                "a field figure needs at least one cell",
            ));
        };
        let values = if values.span() > 1e-12 * values.lo.abs().max(values.hi.abs()) {
            values
        } else {
            values.padded(0.0, "field values")?
        };
        let corners = || cells.iter().flat_map(|c| c.corners.iter());
        let pts = || corners().chain(overlay.iter().flat_map(|l| l.points.iter()));
        let bx = Bounds::of(pts().map(|p| p[0])).expect("cells are not empty");
        let by = Bounds::of(pts().map(|p| p[1])).expect("cells are not empty");
        let (bx, by) = square_pad(bx, by)?;
        // The bar's height, hence its ticks, is only known after the layout,
        // which needs the labels' width: reserve room for the widest labels
        // any tick density could produce.
        let widest = (2..=10)
            .map(|n| Ticks::new(values, false, n).max_label_width())
            .max()
            .unwrap_or(0);
        let label_h = if label.is_empty() {
            0
        } else {
            text_size(label, DESC_SIZE).1 + 10
        };
        let reserve = BAR_GAP + BAR_WIDTH + 2 * TICK_MARK + widest + label_h + 4;
        let frame = Frame::equal_aspect(WIDTH, reserve, title, polyline_legend(overlay), bx, by);
        let bar_ticks = Ticks::fitting(values, false, frame.plot.3, false);
        Ok(FieldFigure {
            frame,
            label: label.to_string(),
            cells: cells.to_vec(),
            overlay: overlay.to_vec(),
            values,
            bar_ticks,
        })
    }

    fn color(&self, v: f64) -> RGBColor {
        let (r, g, b) = viridis((v - self.values.lo) / self.values.span());
        RGBColor(r, g, b)
    }

    fn draw_colorbar<DB: DrawingBackend>(
        &self,
        root: &DrawingArea<DB, Shift>,
    ) -> DrawResult<(), DB> {
        let (left, top, w, h) = self.frame.plot;
        let x0 = left + w + BAR_GAP;
        let x1 = x0 + BAR_WIDTH;
        let bottom = top + h - 1;
        let to_y = |v: f64| {
            bottom - ((v - self.values.lo) / self.values.span() * (h - 1) as f64).round() as i32
        };
        // One band per pixel row (capped) looks continuous at any size.
        let bands = (h - 1).clamp(1, 256);
        for i in 0..bands {
            let ya = bottom - (i * (h - 1)) / bands;
            let yb = bottom - ((i + 1) * (h - 1)) / bands;
            let t = (i as f64 + 0.5) / bands as f64;
            let (r, g, b) = viridis(t);
            root.draw(&Rectangle::new(
                [(x0, yb), (x1, ya)],
                RGBColor(r, g, b).filled(),
            ))?;
        }
        root.draw(&Rectangle::new(
            [(x0, top), (x1, bottom)],
            BLACK.stroke_width(1),
        ))?;
        let text = font(TICK_SIZE)
            .color(&BLACK)
            .pos(Pos::new(HPos::Left, VPos::Center));
        let mut label_right = x1 + 2 * TICK_MARK;
        for (v, s) in &self.bar_ticks.major {
            let y = to_y(*v);
            if y < top - 1 || y > bottom + 1 {
                continue;
            }
            root.draw(&PathElement::new(vec![(x1, y), (x1 + TICK_MARK, y)], BLACK))?;
            root.draw(&Text::new(s.clone(), (x1 + 2 * TICK_MARK, y), text.clone()))?;
            label_right = label_right.max(x1 + 2 * TICK_MARK + text_size(s, TICK_SIZE).0);
        }
        if !self.label.is_empty() {
            let style = font(DESC_SIZE)
                .transform(FontTransform::Rotate270)
                .color(&BLACK)
                .pos(Pos::new(HPos::Center, VPos::Top));
            root.draw(&Text::new(
                self.label.clone(),
                (label_right + 10, top + h / 2),
                style,
            ))?;
        }
        Ok(())
    }
}

/// The quadrilateral `q` (pixels) pushed about a pixel outwards.
///
/// Anti-aliased renderers leave hairline gaps between abutting polygons;
/// growing every cell makes neighbours overlap instead, at no cost in file
/// size. Each corner moves along its miter so that both adjacent edges move
/// out by one pixel, whatever the cell's shape and orientation.
fn grow(q: [(i32, i32); 4]) -> Vec<(i32, i32)> {
    let p = q.map(|(x, y)| (x as f64, y as f64));
    let area2: f64 = (0..4)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 4]);
            a.0 * b.1 - b.0 * a.1
        })
        .sum();
    let sign = area2.signum();
    let normals: Vec<(f64, f64)> = (0..4)
        .map(|i| {
            let (a, b) = (p[i], p[(i + 1) % 4]);
            let (dx, dy) = (b.0 - a.0, b.1 - a.1);
            let len = dx.hypot(dy);
            if len == 0.0 || sign == 0.0 {
                (0.0, 0.0)
            } else {
                (sign * dy / len, -sign * dx / len)
            }
        })
        .collect();
    (0..4)
        .map(|i| {
            let (n0, n1) = (normals[(i + 3) % 4], normals[i]);
            let (mx, my) = (n0.0 + n1.0, n0.1 + n1.1);
            let denom = 1.0 + n0.0 * n1.0 + n0.1 * n1.1;
            // Sharp corners would shoot a long miter spike; cap it.
            let (mut ox, mut oy) = if denom > 1e-9 {
                (mx / denom, my / denom)
            } else {
                (0.0, 0.0)
            };
            let len = ox.hypot(oy);
            if len > 2.0 {
                ox *= 2.0 / len;
                oy *= 2.0 / len;
            }
            (q[i].0 + ox.round() as i32, q[i].1 + oy.round() as i32)
        })
        .collect()
}

impl Figure for FieldFigure {
    fn frame(&self) -> &Frame {
        &self.frame
    }

    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB> {
        draw_header(root, &self.frame)?;
        let region = chart_region(root, &self.frame);
        let mut chart = draw_axes(&region, &self.frame, false)?;
        for c in &self.cells {
            let px = c.corners.map(|p| chart.backend_coord(&(p[0], p[1])));
            root.draw(&Polygon::new(grow(px), self.color(c.value).filled()))?;
        }
        draw_polylines(&mut chart, &self.overlay)?;
        self.draw_colorbar(root)?;
        draw_box(root, &self.frame)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn grown_cells_cover_their_edges() {
        // Either orientation grows outwards.
        let ccw = grow([(0, 0), (10, 0), (10, 10), (0, 10)]);
        assert_eq!(ccw, [(-1, -1), (11, -1), (11, 11), (-1, 11)]);
        let cw = grow([(0, 0), (0, 10), (10, 10), (10, 0)]);
        assert_eq!(cw, [(-1, -1), (-1, 11), (11, 11), (11, -1)]);
        // A cell collapsed to a point stays put rather than exploding.
        assert_eq!(grow([(3, 3); 4]), [(3, 3); 4]);
    }
}
