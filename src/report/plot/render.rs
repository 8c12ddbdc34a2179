//! Drawing: the one place that talks to plotters. A validated figure is laid
//! out as a `Frame` and drawn here, to SVG or PNG, and written atomically.

use super::bounds::Bounds;
use super::figure::stroke_of;
use super::font::{ensure_fonts, font, DESC_SIZE, LEGEND_SIZE, TICK_SIZE, TITLE_SIZE};
use super::layout::{Frame, PAD, TICK_MARK};
use super::legend::{LEGEND_GAP, LEGEND_ROW, LEGEND_SAMPLE, LEGEND_SPACING};
use super::palette::{palette, GRID_MAJOR, GRID_MINOR};
use super::ticks::Ticks;
use super::{Polyline, Stroke};
use crate::error::{Error, Result};
use crate::report::atomic::write_atomic;
use plotters::coord::ranged1d::{DefaultFormatting, KeyPointHint};
use plotters::coord::types::RangedCoordf64;
use plotters::coord::Shift;
use plotters::element::DashedPathElement;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, Pos, VPos};
use std::path::Path;

pub(super) type DrawResult<T, DB> =
    std::result::Result<T, DrawingAreaErrorKind<<DB as DrawingBackend>::ErrorType>>;
pub(super) type Coords = Cartesian2d<TickAxis, TickAxis>;

/// A linear axis whose grid lines are exactly the precomputed ticks.
///
/// plotters' own key-point wrapper drops the value formatter of `f64` axes,
/// and its log axis finds no ticks inside a single decade; owning the axis
/// sidesteps both (log axes are linear axes over log10 of the data).
pub(super) struct TickAxis {
    linear: RangedCoordf64,
    range: Bounds,
    major: Vec<f64>,
    minor: Vec<f64>,
}

impl TickAxis {
    fn new(range: Bounds, ticks: &Ticks) -> TickAxis {
        TickAxis {
            linear: (range.lo..range.hi).into(),
            range,
            major: ticks.major.iter().map(|(p, _)| *p).collect(),
            minor: ticks.minor.clone(),
        }
    }
}

impl Ranged for TickAxis {
    type FormatOption = DefaultFormatting;
    type ValueType = f64;

    fn map(&self, value: &f64, limit: (i32, i32)) -> i32 {
        self.linear.map(value, limit)
    }

    fn key_points<Hint: KeyPointHint>(&self, hint: Hint) -> Vec<f64> {
        if hint.weight().allow_light_points() {
            self.minor.clone()
        } else {
            self.major.clone()
        }
    }

    fn range(&self) -> std::ops::Range<f64> {
        self.range.lo..self.range.hi
    }
}

/// A validated figure, ready to be drawn on any backend.
pub(super) trait Figure {
    fn frame(&self) -> &Frame;
    fn draw<DB: DrawingBackend>(&self, root: &DrawingArea<DB, Shift>) -> DrawResult<(), DB>;
}

/// The SVG text of `fig`, for a caller that stages it itself (an output
/// set, whose writes hold its lock); `name` names it in an error.
pub(super) fn svg_text(name: &Path, fig: &impl Figure) -> Result<String> {
    ensure_fonts();
    let failed = |e: String| Error::Io {
        path: name.display().to_string(),
        source: std::io::Error::other(format!("drawing the figure failed: {e}")),
    };
    let mut svg = String::new();
    {
        let root = SVGBackend::with_string(&mut svg, fig.frame().size).into_drawing_area();
        fig.draw(&root).map_err(|e| failed(e.to_string()))?;
        root.present().map_err(|e| failed(e.to_string()))?;
    }
    // plotters escapes markup but passes control characters through,
    // which no XML reader accepts.
    Ok(crate::report::xml::xml_safe(&svg).into_owned())
}

pub(super) fn render(path: &Path, fig: &impl Figure) -> Result<()> {
    ensure_fonts();
    let size = fig.frame().size;
    let failed = |e: String| Error::Io {
        path: path.display().to_string(),
        source: std::io::Error::other(format!("drawing the figure failed: {e}")),
    };
    let png = path
        .extension()
        .is_some_and(|e| e.eq_ignore_ascii_case("png"));
    if !png {
        return write_atomic(path, svg_text(path, fig)?.as_bytes());
    }
    // The bitmap backend can only encode to a file; render next to the target
    // and move the bytes through write_atomic like every other output.
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_default();
    // Threads of one process may render the same target concurrently.
    static RENDERS: std::sync::atomic::AtomicUsize = std::sync::atomic::AtomicUsize::new(0);
    let n = RENDERS.fetch_add(1, std::sync::atomic::Ordering::Relaxed);
    let tmp = path.with_file_name(format!(".{name}.{}.{n}.render.png", std::process::id()));
    if let Some(dir) = tmp.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir).map_err(|source| Error::Io {
            path: dir.display().to_string(),
            source,
        })?;
    }
    let drawn = (|| {
        let root = BitMapBackend::new(&tmp, size).into_drawing_area();
        fig.draw(&root).map_err(|e| failed(e.to_string()))?;
        root.present().map_err(|e| failed(e.to_string()))
    })();
    let bytes = drawn.and_then(|()| {
        std::fs::read(&tmp).map_err(|source| Error::Io {
            path: tmp.display().to_string(),
            source,
        })
    });
    let _ = std::fs::remove_file(&tmp);
    write_atomic(path, &bytes?)
}

pub(super) fn draw_header<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> DrawResult<(), DB> {
    root.fill(&WHITE)?;
    let (left, _, plot_w, _) = frame.plot;
    let centre = left + plot_w / 2;
    let style = font(TITLE_SIZE)
        .color(&BLACK)
        .pos(Pos::new(HPos::Center, VPos::Top));
    root.draw(&Text::new(frame.title.clone(), (centre, PAD), style))?;
    for (r, row) in frame.rows.iter().enumerate() {
        let extent: i32 = row.iter().map(|&i| frame.legend[i].extent()).sum::<i32>()
            + LEGEND_SPACING * (row.len() as i32 - 1);
        let y = frame.legend_top + r as i32 * LEGEND_ROW + LEGEND_ROW / 2;
        let mut x = centre - extent / 2;
        for &i in row {
            let e = &frame.legend[i];
            let color = e.color.rgb();
            let style = ShapeStyle::from(&color).stroke_width(e.width);
            let RGBColor(r, g, b) = color;
            if 0.2126 * r as f64 + 0.7152 * g as f64 + 0.0722 * b as f64 > 200.0 {
                // A white overlay line would vanish against the page; show
                // it on a grey swatch, as it appears on the field.
                root.draw(&Rectangle::new(
                    [(x - 3, y - 7), (x + LEGEND_SAMPLE + 3, y + 7)],
                    RGBColor(0x90, 0x90, 0x90).filled(),
                ))?;
            }
            let ends = vec![(x, y), (x + LEGEND_SAMPLE, y)];
            // the legend's samples are short, so their dashes are too
            let pattern = match e.stroke {
                Stroke::Solid => None,
                Stroke::Dashed => Some((6, 4)),
                Stroke::Dotted => Some((2, 3)),
            };
            if let Some((dash, gap)) = pattern {
                root.draw(&DashedPathElement::new(ends, dash, gap, style))?;
            } else {
                root.draw(&PathElement::new(ends, style))?;
            }
            if let Some(m) = e.marker {
                root.draw(&Polygon::new(
                    marker_outline(m)
                        .into_iter()
                        .map(|(dx, dy)| (x + LEGEND_SAMPLE / 2 + dx, y + dy))
                        .collect::<Vec<_>>(),
                    color.filled(),
                ))?;
            }
            let text = font(LEGEND_SIZE)
                .color(&BLACK)
                .pos(Pos::new(HPos::Left, VPos::Center));
            root.draw(&Text::new(
                e.label.clone(),
                (x + LEGEND_SAMPLE + LEGEND_GAP, y),
                text,
            ))?;
            x += e.extent() + LEGEND_SPACING;
        }
    }
    Ok(())
}

/// The plot area together with its label areas.
pub(super) fn chart_region<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> DrawingArea<DB, Shift> {
    let (left, top, w, h) = frame.plot;
    root.clone().shrink(
        (left - frame.y_area, top),
        ((w + frame.y_area) as u32, (h + frame.x_area) as u32),
    )
}

/// The axes and grid of the plot; returns the chart to draw into.
pub(super) fn draw_axes<'a, DB: DrawingBackend>(
    region: &'a DrawingArea<DB, Shift>,
    frame: &Frame,
    grid: bool,
) -> DrawResult<ChartContext<'a, DB, Coords>, DB> {
    let mut chart = ChartBuilder::on(region)
        .x_label_area_size(frame.x_area)
        .y_label_area_size(frame.y_area)
        .build_cartesian_2d(
            TickAxis::new(frame.x_range, &frame.x_ticks),
            TickAxis::new(frame.y_range, &frame.y_ticks),
        )?;
    let x_fmt = |v: &f64| frame.x_ticks.label_of(*v);
    let y_fmt = |v: &f64| frame.y_ticks.label_of(*v);
    let mut mesh = chart.configure_mesh();
    mesh.x_label_formatter(&x_fmt)
        .y_label_formatter(&y_fmt)
        .label_style(font(TICK_SIZE).color(&BLACK))
        .axis_desc_style(font(DESC_SIZE).color(&BLACK))
        .bold_line_style(GRID_MAJOR)
        .light_line_style(GRID_MINOR)
        .axis_style(BLACK)
        .set_all_tick_mark_size(TICK_MARK);
    if !frame.x_desc.is_empty() {
        mesh.x_desc(frame.x_desc.clone());
    }
    if !frame.y_desc.is_empty() {
        mesh.y_desc(frame.y_desc.clone());
    }
    if !grid {
        // A field covers the grid anyway, and it would show through gaps
        // between cells as stray lines.
        mesh.disable_mesh();
    }
    mesh.draw()?;
    Ok(chart)
}

/// A frame around the plot area, drawn last so that cells do not cover it.
pub(super) fn draw_box<DB: DrawingBackend>(
    root: &DrawingArea<DB, Shift>,
    frame: &Frame,
) -> DrawResult<(), DB> {
    let (left, top, w, h) = frame.plot;
    root.draw(&Rectangle::new(
        [(left, top), (left + w - 1, top + h - 1)],
        BLACK.stroke_width(1),
    ))
}

/// Pixel outline of a marker; `shape` cycles through circle, square,
/// triangle, diamond and inverted triangle. All are polygons so that one
/// element type serves every shape (a 12-gon is a circle to the eye).
pub(super) fn marker_outline(shape: usize) -> Vec<(i32, i32)> {
    let s = 4;
    match shape % 5 {
        0 => (0..12)
            .map(|k| {
                let a = k as f64 * std::f64::consts::PI / 6.0;
                (
                    (4.5 * a.cos()).round() as i32,
                    (4.5 * a.sin()).round() as i32,
                )
            })
            .collect(),
        1 => vec![(-s, -s), (s, -s), (s, s), (-s, s)],
        2 => vec![(0, -s - 1), (s + 1, s), (-s - 1, s)],
        3 => vec![(0, -s - 2), (s + 1, 0), (0, s + 2), (-s - 1, 0)],
        _ => vec![(0, s + 1), (s + 1, -s), (-s - 1, -s)],
    }
}

pub(super) fn draw_polylines<DB: DrawingBackend>(
    chart: &mut ChartContext<'_, DB, Coords>,
    lines: &[Polyline],
) -> DrawResult<(), DB> {
    for line in lines {
        let (width, dashed, markers) = stroke_of(line.style);
        let color = palette(line.color);
        let style = ShapeStyle::from(&color).stroke_width(width);
        let pts: Vec<(f64, f64)> = line.points.iter().map(|p| (p[0], p[1])).collect();
        if dashed {
            chart.draw_series(DashedLineSeries::new(pts.clone(), 6, 4, style))?;
        } else {
            chart.draw_series(LineSeries::new(pts.clone(), style))?;
        }
        if markers {
            let outline = marker_outline(0);
            chart
                .draw_series(pts.into_iter().map(|p| {
                    EmptyElement::at(p) + Polygon::new(outline.clone(), color.filled())
                }))?;
        }
    }
    Ok(())
}
